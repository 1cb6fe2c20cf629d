// rockhatch.carto: rasters as numpy arrays, control fields, the partition, the hatching
// building blocks and styles, and the pipeline the rockhatch command runs. bind_carto
// registers it area by area (carto_bindings.hpp); this file holds the rasters, the terrain,
// the control fields and the helpers the areas share.
#include <cmath>

#include "carto/control_fields.hpp"
#include "carto/pipeline.hpp"
#include "carto/raster.hpp"
#include "carto/styles.hpp"
#include "carto/terrain.hpp"
#include "carto_bindings.hpp"

namespace rhpy {

using namespace carto;

// ---- Helpers shared by the areas (carto_bindings.hpp) ----

PyTerrain share(Terrain t) {
    auto own = [](Raster& r) { return std::make_shared<Raster>(std::move(r)); };
    return {own(t.elevation), own(t.slope), own(t.aspect), own(t.roughness), own(t.hillshade)};
}

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

// ---- rockhatch.carto, area by area ----

void bind_carto(py::module_& m) {
    add_raster_bindings(m);
    add_control_field_bindings(m);
    add_partition_bindings(m);
    add_hatch_bindings(m);
    add_style_bindings(m);
    add_pipeline_bindings(m);
    add_output_bindings(m);
    add_tile_bindings(m);
    add_extraction_bindings(m);
    add_cli_bindings(m);
}

// Rasters (Raster, reading, writing, warping, CRS helpers) and the terrain of a DEM.
void add_raster_bindings(py::module_& m) {
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
}

// Control fields (seed 5.3): rockhatch.tex.Field, with raster constructors, and the
// ControlFields a style is applied to.
void add_control_field_bindings(py::module_& m) {
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
                         const py::object& sl, const py::object& fl, const py::object& sh, const py::object& el) {
                 return ControlFields{to_field(o),  to_field(d),  to_field(h),  to_field(r),
                                      to_field(sl), to_field(fl), to_field(sh), to_field(el)};
             }),
             py::arg("orientation"), py::arg("density"), py::arg("height"), py::arg("roughness"),
             py::arg("slope") = py::float_(std::nan("")), py::arg("fall_line") = py::float_(std::nan("")),
             py::arg("shade") = py::float_(std::nan("")), py::arg("elevation") = py::float_(std::nan("")))
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
            "1 - hillshade smoothed at map scale (0 lit, 1 in shade)")
        .def_property(
            "elevation", [](const ControlFields& c) { return c.elevation; },
            [](ControlFields& c, const py::object& o) { c.elevation = to_field(o); },
            "the elevation (metres) smoothed at map scale, where crease lines are read");
}

}  // namespace rhpy
