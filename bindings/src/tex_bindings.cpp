// rockhatch.tex: every libtex operator and built-in under the thesis's names (tables 3.2 to
// 3.6), so that Appendix A scripts run after `from rockhatch.tex import *`.
#include <sstream>

#include <pybind11/operators.h>

#include "common.hpp"

namespace rhpy {
namespace {

using namespace tex;

std::string repr(const Point& p) {
    std::ostringstream s;
    s.precision(17);
    s << "Point(" << p.x << ", " << p.y << ")";
    return s.str();
}

std::vector<std::string> names(const Labels& l) { return l.names(); }

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

// Scope classes of libtex (SeedScope, StreamScope, SavedSeed) as Python context managers;
// `arg` names the value a scope takes (nullptr: it takes none).
template <class S>
struct PyGuard {
    std::uint64_t value;
    std::unique_ptr<S> live;
};

template <class S>
void bind_guard(py::module_& m, const char* name, const char* arg, const char* doc) {
    using G = PyGuard<S>;
    py::class_<G> c(m, name, doc);
    if constexpr (std::is_default_constructible_v<S>) c.def(py::init([] { return G{0, nullptr}; }));
    else c.def(py::init([](std::uint64_t v) { return G{v, nullptr}; }), py::arg(arg));
    c.def(
         "__enter__",
         [](G& g) -> G& {
             if constexpr (std::is_default_constructible_v<S>) g.live = std::make_unique<S>();
             else g.live = std::make_unique<S>(g.value);
             return g;
         },
         py::return_value_policy::reference_internal)
        .def("__exit__", [](G& g, const py::args&) {
            g.live.reset();
            return false;
        });
}

template <class Tag>
py::class_<Cell<Tag>> bind_cell(py::module_& m, const char* name, const char* doc) {
    using C = Cell<Tag>;
    py::class_<C> cls(m, name, doc);
    cls
        .def_property_readonly("id", &C::id, "index of the cell in its planar map (canonical geometric order)")
        .def("__eq__", [](const C& a, const C& b) { return a == b; })
        .def("__eq__", [](const C&, const py::object&) { return false; })
        .def("__ne__", [](const C& a, const C& b) { return a != b; })
        .def("__ne__", [](const C&, const py::object&) { return true; })
        .def("__hash__", [](const C& c) {
            return py::hash(py::make_tuple(reinterpret_cast<std::uintptr_t>(c.map_ptr().get()), c.id()));
        })
        .def("__repr__", [name](const C& c) { return std::string(name) + "(" + std::to_string(c.id()) + ")"; });
    return cls;
}

Curves polyline(const std::vector<Point>& pts, bool closed) { return Polyline(pts, closed); }

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

void bind_tex(py::module_& m) {
    m.attr("pi") = tex::pi;

    // ---- Geometry ----
    py::class_<Point>(m, "Point", "A point or vector of the plane, with + - * / and ==")
        .def(py::init<>())
        .def(py::init<double, double>(), py::arg("x"), py::arg("y"))
        .def(py::init([](const py::tuple& t) {
            if (t.size() != 2) throw py::type_error("Point: a tuple of two numbers is needed");
            return Point(t[0].cast<double>(), t[1].cast<double>());
        }))
        .def_readwrite("x", &Point::x)
        .def_readwrite("y", &Point::y)
        .def(py::self + py::self)
        .def(py::self - py::self)
        .def(py::self * double())
        .def(double() * py::self)
        .def(py::self / double())
        .def(-py::self)
        .def(py::self == py::self)
        .def(py::self != py::self)
        .def("__hash__", [](const Point& p) { return py::hash(py::make_tuple(p.x, p.y)); })
        .def("__iter__", [](const Point& p) { return py::iter(py::make_tuple(p.x, p.y)); })
        .def("__repr__", &repr)
        .def(py::pickle([](const Point& p) { return py::make_tuple(p.x, p.y); },
                        [](const py::tuple& t) { return Point(t[0].cast<double>(), t[1].cast<double>()); }));
    py::implicitly_convertible<py::tuple, Point>();
    m.def("dot", &dot);
    m.def("cross", &cross);
    m.def("norm", &norm, "length of a vector (std::hypot)");
    m.def("distance", &distance, "distance between two points (std::hypot)");
    m.def("signed_area", &signed_area, "signed area of a ring (positive when counter-clockwise)");

    py::class_<BBox>(m, "BBox", "Axis-aligned box")
        .def(py::init<>())
        .def(py::init([](double x0, double y0, double x1, double y1) { return BBox{x0, y0, x1, y1}; }),
             py::arg("xmin"), py::arg("ymin"), py::arg("xmax"), py::arg("ymax"))
        .def_readwrite("xmin", &BBox::xmin)
        .def_readwrite("ymin", &BBox::ymin)
        .def_readwrite("xmax", &BBox::xmax)
        .def_readwrite("ymax", &BBox::ymax)
        .def("empty", &BBox::empty)
        .def("width", &BBox::width)
        .def("height", &BBox::height)
        .def("center", &BBox::center)
        .def("add", py::overload_cast<const Point&>(&BBox::add))
        .def("add", py::overload_cast<const BBox&>(&BBox::add))
        .def("contains", &BBox::contains)
        .def("intersects", &BBox::intersects)
        .def("expanded", &BBox::expanded)
        .def("__repr__", [](const BBox& b) {
            std::ostringstream s;
            s << "BBox(" << b.xmin << ", " << b.ymin << ", " << b.xmax << ", " << b.ymax << ")";
            return s.str();
        });

    py::class_<Region>(m, "Region", "A polygon with holes: the domain an arrangement is evaluated on")
        .def(py::init<std::vector<Point>, std::vector<std::vector<Point>>, const std::string&>(), py::arg("outer"),
             py::arg("holes") = std::vector<std::vector<Point>>{}, py::arg("op") = "Region")
        .def_static("rectangle", &Region::rectangle, py::arg("xmin"), py::arg("ymin"), py::arg("xmax"), py::arg("ymax"))
        .def_property_readonly("outer", &Region::outer)
        .def_property_readonly("holes", &Region::holes)
        .def("bbox", &Region::bbox)
        .def("area", &Region::area)
        .def("contains", &Region::contains, "even-odd test; points on a ring count as inside")
        .def("boundary", &Region::boundary,
             "the boundary as curves, inside on the left: its labelled edges when it has them, else its rings")
        .def("with_edges", &Region::with_edges, py::arg("edges"),
             "the same region with its boundary given as labelled curves (a face's edges), which partitions "
             "cropped to it with CROP_ADD_BOUNDARY keep on their outline")
        .def("has_edges", &Region::has_edges);

    // ---- Curves ----
    py::class_<Curve>(m, "Curve", "A labelled polyline")
        .def(py::init([](std::vector<Point> pts, bool closed, std::vector<std::string> labels) {
                 Curve c;
                 c.points = std::move(pts);
                 c.closed = closed;
                 c.labels = Labels::from_names(labels);
                 return c;
             }),
             py::arg("points"), py::arg("closed") = false, py::arg("labels") = std::vector<std::string>{})
        .def_readwrite("points", &Curve::points)
        .def_readwrite("closed", &Curve::closed)
        .def_property(
            "labels", [](const Curve& c) { return names(c.labels); },
            [](Curve& c, const std::vector<std::string>& l) { c.labels = Labels::from_names(l); })
        .def_property(
            "left", [](const Curve& c) { return names(c.left); },
            [](Curve& c, const std::vector<std::string>& l) { c.left = Labels::from_names(l); })
        .def_property(
            "right", [](const Curve& c) { return names(c.right); },
            [](Curve& c, const std::vector<std::string>& l) { c.right = Labels::from_names(l); });

    py::class_<LabeledPoint>(m, "LabeledPoint", "A labelled point carried along with curves (e.g. start, end)")
        .def_readonly("point", &LabeledPoint::point)
        .def_property_readonly("labels", [](const LabeledPoint& p) { return names(p.labels); });

    py::class_<Curves>(m, "Curves", "What arrangements return and mappers produce: labelled curves and points")
        .def(py::init<>())
        .def_property(
            "curves", [](const Curves& c) { return c.curves; },
            [](Curves& c, std::vector<Curve> v) { c.curves = std::move(v); })
        .def_property_readonly("points", [](const Curves& c) { return c.points; })
        .def_readwrite("origin", &Curves::origin)
        .def("__len__", &Curves::size)
        .def("empty", &Curves::empty)
        .def("bbox", &Curves::bbox)
        .def("append", [](Curves& c, const Curves& o) { c.append(o); }, "appends the curves of another set in place")
        .def("add_point", [](Curves& c, const Point& p, const std::vector<std::string>& labels) {
            c.points.push_back({p, Labels::from_names(labels)});
        })
        .def("__repr__", [](const Curves& c) {
            return "Curves(" + std::to_string(c.curves.size()) + " curves, " + std::to_string(c.points.size()) +
                   " labelled points)";
        });

    // Table 3.6 utilities.
    m.def("Nothing", &Nothing, "an empty set of curves");
    m.def("Append", &Append, py::arg("c1"), py::arg("c2"));
    m.def("BBoxWidth", [](const Curves& c) { return BBoxWidth(c); });
    m.def("BBoxHeight", [](const Curves& c) { return BBoxHeight(c); });
    m.def("BBoxCenter", [](const Curves& c) { return BBoxCenter(c); });
    m.def("Scale", py::overload_cast<const Curves&, double>(&Scale), py::arg("c"), py::arg("s"),
          "scales about the centre of the bounding box");
    m.def("Scale", py::overload_cast<const Curves&, double, double>(&Scale), py::arg("c"), py::arg("sx"),
          py::arg("sy"));
    m.def("Rotate", &Rotate, py::arg("c"), py::arg("a"), "rotates by a radians about the centre of the bounding box");
    m.def("Translate", &Translate, py::arg("c"), py::arg("v"));
    m.def("MatchPoint", &MatchPoint, py::arg("c"), py::arg("s"), py::arg("t"), "translates c by t - s");
    m.def("MatchPoints", &MatchPoints, py::arg("c"), py::arg("s1"), py::arg("s2"), py::arg("t1"), py::arg("t2"),
          "the similarity sending s1 to t1 and s2 to t2");
    m.def("PointLabeled", &PointLabeled, py::arg("c"), py::arg("label"));
    m.def("CurveLabeled", &CurveLabeled, py::arg("c"), py::arg("label"));
    m.def("Labelled", &Labelled, py::arg("c"), py::arg("label"), "the curves with one more label");
    m.def("Polyline", &polyline, py::arg("points"), py::arg("closed") = false, "one polyline as curves");

    // ---- Planar maps and cells ----
    bind_cell<VertexTag>(m, "Vertex", "A vertex of a planar map (a handle: equal when the same cell)");
    bind_cell<EdgeTag>(m, "Edge", "An edge of a planar map");
    bind_cell<FaceTag>(m, "Face", "A face of a planar map").def("is_bounded_face", [](const Face& f) { return !record(f).unbounded; },
                                          "false for the unbounded face (outside every bounded face)");

    py::class_<PlanarMap, std::shared_ptr<PlanarMap>>(m, "PlanarMap", "An induced planar map (immutable)")
        .def_static("induce", [](const Curves& c) { return std::const_pointer_cast<PlanarMap>(PlanarMap::induce(c)); },
                    py::call_guard<py::gil_scoped_release>())
        .def("vertices", [](const std::shared_ptr<PlanarMap>& m) {
            std::vector<Vertex> out;
            for (std::size_t i = 0; i < m->vertices().size(); ++i) out.emplace_back(m, int(i));
            return out;
        })
        .def("edges", [](const std::shared_ptr<PlanarMap>& m) {
            std::vector<Edge> out;
            for (std::size_t i = 0; i < m->edges().size(); ++i) out.emplace_back(m, int(i));
            return out;
        })
        .def("faces", [](const std::shared_ptr<PlanarMap>& m) {
            std::vector<Face> out;  // bounded faces, as MapToFaces visits them
            for (std::size_t i = 0; i < m->faces().size(); ++i)
                if (!m->faces()[i].unbounded) out.emplace_back(m, int(i));
            return out;
        })
        .def("unbounded_face", [](const std::shared_ptr<PlanarMap>& m) { return Face(m, m->unbounded_face()); })
        .def("edge_curves", &PlanarMap::edge_curves);
    py::class_<FaceLocator>(m, "FaceLocator",
                            "Point location in a planar map: FaceLocator(map[, area]).face_at(p) is the face holding p "
                            "(the unbounded face outside every bounded one); built once, each query costs what the "
                            "faces near p cost")
        .def(py::init([](const std::shared_ptr<PlanarMap>& map, std::optional<BBox> area) {
                 return FaceLocator(map, area);
             }),
             py::arg("map"), py::arg("area") = std::nullopt, py::call_guard<py::gil_scoped_release>())
        .def("face_at", [](const FaceLocator& l, const Point& p) {
            return Face(l.shared_map(), l.face_at(p));
        }, py::arg("p"));

    // Table 3.4 built-ins: incidence, adjacency, geometry, labels, random.
    m.def("IncidentFaces", &IncidentFaces);
    m.def("IncidentEdges", py::overload_cast<const Vertex&>(&IncidentEdges));
    m.def("IncidentEdges", py::overload_cast<const Face&>(&IncidentEdges));
    m.def("IncidentVertices", &IncidentVertices);
    m.def("SourceVertex", &SourceVertex);
    m.def("TargetVertex", &TargetVertex);
    m.def("LeftFace", &LeftFace);
    m.def("RightFace", &RightFace);
    m.def("MatchFace", &MatchFace, py::arg("c"), py::arg("face"));
    m.def("Location", &Location);
    m.def("LocationAt", &LocationAt, py::arg("edge"), py::arg("s"));
    m.def("Centroid", &Centroid);
    m.def("Contour", &Contour);
    m.def("ToCurve", &ToCurve);
    m.def("ToRegion", &ToRegion);
    m.def("HasLabel", py::overload_cast<const Vertex&, const std::string&>(&HasLabel));
    m.def("HasLabel", py::overload_cast<const Edge&, const std::string&>(&HasLabel));
    m.def("HasLabel", py::overload_cast<const Face&, const std::string&>(&HasLabel));
    m.def("HasLabel", py::overload_cast<const std::vector<Vertex>&, const std::string&>(&HasLabel));
    m.def("HasLabel", py::overload_cast<const std::vector<Edge>&, const std::string&>(&HasLabel));
    m.def("HasLabel", py::overload_cast<const std::vector<Face>&, const std::string&>(&HasLabel));
    m.def("Labels", [](const Vertex& c) { return names(record(c).labels); }, "the labels of a cell");
    m.def("Labels", [](const Edge& c) { return names(record(c).labels); });
    m.def("Labels", [](const Face& c) { return names(record(c).labels); });
    m.def("IsBoundary", py::overload_cast<const Vertex&>(&IsBoundary));
    m.def("IsBoundary", py::overload_cast<const Edge&>(&IsBoundary));
    m.def("IsBoundary", py::overload_cast<const Face&>(&IsBoundary));
    m.def("Random", py::overload_cast<const Vertex&, double, double, double>(&Random), py::arg("cell"),
          py::arg("min"), py::arg("max"), py::arg("n"), "value in [min, max) keyed by the cell's geometry, n and the seed");
    m.def("Random", py::overload_cast<const Edge&, double, double, double>(&Random), py::arg("cell"), py::arg("min"),
          py::arg("max"), py::arg("n"));
    m.def("Random", py::overload_cast<const Face&, double, double, double>(&Random), py::arg("cell"), py::arg("min"),
          py::arg("max"), py::arg("n"));
    m.def("Random", py::overload_cast<double, double>(&Random), py::arg("min"), py::arg("max"),
          "value in [min, max): inside a mapper keyed by the visited cell, else a seeded stream");
    m.def("BBoxWidth", [](const Vertex& c) { return BBoxWidth(c); });
    m.def("BBoxWidth", [](const Edge& c) { return BBoxWidth(c); });
    m.def("BBoxWidth", [](const Face& c) { return BBoxWidth(c); });
    m.def("BBoxHeight", [](const Vertex& c) { return BBoxHeight(c); });
    m.def("BBoxHeight", [](const Edge& c) { return BBoxHeight(c); });
    m.def("BBoxHeight", [](const Face& c) { return BBoxHeight(c); });
    m.def("BBoxCenter", [](const Vertex& c) { return BBoxCenter(c); });
    m.def("BBoxCenter", [](const Edge& c) { return BBoxCenter(c); });
    m.def("BBoxCenter", [](const Face& c) { return BBoxCenter(c); });

    // ---- Arrangements ----
    py::class_<Arrangement>(m, "Arrangement", "A function from a region (or a face) to curves; lazy until called")
        .def(py::init<>())
        .def(py::init([](py::function fn) {
                 PyRef ref(std::move(fn));
                 return Arrangement([ref](const Region& r) -> Curves {
                     py::gil_scoped_acquire gil;
                     py::object out = ref.get()(r);
                     if (!py::isinstance<Curves>(out))
                         throw py::type_error("Arrangement: the function returned " + type_name(out) + ", not Curves");
                     return out.cast<const Curves&>();
                 });
             }),
             py::arg("fn"), "an arrangement from a Python function region -> Curves")
        .def("__call__", py::overload_cast<const Region&>(&Arrangement::operator(), py::const_),
             py::call_guard<py::gil_scoped_release>())
        .def("__call__", py::overload_cast<const Face&>(&Arrangement::operator(), py::const_),
             py::call_guard<py::gil_scoped_release>())
        .def("induce",
             [](const Arrangement& a, const Region& r) { return std::const_pointer_cast<PlanarMap>(a.induce(r)); },
             py::call_guard<py::gil_scoped_release>(), "evaluates and induces the planar map of the result");
    m.def("Constant", &Constant, "an arrangement returning fixed curves");

    // ---- Partitions (table 3.2) ----
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

    // ---- Mapping (table 3.3) and merging (table 3.5) ----
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
    m.def("Union", py::overload_cast<Arrangement, Arrangement>(&Union), py::arg("a1"), py::arg("a2"));
    m.def("Crop", &Crop, py::arg("a"), py::arg("border"),
          "a evaluated on the region and cut to it (CROP_ADD_BOUNDARY adds the region's labelled outline)");
    m.def("Outline", &Outline, "the region evaluated on as an arrangement: its labelled edges, else its rings");
    m.def("Merge", &Merge, py::arg("a1"), py::arg("a2"), "Union's name in the thesis's Chapter 4");
    m.def("Inside", py::overload_cast<Arrangement, Arrangement, Border>(&Inside), py::arg("a1"), py::arg("a2"), py::arg("border"));
    m.def("Outside", py::overload_cast<Arrangement, Arrangement, Border>(&Outside), py::arg("a1"), py::arg("a2"), py::arg("border"));

    // ---- SVG, seed, threads ----
    py::class_<SvgStyle>(m, "SvgStyle")
        .def(py::init([](double w, bool bg) { return SvgStyle{w, bg}; }), py::arg("stroke_width") = 2.0,
             py::arg("background") = true)
        .def_readwrite("stroke_width", &SvgStyle::stroke_width)
        .def_readwrite("background", &SvgStyle::background);
    m.def("ImportSVG", &ImportSVG, py::arg("filename"));
    m.def("ParseSVG", &ParseSVG, py::arg("text"), py::arg("origin") = "<svg text>");
    m.def("ToSVG", py::overload_cast<const Curves&, double, const SvgStyle&>(&ToSVG), py::arg("curves"), py::arg("size"), py::arg("style") = SvgStyle{});
    m.def("ExportSVG", py::overload_cast<const Arrangement&, double, const std::string&, const SvgStyle&>(&ExportSVG),
          py::arg("arrangement"), py::arg("size"), py::arg("filename"), py::arg("style") = SvgStyle{},
          py::call_guard<py::gil_scoped_release>(),
          "evaluates the arrangement on [0, size]^2 and writes it (atomically); returns the curves");
    m.def("ExportSVG", py::overload_cast<const Curves&, double, const std::string&, const SvgStyle&>(&ExportSVG),
          py::arg("curves"), py::arg("size"), py::arg("filename"), py::arg("style") = SvgStyle{},
          py::call_guard<py::gil_scoped_release>());
    m.def("FrameRegion", &FrameRegion, py::arg("frame"), py::arg("op") = "FrameRegion",
          "the region bounded by the frame's closed curves (the largest one outside, those inside it holes)");
    m.def("EvaluateInDomain", &EvaluateInDomain, py::arg("arrangement"), py::arg("frame"),
          py::call_guard<py::gil_scoped_release>(),
          "the arrangement evaluated in the frame's region, cut to it, with the frame's outline");
    m.def("InDomain", &InDomain, py::arg("arrangement"), py::arg("frame"),
          "an arrangement returning EvaluateInDomain(arrangement, frame) whatever the region");
    m.def("ExportSVGinDomain", &ExportSVGinDomain, py::arg("arrangement"), py::arg("frame"), py::arg("filename"),
          py::arg("margin") = 10.0, py::arg("style") = SvgStyle{}, py::call_guard<py::gil_scoped_release>(),
          "fills the frame: the arrangement evaluated in the frame's region, cut to it, with the frame's outline, "
          "written (atomically) with a viewBox covering the frame grown by margin; returns the curves");
    m.def("SetSeed", &SetSeed, py::arg("seed"),
          "sets the global seed and restarts the numbering of the partitions' random streams");
    m.def("GetSeed", &GetSeed);
    bind_guard<SeedScope>(m, "SeedScope", "seed",
                          "with SeedScope(seed): GetSeed() is seed on this thread (and its work items) inside");
    bind_guard<StreamScope>(m, "StreamScope", "key",
                            "with StreamScope(key): the numbering of random streams restarts under key inside");
    bind_guard<SavedSeed>(m, "SavedSeed", nullptr,
                          "with SavedSeed(): the global seed (SetSeed) and this thread's numbering of random streams "
                          "are put back at the end");
    m.def("hash_combine", &hash_combine, py::arg("h"), py::arg("v"), "the 64-bit mix libtex keys streams with");
    m.def("SetThreads", &SetThreads, py::arg("n"), "worker threads (0: all cores); never changes the result");
    m.def("GetThreads", &GetThreads);
}

}  // namespace rhpy
