// Ridges and thalwegs from flow on the (inverted) DEM: flow directions and contributing
// area, channel heads, pruning, heads prolonged along their floor or crest, and the network
// traced into polylines (step 2 of carto/extract.hpp).
#pragma once

#include <cstddef>
#include <vector>

#include "carto/partition.hpp"
#include "carto/raster.hpp"
#include "grid.hpp"

namespace carto::extraction {

// Flow on a surface: every cell's D8 direction (index of the steepest lower neighbour, -1
// for sinks), used to trace lines, and its contributing area by multiple flow directions
// (Freeman: shared among the lower neighbours in proportion to slope^1.1), which follows the
// true gradient on planar flanks instead of D8's straight parallel paths.
//
// Depressions are found by priority flood from the edges and the NoData border. Those at most
// `max_fill` deep are filled and drain through their spill point along the flood's order;
// deeper ones (on the inverted DEM: summits) are kept and are sinks.
struct Flow {
    std::vector<int> down;
    std::vector<double> area;
};

Flow flow(const Grid& g, const std::vector<float>& z, double dx, double dy, double max_fill);

// Contributing area of a cell over the mean of its two neighbours across its D8 direction:
// 1 on a planar flank (where MFD area only grows with the flow length), larger in a hollow.
double convergence(const Grid& g, const Flow& f, std::size_t i);

// The channel network: cells whose contributing area reaches the threshold and where flow
// converges (the area is at least `converge` x the mean of the two neighbours across the D8
// direction: on a planar flank, where MFD area only grows with the flow length, it is equal),
// each followed down its D8 path while the area stays above the threshold: 1-cell wide lines.
std::vector<char> channels(const Grid& g, const Flow& f, double threshold, double converge,
                           const std::vector<char>& edge, int near);

// Removes first-order branches (from a head down to the first junction with another line)
// that are shorter than `min_cells`, or that run for most of their length within `near`
// cells of a line draining more: the short or parallel paths drawn on a wall beside a thalweg.
void prune_spurs(const Grid& g, const Flow& f, std::vector<char>& ch, int min_cells, int near);

// Cross-profile concavity of a surface at each cell: its height minus the mean of the two
// points `dist` away along the contour line (across the fall line). Negative on a valley
// floor, positive on a crest, about 0 on a planar flank.
std::vector<float> concavity(const Grid& g, const std::vector<float>& z, double dx, double dy,
                             double dist);

// Prolongs each head of a network upstream along its valley floor: to the higher neighbour
// (8 around) that is most concave, while concave by at least `depth` (two cells' tolerance),
// for at most `max_cells`; where the floor fades (near a col or a summit) the walk finishes
// by steepest ascent over at most `finish` cells. Kept only when it reaches a cell of `stop`
// (the other lines), or leaves the rock for the `open` non-rock, or comes next to the grid's
// edge (the edge cell joins the line), so the line cuts the rock area instead of dangling in
// it. Holes of the rock (non-rock that is not `open`) are crossed, as a line ending in one
// seldom cuts its face; if the walk then gets nowhere, it is kept up to the hole. A head in a
// hole first walks into the rock.
// Kept steps are linked downstream in `down`, so the network can be traced along them; those
// of the steepest finish are set in `straight` (they cut the rock but follow no crest or floor).
void extend_heads(const Grid& g, std::vector<int>& down, std::vector<char>& ch,
                  std::vector<char>& straight, const std::vector<float>& z,
                  const std::vector<float>& conc, double depth, const std::vector<char>& stop,
                  const std::vector<char>& rock, const std::vector<char>& open, int max_cells,
                  int finish);

// The network cells inside the rock traced into polylines: from each head down the D8
// directions to a junction (included) or out of the rock; simplified.
std::vector<LabelledLine> trace_network(const Grid& g, const std::vector<int>& down,
                                        const std::vector<char>& ch, const std::vector<char>& rock,
                                        LineKind kind, const Raster& grid, double tol);

}  // namespace carto::extraction
