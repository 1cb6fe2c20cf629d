#include "carto/extract.hpp"

#include <gdal_alg.h>
#include <gdal_priv.h>
#include <ogr_geometry.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>

#include "carto/error.hpp"
#include "carto/control_fields.hpp"
#include "carto/output.hpp"
#include "extract/borders.hpp"
#include "extract/faces.hpp"
#include "extract/flow.hpp"
#include "extract/grid.hpp"
#include "extract/mask.hpp"
#include "extract/network.hpp"
#include "extract/outlines.hpp"
#include "extract/polygons.hpp"
#include "gdal_scope.hpp"

namespace carto {

using namespace extraction;

namespace {

// The extraction's distances, with their units and reasons (the comments where each is used
// say more).
constexpr double kMmPerM = 1000.0;            // paper millimetres per metre at 1:1
constexpr double kKeepAreaFactor = 1.5;       // specks and gaps kept above 1.5 x the minimum area
constexpr double kRockWindowRadiusM = 12.5;   // slope and roughness averaged over about 25 m
constexpr double kClosingRadiusM = 15.0;      // the rock mask closed by a disc of about 15 m
constexpr double kEdgeWindowRadiusM = 5.0;    // the edge's slope and roughness over about 10 m
constexpr double kMinLabelRunM = 40.0;        // a border is labelled where it runs 40 m along a line
constexpr int kMinRunCells = 3;               //   (3 cells at least)
constexpr double kLabelSnapCells = 0.1;       // lines are the borders: matched within a tenth of a cell

}  // namespace

double azimuth_degrees(double math_angle) {
    double az = 90.0 - math_angle * 180.0 / M_PI;
    az = std::fmod(az, 360.0);
    if (az < 0) az += 360.0;
    return az;
}

void check_extract_options(const ExtractOptions& o) {
    auto positive = [](double v, const char* name, bool zero_ok) {
        if (!std::isfinite(v) || v < 0 || (!zero_ok && v == 0))
            throw Error(Code::Usage, std::string(name) + ": " + std::to_string(v) + " is not a " +
                                         (zero_ok ? "non-negative" : "positive") + " number");
    };
    positive(o.min_slope, "--min-slope", true);
    positive(o.min_roughness, "--min-roughness", true);
    positive(o.min_area_mm2, "--min-area", true);
    positive(o.scale, "--scale", false);
    positive(o.thalweg_area, "--thalweg-area", false);
    positive(o.ridge_area, "--ridge-area", false);
    positive(o.max_fill, "--max-fill", true);
    positive(o.smooth, "--smooth", true);
    positive(o.converge, "--converge", true);
    positive(o.simplify, "--simplify", true);
    if (o.min_roughness > 1) throw Error(Code::Usage, "--min-roughness: must lie in 0..1");
    if (o.simplify > 2) throw Error(Code::Usage, "--simplify: at most 2 cells (faces would cross)");
}

ExtractResult extract_partition(const ExtractOptions& o, const Progress& progress) {
    const std::string what = o.what + (o.dem.empty() ? std::string() : " '" + o.dem + "'");
    check_extract_options(o);

    ExtractResult res;
    step(progress, 0.0, "reading the DEM");
    Raster dem;
    std::string note;
    if (o.raster) {
        dem = *o.raster;
        if (dem.crs_wkt.empty()) throw Error(Code::NoCrs, what + ": the raster has no CRS");
        if (!dem.north_up()) throw Error(Code::BadLayer, what + ": rotated rasters are not supported");
        dem = to_working_crs(std::move(dem), &note);
    } else {
        // The file's CRS and rotation are checked as it is opened.
        dem = read_working_dem(o.dem, o.what, &note);
    }
    if (std::isnan(dem.min_max().first)) throw Error(Code::BadLayer, what + ": every cell is NoData");
    if (!note.empty()) res.notes.push_back(note);

    step(progress, 0.1, "terrain fields");
    res.terrain = compute_terrain(dem);
    const Grid g{dem.width, dem.height};
    const double dx = dem.cell_x(), dy = dem.cell_y(), cell_area = dx * dy;
    const double ground_m_per_mm = o.scale / kMmPerM;  // metres on the ground per millimetre on paper
    const double min_area = o.min_area_mm2 * ground_m_per_mm * ground_m_per_mm;  // m2 on the ground
    // Rock specks are dropped and gaps filled unless their cells cover 1.5 times the minimum
    // area: generalising their outlines (step 4) takes area from small pieces, and one that
    // fell under `min_area` would be a speck on paper. (Faces under the minimum area merge
    // into a neighbour as before: a margin there would remove ridge and thalweg borders; a
    // face that generalising makes too small keeps borders closer to its cell edges.)
    const double keep_area = kKeepAreaFactor * min_area;

    // ---- 1. Rock mask
    step(progress, 0.2, "rock mask");
    // Slope and roughness averaged over about 25 m (at least 3x3 cells): single cells are noisy.
    const int radius = std::max(1, int(std::lround(kRockWindowRadiusM / dx)));
    const std::vector<float> slope = box_mean(g, res.terrain.slope.data, radius);
    const std::vector<float> rough = box_mean(g, res.terrain.roughness.data, radius);
    std::vector<char> inside_mask;
    if (!o.mask.empty()) inside_mask = rasterize_mask(o.mask, dem);
    // Rock where a slope and a roughness reach the thresholds, inside the user's mask.
    auto steep = [&](const std::vector<float>& s, const std::vector<float>& r) {
        std::vector<char> on(g.size(), 0);
        for (std::size_t i = 0; i < g.size(); ++i)
            on[i] = !std::isnan(dem.data[i]) && s[i] >= o.min_slope && r[i] >= o.min_roughness &&
                    (inside_mask.empty() || inside_mask[i]);
        return on;
    };
    std::vector<char> rock = steep(slope, rough);
    // Closing over about 15 m (at least the 4 neighbours), specks dropped and gaps filled:
    // close_rock (extract/mask.hpp).
    const int closing = std::max(1, int(std::lround(kClosingRadiusM / dx)));
    close_rock(g, rock, dem.data, inside_mask, closing, cell_area, keep_area);
    // The edge on the terrain: within the reach of the wide window and of the closing, the
    // small window decides (follow_terrain_edge), then the same clean-up over one cell. At
    // least a cell either side (a one-cell window would trace the raster steps), so on a DEM
    // whose cells are too coarse for a window narrower than the wide one (about 8 m and
    // more) the edge stays where the wide window and the closing put it.
    const int fine_radius = std::max(1, int(std::lround(kEdgeWindowRadiusM / dx)));
    std::vector<float> fine_slope;
    const std::vector<float>* edge_slope = &slope;  // the slope the edge was drawn with (step 4 places it)
    if (o.terrain_edge && fine_radius < radius) {
        fine_slope = box_mean(g, res.terrain.slope.data, fine_radius);
        follow_terrain_edge(g, rock, steep(fine_slope, box_mean(g, res.terrain.roughness.data, fine_radius)), dem.data,
                            radius + closing);
        close_rock(g, rock, dem.data, inside_mask, 1, cell_area, keep_area);
        edge_slope = &fine_slope;
    }
    std::size_t rock_cells = 0;
    for (char v : rock) rock_cells += v;
    if (rock_cells == 0) {
        char buf[200];
        std::snprintf(buf, sizeof buf,
                      ": no rock: no area of at least %g mm2 at 1:%g has a slope >= %g %% and a roughness >= %g "
                      "(lower --min-slope / --min-roughness / --min-area)",
                      o.min_area_mm2, o.scale, o.min_slope, o.min_roughness);
        throw Error(Code::BadLayer, what + buf);
    }
    res.rock = dem;
    for (std::size_t i = 0; i < g.size(); ++i) res.rock.data[i] = std::isnan(dem.data[i]) ? NAN : float(rock[i]);

    // ---- 2. Thalwegs and ridges
    step(progress, 0.3, "thalwegs and ridges");
    Network net = find_network(g, dem, rock, inside_mask, o);
    res.network = std::move(net.lines);
    res.line_cells.assign(g.size(), 0);
    for (std::size_t i = 0; i < g.size(); ++i) res.line_cells[i] = net.ridge[i] ? 1 : (net.valley[i] ? 2 : 0);
    const std::vector<float>& z = net.z;
    const std::vector<char>& straight = net.straight;

    // ---- 3. Faces
    step(progress, 0.6, "faces");
    int nfaces = 0;
    std::vector<int> face = face_grid(g, rock, res.line_cells, cell_area, min_area, nfaces);
    res.faces = dem;
    for (std::size_t i = 0; i < g.size(); ++i) res.faces.data[i] = float(face[i]);

    // ---- 4. Polygons: shared, simplified borders
    step(progress, 0.75, "polygons");
    // Border pieces are labelled when they run along line cells for at least 40 m (3 cells).
    const int min_run = std::max(kMinRunCells, int(std::lround(kMinLabelRunM / dx)));
    // The steepest finishes of prolonged ridges split faces but follow no crest: the borders
    // along them are "other".
    std::vector<int> label_cells(res.line_cells);
    for (std::size_t i = 0; i < g.size(); ++i)
        if (straight[i]) label_cells[i] = 0;
    std::vector<Chain> chains = label_chains(trace_chains(g, face, label_cells), g.w + 1, min_run, o.label_outline);
    const BorderPlaces places{g, face, label_cells, *edge_slope, z, o.min_slope, window_offset(dem), &inside_mask};
    const Outlines outlines = face_outlines(chains, nfaces, places, dem, {o.simplify, o.smooth_rounds, min_area});
    if (!outlines.note.empty()) res.notes.push_back(outlines.note);

    // ---- 5. The partition, with orientation and density per face
    step(progress, 0.85, "orientation and density");
    Partition& p = res.partition;
    p.crs_wkt = dem.crs_wkt;
    for (int f = 0; f < nfaces; ++f)
        for (const auto& fp : outlines.faces[std::size_t(f)]) {
            RockFace rf;
            rf.id = f + 1;
            rf.region = tex::Region(fp.outer, fp.holes, "extracted face");
            p.faces.push_back(std::move(rf));
        }
    for (const Chain& c : chains) {
        LabelledLine l;
        l.kind = c.kind;
        for (const Point& q : c.shape()) l.points.push_back(whole_pixel_to_world(dem, q));
        p.lines.push_back(std::move(l));
        res.line_faces.push_back({c.right, c.left});
    }
    derive_face_controls(p, res.terrain);
    label_boundaries(p, kLabelSnapCells * dx);  // lines are the borders themselves
    std::size_t nridge = 0, nvalley = 0;
    for (const Chain& c : chains) {
        nridge += c.kind == LineKind::Ridge;
        nvalley += c.kind == LineKind::Valley;
    }
    res.notes.push_back("rock: " + std::to_string(rock_cells) + " cells (" +
                        std::to_string(int(std::round(double(rock_cells) * cell_area / 1e4))) + " ha), " +
                        std::to_string(p.faces.size()) + " faces, " + std::to_string(nridge) + " ridge and " +
                        std::to_string(nvalley) + " valley borders");
    p.notes = res.notes;
    step(progress, 1.0, "done");
    return res;
}

void check_extract_files(const ExtractOptions& o, const std::string& out, const std::string& png, bool overwrite) {
    check_outputs({{o.what, o.dem}, {"--mask", o.mask}}, {{"-o", out}, {"--png", png}}, overwrite);
}

}  // namespace carto
