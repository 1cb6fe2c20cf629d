// Figures 1a to 1g of seed 004 ("discrete texture design using a programmable approach"),
// written with libtex's discrete operator set (libtex/discrete.hpp) in a 2000 x 2000 image.
//
// Each figure is a function returning its sets of regions, so that the tests can check
// the properties that define it (no overlap, counts, distances); the gallery draws their
// outlines. Sizes are the seed's programs scaled to the gallery's window; the counts are
// the seed's numbers of darts thrown.
#pragma once

#include <string>

#include "libtex/tex.hpp"

namespace gallery::discrete {

// Sizes in the 2000 window.
inline constexpr double kHatchLength = 60, kHatchWidth = 8;
inline constexpr double kRectWidth = 300, kRectHeight = 200;
inline constexpr double kCircleRadius = 36;
// Circle distribution: darts thrown, Lloyd iterations.
inline constexpr long long kCircleDarts = 600;
inline constexpr long long kRelaxSteps = 8;
// Stream lines: step of the flow field, largest length, width at the middle, and the gap
// kept between two lines of one set.
inline constexpr double kFlowStep = 5, kStreamLength = 420, kStreamWidth = 7, kStreamGap = 4;

// The regions of a figure, each set by its name in the seed's program.
struct Figure {
    tex::disc::RegionSet main;   // what the seed displays (hatches, shapes, stream lines)
    tex::disc::RegionSet other;  // second set: rectangles (1b), orthogonal hatches (1c),
                                 // relaxed circles (1f), second stream lines (1g)
};

tex::Region image();

// 1a: anisotropic dart throwing of hatches.
Figure fig_1a();
// 1b: 25 rectangles on a 5 x 5 grid, then hatches touching them (main: hatches, other: rectangles).
Figure fig_1b();
// 1c: 1b's hatches, then orthogonal hatches overlapping neither (other: orthogonal hatches).
Figure fig_1c();
// 1d: a user shape (leaf.svg from `elements`), turned and scaled at random.
Figure fig_1d(const std::string& elements);
// The circle distribution of 1e to 1g: dart-thrown circles relaxed by Lloyd steps on their
// Voronoi cells (main: relaxed circles, other: the circles before relaxation).
Figure circle_distribution();
// 1e: the Voronoi cells of the relaxed circles, each scaled by a random factor.
Figure fig_1e();
// 1f: relaxed circles (other) and stream lines between them (main).
Figure fig_1f();
// 1g: stream lines pinned along the circles' contours at 30 degrees to the flow (main), and
// a second set pinned along their contours, following the flow (other).
Figure fig_1g();

// The figures as arrangements for the gallery (outlines of both sets).
tex::Arrangement arrangement_1a(const std::string& elements);
tex::Arrangement arrangement_1b(const std::string& elements);
tex::Arrangement arrangement_1c(const std::string& elements);
tex::Arrangement arrangement_1d(const std::string& elements);
tex::Arrangement arrangement_1e(const std::string& elements);
tex::Arrangement arrangement_1f(const std::string& elements);
tex::Arrangement arrangement_1g(const std::string& elements);

}  // namespace gallery::discrete
