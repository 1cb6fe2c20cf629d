#include "carto/tiles.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>

#include "carto/crest.hpp"
#include "carto/error.hpp"
#include "carto/control_fields.hpp"
#include "carto/output.hpp"
#include "carto/partition.hpp"
#include "carto/styles.hpp"

namespace carto {
namespace {

// The outer tiles reach this far beyond the DEM (ground units), so that a face of the
// partition lying outside the DEM still has an owner, as it is drawn in a whole run.
constexpr double kBeyond = 1e15;

// The DEM cells a tile reads beyond the relief window: the terrain kernels (a 3x3 gradient,
// then a 3x3 mean of normals), the bilinear sampler's neighbour and one cell to spare.
constexpr int kKernelCells = 4;

// How far (in the style's longest paper length) a style reads beyond a face's border: its
// strokes are drawn in the face, but their jittered or bent break points may sample the
// fields of the neighbour just across.
constexpr double kReachLengths = 4.0;

// Whether a raster given with the DEM (--slope, --roughness) lies on the DEM's own grid (else
// on another grid in the working CRS). On another grid in another CRS the whole run warps the
// whole file first, which a window cannot reproduce: refused.
bool on_dem_grid(const std::string& path, const char* what, const WorkingGrid& dem, const std::string& dem_path) {
    const RasterInfo info = raster_info(path, what);
    if (same_grid(info, dem.source)) return true;
    if (same_crs(info.crs_wkt, dem.grid.crs_wkt)) return false;
    throw Error(Code::Usage, std::string(what) + " '" + path + "': a tiled run needs it on the grid of --dem '" +
                                 dem_path + "' or in the CRS the DEM is worked in (" + crs_name(dem.grid.crs_wkt) +
                                 "; e.g. gdalwarp -t_srs to match)");
}

// Such a raster on the tile's window `like` of the working grid, as the whole run reads it
// (carto::prepare): on the DEM's own grid, reprojected as the DEM is; on another grid,
// resampled at the window's cell centres from the window of it that holds their neighbours.
Raster read_like_dem(const std::string& path, const char* what, const WorkingGrid& dem, const Raster& like,
                     const tex::BBox& area, int halo, const std::string& dem_path) {
    // The same cells as the DEM's window (read with the same box and halo).
    if (on_dem_grid(path, what, dem, dem_path)) return read_working_window(path, what, dem, area, halo);
    return resample_like(read_raster_window(path, what, like.bounds(), 2), like);
}

}  // namespace

bool rasters_read_by_window(const Options& o, const WorkingGrid& grid) {
    for (const auto& [path, what] : {std::pair<const std::string&, const char*>{o.slope, "--slope"}, {o.roughness, "--roughness"}}) {
        if (path.empty()) continue;
        const RasterInfo info = raster_info(path, what);
        if (!same_grid(info, grid.source) && !same_crs(info.crs_wkt, grid.grid.crs_wkt)) return false;
    }
    return true;
}

Prepared prepare_around(const Plan& plan, const WorkingGrid& grid, const PartitionOptions& po,
                        const std::optional<tex::BBox>& terrain, long long* dem_cells) {
    const Options& o = plan.options;
    const RasterInfo& dem_info = grid.grid;
    const double cell = std::min(std::abs(dem_info.gt[1]), std::abs(dem_info.gt[5]));
    Prepared p;
    if (o.partition.path != "none") {
        p.partition = load_partition(po, dem_info.crs_wkt);
    } else {
        p.partition.crs_wkt = dem_info.crs_wkt;
    }
    p.extent = dem_info.bounds();
    p.user_window = o.window.has_value();
    // The DEM under all of them (and the terrain's reach), with a halo where the relief
    // window and the terrain kernels see the same cells as in the whole raster.
    tex::BBox area = p.partition.bounds();
    if (terrain) area.add(*terrain);
    const int halo = tile_halo_cells(plan, cell);
    Raster dem = read_working_window(o.dem, "--dem", grid, area, halo);
    if (dem_cells) *dem_cells = (long long)dem.width * dem.height;
    p.terrain = compute_terrain(dem);
    if (!o.slope.empty()) p.terrain.slope = read_like_dem(o.slope, "--slope", grid, dem, area, halo, o.dem);
    if (!o.roughness.empty()) {
        p.terrain.roughness = read_like_dem(o.roughness, "--roughness", grid, dem, area, halo, o.dem);
        check_roughness(p.terrain.roughness, o.roughness);
    }
    p.relief = local_relief(dem, o.relief_radius);
    resolve_face_controls(p, false);
    return p;
}

void check_tiled_rasters(const Options& o) {
    if (o.slope.empty() && o.roughness.empty()) return;
    const WorkingGrid grid = working_grid(raster_info(o.dem, "--dem"));
    if (!o.slope.empty()) on_dem_grid(o.slope, "--slope", grid, o.dem);
    if (!o.roughness.empty()) on_dem_grid(o.roughness, "--roughness", grid, o.dem);
}

std::vector<tex::BBox> tile_grid(const RasterInfo& dem, double size) {
    if (!(size > 0) || !std::isfinite(size))
        throw Error(Code::Usage, "--tile-size: " + std::to_string(size) + " is not a positive length");
    const tex::BBox b = dem.bounds();
    const long nx = std::max(1L, long(std::ceil(b.width() / size))), ny = std::max(1L, long(std::ceil(b.height() / size)));
    if (double(nx) * double(ny) > 1e7)
        throw Error(Code::Usage, "--tile-size " + std::to_string(size) + ": " + std::to_string(nx * ny) +
                                     " tiles, more than 10 million; choose larger tiles");
    std::vector<tex::BBox> tiles;
    for (long j = 0; j < ny; ++j)
        for (long i = 0; i < nx; ++i) {
            tex::BBox t{b.xmin + double(i) * size, b.ymax - double(j + 1) * size, b.xmin + double(i + 1) * size,
                        b.ymax - double(j) * size};
            if (i == 0) t.xmin = -kBeyond;
            if (i == nx - 1) t.xmax = kBeyond;
            if (j == 0) t.ymax = kBeyond;
            if (j == ny - 1) t.ymin = -kBeyond;
            tiles.push_back(t);
        }
    return tiles;
}

double tile_context_margin(const Plan& plan, double cell) {
    // The style that hatches the faces (a terrain style hatches them with the default rock
    // style at its defaults, Plan::rock).
    double longest = 0;
    for (const auto& sp : plan.rock.params)
        if (sp.unit == "mm") longest = std::max(longest, plan.rock_params.at(sp.name));
    return kReachLengths * longest + kKernelCells * cell + 4 * plan.options.partition.snap;
}

int tile_halo_cells(const Plan& plan, double cell) {
    // The relief window, or the style's reach when longer (its smoothed fields, such as the
    // fall line and the shade, average over a paper length shorter than that reach).
    return int(std::ceil(std::max(plan.options.relief_radius, tile_context_margin(plan, cell)) / cell)) + kKernelCells;
}

TileReport run_tile(const Options& o, const tex::BBox& tile, const std::string& out) {
    // The tile file is one more output: never an input, never an existing file unless asked.
    Options checked = o;
    checked.outputs.push_back(out);
    Plan plan = make_plan(checked);
    plan.outputs.pop_back();
    plan.options.outputs.pop_back();
    return run_tile(plan, tile, out);
}

TileReport run_tile(const Plan& plan, const tex::BBox& tile, const std::string& out) {
    const auto t0 = std::chrono::steady_clock::now();
    const Options& o = plan.options;
    TileReport report;
    if (o.partition.path == "auto")
        // A tiled run extracts the partition tile by tile first (extract_tile, rockhatch.tiles)
        // and hands its hatching tiles the merged file.
        throw Error(Code::Usage, "--partition auto: a hatching tile reads a partition file; rockhatch tiles extracts "
                                 "the partition tile by tile first (carto::extract_tile) and passes the merged file");
    // The grid the whole run works on (a geographic DEM's UTM grid), read window by window.
    const WorkingGrid grid = working_grid(raster_info(o.dem, "--dem"));
    const RasterInfo& dem_info = grid.grid;
    // The smaller side of a cell: halos counted in it are wide enough along both axes.
    const double cell = std::min(std::abs(dem_info.gt[1]), std::abs(dem_info.gt[5]));

    // 1. The faces the tile owns, and the box they cover.
    PartitionOptions po = o.partition;
    po.filter = tile;
    tex::BBox reach;
    // A face is the tile's when its anchor lies in the tile (and in --window, when given).
    auto mine = [&](const RockFace& f) {
        const Point a = face_anchor(f);
        return owns(tile, a) && (!o.window || owns(*o.window, a));
    };
    // The crest ornaments of the ridge lines whose anchor (a point on the line) lies in the
    // tile: the window of the tile's hatching, so the ridges and their neighbours are read.
    const std::optional<double>& band = plan.crest_band;
    Plan tile_plan = plan;
    tile_plan.options.window = o.window ? tile.intersection(*o.window) : tile;
    const tex::BBox& tile_window = *tile_plan.options.window;
    // A terrain style draws the elements the tile owns, reading the DEM and the faces (their
    // hatches) within its reach of the tile's part of the DEM.
    const std::optional<tex::BBox> terrain = terrain_read_area(tile_plan, dem_info.bounds(), cell);
    if (terrain && !terrain->empty()) {
        po.filter = tex::BBox{std::min(tile.xmin, terrain->xmin), std::min(tile.ymin, terrain->ymin),
                              std::max(tile.xmax, terrain->xmax), std::max(tile.ymax, terrain->ymax)};
        reach.add(*terrain);
    }
    // --partition none (a terrain style over ground without rock): no faces.
    Partition around;
    if (o.partition.path != "none") around = load_partition(po, dem_info.crs_wkt);
    for (const RockFace& f : around.faces)
        if (mine(f) || (terrain && f.region.bbox().intersects(*terrain))) reach.add(f.region.bbox());
    double margin = tile_context_margin(plan, cell);
    if (band) {
        for (const LabelledLine& l : around.lines)
            if (l.kind == LineKind::Ridge && owns(tile_window, ridge_anchor(l.points)))
                for (const Point& q : l.points) reach.add(q);
        margin = std::max(margin, crest_context(*band));
    }

    Drawing d;
    d.crs_wkt = dem_info.crs_wkt;
    d.style = plan.style.info.name;
    d.scale = o.scale;
    if (!reach.empty()) {
        // 2. Their neighbourhood: every face a style may read across an owned face's border;
        // 3. the DEM under all of them.
        po.filter = reach.expanded(margin);
        const Prepared p = prepare_around(plan, grid, po, terrain, &report.dem_cells);
        std::vector<int> owned;
        for (std::size_t i = 0; i < p.partition.faces.size(); ++i)
            if (mine(p.partition.faces[i])) owned.push_back(int(i));
        report.context_faces = p.partition.faces.size();
        d = hatch(p, tile_plan, owned);
    }
    report.faces = std::size_t(std::count_if(d.faces.begin(), d.faces.end(),
                                             [](const FaceHatches& f) { return f.face_id != kTerrainFaceId; }));
    for (const auto& f : d.faces) report.hatches += f.hatches.size();
    write_gpkg(d, out, false);
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return report;
}

}  // namespace carto
