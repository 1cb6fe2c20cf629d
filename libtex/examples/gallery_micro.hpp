// Appendix A's last script, "Microprocessor": circuit traces, chips and solder joints,
// written with libtex.
//
// Level 1 scatters twelve traces, each on its own random partition, their "start" point on
// the cell's centroid snapped to a 50 grid; level 2 puts a chip (an outline whose inside is
// labelled "ship") on the snapped centroid of the cells of a sparse uniform partition. The
// board is the traces outside the chips with the chips' outlines added; on its vertices a
// pad goes where a trace enters a chip and a solder joint on every free end. The layers
// are functions so that the tests can check the drawing against them. Elements are loaded
// from `dir`.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "libtex/tex.hpp"

namespace gallery::micro {

// The grid the traces and chips snap to, and the snap (step * floor(x / step)).
inline constexpr double kStep = 50;
tex::Point snap(const tex::Point& p);

// ---- Level 1: traces ----
// The thesis's five densities (sites per unit area) divided by kTraceThinning: at the
// thesis's values each of the 1600 grid points of the window would get nearly every trace
// (about 87000 traces); thinned, about 870.
inline constexpr double kTraceThinning = 100;
inline constexpr std::array<double, 5> kTraceDensities = {0.002, 0.00175, 0.00125, 0.00225, 0.001};
// Density index of mp_net1.svg .. mp_net12.svg (the thesis's table).
inline constexpr std::array<int, 12> kTraceDensityOf = {0, 0, 1, 0, 1, 1, 2, 1, 0, 3, 3, 4};
// Trace i (1..12) on its own RandomPartition, "start" on each cell's snapped centroid.
tex::Arrangement trace_layer(const std::string& dir, int i);
// The twelve layers merged in order.
tex::Arrangement traces(const std::string& dir);

// ---- Level 2: chips ----
inline constexpr double kChipDensity = 8.0 / (2000.0 * 2000.0);
inline constexpr int kChipKinds = 6;
// The chip of a face: kind floor(Random(f, 0, 6, 0)), scale 1 + floor(Random(f, 0, 4, 1))
// (the thesis's floor(Random(f, 0, 4, 0)) leaves a quarter of its few cells empty, and
// draws the scale from the same number as the kind), its bounding-box centre on the
// face's snapped centroid.
tex::Curves chip_on(const std::vector<tex::Curves>& kinds, const tex::Face& f);
tex::Arrangement chips(const std::string& dir);

// ---- The board and its pads ----
// Outside(traces, chips, CROP_ADD_BOUNDARY): the chips' outlines come back with "ship".
tex::Arrangement board(const std::string& dir);
// A trace entering a chip: three incident edges and an incident face labelled "ship".
bool is_connector(const tex::Vertex& v);
// A free end: one incident edge.
bool is_joint(const tex::Vertex& v);
// Connectors and joints on the board's vertices.
tex::Arrangement pads(const std::string& dir);
// Outside(board, pads, CROP_ADD_BOUNDARY).
tex::Arrangement microprocessor(const std::string& dir);

}  // namespace gallery::micro
