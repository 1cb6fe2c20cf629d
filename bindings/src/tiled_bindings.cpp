// rockhatch.tex, tiled planar maps (thesis Ch. 4): the same names as in C++ (tiled.hpp).
// A partition given Tiled(border) returns a TiledMap; MapToVertices / MapToEdges /
// MapToFaces, Union and GhostMap on a TiledMap return one; a TiledMap is accepted wherever an
// Arrangement is (converted with the border mode of its Tiled).
#include "common.hpp"

namespace rhpy {

using namespace tex;

namespace {

// MapToVertices / MapToEdges / MapToFaces on a tiled map with a Python mapper.
template <class CellT>
void bind_tiled_mapping(py::module_& m, const char* name,
                        TiledMap (*op)(std::function<Curves(const CellT&)>, const TiledMap&, MapperThreads),
                        const char* doc) {
    m.def(
        name,
        [op, name](py::function f, const TiledMap& a) {
            auto fn = mapper<CellT>(std::move(f), name);
            py::gil_scoped_release release;
            return op(fn, a, MapperThreads::Serial);
        },
        py::arg("mapper"), py::arg("arrangement"), doc);
}

}  // namespace

void bind_tiled(py::module_& m) {
    py::class_<Tiled>(m, "Tiled",
                      "Asks a partition for its tiled form; `border` is the mode of its implicit conversion")
        .def(py::init<Border>(), py::arg("border") = Border::KEEP_OUTSIDE)
        .def_readwrite("border", &Tiled::border);

    py::class_<TiledElement>(m, "TiledElement", "One copy of an element met at conversion, as a ghost mapper sees it")
        .def_readonly("curves", &TiledElement::curves)
        .def_readonly("anchor", &TiledElement::anchor)
        .def_readonly("i", &TiledElement::i)
        .def_readonly("j", &TiledElement::j)
        .def_readonly("key", &TiledElement::key);
    m.def("Random", py::overload_cast<const TiledElement&, double, double, double>(&Random), py::arg("element"),
          py::arg("min"), py::arg("max"), py::arg("n"),
          "deterministic value in [min, max) for a copy of an element (its key, n and the seed)");

    py::class_<TiledMap>(m, "TiledMap",
                         "A periodic arrangement stored once per period (thesis Ch. 4); converted over any region")
        .def_property_readonly("period1", &TiledMap::period1)
        .def_property_readonly("period2", &TiledMap::period2)
        .def_property_readonly("border", &TiledMap::border)
        .def_property_readonly("element_count", [](const TiledMap& t) { return t.elements().size(); })
        .def("Convert", &TiledMap::Convert, py::arg("region"), py::arg("border"),
             py::call_guard<py::gil_scoped_release>(),
             "the curves over the region with that border mode (local: a window's curves do not depend on "
             "the rest of the region)")
        .def("__call__", &TiledMap::operator(), py::arg("region"), py::call_guard<py::gil_scoped_release>(),
             "Convert(region, border of its Tiled)")
        .def("arrangement", [](const TiledMap& t) { return Arrangement(t); },
             "the plain Arrangement (converted with the border mode of its Tiled)")
        .def("DistanceToCurves", &TiledMap::DistanceToCurves, py::arg("p"),
             "distance to the nearest curve of the infinite arrangement")
        .def("FaceLabelsAt", [](const TiledMap& t, const Point& p) { return t.FaceLabelsAt(p).names(); },
             py::arg("p"), "labels of the face containing p");
    py::implicitly_convertible<TiledMap, Arrangement>();

    m.def("GridPartition", py::overload_cast<const Stripes&, const Stripes&, Tiled>(&GridPartition), py::arg("s1"),
          py::arg("s2"), py::arg("border"), "the grid as a tiled map (border: Tiled(...))");
    m.def("StripesPartition", py::overload_cast<const Stripes&, Tiled>(&StripesPartition), py::arg("p"),
          py::arg("border"), "stripes as a tiled map (border: Tiled(...)); its faces are unbounded");
    // A Python mapper runs one call at a time (the interpreter's lock), as for planar maps.
    bind_tiled_mapping<Vertex>(m, "MapToVertices", &MapToVertices, "visits the vertices of the central tile");
    bind_tiled_mapping<Edge>(m, "MapToEdges", &MapToEdges, "visits the edges of the central tile");
    bind_tiled_mapping<Face>(m, "MapToFaces", &MapToFaces, "visits the bounded faces of the central tile");
    m.def(
        "GhostMap",
        [](py::function f, const TiledMap& a) {
            PyRef ref(std::move(f));
            GhostMapper g = [ref](const TiledElement& e) -> Curves {
                py::gil_scoped_acquire gil;
                py::object r = ref.get()(e);
                if (py::isinstance<Curves>(r)) return r.cast<const Curves&>();
                throw py::type_error("GhostMap: the mapper returned " + type_name(r) +
                                     "; a mapper must return Curves (Nothing() for no curves)");
            };
            return GhostMap(std::move(g), a);
        },
        py::arg("mapper"), py::arg("arrangement"),
        "a last mapper, called on every copy of every element at conversion (it may use Random)");
    m.def("Union", py::overload_cast<const TiledMap&, const TiledMap&>(&Union), py::arg("a1"), py::arg("a2"),
          "all elements of both; periods of the result: the least common multiples");
    m.def("Inside", py::overload_cast<const TiledMap&, const TiledMap&, Border>(&Inside), py::arg("a1"),
          py::arg("a2"), py::arg("border"), py::call_guard<py::gil_scoped_release>(),
          "the curves of a1 inside the bounded faces of a2, on their common lattice");
    m.def("Outside", py::overload_cast<const TiledMap&, const TiledMap&, Border>(&Outside), py::arg("a1"),
          py::arg("a2"), py::arg("border"), py::call_guard<py::gil_scoped_release>(),
          "the curves of a1 outside the bounded faces of a2, on their common lattice");
    m.def(
        "Rasterize",
        [](const TiledMap& t, const Region& window, double pixel, double line_width) {
            Raster r;
            {
                py::gil_scoped_release release;
                r = Rasterize(t, window.bbox(), pixel, line_width);
            }
            py::array_t<std::uint8_t> out({r.height, r.width});
            std::copy(r.pixels.begin(), r.pixels.end(), out.mutable_data());
            return out;
        },
        py::arg("map"), py::arg("window"), py::arg("pixel"), py::arg("line_width"),
        "a grey image (rows from the top, 255 paper, 0 ink) of the window's box, `pixel` units per pixel");
}

}  // namespace rhpy
