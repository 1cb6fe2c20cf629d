// rockhatch.tex, planar maps and what runs on them: the cells (Vertex, Edge, Face) and
// their labels, PlanarMap, FaceLocator, the built-ins of table 3.4, and Arrangement.
#include <memory>

#include "tex_bindings.hpp"

namespace rhpy {
namespace {

using namespace tex;

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

}  // namespace

// Planar maps and their cells.
void add_cell_bindings(py::module_& m) {
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
}

// Table 3.4 built-ins: incidence, adjacency, geometry, labels, random.
void add_builtin_bindings(py::module_& m) {
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
    m.def("LocationAt", py::overload_cast<const Edge&, double>(&LocationAt), py::arg("edge"), py::arg("s"));
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
}

// Arrangements: functions from a region (or a face) to curves.
void add_arrangement_bindings(py::module_& m) {
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
}

}  // namespace rhpy
