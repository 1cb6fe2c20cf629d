// The terrain styles drawn around the rock faces (issue 13, "cartography built from these
// operators"): scree and slope hachures, each a program of tex::disc operators (seed 004),
// and the grid helpers they share. Everything here reads the DEM's own grid (north-up, in
// the working CRS). The programs are dart throwing, where each dart depends on the darts
// kept before it: the slope hachures run band after band; the scree runs tiles that cannot
// reach each other in parallel, each from a stream of its own, joined in a fixed order. The
// output does not depend on the thread count.
#pragma once

#include <memory>
#include <vector>

#include "carto/styles.hpp"
#include "libtex/discrete.hpp"

namespace carto::terrain {

// One built-in terrain style: its description and its program.
struct Builtin {
    StyleInfo info;
    TerrainProgram program;
};
Builtin scree();
Builtin slope_hachures();

// Distance (ground units) from every cell centre of `like` to the nearest cell inside a
// rock face, and the elevation of that rock cell (8-neighbour propagation of the nearest
// rock cell, exact distance to it: within a cell of the Euclidean distance). Cells with no
// rock anywhere get +inf and NaN.
struct RockProximity {
    Raster distance;
    Raster rock_elevation;
};
RockProximity rock_proximity(const Partition& p, const Raster& elevation);

// A raster on the grid of `like`, 1 in the cells whose centre passes `keep`, else 0; NaN
// where `like` is NoData.
Raster cell_mask(const Raster& like, const std::function<bool(int col, int row)>& keep);

// Whether the cell of `mask` containing p holds 1 (false outside and in NoData).
inline bool in_mask(const Raster& mask, const Point& p) { return mask.nearest(p) == 1.0; }

// The fall line: at p, a displacement of length `step` straight down the slope of the
// elevation (central differences over one cell, bilinear samples); zero where a sample is
// NoData or the ground is flat, which ends a stream line there.
tex::disc::FlowField fall_line(std::shared_ptr<const Raster> elevation, double step);

// The rock hatches as obstacles: each stroke thickened to its drawn width plus twice
// `clearance`, so that an element at distance > 0 from the set keeps `clearance` from the
// ink of every hatch.
tex::disc::RegionSet hatch_obstacles(const std::vector<Hatch>& rock, double scale, double clearance,
                                     const tex::BBox& near);

// The frame of the raster (its valid and NoData cells alike) as a region.
tex::Region frame(const Raster& r);

// (v - lo) / (hi - lo) clamped to [0, 1] (0 for NaN).
double ramp(double v, double lo, double hi);

// The weight of the ground 0..1 that makes the elements denser, larger or heavier: the slope
// ramped from slope_min to slope_max, mixed with the darkness (1 - hillshade) by `shade`.
using Weight = std::function<double(const Point&)>;
Weight ground_weight(const Terrain& t, double slope_min, double slope_max, double shade);

// The check "every vertex of the region's outer ring passes `inside`".
tex::disc::Check all_vertices(tex::disc::PointCheck inside);

// Throws Error(Usage) "--param lo_name: ... must not exceed hi_name" when lo > hi.
void require_order(const char* style, const char* lo_name, double lo, const char* hi_name, double hi);

// An element as a closed ring of its family.
Hatch ring_hatch(const tex::Region& r, Family f);

}  // namespace carto::terrain
