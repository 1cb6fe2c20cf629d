// rockhatch.carto, hatches and styles: the hatch families, a hatch and its building
// blocks; the built-in styles, Python styles, and the hatching of one face by a style.
#include "carto/partition.hpp"
#include "carto/styles.hpp"
#include "carto_bindings.hpp"

namespace rhpy {
namespace {

using namespace carto;

// A Python style: fn(fields, params) returns the arrangement drawn in each face (a program
// of libtex operators whose mappers may be Python functions). Faces are drawn on the
// engine's threads: every evaluation of an arrangement releases the interpreter's lock, so
// the native operators of one face (partitions, crops, stock mappers) run while another
// face's Python mapper holds it. `serial` draws them one after the other instead (a style
// whose time goes into Python code, see Style::serial). The drawing is the same either way.
// A digest of what a Python style function is made of, for the edit loop's fingerprints:
// the source of its module when it has one (the helpers the function calls change with it),
// else its own source, else its compiled code; a callable without code: its type's name.
std::string source_digest(const py::object& fn) {
    const py::module_ inspect = py::module_::import("inspect");
    py::object data = py::none();
    for (const char* what : {"module", "function"}) {
        try {
            const py::object of = std::string(what) == "module" ? inspect.attr("getmodule")(fn) : fn;
            if (!of.is_none()) data = inspect.attr("getsource")(of).attr("encode")("utf-8");
        } catch (const py::error_already_set&) {
        }
        if (!data.is_none()) break;
    }
    if (data.is_none()) {
        try {
            data = py::module_::import("marshal").attr("dumps")(fn.attr("__code__"));
        } catch (const py::error_already_set&) {
            data = py::str(py::type::of(fn).attr("__qualname__")).attr("encode")("utf-8");
        }
    }
    return py::module_::import("hashlib").attr("sha256")(data).attr("hexdigest")().cast<std::string>();
}

std::shared_ptr<const Style> python_style(StyleInfo info, py::object fn, bool serial) {
    auto s = std::make_shared<Style>();
    s->info = std::move(info);
    s->serial = serial;
    s->source_digest = source_digest(fn);
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

// Hatches and their building blocks.
void add_hatch_bindings(py::module_& m) {
    py::enum_<Family>(m, "Family")
        .value("FILL", Family::Fill)
        .value("RIDGE", Family::Ridge)
        .value("VALLEY", Family::Valley)
        .value("CROSS", Family::Cross)
        .value("STONE", Family::Stone)
        .value("HACHURE", Family::Hachure)
        .value("RIDGELINE", Family::RidgeLine)
        .value("COULOIR", Family::Couloir)
        .value("CLIFF", Family::Cliff);
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
    m.def("area_within", [](const tex::Region& face, const tex::Region& cell) { return face.area_within(cell); },
          py::arg("face"), py::arg("cell"),
          "area of the face (less its holes) inside the cell, whose outer ring is taken as convex");
    m.def("hatches_from_curves", py::overload_cast<const tex::Curves&>(&hatches_from_curves), py::arg("curves"),
          "libtex curves (an evaluated style) as hatches, their family read from their labels");
}

// Styles: their parameters and description, the built-in ones, Python ones.
void add_style_bindings(py::module_& m) {
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
}

}  // namespace rhpy
