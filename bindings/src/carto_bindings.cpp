// rockhatch.carto: rasters as numpy arrays, control fields, the partition, the hatching
// building blocks and styles, and the pipeline the rockhatch command runs.
#include <cmath>
#include <cstring>

#include "carto/cli.hpp"
#include "carto/error.hpp"
#include "carto/extract.hpp"
#include "carto/fields.hpp"
#include "carto/output.hpp"
#include "carto/partition.hpp"
#include "carto/pipeline.hpp"
#include "carto/raster.hpp"
#include "carto/terrain.hpp"
#include "carto/tiles.hpp"
#include "common.hpp"

namespace rhpy {
namespace {

using namespace carto;
using RasterPtr = std::shared_ptr<Raster>;

// The terrain rasters, each shared with Python (fields built on them keep them alive).
struct PyTerrain {
    RasterPtr elevation, slope, aspect, roughness, hillshade;
};

PyTerrain share(Terrain t) {
    auto own = [](Raster& r) { return std::make_shared<Raster>(std::move(r)); };
    return {own(t.elevation), own(t.slope), own(t.aspect), own(t.roughness), own(t.hillshade)};
}

// A face as a style sees it: its geometry and labels, and the ids of its neighbours.
std::string wkt_of(const std::string& crs) {
    if (crs.rfind("EPSG:", 0) == 0 || crs.rfind("epsg:", 0) == 0) return epsg_wkt(std::stoi(crs.substr(5)));
    return crs;
}

RasterPtr raster_from_array(const py::array_t<double, py::array::c_style | py::array::forcecast>& a,
                            const std::vector<double>& gt, const std::string& crs, std::optional<double> nodata) {
    if (a.ndim() != 2) throw py::value_error("Raster.from_array: a 2-D array is needed, got " + std::to_string(a.ndim()) + "-D");
    if (gt.size() != 6) throw py::value_error("Raster.from_array: the geotransform needs 6 numbers");
    auto r = std::make_shared<Raster>();
    r->height = int(a.shape(0));
    r->width = int(a.shape(1));
    if (r->width < 1 || r->height < 1) throw py::value_error("Raster.from_array: the array is empty");
    std::copy(gt.begin(), gt.end(), r->gt.begin());
    if (gt[1] == 0 || gt[5] == 0) throw py::value_error("Raster.from_array: the geotransform has a zero cell size");
    r->crs_wkt = wkt_of(crs);
    r->data.resize(std::size_t(r->width) * r->height);
    const double* src = a.data();
    for (std::size_t i = 0; i < r->data.size(); ++i) {
        const double v = src[i];
        r->data[i] = (nodata && v == *nodata) || !std::isfinite(v) ? NAN : float(v);
    }
    return r;
}

// Called with or without the GIL (inside bindings that release it): takes it to keep a
// reference to the callback.
Progress to_progress(const py::object& cb) {
    if (cb.is_none()) return {};
    py::gil_scoped_acquire gil;
    PyRef ref(cb);
    return [ref](double f, const std::string& stage) {
        py::gil_scoped_acquire gil;
        py::object r = ref.get()(f, stage);
        return r.is_none() || r.cast<bool>();
    };
}

// A Python style: fn(fields, params) returns the arrangement drawn in each face (a program
// of libtex operators whose mappers may be Python functions). Faces are drawn on the
// engine's threads: every evaluation of an arrangement releases the interpreter's lock, so
// the native operators of one face (partitions, crops, stock mappers) run while another
// face's Python mapper holds it. `serial` draws them one after the other instead (a style
// whose time goes into Python code, see Style::serial). The drawing is the same either way.
std::shared_ptr<const Style> python_style(StyleInfo info, py::object fn, bool serial) {
    auto s = std::make_shared<Style>();
    s->info = std::move(info);
    s->serial = serial;
    PyRef ref(std::move(fn));
    const std::string name = s->info.name;
    s->program = [ref, name](const ControlFields& fields, const ParamValues& params) -> tex::Arrangement {
        py::gil_scoped_acquire gil;
        py::dict p;
        for (const auto& [k, v] : params) p[py::str(k)] = v;
        py::object a = ref.get()(fields, p);
        if (!py::isinstance<tex::Arrangement>(a))
            throw py::type_error("style '" + name + "': it returned " + type_name(a) +
                                 "; a style returns the arrangement drawn in each face (an Arrangement)");
        return a.cast<tex::Arrangement>();
    };
    return s;
}

}  // namespace

void bind_carto(py::module_& m) {
    // ---- Rasters ----
    py::class_<Raster, RasterPtr>(m, "Raster",
                                  "A single-band grid: float values with NaN for NoData, a GDAL geotransform and a CRS")
        .def_static("from_array", &raster_from_array, py::arg("array"), py::arg("geotransform"), py::arg("crs") = "",
                    py::arg("nodata") = py::none(),
                    "a raster from a 2-D array (row 0 at the top for a north-up geotransform); cells equal to "
                    "nodata, and non-finite cells, become NoData (NaN); crs is WKT or 'EPSG:n'")
        .def_readonly("width", &Raster::width)
        .def_readonly("height", &Raster::height)
        .def_property_readonly("geotransform", [](const Raster& r) { return std::vector<double>(r.gt.begin(), r.gt.end()); })
        .def_readonly("crs", &Raster::crs_wkt, "WKT ('' when the raster has none)")
        .def_property_readonly("crs_name", [](const Raster& r) { return r.crs_wkt.empty() ? "" : crs_name(r.crs_wkt); })
        .def_property_readonly("nodata", [](const Raster&) { return NAN; }, "NoData cells are NaN in the array")
        .def_property_readonly(
            "array",
            [](const RasterPtr& r) {
                return py::array_t<float>({r->height, r->width},
                                          {ssize_t(r->width * sizeof(float)), ssize_t(sizeof(float))}, r->data.data(),
                                          py::cast(r));
            },
            "the values as a float32 (height, width) array sharing the raster's memory; NaN = NoData")
        .def(
            "to_array",
            [](const Raster& r, std::optional<double> nodata) {
                py::array_t<double> a({r.height, r.width});
                double* dst = a.mutable_data();
                for (std::size_t i = 0; i < r.data.size(); ++i)
                    dst[i] = std::isnan(r.data[i]) && nodata ? *nodata : double(r.data[i]);
                return a;
            },
            py::arg("nodata") = py::none(), "a float64 copy, NoData as NaN or as the given value")
        .def("bounds", &Raster::bounds)
        .def("sample", &Raster::sample, "bilinear value at a world point (NaN outside or NoData)")
        .def("nearest", &Raster::nearest)
        .def("to_world", &Raster::to_world, py::arg("col"), py::arg("row"))
        .def("min_max", &Raster::min_max)
        .def("cell_size", [](const Raster& r) { return py::make_tuple(r.cell_x(), r.cell_y()); });
    m.def(
        "read_raster", [](const std::string& path, const std::string& what) { return std::make_shared<Raster>(read_raster(path, what)); },
        py::arg("path"), py::arg("what") = "raster", py::call_guard<py::gil_scoped_release>());
    m.def(
        "load_dem",
        [](const std::string& path) {
            std::vector<std::string> notes;
            auto r = std::make_shared<Raster>(load_dem(path, &notes));
            return py::make_tuple(r, notes);
        },
        py::arg("path"), "the DEM as the pipeline reads it (geographic DEMs reprojected to UTM): (raster, notes)");
    m.def("write_geotiff", &write_geotiff, py::arg("raster"), py::arg("path"), py::arg("nodata") = -9999.0,
          py::call_guard<py::gil_scoped_release>());
    m.def(
        "warp", [](const Raster& r, const std::string& crs) { return std::make_shared<Raster>(warp(r, wkt_of(crs))); },
        py::arg("raster"), py::arg("crs"), py::call_guard<py::gil_scoped_release>());
    m.def(
        "resample_like", [](const Raster& r, const Raster& like) { return std::make_shared<Raster>(resample_like(r, like)); },
        py::arg("raster"), py::arg("like"), py::call_guard<py::gil_scoped_release>());
    m.def("is_geographic", &is_geographic);
    m.def("epsg_wkt", &epsg_wkt);
    m.def("crs_name", &crs_name);
    m.def("same_crs", &same_crs);
    m.def("utm_epsg", &utm_epsg, py::arg("lon"), py::arg("lat"));

    py::class_<PyTerrain>(m, "Terrain", "Terrain fields of a DEM (Horn's gradient)")
        .def_readonly("elevation", &PyTerrain::elevation, "metres")
        .def_readonly("slope", &PyTerrain::slope, "percent (100 x tan)")
        .def_readonly("aspect", &PyTerrain::aspect, "downhill direction, radians, math angle")
        .def_readonly("roughness", &PyTerrain::roughness, "0..1, vector ruggedness")
        .def_readonly("hillshade", &PyTerrain::hillshade, "0..1, lit from the north-west");
    m.def(
        "compute_terrain", [](const Raster& dem) { return share(compute_terrain(dem)); }, py::arg("dem"),
        py::call_guard<py::gil_scoped_release>(), "slope, aspect, roughness and hillshade of a DEM in a projected CRS");

    // ---- Control fields (seed 5.3): rockhatch.tex.Field, with raster constructors ----
    add_field_converter([](const py::object& o) -> std::optional<Field> {
        if (!py::isinstance<Raster>(o)) return std::nullopt;
        return raster_field(std::const_pointer_cast<const Raster>(o.cast<RasterPtr>()));
    });
    auto field = py::reinterpret_borrow<py::class_<Field>>(py::type::of<Field>());
    field
        .def_static(
            "from_raster",
            [](const RasterPtr& r, double offset, double range) { return raster_field(RasterPtr(r), offset, range); },
            py::arg("raster"), py::arg("offset") = 0.0, py::arg("range") = 1.0,
            "bilinear, NoData-aware: (value - offset) / range")
        .def_static(
            "from_array",
            [](const py::array_t<double, py::array::c_style | py::array::forcecast>& a, const std::vector<double>& gt,
               const std::string& crs, std::optional<double> nodata) {
                return raster_field(raster_from_array(a, gt, crs, nodata));
            },
            py::arg("array"), py::arg("geotransform"), py::arg("crs") = "", py::arg("nodata") = py::none());
    m.attr("Field") = field;
    py::implicitly_convertible<Raster, Field>();

    py::class_<ControlFields>(m, "ControlFields", "The control fields a style is applied to")
        .def(py::init([](const py::object& o, const py::object& d, const py::object& h, const py::object& r,
                         const py::object& sl, const py::object& fl, const py::object& sh) {
                 return ControlFields{to_field(o),  to_field(d), to_field(h), to_field(r),
                                      to_field(sl), to_field(fl), to_field(sh)};
             }),
             py::arg("orientation"), py::arg("density"), py::arg("height"), py::arg("roughness"),
             py::arg("slope") = py::float_(std::nan("")), py::arg("fall_line") = py::float_(std::nan("")),
             py::arg("shade") = py::float_(std::nan("")))
        .def_property(
            "orientation", [](const ControlFields& c) { return c.orientation; },
            [](ControlFields& c, const py::object& o) { c.orientation = to_field(o); }, "hatch direction (radians)")
        .def_property(
            "density", [](const ControlFields& c) { return c.density; },
            [](ControlFields& c, const py::object& o) { c.density = to_field(o); }, "0..1, 1 = darkest")
        .def_property(
            "height", [](const ControlFields& c) { return c.height; },
            [](ControlFields& c, const py::object& o) { c.height = to_field(o); }, "0..1 normalised elevation")
        .def_property(
            "roughness", [](const ControlFields& c) { return c.roughness; },
            [](ControlFields& c, const py::object& o) { c.roughness = to_field(o); }, "0..1")
        .def_property(
            "slope", [](const ControlFields& c) { return c.slope; },
            [](ControlFields& c, const py::object& o) { c.slope = to_field(o); }, "percent")
        .def_property(
            "fall_line", [](const ControlFields& c) { return c.fall_line; },
            [](ControlFields& c, const py::object& o) { c.fall_line = to_field(o); },
            "the fall line smoothed at map scale (radians, axial); NaN where the partition gives the orientation")
        .def_property(
            "shade", [](const ControlFields& c) { return c.shade; },
            [](ControlFields& c, const py::object& o) { c.shade = to_field(o); },
            "1 - hillshade smoothed at map scale (0 lit, 1 in shade)");

    // ---- Partition ----
    py::enum_<LineKind>(m, "LineKind")
        .value("OTHER", LineKind::Other)
        .value("RIDGE", LineKind::Ridge)
        .value("VALLEY", LineKind::Valley);
    py::class_<BoundarySegment>(m, "BoundarySegment", "A segment of a face's border, its label and the face across it")
        .def_readonly("a", &BoundarySegment::a)
        .def_readonly("b", &BoundarySegment::b)
        .def_readonly("kind", &BoundarySegment::kind)
        .def_readonly("neighbor", &BoundarySegment::neighbor, "index of the face across (-1: none)");
    py::class_<RockFace>(m, "RockFace", "A face of the partition of rock areas")
        .def_readonly("id", &RockFace::id)
        .def_readonly("region", &RockFace::region)
        .def_readonly("boundary", &RockFace::boundary)
        .def_readonly("orientation", &RockFace::orientation, "hatch direction (radians) or None")
        .def_readonly("density", &RockFace::density, "0..1 or None");
    py::class_<LabelledLine>(m, "LabelledLine")
        .def_readonly("points", &LabelledLine::points)
        .def_readonly("kind", &LabelledLine::kind);
    py::class_<Partition>(m, "Partition", "Faces to hatch separately and their labelled ridge / valley lines")
        .def_readonly("faces", &Partition::faces)
        .def_readonly("lines", &Partition::lines)
        .def_readonly("crs", &Partition::crs_wkt)
        .def_readonly("notes", &Partition::notes)
        .def("bounds", &Partition::bounds);
    py::class_<PartitionOptions>(m, "PartitionOptions", "Where the partition's faces, labels and attributes are")
        .def(py::init<>())
        .def_readwrite("path", &PartitionOptions::path)
        .def_readwrite("faces_layer", &PartitionOptions::faces_layer)
        .def_readwrite("lines_layer", &PartitionOptions::lines_layer)
        .def_readwrite("label_field", &PartitionOptions::label_field)
        .def_readwrite("id_field", &PartitionOptions::id_field)
        .def_readwrite("orientation_field", &PartitionOptions::orientation_field)
        .def_readwrite("orientation_layer", &PartitionOptions::orientation_layer)
        .def_readwrite("density_field", &PartitionOptions::density_field)
        .def_readwrite("density_layer", &PartitionOptions::density_layer)
        .def_readwrite("scree_layer", &PartitionOptions::scree_layer)
        .def_readwrite("repair", &PartitionOptions::repair)
        .def_readwrite("snap", &PartitionOptions::snap)
        .def_readwrite("filter", &PartitionOptions::filter, "read only the features meeting this box (working CRS)");
    m.def(
        "load_partition",
        [](const PartitionOptions& o, const std::string& crs) { return load_partition(o, wkt_of(crs)); },
        py::arg("options"), py::arg("working_crs"), py::call_guard<py::gil_scoped_release>(),
        "reads and reprojects a partition to the working CRS (WKT or 'EPSG:n')");
    m.def(
        "face_field",
        [](const Partition& p, std::vector<double> values) {
            if (values.size() != p.faces.size())
                throw py::value_error("face_field: " + std::to_string(values.size()) + " values for " +
                                      std::to_string(p.faces.size()) + " faces");
            return face_field(p, std::move(values));
        },
        py::arg("partition"), py::arg("values"), "value i on face i, NaN outside the faces");
    m.def("interior_point", py::overload_cast<const tex::Region&>(&interior_point), py::arg("region"));

    m.def("face_region", &face_region, py::arg("partition"), py::arg("face"),
          "the region a style draws face i in: its rings, its border as edges labelled ridge / valley / other "
          "(and owned where this face draws what lies on a shared border)");

    // ---- Hatches and their building blocks ----
    py::enum_<Family>(m, "Family")
        .value("FILL", Family::Fill)
        .value("RIDGE", Family::Ridge)
        .value("VALLEY", Family::Valley)
        .value("CROSS", Family::Cross)
        .value("STONE", Family::Stone)
        .value("HACHURE", Family::Hachure);
    m.def("family_width_mm", &family_width_mm, py::arg("family"), "stroke width of a hatch family, mm on paper");
    py::class_<Hatch>(m, "Hatch", "One stroke (or closed shape) of a hatch family")
        .def(py::init([](std::vector<Point> pts, bool closed, Family f) { return Hatch{std::move(pts), closed, f}; }),
             py::arg("points"), py::arg("closed") = false, py::arg("family") = Family::Fill)
        .def("__repr__", [](const Hatch& h) {
            return std::string("Hatch(") + family_name(h.family) + ", " + std::to_string(h.points.size()) + " points" +
                   (h.closed ? ", closed)" : ")");
        })
        .def_readwrite("points", &Hatch::points)
        .def_readwrite("closed", &Hatch::closed)
        .def_readwrite("family", &Hatch::family)
        .def("__eq__", [](const Hatch& a, const Hatch& b) {
            return a.points == b.points && a.closed == b.closed && a.family == b.family;
        });
    py::bind_vector<std::vector<Hatch>>(m, "Hatches", "A list of hatches kept as a C++ vector")
        .def(
            "add_lines",
            [](std::vector<Hatch>& out, std::vector<std::vector<Point>>& lines, Family f) {
                for (auto& l : lines) out.push_back({std::move(l), false, f});
            },
            py::arg("lines"), py::arg("family"), "appends every line as an open hatch (the lines are moved)");

    m.def(
        "ink_area",
        [](const tex::Curves& c, double ground_per_mm, const std::optional<tex::Region>& within) {
            return ink_area(c, ground_per_mm, within ? &*within : nullptr);
        },
        py::arg("curves"), py::arg("ground_per_mm"), py::arg("within") = py::none(),
        "ink on the ground: length x family stroke width (mm x ground_per_mm) of the curves, or of their segments "
        "whose middle lies in `within`");
    m.def("area_within", &area_within, py::arg("face"), py::arg("cell"),
          "area of the face (less its holes) inside the cell, whose outer ring is taken as convex");
    m.def("hatches_from_curves", &hatches_from_curves, py::arg("curves"),
          "libtex curves (an evaluated style) as hatches, their family read from their labels");

    // ---- Styles ----
    py::class_<StyleParam>(m, "StyleParam")
        .def(py::init([](std::string n, double v, std::string u, std::string h) { return StyleParam{n, v, u, h}; }),
             py::arg("name"), py::arg("value"), py::arg("unit"), py::arg("help") = "")
        .def_readonly("name", &StyleParam::name)
        .def_readonly("value", &StyleParam::value)
        .def_readonly("unit", &StyleParam::unit)
        .def_readonly("help", &StyleParam::help);
    py::class_<StyleInfo>(m, "StyleInfo")
        .def(py::init([](std::string n, std::string f, std::string t, std::vector<StyleParam> p, bool crest) {
                 StyleInfo s{n, f, t, p};
                 s.crest_ornament = crest;
                 return s;
             }),
             py::arg("name"), py::arg("figure") = "", py::arg("title") = "", py::arg("params") = std::vector<StyleParam>{},
             py::arg("crest_ornament") = false)
        .def_readonly("name", &StyleInfo::name)
        .def_readonly("figure", &StyleInfo::figure)
        .def_readonly("title", &StyleInfo::title)
        .def_readonly("params", &StyleInfo::params)
        .def_readonly("terrain", &StyleInfo::terrain,
                      "True for a terrain style (scree, slope-hachures): it draws around the rock faces, over "
                      "the whole DEM, after the faces are hatched with the default rock style.")
        .def_readonly("crest_ornament", &StyleInfo::crest_ornament,
                      "True when the style draws every ridge line as a crest ornament, its band from its "
                      "parameter crest_band (a script sets CREST_ORNAMENT = True)");
    m.def("styles", &styles, "the built-in styles: Fig. 5.4 (a) to (g), print (the default), aretes, then the terrain styles");
    m.def("default_style", &default_style);
    m.def("find_style", &find_style, py::arg("name"));
    m.def("resolve_params", &resolve_params, py::arg("style"), py::arg("overrides"), py::arg("scale"),
          "parameters in ground units ('mm' x scale / 1000, 'deg' to radians), plus ground_per_mm");
    m.def(
        "hatch_face",
        [](const Style& s, const ParamValues& p, const ControlFields& f, const Partition& part, std::size_t face,
           std::uint64_t seed) {
            if (face >= part.faces.size()) throw py::index_error("hatch_face: no face " + std::to_string(face));
            const tex::Arrangement a = s.program(f, p);
            py::gil_scoped_release release;  // a Python mapper takes the lock back itself
            return hatch_face(a, part, face, seed);
        },
        py::arg("style"), py::arg("params"), py::arg("fields"), py::arg("partition"), py::arg("face"),
        py::arg("seed") = 0, "the hatches of face i of the partition drawn by a style");
    py::class_<Style, std::shared_ptr<Style>>(m, "Style", "A style: its description and its controlled arrangement")
        .def_property_readonly("info", [](const Style& s) { return s.info; })
        .def_property_readonly("name", [](const Style& s) { return s.info.name; });
    m.def(
        "python_style",
        [](const StyleInfo& info, py::object fn, bool serial) {
            return std::const_pointer_cast<Style>(python_style(info, std::move(fn), serial));
        },
        py::arg("info"), py::arg("fn"), py::arg("serial") = false,
        "a style from fn(fields, params) -> Arrangement drawn in each face; params are in ground units. Faces are "
        "drawn on the engine's threads (native operators release the interpreter's lock); serial=True draws them "
        "one after the other, for a style whose time goes into Python mappers. The drawing is the same.");
    m.def("builtin_style", [](const std::string& n) { return std::make_shared<Style>(builtin_style(n)); });

    // ---- Pipeline ----
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
        .def_readwrite("spatial_index", &Options::spatial_index)
        .def_readwrite("window", &Options::window)
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
    m.def("check_tiled_rasters", &check_tiled_rasters, py::arg("options"),
          "refuses a --slope or --roughness raster a tile cannot read as the whole run does (another grid in "
          "another CRS than the DEM's working CRS)");
    m.def("run_tile", py::overload_cast<const Options&, const tex::BBox&, const std::string&>(&run_tile),
          py::arg("options"), py::arg("tile"), py::arg("out"),
          py::call_guard<py::gil_scoped_release>(),
          "hatches the faces whose anchor lies in the half-open box `tile` into the GeoPackage `out`");
    m.def(
        "write_png",
        [](const Drawing& d, const std::string& path, int pixels, const Raster* hillshade) {
            write_png(d, path, pixels, hillshade);
        },
        py::arg("drawing"), py::arg("path"), py::arg("pixels") = 1600, py::arg("hillshade") = nullptr,
        py::call_guard<py::gil_scoped_release>());
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

    // ---- The partition from the DEM alone ----
    py::class_<ExtractOptions>(m, "ExtractOptions", "Options of rockhatch partition (see its --help for units)")
        .def(py::init<>())
        .def_readwrite("dem", &ExtractOptions::dem)
        .def_property(
            "raster", [](const ExtractOptions& o) { return o.raster ? std::make_shared<Raster>(*o.raster) : nullptr; },
            [](ExtractOptions& o, const RasterPtr& r) {
                if (r) o.raster = *r;
                else o.raster.reset();
            },
            "an in-memory DEM used instead of the dem path")
        .def_readwrite("mask", &ExtractOptions::mask)
        .def_readwrite("min_slope", &ExtractOptions::min_slope, "percent")
        .def_readwrite("min_roughness", &ExtractOptions::min_roughness, "vector ruggedness 0..1")
        .def_readwrite("min_area_mm2", &ExtractOptions::min_area_mm2, "mm2 on paper at the scale")
        .def_readwrite("scale", &ExtractOptions::scale)
        .def_readwrite("thalweg_area", &ExtractOptions::thalweg_area, "m2")
        .def_readwrite("ridge_area", &ExtractOptions::ridge_area, "m2")
        .def_readwrite("smooth", &ExtractOptions::smooth, "m")
        .def_readwrite("converge", &ExtractOptions::converge)
        .def_readwrite("extend_ridges", &ExtractOptions::extend_ridges)
        .def_readwrite("max_fill", &ExtractOptions::max_fill, "m")
        .def_readwrite("simplify", &ExtractOptions::simplify, "cells")
        .def_readwrite("label_outline", &ExtractOptions::label_outline,
                       "label the rock outline ridge / valley where it runs along a line")
        .def_readwrite("what", &ExtractOptions::what);
    py::class_<ExtractResult>(m, "ExtractResult", "An extracted partition, its rock mask and terrain")
        .def_readonly("partition", &ExtractResult::partition)
        .def_property_readonly("terrain", [](const ExtractResult& r) { return share(r.terrain); })
        .def_property_readonly("rock", [](const ExtractResult& r) { return std::make_shared<Raster>(r.rock); },
                               "1 rock, 0 not, NaN NoData, on the working grid")
        .def_property_readonly("faces", [](const ExtractResult& r) { return std::make_shared<Raster>(r.faces); },
                               "face index per cell (-1 outside)")
        .def_readonly("network", &ExtractResult::network, "all traced ridges and thalwegs in the rock")
        .def_readonly("notes", &ExtractResult::notes);
    m.def(
        "extract_option_names",
        [] {
            std::vector<std::pair<std::string, bool>> out;
            for (const auto& e : extract_option_names()) out.emplace_back(e.name, e.takes_value);
            return out;
        },
        "(name, takes a value) of the extraction's tuning options, as rockhatch partition spells them");
    m.def("check_extract_options", &check_extract_options, py::arg("options"),
          "the ranges of the tuning options (RockhatchError, code 2); extract_partition checks them first");
    m.def("set_extract_option", &set_extract_option, py::arg("options"), py::arg("name"), py::arg("value") = "",
          "sets one tuning option from its command-line value; False when `name` is not one");
    m.def(
        "extract_partition",
        [](const ExtractOptions& o, const py::object& cb) { return extract_partition(o, to_progress(cb)); },
        py::arg("options"), py::arg("progress") = py::none(), py::call_guard<py::gil_scoped_release>(),
        "the partition of the rock areas from the DEM alone (rockhatch partition)");
    m.def(
        "write_partition_gpkg",
        [](const Partition& p, const std::string& path, bool overwrite, const std::vector<LabelledLine>* network,
           bool fixed_controls) { write_partition_gpkg(p, path, overwrite, network, fixed_controls); },
        py::arg("partition"), py::arg("path"), py::arg("overwrite") = false, py::arg("network") = nullptr,
        py::arg("fixed_controls") = false, py::call_guard<py::gil_scoped_release>(),
        "layers faces, lines, mask (and network), as rockhatch reads them; the faces' fall line and shade as "
        "attributes fall_line and shade (derived: hatching follows the terrain), or, with fixed_controls, as "
        "orientation and density (read as given: one direction per face)");
    py::class_<ExtractTileReport>(m, "ExtractTileReport", "What one tile of a tiled extraction read and kept")
        .def_readonly("faces", &ExtractTileReport::faces)
        .def_readonly("lines", &ExtractTileReport::lines)
        .def_readonly("dem_cells", &ExtractTileReport::dem_cells)
        .def_readonly("rounds", &ExtractTileReport::rounds)
        .def_readonly("seconds", &ExtractTileReport::seconds);
    m.def("extract_tile", &extract_tile, py::arg("options"), py::arg("tile"), py::arg("halo"), py::arg("out"),
          py::call_guard<py::gil_scoped_release>(),
          "the faces of the partition whose anchor lies in the tile, extracted from the DEM window under the tile "
          "plus halo (ground units; larger where an owned face reaches the halo), written to out");
    py::class_<PartitionMerge>(m, "PartitionMerge", "What merge_partition_tiles wrote, and where its tiles disagree")
        .def_readonly("faces", &PartitionMerge::faces, "face polygons written")
        .def_readonly("overlaps", &PartitionMerge::overlaps,
                      "pairs of faces from different tiles that overlap (the tiles placed a face differently)")
        .def_readonly("overlap_area", &PartitionMerge::overlap_area, "their common area, ground units squared")
        .def_readonly("area", &PartitionMerge::area, "the area of all faces");
    m.def("merge_partition_tiles", &merge_partition_tiles, py::arg("parts"), py::arg("out"),
          py::arg("overwrite") = false, py::call_guard<py::gil_scoped_release>(),
          "one partition GeoPackage from the tiles of a tiled extraction; returns a PartitionMerge");
    m.def("check_extract_files", &check_extract_files, py::arg("options"), py::arg("output"), py::arg("png") = "",
          py::arg("overwrite") = false, "the outputs of partition_from_dem against its inputs (check_outputs)");
    m.def("write_partition_png", &write_partition_png, py::arg("result"), py::arg("path"), py::arg("pixels") = 1600,
          py::call_guard<py::gil_scoped_release>());

    // ---- Command line ----
    py::class_<CommandLine>(m, "CommandLine")
        .def_readonly("options", &CommandLine::options)
        .def_readonly("script", &CommandLine::script)
        .def_readonly("quiet", &CommandLine::quiet)
        .def_readonly("list_styles", &CommandLine::list_styles)
        .def_readonly("help", &CommandLine::help);
    m.def("parse_command_line", &parse_command_line, py::arg("args"), "the rockhatch option table");
    py::class_<ProgressBar>(m, "ProgressBar",
                            "The progress bar of the rockhatch command on standard error; as a progress callback it "
                            "never cancels")
        .def(py::init<bool, std::string>(), py::arg("on") = false, py::arg("prefix") = "")
        .def("__call__", &ProgressBar::operator(), py::arg("fraction"), py::arg("stage"))
        .def("finish", &ProgressBar::finish, "ends an unfinished bar line");
    m.def("help_text", &help_text);
    m.def("styles_text", &styles_text);
    m.def(
        "params_text",
        [](const py::iterable& params, int indent) {
            std::vector<StyleParam> ps;
            for (const py::handle& h : params) {
                if (py::isinstance<StyleParam>(h)) {
                    ps.push_back(h.cast<StyleParam>());
                    continue;
                }
                const auto t = h.cast<py::sequence>();
                ps.push_back({t[0].cast<std::string>(), t[1].cast<double>(), t[2].cast<std::string>(),
                              t.size() > 3 ? t[3].cast<std::string>() : std::string()});
            }
            return params_text(ps, indent);
        },
        py::arg("params"), py::arg("indent") = 4,
        "the parameter lines of --list-styles for a table of StyleParam or (name, default, unit, help) tuples "
        "(a style script's header is made from its PARAMS)");
}

}  // namespace rhpy
