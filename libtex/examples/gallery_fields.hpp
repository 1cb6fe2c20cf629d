// A control field steering an element (thesis 5.3, in the spirit of its Fig. 5.2), written
// with libtex's fields: darts on the faces of a uniform partition, each one turned by an
// analytic orientation field so that it points at the centre of the image.
//
// The pieces are the thesis's three roles, kept apart: the field (a closed form), the
// controlled mapper (element -> field -> face mapper) and the controlled arrangement
// (field -> arrangement), applied to the field at the end.
#pragma once

#include <string>

#include "libtex/tex.hpp"

namespace gallery::fields {

// Faces per unit area of the partition (about 400 darts in the 2000 window).
inline constexpr double kDartDensity = 1e-4;

// Direction (radians) from a point towards `target`: the angle of the vector field
// p -> target - p.
tex::Field towards(const tex::Point& target);
// Controlled mapper of one field: the element turned by the field's value at the face's
// centroid, its bounding box then centred on the centroid.
tex::ControlledFaceMapper turned_element(tex::Curves element);
// Controlled arrangement of one field: turned_element on every face of a uniform partition.
tex::ControlledArrangement turned_elements(tex::Curves element, double density);
// dart.svg on a uniform partition, pointing at the centre of the window.
tex::Arrangement darts(const std::string& dir);

}  // namespace gallery::fields
