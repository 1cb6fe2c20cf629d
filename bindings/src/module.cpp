// rockhatch._rockhatch: the compiled part of the Python package. The pure-Python package
// (bindings/python/rockhatch) re-exports it as rockhatch.tex, rockhatch.discrete and
// rockhatch.carto.
#include "common.hpp"

#include "carto/error.hpp"

namespace {

template <class Exc>
void raise(PyObject* type, const Exc& e) {
    py::object err = py::reinterpret_borrow<py::object>(type)(e.what());
    if constexpr (std::is_same_v<Exc, carto::Error>) {
        err.attr("code") = e.exit_code();
    } else {
        err.attr("op") = e.op();
    }
    PyErr_SetObject(type, err.ptr());
}

}  // namespace

PYBIND11_MODULE(_rockhatch, m) {
    m.doc() = "rockhatch: programmable element arrangements (tex) and rock hatching (carto)";

    py::bind_vector<std::vector<tex::Point>>(m, "Points", "A list of points kept as a C++ vector (polyline or ring)");
    py::bind_vector<std::vector<std::vector<tex::Point>>>(m, "Lines", "A list of polylines kept as a C++ vector");
    py::implicitly_convertible<py::list, std::vector<tex::Point>>();
    py::implicitly_convertible<py::tuple, std::vector<tex::Point>>();
    py::implicitly_convertible<py::list, std::vector<std::vector<tex::Point>>>();

    // Errors: libtex's name the operator (TexError, a ValueError: bad values given to an
    // operator); carto's carry the rockhatch exit code (RockhatchError.code).
    static py::handle tex_error =
        PyErr_NewExceptionWithDoc("rockhatch.TexError", "An operator of libtex refused its input; .op names it.",
                                  PyExc_ValueError, nullptr);
    static py::handle carto_error = PyErr_NewExceptionWithDoc(
        "rockhatch.RockhatchError",
        "The rock-hatching pipeline refused its input; .code is the exit code of the rockhatch command.",
        PyExc_RuntimeError, nullptr);
    m.attr("TexError") = tex_error;
    m.attr("RockhatchError") = carto_error;
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const carto::Error& e) {
            raise(carto_error.ptr(), e);
        } catch (const tex::Error& e) {
            raise(tex_error.ptr(), e);
        }
    });

    py::module_ tex = m.def_submodule("tex", "libtex: planar maps, partitions, mappers and merges (thesis Ch. 3)");
    rhpy::bind_tex(tex);
    rhpy::bind_fields(tex);
    rhpy::bind_tiled(tex);
    py::module_ discrete =
        m.def_submodule("discrete", "libtex's discrete operator set (seed 004): pinning, dart throwing, stream lines");
    rhpy::bind_discrete(discrete);
    rhpy::bind_synthesis(tex);
    py::module_ carto = m.def_submodule("carto", "carto: rasters, control fields, styles and the rock-hatching pipeline");
    rhpy::bind_carto(carto);
    py::module_ blocks = carto.def_submodule("blocks", "the building blocks of the rock styles");
    rhpy::bind_blocks(blocks);
}
