// rockhatch.tex control fields: Field, VectorField, their compositions, and the locality
// check as context managers. rockhatch.carto.Field is this same class (carto adds its
// raster constructors to it).
#include <cmath>

#include <pybind11/operators.h>

#include "common.hpp"

namespace rhpy {
namespace {

using namespace tex;

std::vector<FieldConverter>& converters() {
    static std::vector<FieldConverter> all;
    return all;
}

// A Python callable of a Point returning T (None: no value); it takes the GIL on whatever
// thread reads it.
template <class Base, class T>
class PythonFn : public Base {
public:
    explicit PythonFn(py::object fn) : fn_(std::move(fn)) {}
    T eval(const Point& p) const override {
        py::gil_scoped_acquire gil;
        py::object v = fn_.get()(p);
        if (v.is_none()) {
            if constexpr (std::is_same_v<T, Point>) return Point{NAN, NAN};
            else return NAN;
        }
        return v.cast<T>();
    }

private:
    PyRef fn_;
};

class PythonField : public PythonFn<FieldImpl, double> {
public:
    using PythonFn::PythonFn;
    const char* kind() const override { return "python"; }
};
using PythonVectorField = PythonFn<VectorFieldImpl, Point>;

bool is_number(const py::handle& o) {
    return (py::isinstance<py::float_>(o) || py::isinstance<py::int_>(o)) && !py::isinstance<py::bool_>(o);
}

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

Field grid_field(const Array& a, const std::vector<double>& gt, std::optional<double> nodata) {
    if (a.ndim() != 2) throw py::value_error("Field.grid: a 2-D array is needed, got " + std::to_string(a.ndim()) + "-D");
    if (gt.size() != 6) throw py::value_error("Field.grid: the geotransform needs 6 numbers");
    GridSamples g;
    g.height = int(a.shape(0));
    g.width = int(a.shape(1));
    std::copy(gt.begin(), gt.end(), g.transform.begin());
    auto values = std::make_shared<std::vector<float>>(std::size_t(g.width) * g.height);
    const double* src = a.data();
    for (std::size_t i = 0; i < values->size(); ++i) {
        const double v = src[i];
        (*values)[i] = (nodata && v == *nodata) || !std::isfinite(v) ? NAN : float(v);
    }
    g.values = std::move(values);
    return GridField(std::move(g));
}

// A Python function of numbers, called under the GIL.
template <class... Args>
std::function<double(Args...)> numeric_fn(py::function fn) {
    PyRef ref(std::move(fn));
    return [ref](Args... v) -> double {
        py::gil_scoped_acquire gil;
        return ref.get()(v...).template cast<double>();
    };
}

// A Python context manager around a C++ scope object.
template <class Scope, class Arg>
struct PyScope {
    Arg arg;
    std::unique_ptr<Scope> live;
    void enter(const char* name) {
        if (live) throw py::value_error(std::string(name) + ": already entered");
        live = std::make_unique<Scope>(arg);
    }
};

struct PyLocality : PyScope<LocalityCheck, double> {
    std::size_t reads = 0, violations = 0;
    double worst = 0;
    void exit() {
        if (!live) return;
        reads = live->reads();
        violations = live->violations();
        worst = live->worst();
        live.reset();
    }
};
using PyWindow = PyScope<FieldWindow, BBox>;

template <class S>
void bind_scope(py::class_<S>& cls, const char* name) {
    cls.def(
           "__enter__", [name](S& s) -> S& {
               s.enter(name);
               return s;
           },
           py::return_value_policy::reference_internal)
        .def("__exit__", [](S& s, const py::args&) {
            if constexpr (std::is_same_v<S, PyLocality>) s.exit();
            else s.live.reset();
            return false;
        });
}

}  // namespace

void add_field_converter(FieldConverter c) { converters().push_back(std::move(c)); }

Field to_field(const py::object& o) {
    if (py::isinstance<Field>(o)) return o.cast<Field>();
    if (is_number(o)) return Field(o.cast<double>());
    for (const auto& c : converters())
        if (auto f = c(o)) return *f;
    if (PyCallable_Check(o.ptr())) return Field(std::make_shared<PythonField>(o));
    throw py::type_error("a field is a Field, a Raster, a number or a callable f(Point) -> float; got " + type_name(o));
}

void bind_fields(py::module_& m) {
    py::class_<Field> field(m, "Field",
                            "A control field: a value at every point of the plane, NaN where it has none");
    field.def(py::init<>(), "NaN everywhere")
        .def(py::init([](const py::object& o) { return to_field(o); }), py::arg("source"),
             "from a number, a callable f(Point) -> float (None: no value), another Field or a Raster")
        .def_static("constant", &ConstantField, py::arg("value"))
        .def_static(
            "function",
            [](py::function fn, std::optional<BBox> domain) {
                Field f(std::make_shared<PythonField>(std::move(fn)));
                return domain ? Restrict(f, *domain) : f;
            },
            py::arg("fn"), py::arg("domain") = py::none(), "a Python function of a Point, NaN outside the domain box")
        .def_static("grid", &grid_field, py::arg("array"), py::arg("geotransform"), py::arg("nodata") = py::none(),
                    "bilinear over a 2-D array (row 0 first) placed by a GDAL geotransform; cells equal to nodata "
                    "and non-finite cells have no value")
        .def_static(
            "faces",
            [](const std::shared_ptr<PlanarMap>& map, std::vector<double> values) { return FaceField(map, std::move(values)); },
            py::arg("map"), py::arg("values"), "values[face id] on each bounded face of a planar map")
        .def_static("faces", &RegionField, py::arg("regions"), py::arg("values"),
                    "values[i] inside regions[i], NaN outside all")
        .def_property_readonly("kind", [](const Field& f) { return std::string(f.kind()); },
                               "constant, function, python, grid, raster, faces, composite or none")
        .def("__call__", [](const Field& f, const Point& p) { return f(p); }, py::arg("p"))
        .def("__call__", [](const Field& f, double x, double y) { return f(x, y); }, py::arg("x"), py::arg("y"))
        .def("domain", &Field::domain, "the box where it may have values (None: anywhere)")
        .def("has_value", &Field::has_value, py::arg("p"))
        .def(
            "sample",
            [](const Field& f, const Array& xs, const Array& ys) {
                if (xs.size() != ys.size()) throw py::value_error("Field.sample: xs and ys differ in size");
                py::array_t<double> out(xs.size());
                const double *x = xs.data(), *y = ys.data();
                double* o = out.mutable_data();
                const py::ssize_t n = xs.size();
                auto run = [&] {
                    for (py::ssize_t i = 0; i < n; ++i) o[i] = f({x[i], y[i]});
                };
                if (std::string(f.kind()) == "python") {
                    run();
                } else {
                    py::gil_scoped_release release;  // Python parts take the GIL back themselves
                    run();
                }
                return out;
            },
            py::arg("xs"), py::arg("ys"), "values at many points (1-D arrays)")
        .def("__add__", [](const Field& a, const py::object& b) { return a + to_field(b); }, py::is_operator())
        .def("__radd__", [](const Field& a, const py::object& b) { return to_field(b) + a; }, py::is_operator())
        .def("__sub__", [](const Field& a, const py::object& b) { return a - to_field(b); }, py::is_operator())
        .def("__rsub__", [](const Field& a, const py::object& b) { return to_field(b) - a; }, py::is_operator())
        .def("__mul__", [](const Field& a, const py::object& b) { return a * to_field(b); }, py::is_operator())
        .def("__rmul__", [](const Field& a, const py::object& b) { return to_field(b) * a; }, py::is_operator())
        .def("__truediv__", [](const Field& a, const py::object& b) { return a / to_field(b); }, py::is_operator())
        .def("__rtruediv__", [](const Field& a, const py::object& b) { return to_field(b) / a; }, py::is_operator())
        .def("__neg__", [](const Field& a) { return -a; })
        .def("__repr__", [](const Field& f) { return std::string("Field(") + f.kind() + ")"; });
    py::implicitly_convertible<py::float_, Field>();
    py::implicitly_convertible<py::int_, Field>();
    py::implicitly_convertible<py::function, Field>();

    m.def("Apply", [](const py::object& f, py::function fn) { return Apply(to_field(f), numeric_fn<double>(fn)); },
          py::arg("f"), py::arg("fn"), "fn(value) where f has a value, NaN elsewhere");
    m.def(
        "Combine",
        [](const py::object& f, const py::object& g, py::function fn) {
            return Combine(to_field(f), to_field(g), numeric_fn<double, double>(fn));
        },
        py::arg("f"), py::arg("g"), py::arg("fn"), "fn(f, g) where both have a value, NaN elsewhere");
    m.def("Clamp", [](const py::object& f, double lo, double hi) { return Clamp(to_field(f), lo, hi); }, py::arg("f"),
          py::arg("lo"), py::arg("hi"));
    m.def("Pow", [](const py::object& f, double e) { return Pow(to_field(f), e); }, py::arg("f"), py::arg("exponent"),
          "value to the power exponent (NaN stays NaN)");
    m.def("Restrict", [](const py::object& f, const BBox& b) { return Restrict(to_field(f), b); }, py::arg("f"),
          py::arg("box"), "f inside the box, NaN outside");
    m.def("Restrict", [](const py::object& f, const Region& r) { return Restrict(to_field(f), r); }, py::arg("f"),
          py::arg("region"), "f inside the region (borders included), NaN outside");
    m.def("Fallback", [](const py::object& f, const py::object& g) { return Fallback(to_field(f), to_field(g)); },
          py::arg("f"), py::arg("g"), "f where it has a value, else g");
    m.def("Noise", &Noise, py::arg("wavelength"),
          "smooth noise of the plane in [-1, 1]: values at the nodes of a lattice `wavelength` apart, keyed by the "
          "node and the seed at the call, interpolated with a smoothstep");

    py::class_<VectorField>(m, "VectorField", "A vector at every point of the plane (NaN components: none)")
        .def(py::init<>())
        .def(py::init([](const py::object& x, const py::object& y) { return VectorField(to_field(x), to_field(y)); }),
             py::arg("x"), py::arg("y"), "from two scalar fields (numbers, callables, Fields)")
        .def(py::init([](const py::object& o) {
                 if (py::isinstance<VectorField>(o)) return o.cast<VectorField>();
                 if (py::isinstance<Point>(o) || py::isinstance<py::tuple>(o)) return VectorField(o.cast<Point>());
                 if (PyCallable_Check(o.ptr())) return VectorField(std::make_shared<PythonVectorField>(o));
                 throw py::type_error("a vector field is a VectorField, a Point or a callable f(Point) -> Point; got " +
                                      type_name(o));
             }),
             py::arg("source"))
        .def("__call__", [](const VectorField& v, const Point& p) { return v(p); }, py::arg("p"))
        .def("__call__", [](const VectorField& v, double x, double y) { return v({x, y}); }, py::arg("x"), py::arg("y"));
    m.def("AlignToField", &AlignToField, py::arg("a"), py::arg("angle"),
          "each open curve of the arrangement turned about its middle onto the axis the angle field (radians) "
          "gives there");
    m.def(
        "IsoLines", [](const py::object& f, double level, double cell) { return IsoLines(to_field(f), level, cell); },
        py::arg("field"), py::arg("level"), py::arg("cell"),
        "the level set field = level by marching squares on the global lattice of spacing `cell`, higher values on "
        "the left of each line");
    m.def(
        "Creases",
        [](const py::object& f, const std::string& kind, double cell, double min_bend) {
            if (kind != "ridge" && kind != "valley" && kind != "both")
                throw py::value_error("Creases: kind must be 'ridge', 'valley' or 'both' (got '" + kind + "')");
            const CreaseKind k =
                kind == "ridge" ? CreaseKind::Ridge : kind == "valley" ? CreaseKind::Valley : CreaseKind::Both;
            return Creases(to_field(f), k, cell, min_bend);
        },
        py::arg("field"), py::arg("kind"), py::arg("cell"), py::arg("min_bend"),
        "the ridge ('ridge') or valley ('valley') lines of a surface where it bends across them by at least "
        "min_bend (change of slope per unit length), traced on the global lattice of spacing `cell`; 'both': the "
        "two from one sampling, labelled 'ridge' and 'valley'");
    m.def("Angle", &Angle, py::arg("v"), "atan2 of the vectors");
    m.def("Norm", &Norm, py::arg("v"), "length of the vectors");
    m.def("Gradient", [](const py::object& f, double h) { return Gradient(to_field(f), h); }, py::arg("f"),
          py::arg("h"), "central differences with step h");

    py::class_<PyLocality> check(m, "LocalityCheck",
                                 "with LocalityCheck(margin) as c: counts field reads farther than margin outside "
                                 "the window of the reading thread (the visited cell, or a FieldWindow)");
    check.def(py::init([](double margin) { return PyLocality{{margin, nullptr}}; }), py::arg("margin") = 0.0)
        .def_property_readonly("reads", [](const PyLocality& c) { return c.live ? c.live->reads() : c.reads; })
        .def_property_readonly("violations",
                               [](const PyLocality& c) { return c.live ? c.live->violations() : c.violations; })
        .def_property_readonly("worst", [](const PyLocality& c) { return c.live ? c.live->worst() : c.worst; });
    bind_scope(check, "LocalityCheck");
    py::class_<PyWindow> window(m, "FieldWindow", "with FieldWindow(box): field reads of this thread are checked "
                                                  "against the box");
    window.def(py::init([](const BBox& b) { return PyWindow{b, nullptr}; }), py::arg("box"));
    bind_scope(window, "FieldWindow");
}

}  // namespace rhpy
