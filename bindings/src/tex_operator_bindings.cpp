// rockhatch.tex, the operators on arrangements: partitions (table 3.2), mapping (table 3.3)
// and merging (table 3.5).
#include <functional>
#include <optional>

#include "tex_bindings.hpp"

namespace rhpy {
namespace {

using namespace tex;

// A mapper the engine runs natively (a stock mapper such as JitterEdges): the mapping
// operators take it as it is, so no Python call is made per cell and it runs on the
// engine's worker threads.
template <class CellT>
struct NativeMapper {
    std::function<Curves(const CellT&)> fn;
    std::string name;
};

template <class CellT>
void bind_native_mapper(py::module_& m, const char* name, const char* doc) {
    using N = NativeMapper<CellT>;
    py::class_<N>(m, name, doc)
        .def("__call__", [](const N& n, const CellT& c) { return n.fn(c); }, py::arg("cell"),
             py::call_guard<py::gil_scoped_release>(), "the curves the mapper gives this cell")
        .def_property_readonly("name", [](const N& n) { return n.name; })
        .def("__repr__", [name](const N& n) { return std::string(name) + "(" + n.name + ")"; });
}

double number(const py::handle& o, const char* op, const char* what) {
    if (!py::isinstance<py::float_>(o) && !py::isinstance<py::int_>(o) && !py::hasattr(o, "__float__"))
        throw py::type_error(std::string(op) + ": " + what + " must be a number, got " + type_name(o));
    return py::float_(py::reinterpret_borrow<py::object>(o)).cast<double>();
}

std::vector<std::string> string_args(const py::args& args, const char* op) {
    std::vector<std::string> out;
    for (const auto& a : args) {
        if (!py::isinstance<py::str>(a))
            throw py::type_error(std::string(op) + ": labels must be strings, got " + type_name(a));
        out.push_back(a.cast<std::string>());
    }
    return out;
}

// SetWeighted*Labels(p, "l1", w1, "l2", w2, ...)
std::vector<WeightedLabel> weighted_args(const py::args& args, const char* op) {
    if (args.size() % 2 != 0)
        throw py::type_error(std::string(op) + ": expected label, weight pairs, got " + std::to_string(args.size()) +
                             " values");
    std::vector<WeightedLabel> out;
    for (std::size_t i = 0; i < args.size(); i += 2) {
        if (!py::isinstance<py::str>(args[i]))
            throw py::type_error(std::string(op) + ": argument " + std::to_string(i + 2) + " must be a label string");
        out.push_back({args[i].cast<std::string>(), number(args[i + 1], op, "a weight")});
    }
    return out;
}

}  // namespace

// Partitions (table 3.2): their properties and labels, and the partition operators.
void add_partition_operator_bindings(py::module_& m) {
    py::enum_<Border>(m, "Border")
        .value("CROP", Border::CROP)
        .value("CROP_ADD_BOUNDARY", Border::CROP_ADD_BOUNDARY)
        .value("KEEP_INSIDE", Border::KEEP_INSIDE)
        .value("KEEP_OUTSIDE", Border::KEEP_OUTSIDE)
        .export_values();

    py::class_<Stripes>(m, "Stripes", "Properties of a family of parallel lines (StripesProperties)")
        .def_readwrite("angle", &Stripes::angle)
        .def_readwrite("widths", &Stripes::widths)
        .def_readwrite("edge_labels", &Stripes::edge_labels)
        .def_readwrite("face_labels", &Stripes::face_labels);
    m.def(
        "StripesProperties",
        [](double angle, const py::args& widths) {
            std::vector<double> w;
            for (const auto& x : widths) {
                if (py::isinstance<py::list>(x) || py::isinstance<py::tuple>(x)) {
                    for (const auto& y : x) w.push_back(number(y, "StripesProperties", "a width"));
                } else {
                    w.push_back(number(x, "StripesProperties", "a width"));
                }
            }
            return StripesProperties(angle, w);
        },
        py::arg("angle"), "StripesProperties(angle, w1[, w2...]): lines at angle (radians), widths cycled");
    m.def(
        "SetEdgeLabels",
        [](Stripes& p, const py::args& l) -> Stripes& { return SetEdgeLabels(p, string_args(l, "SetEdgeLabels")); },
        py::return_value_policy::reference, "sets the cycle of line labels (in place)");
    m.def(
        "SetFaceLabels",
        [](Stripes& p, const py::args& l) -> Stripes& { return SetFaceLabels(p, string_args(l, "SetFaceLabels")); },
        py::return_value_policy::reference, "sets the cycle of band labels (in place)");

    py::class_<WeightedLabel>(m, "WeightedLabel")
        .def_readonly("label", &WeightedLabel::label)
        .def_readonly("weight", &WeightedLabel::weight);
    py::class_<Irregular>(m, "Irregular", "Properties of an irregular partition (IrregularProperties)")
        .def_readwrite("density", &Irregular::density)
        .def_readonly("vertex_labels", &Irregular::vertex_labels)
        .def_readonly("edge_labels", &Irregular::edge_labels)
        .def_readonly("face_labels", &Irregular::face_labels);
    m.def("IrregularProperties", &IrregularProperties, py::arg("density"), "density: sites per unit area");
    m.def(
        "SetWeightedVertexLabels",
        [](Irregular& p, const py::args& a) -> Irregular& {
            return SetWeightedVertexLabels(p, weighted_args(a, "SetWeightedVertexLabels"));
        },
        py::return_value_policy::reference);
    m.def(
        "SetWeightedEdgeLabels",
        [](Irregular& p, const py::args& a) -> Irregular& {
            return SetWeightedEdgeLabels(p, weighted_args(a, "SetWeightedEdgeLabels"));
        },
        py::return_value_policy::reference);
    m.def(
        "SetWeightedFaceLabels",
        [](Irregular& p, const py::args& a) -> Irregular& {
            return SetWeightedFaceLabels(p, weighted_args(a, "SetWeightedFaceLabels"));
        },
        py::return_value_policy::reference);
    m.def("StripesPartition", py::overload_cast<const Stripes&, Border>(&StripesPartition), py::arg("p"), py::arg("border") = Border::CROP_ADD_BOUNDARY);
    m.def("GridPartition", py::overload_cast<const Stripes&, const Stripes&, Border>(&GridPartition), py::arg("s1"), py::arg("s2"), py::arg("border"));
    m.def("UniformPartition", &UniformPartition, py::arg("p"), py::arg("border"), py::arg("seed") = py::none(),
          "Voronoi cells of Poisson-disk sites; each call draws its own sites unless `seed` repeats them");
    m.def("RandomPartition", &RandomPartition, py::arg("p"), py::arg("border"), py::arg("seed") = py::none(),
          "Voronoi cells of Poisson sites; each call draws its own sites unless `seed` repeats them");
    m.def("PoissonDiskSites", &PoissonDiskSites, py::arg("density"), py::arg("box"), py::arg("stream") = 0);
    m.def("PoissonSites", &PoissonSites, py::arg("density"), py::arg("box"), py::arg("stream") = 0);
    m.def("PoissonDiskRadius", &PoissonDiskRadius, py::arg("density"));
}

// Mapping (table 3.3): native and Python mappers on the cells of an arrangement.
void add_mapping_bindings(py::module_& m) {
    // A Python mapper runs one call at a time (the interpreter's lock): the engine calls it
    // cell after cell on the evaluating thread, instead of handing the lock between workers.
    bind_native_mapper<Edge>(m, "EdgeMapper",
                             "A native edge mapper (e.g. JitterEdges): MapToEdges runs it with no Python call per "
                             "edge, on the engine's threads");
    m.def(
        "JitterEdges",
        [](const std::string& label, double theta, double across, double along, double r, double gap,
           const py::object& gate, double gate_min) {
            const Field g = gate.is_none() ? Field() : to_field(gate);
            return NativeMapper<Edge>{JitterEdges(label, theta, across, along, r, gap, g, gate_min),
                                      "JitterEdges '" + label + "'"};
        },
        py::arg("label"), py::arg("theta"), py::arg("across"), py::arg("along"), py::arg("r"), py::arg("gap") = 1.0,
        py::arg("gate") = py::none(), py::arg("gate_min") = 0.0,
        "the jitter mapper of App. E: an edge labelled `label` moved so that its end vertices land on themselves "
        "shifted by Random(v, -r*across/2, r*across/2, 0) across theta and Random(v, -r*along/2, r*along/2, 1) "
        "along it, then scaled by gap about its middle when gap < 1; other edges give nothing, and so do edges "
        "whose middle reads below gate_min (or NaN) in the gate field when gate_min > 0");
    m.def(
        "ThinLines",
        [](const NativeMapper<Edge>& inner, double theta, double spacing, const py::object& keep,
           const std::optional<Region>& owner) {
            return NativeMapper<Edge>{ThinLines(inner.fn, theta, spacing, to_field(keep), owner.value_or(Region())),
                                      "ThinLines(" + inner.name + ")"};
        },
        py::arg("inner"), py::arg("theta"), py::arg("spacing"), py::arg("keep"), py::arg("owner") = py::none(),
        "thins the lines of StripesProperties(theta, spacing): an edge on line k is handed to `inner` where "
        "ThinRank(k) < keep(its middle), else nothing (golden-ratio ranks: the kept lines are evenly spread at any "
        "fraction, and a smaller fraction keeps a subset); with `owner`, only edges whose middle lies in it");
    m.def("ThinRank", &ThinRank, py::arg("k"), "the rank of line k in ThinLines's order, in [0, 1)");
    m.def("MovingAverage", &MovingAverage, py::arg("curves"), py::arg("half_window"),
          "each point the mean of the points up to half_window before and after it (ends kept; closed curves wrap)");
    m.def("Smoothed", &Smoothed, py::arg("curves"), py::arg("step"),
          "each curve drawn smooth at `step`: its points every `step` of length (its last point kept), then three "
          "rounds of corner cutting; the ends stay put, bends and steps shorter than about `step` go");
    m.def(
        "MapAlong",
        [](const Curves& c, double spacing, py::function f) {
            return MapAlong(c, spacing, [&f](const Point& at, const Point& tangent, long long k, double to_end) {
                return f(at, tangent, k, to_end).cast<Curves>();
            });
        },
        py::arg("curves"), py::arg("spacing"), py::arg("mapper"),
        "mapper(point, unit tangent, k, length left to the end) at the points every `spacing` along each curve, "
        "the first half a spacing from its start; their curves together");
    m.def(
        "MapToEdges", [](const NativeMapper<Edge>& f, Arrangement a) { return MapToEdges(f.fn, a); },
        py::arg("mapper"), py::arg("arrangement"));
    m.def(
        "MapToVertices", [](py::function f, Arrangement a) { return MapToVertices(mapper<Vertex>(f, "MapToVertices"), a, MapperThreads::Serial); },
        py::arg("mapper"), py::arg("arrangement"));
    m.def(
        "MapToEdges", [](py::function f, Arrangement a) { return MapToEdges(mapper<Edge>(f, "MapToEdges"), a, MapperThreads::Serial); },
        py::arg("mapper"), py::arg("arrangement"));
    m.def(
        "MapToFaces", [](py::function f, Arrangement a) { return MapToFaces(mapper<Face>(f, "MapToFaces"), a, MapperThreads::Serial); },
        py::arg("mapper"), py::arg("arrangement"), "visits the bounded faces");
}

// Merging (table 3.5).
void add_merge_bindings(py::module_& m) {
    m.def("Union", py::overload_cast<Arrangement, Arrangement>(&Union), py::arg("a1"), py::arg("a2"));
    m.def("Crop", &Crop, py::arg("a"), py::arg("border"),
          "a evaluated on the region and cut to it (CROP_ADD_BOUNDARY adds the region's labelled outline)");
    m.def(
        "FrayedCrop",
        [](Arrangement a, double min, double max, const py::object& across, std::vector<std::string> hard,
           double beyond) {
            return FrayedCrop(std::move(a), min, max, across.is_none() ? Field() : to_field(across), std::move(hard),
                              beyond);
        },
        py::arg("a"), py::arg("min"), py::arg("max"), py::arg("across") = py::none(),
        py::arg("hard") = std::vector<std::string>{}, py::arg("beyond") = 0.0,
        "a cut to the region, each end of an open curve on the region's border drawn back by a random length in "
        "[min, max], except on edges labelled one of `hard` and where `across` has a value beyond the border; "
        "the share `beyond` of those ends drawn on past the border to that depth instead, where the way is free");
    m.def("Apart", &Apart, py::arg("a"), py::arg("lines"), py::arg("distance"),
          "the curves of a less their parts within `distance` of the lines (a gap left along them)");
    m.def(
        "CutAtLevels",
        [](Arrangement a, const py::object& f, double step, double gap, double sampling) {
            return CutAtLevels(std::move(a), to_field(f), step, gap, sampling);
        },
        py::arg("a"), py::arg("f"), py::arg("step"), py::arg("gap"), py::arg("sampling") = 0.0,
        "the curves of a cut into rows where the field f crosses a multiple of step: each piece starts on a level "
        "line and ends `gap` before the next one; f read every `sampling` along the curves");
    m.def("Outline", &Outline, "the region evaluated on as an arrangement: its labelled edges, else its rings");
    m.def("Merge", &Merge, py::arg("a1"), py::arg("a2"), "Union's name in the thesis's Chapter 4");
    m.def("Inside", py::overload_cast<Arrangement, Arrangement, Border>(&Inside), py::arg("a1"), py::arg("a2"), py::arg("border"));
    m.def("Outside", py::overload_cast<Arrangement, Arrangement, Border>(&Outside), py::arg("a1"), py::arg("a2"), py::arg("border"));
}

}  // namespace rhpy
