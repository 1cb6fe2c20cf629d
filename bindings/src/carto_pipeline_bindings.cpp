// rockhatch.carto, the pipeline the rockhatch command runs: its options and plan, the
// stages (prepare, hatch, run), the crest ornaments, the writers of its outputs, and the
// tiled run.
#include "carto/crest.hpp"
#include "carto/output.hpp"
#include "carto/pipeline.hpp"
#include "carto/plan.hpp"
#include "carto/raster.hpp"
#include "carto/tiles.hpp"
#include "carto/update.hpp"
#include "carto_bindings.hpp"

namespace rhpy {

using namespace carto;

// The pipeline: Options, Stats, Prepared, the crest ornaments, Drawing, Plan, and the
// stages.
void add_pipeline_bindings(py::module_& m) {
    py::class_<Options>(m, "Options", "Everything the rockhatch command takes")
        .def(py::init<>())
        .def_readwrite("dem", &Options::dem)
        .def_readwrite("partition", &Options::partition)
        .def_readwrite("slope", &Options::slope)
        .def_readwrite("roughness", &Options::roughness)
        .def_readwrite("style", &Options::style)
        .def_readwrite("style_file", &Options::style_file, "the style script's path (an input: never written onto)")
        .def_property(
            "custom_style", [](const Options& o) { return std::const_pointer_cast<Style>(o.custom_style); },
            [](Options& o, std::shared_ptr<Style> s) { o.custom_style = std::move(s); })
        .def_readwrite("params", &Options::params)
        .def_readwrite("scale", &Options::scale)
        .def_readwrite("relief_radius", &Options::relief_radius)
        .def_readwrite("seed", &Options::seed)
        .def_readwrite("threads", &Options::threads)
        .def_readwrite("outputs", &Options::outputs)
        .def_readwrite("overwrite", &Options::overwrite)
        .def_readwrite("png_pixels", &Options::png_pixels)
        .def_readwrite("page", &Options::page, "page of a .pdf output: A0..A5 or WxH in mm ('' = the drawing's frame)")
        .def_readwrite("zoom", &Options::zoom, "zoom levels of a vector-tile output, 'Z1-Z2' ('' = 12-16)")
        .def_readwrite("spatial_index", &Options::spatial_index)
        .def_readwrite("window", &Options::window)
        .def_readwrite("mask", &Options::mask, "with partition 'auto': rock only inside this polygon layer")
        .def_readwrite("crest_ornament", &Options::crest_ornament,
                       "'default' (the project's exemplar) or an SVG file: draw the ridges as crest ornaments; None: no crests")
        .def_readwrite("crest_height_mm", &Options::crest_height_mm, "height of the crest band, mm on paper (None: 2)");
    py::class_<Stats>(m, "Stats")
        .def_readonly("faces", &Stats::faces)
        .def_readonly("hatches", &Stats::hatches)
        .def_readonly("seconds", &Stats::seconds)
        .def_readonly("crs", &Stats::crs)
        .def_readonly("notes", &Stats::notes)
        .def_readonly("crests", &Stats::crests, "ridge lines drawn with a crest ornament")
        .def_readonly("tiles", &Stats::tiles, "the vector-tile output's tiles (zero without one)")
        .def("__repr__", [](const Stats& s) {
            return "Stats(faces=" + std::to_string(s.faces) + ", hatches=" + std::to_string(s.hatches) + ")";
        });
    py::class_<Prepared>(m, "Prepared", "The inputs read and prepared: terrain in the working CRS and the partition")
        .def_property_readonly("terrain", [](const Prepared& p) { return share(p.terrain); })
        .def_readonly("partition", &Prepared::partition)
        .def_property_readonly("relief", [](const Prepared& p) { return std::make_shared<Raster>(p.relief); })
        .def_readonly("notes", &Prepared::notes);
    py::class_<FaceHatches>(m, "FaceHatches")
        .def_readonly("face_id", &FaceHatches::face_id)
        .def_readonly("hatches", &FaceHatches::hatches);
    py::class_<CrestOrnament>(m, "CrestOrnament", "One ridge's crest ornament: closed rings (outer counter-clockwise, holes clockwise)")
        .def_readonly("ridge", &CrestOrnament::ridge, "index of the ridge in Partition.lines")
        .def_readonly("id", &CrestOrnament::id,
                      "the ridge's key (ridge_key, from its points): the ridge_id written, the same in tiled and whole runs")
        .def_readonly("rings", &CrestOrnament::rings);
    py::class_<CrestResult>(m, "CrestResult")
        .def_readonly("ornaments", &CrestResult::ornaments)
        .def_readonly("notes", &CrestResult::notes);
    m.def("default_crest_svg", &default_crest_svg, "the project's crest exemplar as SVG text");
    m.def(
        "draw_crests",
        [](const Partition& p, const std::string& exemplar, double band_height, std::uint64_t seed,
           const std::optional<tex::BBox>& window) {
            const CrestExemplar ex = load_crest_exemplar(exemplar);
            py::gil_scoped_release release;
            return draw_crests(p, ex, band_height, seed, window);
        },
        py::arg("partition"), py::arg("exemplar") = std::string(kDefaultCrest), py::arg("band_height"),
        py::arg("seed") = 0, py::arg("window") = py::none(),
        R"(Crest ornaments of the partition's ridge lines.

Parameters
----------
partition : Partition
    Its lines labelled ridge are drawn.
exemplar : str
    'default' (the project's exemplar) or the path of an SVG file of polygons.
band_height : float
    Height of the band centred on each ridge, in ground units.
seed : int
    Each ridge's pattern is keyed by this seed and the ridge's own points.
window : BBox, optional
    Only the ridges whose anchor (the smaller of their two end points) lies in it,
    half-open (as the tiles of a tiled run own them).

Returns
-------
CrestResult
    One ornament per ridge drawn, and a note counting the ridges skipped (shorter than the
    band, or too tight for it).)");
    py::class_<Drawing>(m, "Drawing", "Hatches of every face, in the working CRS")
        .def_readonly("faces", &Drawing::faces)
        .def_readonly("crests", &Drawing::crests, "the crest ornaments, or None when not asked")
        .def_readonly("crs", &Drawing::crs_wkt)
        .def_readonly("style", &Drawing::style)
        .def_readonly("scale", &Drawing::scale)
        .def_readonly("bounds", &Drawing::bounds)
        .def("hatch_count", [](const Drawing& d) {
            std::size_t n = 0;
            for (const auto& f : d.faces) n += f.hatches.size();
            return n;
        });
    py::enum_<PlanFor>(m, "PlanFor").value("RUN", PlanFor::Run).value("DRAWING", PlanFor::Drawing);
    py::class_<Plan>(m, "Plan",
                     "The options of a run resolved once: the style, the rock style and their parameters in ground "
                     "units, the crest band, the outputs")
        .def_property_readonly("options", [](const Plan& p) { return p.options; })
        .def_property_readonly("style", [](const Plan& p) { return p.style.info; })
        .def_property_readonly("rock", [](const Plan& p) { return p.rock; })
        .def_readonly("rock_params", &Plan::rock_params)
        .def_readonly("terrain_params", &Plan::terrain_params)
        .def_readonly("crest_band", &Plan::crest_band, "ground units; None when the run draws no crest ornaments")
        .def_property_readonly("outputs", [](const Plan& p) {
            std::vector<std::string> out;
            for (const auto& o : p.outputs) out.push_back(o.path);
            return out;
        });
    m.def("make_plan", &make_plan, py::arg("options"), py::arg("use") = PlanFor::Run,
          "the run plan of the options, every option checked (RockhatchError naming the bad one); DRAWING: "
          "--dem, --partition and -o are not required");
    m.def(
        "prepare", [](const Options& o, const py::object& cb) { return prepare(o, to_progress(cb)); }, py::arg("options"),
        py::arg("progress") = py::none(), py::call_guard<py::gil_scoped_release>());
    m.def(
        "hatch", [](const Prepared& p, const Options& o, const py::object& cb) { return hatch(p, o, to_progress(cb)); },
        py::arg("prepared"), py::arg("options"), py::arg("progress") = py::none(),
        py::call_guard<py::gil_scoped_release>(), "hatches the faces (in parallel; Python styles take turns on the GIL)");
    m.def(
        "run", [](const Options& o, const py::object& cb) { return run(o, to_progress(cb)); }, py::arg("options"),
        py::arg("progress") = py::none(), py::call_guard<py::gil_scoped_release>(),
        "everything the rockhatch command does: make the plan, prepare, hatch, write");
    py::class_<UpdateReport>(m, "UpdateReport", "What rockhatch update redrew and rewrote")
        .def_readonly("faces", &UpdateReport::faces, "faces of the plan")
        .def_readonly("redrawn", &UpdateReport::redrawn, "faces drawn again (changed, new, asked for)")
        .def_readonly("appeared", &UpdateReport::appeared, "of which new")
        .def_readonly("removed", &UpdateReport::removed, "faces gone, their features removed")
        .def_readonly("deleted", &UpdateReport::deleted, "features removed")
        .def_readonly("written", &UpdateReport::written, "features written")
        .def_readonly("kept", &UpdateReport::kept, "features of redrawn faces drawn again as they were, left in place")
        .def_readonly("redrawn_ids", &UpdateReport::redrawn_ids)
        .def_readonly("removed_ids", &UpdateReport::removed_ids)
        .def_readonly("seconds", &UpdateReport::seconds)
        .def_readonly("crs", &UpdateReport::crs)
        .def_readonly("notes", &UpdateReport::notes);
    m.def(
        "update",
        [](const Options& o, bool reset, const std::vector<std::int64_t>& faces, const std::string& undo,
           const py::object& cb) { return update(o, UpdateOptions{reset, faces, undo}, to_progress(cb)); },
        py::arg("options"), py::arg("reset") = false, py::arg("faces") = std::vector<std::int64_t>{},
        py::arg("undo") = "", py::arg("progress") = py::none(), py::call_guard<py::gil_scoped_release>(),
        "rockhatch update: redraws the faces whose fingerprint changed (or `faces`, or every face with reset) "
        "in the options' GeoPackage output, in one transaction; with `undo`, what it replaces is written "
        "there first (restore_faces)");
    m.def(
        "restore_faces",
        [](const std::string& path, const std::string& undo) {
            FaceReplacement r;
            {
                const py::gil_scoped_release released;
                r = restore_faces(path, undo);
            }
            return py::make_tuple(r.deleted, r.written);
        },
        py::arg("path"), py::arg("undo"),
        "undoes the update that wrote `undo` (one transaction); returns (features removed, features written)");
    m.def(
        "read_fingerprints",
        [](const std::string& path) -> py::object {
            const auto fp = read_fingerprints(path, "hatches");
            if (!fp) return py::none();
            py::dict faces;
            for (const auto& [id, f] : fp->faces) faces[py::int_(id)] = f;
            return py::make_tuple(fp->run, faces);
        },
        py::arg("path"), "(run metadata, {face id: fingerprint}) a hatch GeoPackage keeps, or None");
}

// The outputs: the writers (GeoPackage, SVG, PNG), reading a drawing back, and the checks
// that an output overwrites no input.
void add_output_bindings(py::module_& m) {
    m.def(
        "write_gpkg",
        [](const Drawing& d, const std::string& path, bool spatial_index, const py::object& cb) {
            const Progress p = to_progress(cb);
            write_gpkg(d, path, spatial_index, [&p](double f) { return !p || p(f, "writing"); });
        },
        py::arg("drawing"), py::arg("path"), py::arg("spatial_index") = true, py::arg("progress") = py::none(),
        py::call_guard<py::gil_scoped_release>());
    m.def("write_svg", &write_svg, py::arg("drawing"), py::arg("path"), py::call_guard<py::gil_scoped_release>());
    m.def(
        "merge_gpkg",
        [](const std::vector<std::string>& parts, const std::string& path, bool spatial_index, const py::object& cb) {
            const Progress p = to_progress(cb);
            return merge_gpkg(parts, path, spatial_index, [&p](double f) { return !p || p(f, "merging"); });
        },
        py::arg("parts"), py::arg("path"), py::arg("spatial_index") = true, py::arg("progress") = py::none(),
        py::call_guard<py::gil_scoped_release>(),
        "merges hatch GeoPackages (tiles) into one, in order, features copied bit for bit; returns the hatch count");
    m.def("read_gpkg", &read_gpkg, py::arg("path"), py::arg("scale"), py::call_guard<py::gil_scoped_release>(),
          "a hatch GeoPackage read back as a Drawing");
    m.def(
        "write_png",
        [](const Drawing& d, const std::string& path, int pixels, const Raster* hillshade) {
            write_png(d, path, pixels, hillshade);
        },
        py::arg("drawing"), py::arg("path"), py::arg("pixels") = 1600, py::arg("hillshade") = nullptr,
        py::call_guard<py::gil_scoped_release>());
    m.def("write_pdf", [](const Drawing& d, const std::string& path, const std::string& page) {
              write_pdf(d, path, page.empty() ? std::nullopt : std::optional<PageSize>(parse_page(page)));
          },
          py::arg("drawing"), py::arg("path"), py::arg("page") = "", py::call_guard<py::gil_scoped_release>(),
          "a georeferenced PDF at true scale, one optional-content layer per family; page A0..A5 or WxH mm");
    py::class_<TileStats>(m, "TileStats")
        .def_readonly("tiles", &TileStats::tiles)
        .def_readonly("bytes", &TileStats::bytes)
        .def_readonly("largest", &TileStats::largest, "bytes of the largest tile")
        .def_property_readonly("largest_tile", [](const TileStats& s) {
            return py::make_tuple(s.largest_z, s.largest_x, s.largest_y);
        }, "(z, x, y) of the largest tile")
        .def_readonly("features", &TileStats::features)
        .def("__repr__", [](const TileStats& s) {
            return "TileStats(tiles=" + std::to_string(s.tiles) + ", bytes=" + std::to_string(s.bytes) +
                   ", largest=" + std::to_string(s.largest) + ")";
        });
    m.def(
        "write_vector_tiles",
        [](const std::vector<std::pair<int, std::string>>& zooms, const std::string& path, const std::string& name,
           const py::object& cb) {
            const Progress p = to_progress(cb);
            std::vector<ZoomDrawing> z;
            for (const auto& [zoom, gpkg] : zooms) z.push_back({zoom, gpkg});
            return write_vector_tiles(z, path, name, [&p](double f) { return !p || p(f, "writing tiles"); });
        },
        py::arg("zooms"), py::arg("path"), py::arg("name") = "rockhatch", py::arg("progress") = py::none(),
        py::call_guard<py::gil_scoped_release>(),
        "vector tiles (.mbtiles or a folder) from [(zoom, hatch GeoPackage drawn at zoom_scale(zoom))]");
    m.def("mbtiles_stats", &mbtiles_stats, py::arg("path"));
    m.def("zoom_scale", &zoom_scale, py::arg("zoom"), py::arg("latitude"),
          "the map scale of a web zoom level at a latitude (OGC's 0.28 mm pixel)");
    m.def("dem_latitude", &dem_latitude, py::arg("dem"), "latitude (WGS 84) of the DEM's centre");
    m.def("parse_zoom_range", [](const std::string& t) {
        const ZoomRange r = parse_zoom_range(t);
        return py::make_tuple(r.min, r.max);
    }, py::arg("text"));
    m.def("check_output", &check_output, py::arg("path"), py::arg("overwrite"), py::arg("what") = "-o");
    m.def(
        "check_outputs",
        [](const std::vector<std::pair<std::string, std::string>>& inputs,
           const std::vector<std::pair<std::string, std::string>>& outputs, bool overwrite) {
            auto args = [](const std::vector<std::pair<std::string, std::string>>& v) {
                std::vector<FileArg> out;
                for (const auto& [what, path] : v) out.push_back({what, path});
                return out;
            };
            check_outputs(args(inputs), args(outputs), overwrite);
        },
        py::arg("inputs"), py::arg("outputs"), py::arg("overwrite"),
        "inputs and outputs as (name, path) pairs: raises RockhatchError (code 9) when an output exists without "
        "overwrite, is one of the inputs or another output (however spelt: ./x, a/../x, links)");
    m.def("check_files", &check_files, py::arg("options"),
          "the outputs of a run against the files it reads (check_outputs); run does it first");
}

// The tiled run: a raster's grid, the working grid, its windows, the tiles.
void add_tile_bindings(py::module_& m) {
    py::class_<RasterInfo>(m, "RasterInfo", "A raster's grid and CRS, without its cells")
        .def_readonly("width", &RasterInfo::width)
        .def_readonly("height", &RasterInfo::height)
        .def_readonly("geotransform", &RasterInfo::gt)
        .def_readonly("crs", &RasterInfo::crs_wkt)
        .def("bounds", &RasterInfo::bounds);
    m.def("raster_info", &raster_info, py::arg("path"), py::arg("what") = "raster");
    py::class_<WorkingGrid>(m, "WorkingGrid",
                            "The grid a DEM is worked on: its own, or for a geographic DEM its UTM reprojection")
        .def_readonly("source", &WorkingGrid::source)
        .def_readonly("grid", &WorkingGrid::grid)
        .def_readonly("epsg", &WorkingGrid::epsg)
        .def_property_readonly("reprojected", &WorkingGrid::reprojected)
        .def_property_readonly("note", &WorkingGrid::note);
    m.def("working_grid", &working_grid, py::arg("dem"));
    m.def(
        "read_working_window",
        [](const std::string& path, const std::string& what, const WorkingGrid& g, const tex::BBox& box, int halo) {
            return std::make_shared<Raster>(read_working_window(path, what, g, box, halo));
        },
        py::arg("path"), py::arg("what"), py::arg("grid"), py::arg("box"), py::arg("halo") = 0,
        py::call_guard<py::gil_scoped_release>(),
        "the cells of the working grid a box touches (grown by `halo` cells), read from a raster on the DEM's grid");
    py::class_<TileReport>(m, "TileReport", "What one tile of a tiled run read and drew")
        .def_readonly("faces", &TileReport::faces)
        .def_readonly("context_faces", &TileReport::context_faces)
        .def_readonly("hatches", &TileReport::hatches)
        .def_readonly("dem_cells", &TileReport::dem_cells)
        .def_readonly("seconds", &TileReport::seconds);
    m.def("tile_grid", &tile_grid, py::arg("dem"), py::arg("size"),
          "square tiles of side `size` covering the DEM from its north-west corner, row by row (outer tiles reach "
          "beyond it)");
    m.def("tile_context_margin", &tile_context_margin, py::arg("plan"), py::arg("cell"),
          "how far (ground units) around a face the faces and lines its drawing reads reach (a tile's context, "
          "a face's fingerprint)");
    m.def("tile_halo_cells", &tile_halo_cells, py::arg("plan"), py::arg("cell"),
          "the DEM cells read around that margin (the relief radius or the style's reach)");
    m.def("check_tiled_rasters", &check_tiled_rasters, py::arg("options"),
          "refuses a --slope or --roughness raster a tile cannot read as the whole run does (another grid in "
          "another CRS than the DEM's working CRS)");
    m.def("run_tile", py::overload_cast<const Options&, const tex::BBox&, const std::string&>(&run_tile),
          py::arg("options"), py::arg("tile"), py::arg("out"),
          py::call_guard<py::gil_scoped_release>(),
          "hatches the faces whose anchor lies in the half-open box `tile` into the GeoPackage `out`");
}

}  // namespace rhpy
