// rockhatch.tex: every libtex operator and built-in under the thesis's names (tables 3.2 to
// 3.6), so that Appendix A scripts run after `from rockhatch.tex import *`. bind_tex
// registers it area by area (tex_bindings.hpp); this file holds the SVG input and output,
// the seed and its scopes, and the threads.
#include <memory>

#include "tex_bindings.hpp"

namespace rhpy {
namespace {

using namespace tex;

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

}  // namespace

void bind_tex(py::module_& m) {
    add_geometry_bindings(m);
    add_curve_bindings(m);
    add_cell_bindings(m);
    add_builtin_bindings(m);
    add_arrangement_bindings(m);
    add_partition_operator_bindings(m);
    add_mapping_bindings(m);
    add_merge_bindings(m);
    add_svg_bindings(m);
    add_seed_bindings(m);
}

// SVG: reading it, writing curves and arrangements, and framing a drawing in a domain.
void add_svg_bindings(py::module_& m) {
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
}

// The global seed, the scopes of the seed and of the random streams, and the worker threads.
void add_seed_bindings(py::module_& m) {
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
