// The terrain styles drawn around the rock faces (issue 13, "cartography built from these
// operators"): scree and slope hachures, each a program of tex::disc operators (seed 004),
// and the grid helpers they share. Everything here reads the DEM's own grid (north-up, in
// the working CRS). The programs are dart throwing, where each dart depends on the darts
// kept before it. Both throw over one grid of tiles anchored at the origin of the working
// CRS, in four colour phases (throw_in_phases): tiles that cannot reach each other run in
// parallel, and a tile's elements depend only on the tiles within three tiles of it. So the
// output does not depend on the thread count, nor on the DEM's extent: a window of the map
// (a tile of a tiled run, --window) draws exactly the elements a whole run draws there.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "carto/partition.hpp"
#include "carto/styles.hpp"
#include "libtex/discrete.hpp"

namespace carto::terrain {

// One built-in terrain style: its description and its program.
struct Builtin {
    StyleInfo info;
    TerrainProgram program;
    TerrainReach reach;
};
Builtin scree();
Builtin slope_hachures();

// Distance (ground units) from every cell centre of `elevation` to the nearest cell whose
// centre lies inside a rock face, and the elevation of that rock cell, for the rock cells
// within `radius`: exact (the nearest by cell offsets, ties broken by the offset's place in
// a fixed order), so a cell's values depend on the rock within `radius` of it only, and a
// window of the DEM gives the whole raster's values wherever it holds that neighbourhood.
// Cells with no rock cell within `radius` get +inf and NaN.
struct RockProximity {
    Raster distance;
    Raster rock_elevation;
};
RockProximity rock_proximity(const Partition& p, const Raster& elevation, double radius);

// ---- One grid of tiles for the dart throwing, in colour phases ----
//
// Tile (i, j) covers [i side, (i + 1) side) x [j side, (j + 1) side) of the working CRS.
// The tiles are thrown in four phases by the parities of i and j, the tiles of a phase in
// parallel, each seeing its own elements and those of the phases before. When an element
// reaches at most E beyond its tile and elements interact only within D, a `side` larger
// than 2 E + D keeps two tiles of one phase apart: a tile's elements then depend on its
// neighbours of earlier phases only, and through them on the tiles within three tiles of
// it, never further. A window draws the tiles whose centre it holds and, first, the tiles
// they depend on, which gives it the whole run's elements of those tiles.
using TileIndex = std::pair<long long, long long>;  // (i, j)
TileIndex tile_of(const Point& p, double side);
tex::BBox tile_box(const TileIndex& t, double side);
// How far beyond a window the tiles it throws reach, in tiles: half a tile past the centre
// it holds, and three tiles of dependencies.
inline constexpr double kPhasedReachTiles = 3.5;

// An element and a tag (the hachures' contour band), and the elements of the phases done.
struct Element {
    tex::Region region;
    long long tag = 0;
};
struct Placed {
    tex::disc::RegionSet all;
    std::map<long long, tex::disc::RegionSet> by_tag;  // filled when asked for
    // The elements of one tag (an empty set when none).
    const tex::disc::RegionSet& tagged(long long tag) const;
};
// One tile's dart throwing, given the elements of the phases before (read only).
using ThrowTile = std::function<std::vector<Element>(const TileIndex&, const Placed& before)>;

// Throws the tiles `work` (those with anything to throw), phase after phase, and returns the
// elements of every tile, or with `window` of the tiles whose centre it owns (half-open), in
// the order of the phases, then of the tiles. `by_tag`: Placed::by_tag is kept.
std::vector<Element> throw_in_phases(std::vector<TileIndex> work, double side, const std::optional<tex::BBox>& window,
                                     bool by_tag, const ThrowTile& throw_tile);

// A raster on the grid of `like`, 1 in the cells whose centre passes `keep`, else 0; NaN
// where `like` is NoData. `keep` is called from several threads.
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
