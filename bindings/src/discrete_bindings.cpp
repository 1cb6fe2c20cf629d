// rockhatch.discrete: the discrete operator set of seed 004 under its names (libtex/discrete.hpp).
//
// Operators that take functions accept any Python callable (a lambda, or what another
// operator returned); partial forms return callables. Not, And, Compose and Const are
// written in Python (bindings/python/rockhatch/discrete.py) since they only combine
// callables. The GIL stays held during the programs: they call back into Python for every
// dart when a check or shaping is a Python function, and they are sequential anyway.
#include <sstream>

#include "common.hpp"
#include "libtex/discrete.hpp"

namespace rhpy {
namespace {

using namespace tex::disc;
using tex::BBox;
using tex::Curves;
using tex::Field;
using tex::GridSamples;
using tex::Point;
using tex::Region;

// A partially applied operator of any element (Rotation(a), Scale(s), Overlap(set), ...):
// called on a region, a polyline or a point.
template <class Op>
void bind_element_operator(py::module_& m, const char* name, const char* doc) {
    py::class_<Op>(m, name, doc)
        .def(
            "__call__", [](const Op& op, const Region& e) { return op(e); }, py::arg("element"))
        .def(
            "__call__", [](const Op& op, const Polyline& e) { return op(e); }, py::arg("element"))
        .def(
            "__call__", [](const Op& op, const Point& e) { return op(e); }, py::arg("element"));
}

std::optional<Field> optional_field(const py::object& o) {
    if (o.is_none()) return std::nullopt;
    return to_field(o);
}

}  // namespace

void bind_discrete(py::module_& m) {
    // ---- Elements and sets ----
    py::class_<Polyline>(m, "Polyline", "A 1D element: a polyline, open or closed")
        .def(py::init([](std::vector<Point> pts, bool closed) {
                 return Polyline{std::move(pts), closed};
             }),
             py::arg("points"), py::arg("closed") = false)
        .def_readwrite("points", &Polyline::points)
        .def_readwrite("closed", &Polyline::closed)
        .def("__len__", [](const Polyline& c) { return c.points.size(); })
        .def("__repr__", [](const Polyline& c) {
            return "Polyline(" + std::to_string(c.points.size()) + " points" +
                   (c.closed ? ", closed)" : ")");
        });

    py::class_<RegionSet>(
        m, "RegionSet",
        "A set of regions with a spatial index; copies share the set (the predicates built "
        "on it see it grow)")
        .def(py::init<>())
        .def(py::init<const std::vector<Region>&>(), py::arg("regions"))
        .def("add", py::overload_cast<Region>(&RegionSet::add), py::arg("region"))
        .def("clear", &RegionSet::clear)
        .def("__len__", &RegionSet::size)
        .def("__getitem__", [](const RegionSet& s, std::size_t i) { return s[i]; })
        .def("__iter__", [](const RegionSet& s) { return py::iter(py::cast(s.regions())); })
        .def_property_readonly("regions", [](const RegionSet& s) { return s.regions(); })
        .def("__repr__", [](const RegionSet& s) {
            return "RegionSet(" + std::to_string(s.size()) + " regions)";
        });

    bind_element_operator<Rotator>(
        m, "Rotator",
        "Rotation(angle): turns any element (about its centroid; a point about the origin)");
    bind_element_operator<Scaler>(
        m, "Scaler",
        "Scale(factor): scales any element (about its centroid; a point about the origin)");
    bind_element_operator<OverlapTest>(
        m, "OverlapTest",
        "Overlap(set): whether an element shares a point with a region of the set");
    bind_element_operator<DistanceTest>(
        m, "DistanceTest",
        "MinimalDistance(set, d): whether an element comes nearer than d to a region of the set");

    // ---- Construction ----
    m.def("Sequence", &Sequence, py::arg("points"),
          "A set of points as a pinning: its points in order");
    m.def(
        "RandomPinning",
        [](const Region& r, const py::object& density) {
            const auto d = optional_field(density);
            return d ? RandomPinning(r, *d) : RandomPinning(r);
        },
        py::arg("region"), py::arg("density") = py::none(),
        "A pinning of uniform random points in the region (density: a field read as acceptance "
        "probability)");
    m.def("RegularPinning", &RegularPinning, py::arg("region"), py::arg("nx"), py::arg("ny"),
          "Centres of an nx x ny grid over the region's box, those inside it");
    m.def("RegularPinning1D", py::overload_cast<const Polyline&, double>(&RegularPinning1D),
          py::arg("curve"), py::arg("density"), "Points along the curve every 1/density");
    m.def("RegularPinning1D",
          py::overload_cast<const std::vector<Polyline>&, double>(&RegularPinning1D),
          py::arg("curves"), py::arg("density"));
    m.def("Centroid", py::overload_cast<const Region&>(&Centroid), py::arg("element"),
          "Area centroid of a region");
    m.def("Centroid", py::overload_cast<const Polyline&>(&Centroid), py::arg("element"));
    m.def("TangentFlowField", &TangentFlowField, py::arg("regions"), py::arg("step"),
          "A field point -> displacement of length step along the tangents of the nearest region "
          "boundaries");
    m.def("Contour", py::overload_cast<const Region&>(&Contour), py::arg("region"),
          "The outer ring as a closed curve");
    m.def("Contour", py::overload_cast<const RegionSet&>(&Contour), py::arg("regions"));
    m.def("Interpolation", &Interpolation, py::arg("points"), py::arg("subdivisions") = 4,
          "A Catmull-Rom curve through the points");
    m.def("VoronoiCells",
          py::overload_cast<const std::vector<Region>&, const BBox&, double>(&VoronoiCells),
          py::arg("regions"), py::arg("domain"), py::arg("spacing") = 0.0,
          "The Voronoi cells of the regions, cut to the domain (boundaries sampled every spacing; "
          "0: automatic)");
    m.def("VoronoiCells", py::overload_cast<const BBox&, double>(&VoronoiCells), py::arg("domain"),
          py::arg("spacing") = 0.0, "Partial form: the reshaping of a relaxation");
    m.def("ApplyThickness", &ApplyThickness, py::arg("curve"), py::arg("thickness"),
          "A region around the curve, thickness(t) wide at arc-length fraction t");

    // ---- Transformations ----
    m.def("Translation", py::overload_cast<const Region&, const Point&>(&Translation),
          py::arg("element"), py::arg("location"), "Moves the element's centroid to the location");
    m.def("Translation", py::overload_cast<const Polyline&, const Point&>(&Translation),
          py::arg("element"), py::arg("location"));
    m.def("Translation", py::overload_cast<const Point&, const Point&>(&Translation),
          py::arg("element"), py::arg("location"));
    m.def("Translation", py::overload_cast<Region>(&Translation), py::arg("element"),
          "Partial form: the shaping point -> element moved there");
    m.def("Translation", py::overload_cast<std::function<Region()>>(&Translation),
          py::arg("generator"));
    m.def("Rotation", py::overload_cast<const Region&, double>(&Rotation), py::arg("element"),
          py::arg("angle"));
    m.def("Rotation", py::overload_cast<const Polyline&, double>(&Rotation), py::arg("element"),
          py::arg("angle"));
    m.def("Rotation", py::overload_cast<const Point&, double>(&Rotation), py::arg("element"),
          py::arg("angle"));
    m.def("Rotation", py::overload_cast<double>(&Rotation), py::arg("angle"),
          "Partial form: an element operator");
    m.def("Rotation", py::overload_cast<RealGen>(&Rotation), py::arg("angle"));
    m.def("Scale", py::overload_cast<const Region&, double>(&Scale), py::arg("element"),
          py::arg("factor"));
    m.def("Scale", py::overload_cast<const Polyline&, double>(&Scale), py::arg("element"),
          py::arg("factor"));
    m.def("Scale", py::overload_cast<const Point&, double>(&Scale), py::arg("element"),
          py::arg("factor"));
    m.def("Scale", py::overload_cast<const std::vector<Region>&, double>(&Scale),
          py::arg("elements"), py::arg("factor"));
    m.def("Scale", py::overload_cast<double>(&Scale), py::arg("factor"),
          "Partial form: an element operator");
    m.def("Scale", py::overload_cast<RealGen>(&Scale), py::arg("factor"));
    // A generator for the element or the parameter (after the plain forms, which pybind11
    // tries first): a generator of regions, both drawn anew at every call.
    m.def("Translation", py::overload_cast<const Region&, Pinning>(&Translation), py::arg("element"),
          py::arg("location"), "With a pinning: a generator of the element at its successive points");
    m.def("Translation", py::overload_cast<RegionGen, const Point&>(&Translation), py::arg("element"),
          py::arg("location"));
    m.def("Translation", py::overload_cast<RegionGen, Pinning>(&Translation), py::arg("element"),
          py::arg("location"));
    m.def("Rotation", py::overload_cast<const Region&, RealGen>(&Rotation), py::arg("element"),
          py::arg("angle"), "With a generator: a generator of the element turned by a new angle at every call");
    m.def("Rotation", py::overload_cast<RegionGen, double>(&Rotation), py::arg("element"), py::arg("angle"));
    m.def("Rotation", py::overload_cast<RegionGen, RealGen>(&Rotation), py::arg("element"), py::arg("angle"));
    m.def("Scale", py::overload_cast<const Region&, RealGen>(&Scale), py::arg("element"), py::arg("factor"),
          "With a generator: a generator of the element scaled by a new factor at every call");
    m.def("Scale", py::overload_cast<RegionGen, double>(&Scale), py::arg("element"), py::arg("factor"));
    m.def("Scale", py::overload_cast<RegionGen, RealGen>(&Scale), py::arg("element"), py::arg("factor"));

    // ---- Scalars ----
    m.def("CountUpTo", &CountUpTo, py::arg("n"), "A condition true n times, then false");
    m.def("RandomR", &RandomR, py::arg("a"), py::arg("b"),
          "A generator of uniform reals in [a, b)");
    m.def("Distance", py::overload_cast<const Point&, const Point&>(&Distance), py::arg("a"),
          py::arg("b"));
    m.def("Distance", py::overload_cast<const Point&, const Polyline&>(&Distance), py::arg("a"),
          py::arg("b"));
    m.def("Distance", py::overload_cast<const Point&, const Region&>(&Distance), py::arg("a"),
          py::arg("b"));
    m.def("Distance", py::overload_cast<const Polyline&, const Polyline&>(&Distance), py::arg("a"),
          py::arg("b"));
    m.def("Distance", py::overload_cast<const Polyline&, const Region&>(&Distance), py::arg("a"),
          py::arg("b"));
    m.def("Distance", py::overload_cast<const Region&, const Region&>(&Distance), py::arg("a"),
          py::arg("b"), "Smallest distance between two elements (0 when they touch)");
    m.def("Overlap", py::overload_cast<const RegionSet&>(&Overlap), py::arg("regions"),
          "Partial form: the test element -> bool");
    m.def("Overlap", py::overload_cast<const RegionSet&, const Region&>(&Overlap),
          py::arg("regions"), py::arg("element"));
    m.def("Overlap", py::overload_cast<const RegionSet&, const Polyline&>(&Overlap),
          py::arg("regions"), py::arg("element"));
    m.def("Overlap", py::overload_cast<const RegionSet&, const Point&>(&Overlap),
          py::arg("regions"), py::arg("element"));
    m.def("MinimalDistance", py::overload_cast<const RegionSet&, double>(&MinimalDistance),
          py::arg("regions"), py::arg("d"),
          "Partial form: the test element -> bool (True: nearer than d)");
    m.def("MinimalDistance",
          py::overload_cast<const RegionSet&, const Region&, double>(&MinimalDistance),
          py::arg("regions"), py::arg("element"), py::arg("d"));
    m.def("MinimalDistance",
          py::overload_cast<const RegionSet&, const Polyline&, double>(&MinimalDistance),
          py::arg("regions"), py::arg("element"), py::arg("d"));
    m.def("MinimalDistance",
          py::overload_cast<const RegionSet&, const Point&, double>(&MinimalDistance),
          py::arg("regions"), py::arg("element"), py::arg("d"));

    // ---- Input / output ----
    m.def("Image", py::overload_cast<double, double>(&Image), py::arg("width"), py::arg("height"),
          "The frame of a width x height image");
    m.def(
        "ReadPGM",
        [](const std::string& f) {
            GridSamples g = ReadPGM(f);
            const Region frame = Image(g);
            return py::make_tuple(tex::GridField(std::move(g)), frame);
        },
        py::arg("filename"), "A grey PGM image as (field of grey levels in [0, 1], frame)");
    m.def(
        "ParsePGM",
        [](const py::bytes& b) {
            GridSamples g = ParsePGM(std::string(b), "<pgm bytes>");
            const Region frame = Image(g);
            return py::make_tuple(tex::GridField(std::move(g)), frame);
        },
        py::arg("data"), "The same as ReadPGM, from the bytes of a PGM file");
    m.def("BuiltinHatch", &BuiltinHatch, py::arg("length") = 24.0, py::arg("width") = 3.0);
    m.def("BuiltinRectangle", &BuiltinRectangle, py::arg("width") = 240.0,
          py::arg("height") = 160.0);
    m.def("BuiltinCircle", &BuiltinCircle, py::arg("radius") = 20.0, py::arg("segments") = 40);
    m.def("UserRegion", &UserRegion, py::arg("curves"),
          "The region bounded by the closed curves (e.g. ImportSVG)");
    m.def("ToCurves", py::overload_cast<const Region&>(&ToCurves), py::arg("elements"));
    m.def("ToCurves", py::overload_cast<const Polyline&>(&ToCurves), py::arg("elements"));
    m.def("ToCurves", py::overload_cast<const RegionSet&>(&ToCurves), py::arg("elements"));
    m.def("ToCurves", py::overload_cast<const std::vector<Region>&>(&ToCurves),
          py::arg("elements"));
    m.def("ToCurves", py::overload_cast<const std::vector<Point>&>(&ToCurves), py::arg("elements"),
          "Elements as Curves, for ExportSVG / ToSVG and for mappers");

    // ---- Programs ----
    m.def("greedy_distribution", &greedy_distribution, py::arg("out"), py::arg("loop_condition"),
          py::arg("pinning"), py::arg("shaping"), py::arg("checking"),
          "Dart throwing into out: while loop_condition(), shape a pin and keep it if "
          "checking(shape). "
          "Returns the number of darts thrown");
    m.def("relaxation", &relaxation, py::arg("input"), py::arg("out"), py::arg("loop_condition"),
          py::arg("reshaping"), py::arg("repinning"),
          "Lloyd-like relaxation: each element moves to the pin of its reshaped cell");
    m.def("stream_line",
          py::overload_cast<const Point&, const FlowField&, const PointCheck&, double,
                            const ThicknessFn&, double>(&stream_line),
          py::arg("start"), py::arg("flow_field"), py::arg("check"), py::arg("length"),
          py::arg("thickness"), py::arg("min_length") = 0.0,
          "A stream line from start, thickened (empty region when too short)");
    m.def("stream_line",
          py::overload_cast<FlowField, PointCheck, double, ThicknessFn, double>(&stream_line),
          py::arg("flow_field"), py::arg("check"), py::arg("length"), py::arg("thickness"),
          py::arg("min_length") = 0.0, "Partial form: the shaping point -> stream line");
    m.def("trace_stream", &trace_stream, py::arg("start"), py::arg("flow_field"), py::arg("check"),
          py::arg("length"), "The polyline of a stream line before thickness");
}

}  // namespace rhpy
