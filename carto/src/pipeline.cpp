#include "carto/pipeline.hpp"

#include <algorithm>
#include <optional>
#include <chrono>
#include <cmath>
#include <atomic>
#include <filesystem>
#include <iomanip>
#include <sstream>
#include <mutex>

#include "carto/crest.hpp"
#include "carto/error.hpp"
#include "carto/extract.hpp"
#include "carto/publish.hpp"
#include "carto/update.hpp"
#include "temp_file.hpp"
#include "carto/control_fields.hpp"
#include "libtex/parallel.hpp"
#include "libtex/random.hpp"

namespace carto {
namespace {

bool tick(const Progress& p, double f, const std::string& stage) {
    if (p && !p(f, stage)) throw Error(Code::Cancelled, "cancelled during " + stage);
    return true;
}

}  // namespace

Raster load_dem(const std::string& path, std::vector<std::string>* notes) {
    std::string note;
    Raster dem = read_working_dem(path, "--dem", &note);
    if (dem.min_max().first != dem.min_max().first)
        throw Error(Code::BadLayer, "--dem '" + path + "': every cell is NoData");
    if (notes && !note.empty()) notes->push_back(note);
    return dem;
}

// The number of squares of the style's finest length (a "mm" parameter, in ground units)
// over the faces to hatch: beyond this, a scale or a parameter asks for more geometry than
// a machine holds, so the run is refused before it starts. The rock style's min_gap at
// 1:10000 makes about 1.3e6 squares of the sample and 3.8e7 of Chamonix.tif (386 MB at the
// peak with the whole drawing in memory, about 200 MB written to a GeoPackage alone); the limit lets Chamonix.tif be drawn at zoom 16 of a vector-tile output (1:5,940,
// 1.1e8) and refuses what would take several GB.
constexpr double kMaxFinestCells = 4e8;

void check_workload(const StyleInfo& info, const ParamValues& params, const Partition& part,
                    const std::vector<int>& selected, double scale) {
    const StyleParam* finest = nullptr;
    for (const auto& sp : info.params)
        if (sp.unit == "mm" && (!finest || params.at(sp.name) < params.at(finest->name))) finest = &sp;
    if (!finest) return;
    double area = 0;
    for (int i : selected) area += part.faces[std::size_t(i)].region.area();
    const double side = params.at(finest->name), cells = area / (side * side);
    if (cells <= kMaxFinestCells) return;
    std::ostringstream m;
    m << std::setprecision(3) << "--scale " << scale << " and --param " << finest->name << "=" << side * 1000 / scale
      << " mm (" << side << " on the ground): the faces (" << area << " square units) would hold about " << cells
      << " squares of that side, more than " << kMaxFinestCells << "; raise --scale or " << finest->name
      << ", or hatch a --window";
    throw Error(Code::Usage, m.str());
}

void check_roughness(const Raster& r, const std::string& path) {
    for (float v : r.data)
        if (!std::isnan(v) && (v < -1e-6 || v > 1 + 1e-6))
            throw Error(Code::BadLayer, "--roughness '" + path + "': values must lie in 0..1 (found " +
                                            std::to_string(v) + ")");
}

Prepared prepare(const Plan& plan, const Progress& progress) {
    const Options& o = plan.options;
    Prepared p;
    // The DEM and its fields, and the partition from its file, are read side by side (two
    // work items of parallel_for: in turn with one thread; an error of the DEM's item comes
    // first, as it did read first). The partition is read in the DEM's working CRS, which
    // the DEM's header gives.
    const bool partition_file = o.partition.path != "none" && o.partition.path != "auto";
    const WorkingGrid dem_grid = working_grid(raster_info(o.dem, "--dem"));
    std::vector<std::string> dem_notes;
    Raster dem;
    std::optional<FingerprintRasters> fingerprint_rasters;
    std::optional<Partition> digitised;  // the partition file as digitised, for the fingerprints
    tick(progress, 0.0, "reading the DEM");
    tex::parallel_for(partition_file ? 2 : 1, [&](std::size_t item) {
        if (item == 1) {
            p.partition = load_partition(o.partition, dem_grid.grid.crs_wkt);
            return;
        }
        dem = load_dem(o.dem, &dem_notes);
        p.terrain = compute_terrain(dem);
        auto load_like = [&](const std::string& path, const char* what, Raster& target) {
            // On the grid of a geographic DEM: reprojected as the DEM is (the cells a tiled run
            // reads too); on another grid: resampled onto the DEM's.
            const WorkingGrid& g = dem_grid;
            Raster r = g.reprojected() && same_grid(raster_info(path, what), g.source) ? read_working(path, what, g)
                                                                                       : read_raster(path, what);
            if (!same_crs(r.crs_wkt, dem.crs_wkt) || r.width != dem.width || r.height != dem.height || r.gt != dem.gt)
                r = resample_like(r, dem);
            target = std::move(r);
            if (std::none_of(target.data.begin(), target.data.end(), [](float v) { return std::isfinite(v); }))
                throw Error(Code::NoOverlap, std::string(what) + " '" + path + "' does not overlap --dem '" + o.dem + "'");
        };
        if (!o.slope.empty()) load_like(o.slope, "--slope", p.terrain.slope);
        if (!o.roughness.empty()) {
            load_like(o.roughness, "--roughness", p.terrain.roughness);
            check_roughness(p.terrain.roughness, o.roughness);
        }
        p.relief = local_relief(dem, o.relief_radius);
        if (keeps_fingerprints(plan)) {
            fingerprint_rasters = read_fingerprint_rasters(o, dem_grid);
            if (partition_file) digitised = read_digitised(o, dem_grid.grid.crs_wkt);
        }
    });
    p.notes = std::move(dem_notes);
    tick(progress, 0.15, "reading the partition");
    if (o.partition.path == "none") {
        // No rock at all: a terrain style draws the whole DEM (validate refuses it otherwise).
        p.partition.crs_wkt = dem.crs_wkt;
        return p;
    } else if (o.partition.path == "auto") {
        // No partition: extract one from the DEM (carto/extract.hpp) with its defaults.
        ExtractOptions eo;
        eo.raster = dem;
        eo.scale = o.scale;
        eo.what = "--dem '" + o.dem + "'";
        eo.mask = o.mask;
        p.partition = extract_partition(eo).partition;
    } else if (p.partition.crs_wkt != dem.crs_wkt) {
        p.partition = load_partition(o.partition, dem.crs_wkt);  // the header's CRS was not the grid's
    }
    for (const auto& n : p.partition.notes) p.notes.push_back(n);
    if (!p.partition.bounds().intersects(dem.bounds()))
        throw Error(Code::NoOverlap, "--partition '" + o.partition.path + "' does not overlap --dem '" + o.dem + "'");

    // Of the partition as read: what the faces' drawing depends on before the terrain fills in
    // their controls (the terrain's cells are in the fingerprint themselves).
    if (fingerprint_rasters) {
        // An extracted partition is fingerprinted as extracted.
        p.fingerprints = face_fingerprints(plan, digitised ? *digitised : p.partition, *fingerprint_rasters);
        set_drawn_boxes(*p.fingerprints, plan, p.partition);
    }
    resolve_face_controls(p, o.partition.path == "auto");
    return p;
}

void resolve_face_controls(Prepared& p, bool extracted) {
    // Resolve orientation and density of every face (neighbours need them too).
    // An extracted partition's orientations are its faces' mean fall lines (derived, not given).
    p.orientation_derived.clear();
    for (const auto& f : p.partition.faces) p.orientation_derived.push_back(extracted || !f.orientation);
    const auto [derived_o, derived_d] = derive_face_controls(p.partition, p.terrain);
    if (derived_o)
        p.notes.push_back("orientation of " + std::to_string(derived_o) + " face(s) derived from the terrain (mean fall line)");
    if (derived_d)
        p.notes.push_back("density of " + std::to_string(derived_d) + " face(s) derived from the terrain (1 - mean hillshade)");
}

Drawing hatch(const Prepared& p, const Plan& plan, const Progress& progress) {
    const std::optional<tex::BBox>& window = plan.options.window;
    std::vector<int> selected;
    for (std::size_t i = 0; i < p.partition.faces.size(); ++i)
        // Half-open window: a face whose anchor lies on the shared border of two windows goes
        // to one of them (the rule a tiled run uses, carto/tiles.hpp).
        if (!window || owns(*window, face_anchor(p.partition.faces[i]))) selected.push_back(int(i));
    return hatch(p, plan, selected, progress);
}

std::optional<tex::BBox> terrain_read_area(const Plan& plan, const tex::BBox& dem_extent, double cell) {
    const std::optional<tex::BBox>& window = plan.options.window;
    if (!plan.terrain_style() || !window) return std::nullopt;
    const tex::BBox w = window->intersection(dem_extent);
    if (!(w.xmin <= w.xmax && w.ymin <= w.ymax)) return tex::BBox{};
    return w.expanded(plan.style.terrain_reach(plan.terrain_params, cell));
}

ControlFields control_fields(const Prepared& p, const Plan& plan) {
    const Partition& part = p.partition;
    // Face-wise orientation and density (resolved for every face by prepare).
    std::vector<double> orient, dens;
    for (const auto& f : part.faces) {
        orient.push_back(*f.orientation);
        dens.push_back(*f.density);
    }
    // The local fall line, smoothed at map scale, where the partition gave no orientation.
    std::vector<double> follows;
    for (std::size_t i = 0; i < part.faces.size(); ++i)
        follows.push_back(i < p.orientation_derived.size() && p.orientation_derived[i] ? 1.0 : NAN);
    const Field fall_line =
        tex::Combine(face_field(part, std::move(follows)), fall_line_field(p.terrain, plan.field_smoothing),
                     [](double, double angle) { return angle; });
    return ControlFields{face_field(part, std::move(orient)),
                         face_field(part, std::move(dens)),
                         raster_field(p.relief),
                         raster_field(p.terrain.roughness),
                         raster_field(p.terrain.slope),
                         fall_line,
                         shade_field(p.terrain, plan.field_smoothing),
                         elevation_field(p.terrain, plan.field_smoothing / 4)};
}

namespace {

// The faces a run draws: the chosen ones, then, for a terrain style in a window, the faces
// around it whose hatches the terrain reads (drawn after the chosen ones, dropped once the
// terrain is drawn).
std::vector<int> faces_to_draw(const Prepared& p, const Plan& plan, const std::vector<int>& chosen) {
    std::vector<int> selected = chosen;
    const Partition& part = p.partition;
    const Raster& elevation = p.terrain.elevation;
    if (const auto around = terrain_read_area(plan, p.extent.empty() ? elevation.bounds() : p.extent,
                                              std::max(elevation.cell_x(), elevation.cell_y()))) {
        std::vector<char> taken(part.faces.size(), 0);
        for (int i : chosen) taken[std::size_t(i)] = 1;
        for (std::size_t i = 0; i < part.faces.size(); ++i)
            if (!taken[i] && !around->empty() && part.faces[i].region.bbox().intersects(*around)) selected.push_back(int(i));
    }
    return selected;
}

// Draws the faces `selected` of the partition one at a time, on any thread (the style's
// program is made once); counts them for the progress, which may cancel. Lives on the thread
// that runs the faces (its thread count is that thread's).
class FaceDrawer {
public:
    FaceDrawer(const Prepared& p, const Plan& plan, const std::vector<int>& selected, const Progress& progress)
        : p_(p), plan_(plan), selected_(selected), progress_(progress), threads_(plan.options.threads),
          program_([&] {
              // A style script may call SetSeed (the faces draw from o.seed, see hatch_face): the
              // process's seed and stream numbering come back after it.
              const tex::SavedSeed saved;
              ParamValues params = plan.rock_params;
              params[kDemCell] = std::max(p.terrain.elevation.cell_x(), p.terrain.elevation.cell_y());
              return plan.style.program(control_fields(p, plan), params);
          }()) {}
    std::size_t size() const { return selected_.size(); }
    bool serial() const { return plan_.style.serial; }
    // Face k of the selection; throws Error(Cancelled) once the progress said stop.
    FaceHatches draw(std::size_t k) {
        if (cancelled_) throw Error(Code::Cancelled, "cancelled during hatching");
        const RockFace& f = p_.partition.faces[std::size_t(selected_[k])];
        FaceHatches out;
        try {
            out = {f.id, hatch_face(program_, p_.partition, std::size_t(selected_[k]), plan_.options.seed)};
        } catch (const Error&) {
            throw;
        } catch (const std::exception& e) {
            throw Error(Code::Failure, "style '" + plan_.style.info.name + "', face " + std::to_string(f.id) + ": " + e.what());
        }
        if (progress_) {
            // Counted under the lock: the fractions reach the caller in increasing order
            // whichever thread finishes first.
            std::lock_guard lock(progress_mutex_);
            const std::size_t n = ++done_;
            if (!progress_(0.2 + 0.7 * double(n) / double(selected_.size()), "hatching")) cancelled_ = true;
        }
        return out;
    }
    bool cancelled() const { return cancelled_; }

private:
    const Prepared& p_;
    const Plan& plan_;
    const std::vector<int>& selected_;
    const Progress& progress_;
    // The run's thread count, on this thread only: the process's (tex::SetThreads) is left
    // as it was, and the next call does not inherit this one's.
    const tex::ThreadsScope threads_;
    const tex::Arrangement program_;
    std::mutex progress_mutex_;
    std::size_t done_ = 0;
    std::atomic<bool> cancelled_{false};
};

// The crest ornaments of the run, when it asks for them, into the drawing (and its frame).
void add_crests(Drawing& d, const Prepared& p, const Plan& plan, const Progress& progress) {
    if (!plan.crest_band) return;
    tick(progress, 0.9, "crest ornaments");
    CrestResult crests = draw_crests(p.partition, *plan.crest_exemplar, *plan.crest_band, plan.options.seed, plan.options.window);
    for (const auto& c : crests.ornaments)
        for (const auto& ring : c.rings)
            for (const Point& q : ring) d.bounds.add(q);
    d.crests = std::move(crests.ornaments);
    d.notes = std::move(crests.notes);
}

}  // namespace

Drawing hatch(const Prepared& p, const Plan& plan, const std::vector<int>& chosen, const Progress& progress) {
    const Options& o = plan.options;
    const Style& style = plan.style;
    const Partition& part = p.partition;
    const std::vector<int> selected = faces_to_draw(p, plan, chosen);
    check_workload(plan.rock, plan.rock_params, part, selected, o.scale);
    Drawing d;
    d.crs_wkt = part.crs_wkt;
    d.style = style.info.name;
    d.scale = o.scale;
    d.faces.resize(selected.size());
    {
        FaceDrawer drawer(p, plan, selected, progress);
        auto draw = [&](std::size_t k) {
            if (!drawer.cancelled()) d.faces[k] = drawer.draw(k);
        };
        if (drawer.serial()) {
            for (std::size_t k = 0; k < selected.size(); ++k) draw(k);
        } else {
            tex::parallel_for(selected.size(), draw);
        }
        if (drawer.cancelled()) throw Error(Code::Cancelled, "cancelled during hatching");
    }
    for (std::size_t k = 0; k < chosen.size(); ++k) d.bounds.add(part.faces[chosen[k]].region.bbox());
    add_crests(d, p, plan, progress);
    if (style.terrain) {
        tick(progress, 0.9, "drawing the terrain");
        std::vector<Hatch> rock;
        for (const auto& f : d.faces) rock.insert(rock.end(), f.hatches.begin(), f.hatches.end());
        d.faces.resize(chosen.size());  // the faces read around the window are not drawn
        try {
            d.faces.push_back({kTerrainFaceId,
                               style.terrain({p.terrain, part, rock, o.scale, o.seed, o.window}, plan.terrain_params)});
        } catch (const Error&) {
            throw;
        } catch (const std::exception& e) {
            throw Error(Code::Failure, "style '" + style.info.name + "': " + e.what());
        }
        // The terrain is framed by the DEM's extent, also in a tile of a tiled run (p.extent),
        // whose merged drawing then has the whole run's frame; a user's window by what it drew,
        // also in a tile (each element is drawn by one tile, so the tiles' frames together are
        // the whole run's).
        if (!o.window) d.bounds.add(p.terrain.elevation.bounds());
        else if (!p.extent.empty() && !p.user_window) d.bounds.add(p.extent);
        else
            for (const Hatch& h : d.faces.back().hatches)
                for (const Point& q : h.points) d.bounds.add(q);
    }
    return d;
}

namespace {

// The one GeoPackage a run writes while it draws (streamed: the faces are never all in
// memory), when its outputs are that file alone and its style draws no terrain (which reads
// every face's hatches); nullptr otherwise.
const Output* streamed_output(const Plan& plan) {
    if (plan.style.terrain) return nullptr;
    const Output* gpkg = nullptr;
    for (const Output& out : plan.outputs) {
        if (out.format == OutputFormat::VectorTiles) continue;
        if (out.format != OutputFormat::GeoPackage || gpkg) return nullptr;
        gpkg = &out;
    }
    return gpkg;
}

// hatch() and write_outputs() for a streamed GeoPackage: the same faces, crests, frame and
// file, each face's rows written as soon as the faces before it are. Fills the counts of `s`.
void hatch_and_write(const Prepared& p, const Plan& plan, const Output& out, const Progress& progress, Stats& s,
                     std::vector<std::string>& notes) {
    const Partition& part = p.partition;
    std::vector<int> chosen;
    for (std::size_t i = 0; i < part.faces.size(); ++i)
        if (!plan.options.window || owns(*plan.options.window, face_anchor(part.faces[i]))) chosen.push_back(int(i));
    check_workload(plan.rock, plan.rock_params, part, chosen, plan.options.scale);
    std::atomic<std::size_t> hatches{0};
    Drawing rest;
    rest.crs_wkt = part.crs_wkt;
    rest.style = plan.style.info.name;
    rest.scale = plan.options.scale;
    rest.fingerprints = p.fingerprints;
    {
        FaceDrawer drawer(p, plan, chosen, progress);
        const FaceStream faces{part.crs_wkt, plan.style.info.name, chosen.size(), drawer.serial(),
                               [&](std::size_t k, const std::function<void(const FaceHatches&)>& use) {
                                   const FaceHatches f = drawer.draw(k);
                                   hatches += f.hatches.size();
                                   use(f);
                               },
                               p.fingerprints.has_value()};
        write_gpkg(faces, [&]() -> const Drawing& {
            for (int i : chosen) rest.bounds.add(part.faces[std::size_t(i)].region.bbox());
            add_crests(rest, p, plan, progress);
            tick(progress, 0.92, "writing");
            return rest;
        }, out.path, plan.options.spatial_index, [&](double f) { return !progress || progress(0.92 + 0.07 * f, "writing"); });
    }
    s.faces = chosen.size();
    s.hatches = hatches;
    if (rest.crests) s.crests = rest.crests->size();
    notes = std::move(rest.notes);
    tick(progress, 1.0, "done");
}

}  // namespace

void write_outputs(const Drawing& d, const Prepared& p, const Plan& plan, const Progress& progress) {
    tick(progress, 0.92, "writing");
    for (const Output& out : plan.outputs) switch (out.format) {
            case OutputFormat::GeoPackage:
                write_gpkg(d, out.path, plan.options.spatial_index,
                           [&](double f) { return !progress || progress(0.92 + 0.07 * f, "writing"); });
                break;
            case OutputFormat::Svg: write_svg(d, out.path); break;
            case OutputFormat::Png: write_png(d, out.path, plan.options.png_pixels, &p.terrain.hillshade); break;
            case OutputFormat::Pdf: write_pdf(d, out.path, plan.page); break;
            case OutputFormat::VectorTiles: break;  // drawn per zoom level: write_zoom_tiles
        }
    tick(progress, 1.0, "done");
}

Plan zoom_plan(const Plan& plan, int zoom, double latitude) {
    Options o = plan.options;
    o.scale = zoom_scale(zoom, latitude);
    o.outputs.clear();
    o.page.clear();
    o.zoom.clear();
    return make_plan(o, PlanFor::Drawing);
}

TileStats write_zoom_tiles(const Plan& plan, const Progress& progress, Stats* counts) {
    std::vector<const Output*> outs;
    for (const Output& out : plan.outputs)
        if (out.format == OutputFormat::VectorTiles) outs.push_back(&out);
    if (outs.empty()) return {};
    const double latitude = dem_latitude(plan.options.dem);
    const int levels = plan.zoom.max - plan.zoom.min + 1;
    // Each level's drawing in a GeoPackage of its own next to the first output, removed at the end.
    std::vector<std::unique_ptr<TempFile>> files;
    std::vector<ZoomDrawing> zooms;
    for (int z = plan.zoom.min; z <= plan.zoom.max; ++z) {
        const int k = z - plan.zoom.min;
        const Progress part = [&](double f, const std::string& stage) {
            return !progress || progress(0.8 * (k + f) / levels, "zoom " + std::to_string(z) + ": " + stage);
        };
        const Plan pz = zoom_plan(plan, z, latitude);
        const Prepared p = prepare(pz, part);
        const Drawing d = hatch(p, pz, part);
        if (counts) {
            counts->faces = 0;  // the finest level's
            for (const auto& f : d.faces) {
                counts->hatches += f.hatches.size();
                counts->faces += f.face_id != kTerrainFaceId;
            }
        }
        files.push_back(std::make_unique<TempFile>(outs.front()->path.back() == '/'
                                                       ? outs.front()->path.substr(0, outs.front()->path.size() - 1)
                                                       : outs.front()->path,
                                                   ".z" + std::to_string(z) + ".gpkg"));
        write_gpkg(d, files.back()->path, false);
        zooms.push_back({z, files.back()->path});
    }
    TileStats stats;
    for (const Output* out : outs)
        stats = write_vector_tiles(zooms, out->path, std::filesystem::path(plan.options.dem).stem().string(),
                                   [&](double f) { return !progress || progress(0.8 + 0.2 * f, "writing tiles"); });
    return stats;
}

Stats run(const Plan& plan, const Progress& progress) {
    const auto t0 = std::chrono::steady_clock::now();
    // The run's thread count for every stage (reading, hatching, writing), on this thread
    // only: the process's is left as it was.
    const tex::ThreadsScope threads(plan.options.threads);
    Stats s;
    const bool drawing = std::any_of(plan.outputs.begin(), plan.outputs.end(),
                                     [](const Output& o) { return o.format != OutputFormat::VectorTiles; });
    if (!drawing) {
        // Vector tiles only: each zoom level is its own drawing.
        s.tiles = write_zoom_tiles(plan, progress, &s);
        s.crs = "EPSG:3857 (vector tiles)";
        s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        return s;
    }
    const Prepared p = prepare(plan, progress);
    // A PDF page too small for the faces is refused before they are hatched (the drawing's
    // frame is at least their extent; write_pdf checks the frame itself).
    if (!plan.options.window && !p.partition.faces.empty())
        for (const Output& out : plan.outputs)
            if (out.format == OutputFormat::Pdf) {
                tex::BBox faces;
                for (const auto& f : p.partition.faces) faces.add(f.region.bbox());
                page_layout(faces, plan.options.scale, plan.page, out.path);
            }
    std::vector<std::string> notes;
    if (const Output* gpkg = streamed_output(plan)) {
        hatch_and_write(p, plan, *gpkg, progress, s, notes);
    } else {
        Drawing d = hatch(p, plan, progress);
        d.fingerprints = p.fingerprints;
        write_outputs(d, p, plan, progress);
        s.faces = std::size_t(std::count_if(d.faces.begin(), d.faces.end(),
                                            [](const FaceHatches& f) { return f.face_id != kTerrainFaceId; }));
        for (const auto& f : d.faces) s.hatches += f.hatches.size();
        if (d.crests) s.crests = d.crests->size();
        notes = std::move(d.notes);
    }
    s.tiles = write_zoom_tiles(plan, progress, nullptr);
    s.crs = crs_name(p.partition.crs_wkt);
    s.notes = p.notes;
    s.notes.insert(s.notes.end(), notes.begin(), notes.end());
    s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return s;
}

Prepared prepare(const Options& o, const Progress& progress) {
    return prepare(make_plan(o, PlanFor::Drawing), progress);
}

Drawing hatch(const Prepared& p, const Options& o, const Progress& progress) {
    return hatch(p, make_plan(o, PlanFor::Drawing), progress);
}

Stats run(const Options& o, const Progress& progress) {
    const auto t0 = std::chrono::steady_clock::now();
    Stats s = run(make_plan(o), progress);
    s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return s;
}

}  // namespace carto
