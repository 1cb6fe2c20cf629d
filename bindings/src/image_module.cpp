// rockhatch._rockhatch_image: WriteImage for Python, in a module of its own.
//
// It is the only part of the Python package linked to OpenImageIO (through libtex_image), and
// rockhatch.tex imports it on the first call of WriteImage: importing rockhatch, and every
// script that writes no image, does not load OpenImageIO's libraries (some 150 of them).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>

#include "libtex/error.hpp"
#include "libtex/tiled_image.hpp"

namespace py = pybind11;

namespace {

// The array Rasterize returns (2-D, uint8, rows from the top) as a tex::Raster. Anything
// else is refused by name rather than converted silently.
tex::Raster raster_of(const py::array& image) {
    if (!py::isinstance<py::array_t<std::uint8_t>>(image) || image.dtype().kind() != 'u' || image.itemsize() != 1)
        throw tex::Error("WriteImage", "the image must be an array of uint8 (as Rasterize returns), not of " +
                                           std::string(py::str(image.dtype())));
    if (image.ndim() != 2)
        throw tex::Error("WriteImage", "the image must have 2 dimensions (rows, columns), not " +
                                           std::to_string(image.ndim()));
    tex::Raster r;
    r.height = int(image.shape(0));
    r.width = int(image.shape(1));
    // A C-contiguous copy whatever the strides of the array given.
    const auto contiguous = py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>::ensure(image);
    r.pixels.assign(contiguous.data(), contiguous.data() + contiguous.size());
    return r;
}

}  // namespace

PYBIND11_MODULE(_rockhatch_image, m) {
    m.doc() = "rockhatch: rasters written through OpenImageIO (loaded only by WriteImage)";

    // tex::Error becomes the package's TexError, as in the main module.
    static py::handle tex_error = py::object(py::module_::import("rockhatch._rockhatch").attr("TexError")).release();
    py::register_local_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const tex::Error& e) {
            py::object err = py::reinterpret_borrow<py::object>(tex_error)(e.what());
            err.attr("op") = e.op();
            PyErr_SetObject(tex_error.ptr(), err.ptr());
        }
    });

    m.def(
        "WriteImage",
        [](const py::array& image, const std::string& path) {
            const tex::Raster r = raster_of(image);
            py::gil_scoped_release release;
            tex::WriteImage(r, path);
        },
        py::arg("image"), py::arg("path"),
        R"doc(Write a grey image to a file through OpenImageIO.

Parameters
----------
image : numpy.ndarray
    2-D array of uint8, rows from the top (what ``Rasterize`` returns).
path : str
    File name; its extension chooses the format (``.png``, ``.tif``, ``.exr``... whatever
    OpenImageIO writes).

Raises
------
TexError
    When the array is not a 2-D uint8 image, or OpenImageIO cannot create or write the file
    (the message names the file).
)doc");
}
