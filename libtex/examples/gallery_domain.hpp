// Appendix A's scripts that fill an outline (ExportSVGinDomain): Parquetry, Table, Bottle
// and Teapot, written with libtex.
//
// The thesis exports each texture cut to a frame (an SVG outline). Here the frame is drawn
// in the gallery's 2000 window and each example returns InDomain(texture, frame): an
// arrangement that, whatever the window, is the texture evaluated on the frame's region,
// cut to it, with the frame's outline. The layers are functions so that the tests can
// check the drawing against them. Elements and frames are loaded from `dir`.
#pragma once

#include <string>

#include "libtex/tex.hpp"

namespace gallery::domain {

// ---- Parquetry: slats of a herringbone-like floor ----
// A grid of horizontal stripes (50, 10, 50, 10: labels h1 to h4) and stripes at about 37
// degrees (400, 10, 400, 10: v1 to v4), cells meeting the region kept.
tex::Arrangement parquet_grid();
// True when the edge between two bounded faces is dropped: its two faces' labels make one
// of the slat rules (two v stripes and an h stripe, or two h stripes and a v stripe, as in
// the thesis's table of sixteen cases).
bool parquet_joint(const tex::Edge& e);
// The grid with those edges dropped: slats with gaps between them.
tex::Arrangement parquet_slats();
tex::Arrangement parquetry(const std::string& dir);

// ---- Table: wood grain on an oval table top ----
// Lines at 60 degrees (60 apart) and 120 degrees (150 apart); on each vertex one of three
// grain elements (chosen at random), moved by up to 20 across and 80 along at random.
tex::Arrangement table_grain(const std::string& dir);
tex::Arrangement table(const std::string& dir);

// ---- Bottle: bubbles in a bottle ----
// The same with a 60 x 60 grid turned by 90 degrees and four bubble elements, moved by up
// to 20 and 40.
tex::Arrangement bottle_bubbles(const std::string& dir);
tex::Arrangement bottle(const std::string& dir);

// ---- Teapot: dots of random sizes on a uniform partition ----
// A uniform partition (3e-4 sites per unit area); on each face's centroid a ring scaled
// by a random factor in [0.05, 0.15).
inline constexpr double kTeapotDensity = 3.0e-4;
tex::Arrangement teapot_dots(const std::string& dir);
tex::Arrangement teapot(const std::string& dir);

// The frames (libtex/examples/elements).
inline constexpr const char* kParquetryFrame = "carpet_outline.svg";
inline constexpr const char* kTableFrame = "table_top.svg";
inline constexpr const char* kBottleFrame = "bottle_outline.svg";
inline constexpr const char* kTeapotFrame = "teapot_outline.svg";

}  // namespace gallery::domain
