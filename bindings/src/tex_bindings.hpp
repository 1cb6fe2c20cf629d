// Private header of the rockhatch.tex bindings: the areas bind_tex registers, one function
// each, and the helpers several areas share.
#pragma once

#include <string>
#include <vector>

#include "common.hpp"

namespace rhpy {

// The names of a set of labels, as Python sees them.
inline std::vector<std::string> names(const tex::Labels& l) { return l.names(); }

// The areas of rockhatch.tex, in the order bind_tex calls them: a class is registered before
// the functions whose signatures or defaults use it.
void add_geometry_bindings(py::module_& m);            // tex_geometry_bindings.cpp
void add_curve_bindings(py::module_& m);               // tex_geometry_bindings.cpp
void add_cell_bindings(py::module_& m);                // tex_cell_bindings.cpp
void add_builtin_bindings(py::module_& m);             // tex_cell_bindings.cpp
void add_arrangement_bindings(py::module_& m);         // tex_cell_bindings.cpp
void add_partition_operator_bindings(py::module_& m);  // tex_operator_bindings.cpp
void add_mapping_bindings(py::module_& m);             // tex_operator_bindings.cpp
void add_merge_bindings(py::module_& m);               // tex_operator_bindings.cpp
void add_svg_bindings(py::module_& m);                 // tex_bindings.cpp
void add_seed_bindings(py::module_& m);                // tex_bindings.cpp

}  // namespace rhpy
