// Shared declarations of the Python bindings.
//
// Threads and the GIL: every binding that may evaluate an arrangement or run the pipeline
// releases the GIL, and every Python callable handed to C++ (mapper, field, style,
// progress) takes it back while it runs. The engine may call those from several worker
// threads: they then take turns on the GIL, and results stay in cell order, so the output
// is the one of a single-threaded run.
#pragma once

#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl_bind.h>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "carto/styles.hpp"
#include "libtex/tex.hpp"

namespace py = pybind11;

// Point lists stay C++ vectors in Python (no copy to lists and back between two C++
// calls): Points (a polyline or ring), Lines (several polylines), Hatches.
PYBIND11_MAKE_OPAQUE(std::vector<tex::Point>)
PYBIND11_MAKE_OPAQUE(std::vector<std::vector<tex::Point>>)
PYBIND11_MAKE_OPAQUE(std::vector<carto::Hatch>)

namespace rhpy {

// A Python object that C++ may copy and drop on any thread: the reference is released
// under the GIL.
class PyRef {
public:
    PyRef() = default;
    explicit PyRef(py::object o)
        : ref_(new py::object(std::move(o)), [](py::object* p) {
              py::gil_scoped_acquire gil;
              delete p;
          }) {}
    const py::object& get() const { return *ref_; }
    explicit operator bool() const { return ref_ && *ref_; }

private:
    std::shared_ptr<py::object> ref_;
};

// Name of a Python object's type, for messages.
inline std::string type_name(const py::handle& o) { return py::str(py::type::of(o).attr("__name__")); }

// Anything usable as a field: a Field, a number, a callable of a Point (it takes the GIL
// when read), or what a registered converter accepts (carto adds its Raster).
using FieldConverter = std::function<std::optional<tex::Field>(const py::object&)>;
void add_field_converter(FieldConverter c);
tex::Field to_field(const py::object& o);

// A Python callable as a mapper. The result must be Curves: anything else is a TypeError
// naming the operator and what came back.
template <class CellT>
std::function<tex::Curves(const CellT&)> mapper(py::function fn, const char* op) {
    PyRef ref(std::move(fn));
    return [ref, op](const CellT& cell) -> tex::Curves {
        py::gil_scoped_acquire gil;
        py::object r = ref.get()(cell);
        if (py::isinstance<tex::Curves>(r)) return r.cast<const tex::Curves&>();
        throw py::type_error(std::string(op) + ": the mapper returned " + type_name(r) +
                             "; a mapper must return Curves (Nothing() for no curves)");
    };
}

void bind_tex(py::module_& m);
void bind_tiled(py::module_& m);
void bind_fields(py::module_& m);
void bind_synthesis(py::module_& m);
void bind_carto(py::module_& m);
void bind_blocks(py::module_& m);
void bind_discrete(py::module_& m);

}  // namespace rhpy
