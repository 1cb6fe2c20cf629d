// The remaining scripts of the thesis's Appendix A ("Regular result" a to d, "Non regular
// result" a to d, "Script edition" a to d), written with libtex.
//
// As for the teasers, each example is one function and the layers it is made of are
// functions too, so that the tests can check a drawing against its parts. Elements are
// loaded from `dir` (libtex/examples/elements: the project's own drawings).
#pragma once

#include <string>
#include <vector>

#include "libtex/tex.hpp"

namespace gallery::more {

// ---- Regular result a: horizontal hatching showing only between tilted tiles ----
// Each cell of a 200 grid turned by 45 degrees (the turned squares overlap their
// neighbours), then every face of that drawing shrunk to 80 %.
tex::Arrangement tilted_tiles();
// Hatching 15 apart, cut away inside the tiles.
tex::Arrangement regular_a(const std::string& dir);

// ---- Regular result b: chevrons of wobbly hatching ----
// A diagonal grid (200, at +-45 degrees, four edge labels each way) from which label rules
// remove one edge in four, leaving chevrons.
tex::Arrangement chevron_grid();
// Its faces shrunk to 80 %.
tex::Arrangement chevron_tiles();
// Horizontal hatching 40 apart in each tile, the hatch lines drawn as wobbly strokes and
// the tiles' outlines dropped.
tex::Arrangement regular_b(const std::string& dir);
// Its steps as named mappers, and the whole script over any diagonal grid (a planar-map
// GridPartition, or a tiled one: the same script runs on both, test_tiled_gallery.cpp).
tex::Stripes chevron_lines(double angle, const char* label);  // 200 apart, labels label1..4
tex::Curves chevron_rule(const tex::Edge& e);
tex::Curves chevron_shrink(const tex::Face& f);
tex::Curves hatch_tile(const tex::Face& f, double spacing);
tex::Curves wobble_stroke(const tex::Curves& wobble, const tex::Edge& e);
template <class Partition>
auto regular_b_on(const Partition& grid, const tex::Curves& wobble, double spacing) {
    auto hatch = [spacing](const tex::Face& f) { return hatch_tile(f, spacing); };
    auto to_stroke = [wobble](const tex::Edge& e) { return wobble_stroke(wobble, e); };
    return MapToEdges(to_stroke, MapToFaces(hatch, MapToFaces(chevron_shrink, MapToEdges(chevron_rule, grid))));
}

// ---- Regular result c: a wavy grid of cells hatched at random angles ----
// Horizontal and vertical stripes 200 apart whose lines become arches, laid up or down by
// their label (the window outline stays straight).
tex::Arrangement wavy_grid(const std::string& dir);
// Its faces shrunk to 90 %.
tex::Arrangement wavy_tiles(const std::string& dir);
// Rippled hatching 30 apart at a random angle in each tile, outlines dropped.
tex::Arrangement regular_c(const std::string& dir);

// ---- Regular result d: pieces of overlapping rings, some missing ----
// A ring fitted to each cell of a 200 grid and enlarged 2.5 times (the rings overlap).
tex::Arrangement hoop_lattice(const std::string& dir);
// Every face of the rings' drawing shrunk to 65 %.
tex::Arrangement hoop_pieces(const std::string& dir);
// The pieces, three in ten dropped at random.
tex::Arrangement regular_d(const std::string& dir);
inline constexpr double kDropShare = 0.3;

// ---- Non regular result a (left): rings of random sizes on a uniform partition ----
tex::Arrangement uniform_cells_100();  // about 100 cells in the window
tex::Arrangement nonregular_a_left(const std::string& dir);

// ---- Non regular result a (right): nested outlines ----
// Level 1: a sparse uniform partition (about 20 cells) with kinked edges; level k + 1:
// every face of level k shrunk to 80 %. The drawing is the union of the ten levels.
inline constexpr int kNestLevels = 10;
std::vector<tex::Arrangement> nest_levels(const std::string& dir);
tex::Arrangement nonregular_a_right(const std::string& dir);

// ---- Non regular result b: a random partition within a random partition ----
// About 10 random cells, inner edges jagged; every cell split by a finer random partition
// (about 100 cells in the window); all inner edges jagged again.
tex::Arrangement jagged_cells(const std::string& dir);
tex::Arrangement nonregular_b(const std::string& dir);

// ---- Non regular result c: fine shrunk cells inside coarse shrunk cells ----
// The cells of a uniform partition (density sites per window) shrunk to 80 %.
tex::Arrangement shrunk_cells(double cells_per_window);
// Coarse (20) and fine (90) shrunk cells, created in that order; the fine ones cut to the
// inside of the coarse ones.
tex::Arrangement nonregular_c(const std::string& dir);

// ---- Non regular result d: the edges of a random partition stretched and turned ----
tex::Arrangement random_cells_30();
// Each edge of the partition scaled 10 times about its centre.
tex::Arrangement stretched_edges();
// Each edge of the stretched lines' drawing turned by 45 degrees.
tex::Arrangement nonregular_d(const std::string& dir);

// ---- Script edition: the overview script (Fig. 3.1) edited four ways ----
// (a) the original: clouds on a sparse uniform partition, a grid at a random angle in
// each cloud, its inner edges drawn as swirls.
tex::Arrangement cloud_layer(const std::string& dir);
tex::Arrangement script_edit_a(const std::string& dir);
// (b) the partitions switched: clouds on a 4 x 4 grid, a uniform partition in each cloud.
tex::Arrangement cloud_grid_layer(const std::string& dir);
tex::Arrangement script_edit_b(const std::string& dir);
// (c) the arrangements switched: a uniform partition with swirled edges, and in each of
// its cells a grid (125) whose cells lying inside get a pebble.
tex::Arrangement swirled_cells(const std::string& dir);
tex::Arrangement script_edit_c(const std::string& dir);
// (d) the mappings varied: the same with curls, and a flower or a leaf (one in two) on
// each grid cell.
tex::Arrangement curled_cells(const std::string& dir);
tex::Arrangement script_edit_d(const std::string& dir);
inline constexpr double kEditCell = 125;  // the grid width of (c) and (d): 2000 / 16

// ---- Triangles, Bee hive and the wallpaper groups ----
// A lozenge grid: two stripe families 200 apart at angles a and b.
tex::Arrangement lozenges(double a, double b);
// The diagonal of a face running from the vertex where both of its edges start to the
// vertex where both end (none when there is no such pair): a segment element matched onto
// the two vertices (MatchPoints lands exactly on them, so the bar splits the face).
tex::Curves split_diagonal(const tex::Face& f);
// The lozenges (at +-60 degrees) with their diagonals: equilateral triangles.
tex::Arrangement triangles(const std::string& dir);
// The dual of the triangles: a bar between the centroids of the two faces of every inner
// edge (exactly, as above), that is a honeycomb.
tex::Arrangement honeycomb(const std::string& dir);
// P6: every edge of the honeycomb replaced by a Z-shaped kink.
tex::Arrangement wallpaper_p6(const std::string& dir);
// P4M: every edge of a square grid turned 45 degrees drawn as a bump, laid both ways.
tex::Arrangement wallpaper_p4m(const std::string& dir);
// P31M: triangles (at 30 and 150 degrees) whose faces are each cut into three by S-bends
// from their corners to their centroid, the bend or its mirror by the face's orientation.
tex::Arrangement wallpaper_p31m(const std::string& dir);

// ---- Escher-like tilings: the wallpaper groups with richer elements ----
// (The thesis exports these in a 1000 window; here they fill the gallery's 2000 one.)
// P6: fish outlines on the honeycomb's edges, a fish's inside on each hexagon.
tex::Arrangement fish_outlines(const std::string& dir);
tex::Arrangement fish_insides(const std::string& dir);
tex::Arrangement escher_p6(const std::string& dir);
// P4M: an octopus along every edge of the square grid turned 45 degrees, a little man on
// every square.
tex::Arrangement escher_p4m(const std::string& dir);
// P31M: the P31M subdivision with feathered bends.
tex::Arrangement escher_p31m(const std::string& dir);

}  // namespace gallery::more
