// The "Teaser" scripts of the thesis's Appendix A (a to h), written with libtex.
//
// Each teaser is one function returning its arrangement; the layers it is made of are
// functions too, so that the tests can check a teaser against its parts (the blobs that
// must hide the strokes, the wheels no stipple may touch...). Elements are loaded from
// `dir` (libtex/examples/elements: the project's own drawings).
#pragma once

#include <string>

#include "libtex/tex.hpp"

namespace gallery::teasers {

// Teaser a, beads on a curvy lattice: a lozenge grid (two stripe families at +-60
// degrees) whose edges become wavy strokes and whose vertices carry blobs; the strokes are
// cut away where a blob covers them.
tex::Arrangement lozenge_lattice();
tex::Arrangement lattice_strokes(const std::string& dir);
tex::Arrangement lattice_beads(const std::string& dir);
tex::Arrangement beads_on_strokes(const std::string& dir);

// Teaser b, stacked tree rings: ten layers of nested hand-drawn rings (one nest per cell
// of a sparse uniform partition); each new layer goes on top and hides what lies under
// its discs.
inline constexpr int kRingLayers = 10;
tex::Arrangement ring_layer(const std::string& dir);  // one layer: its own random sites
tex::Arrangement stacked_rings(const std::string& dir);

// Teaser c, a wall of long and short bricks: label rules on a labelled grid remove
// vertical edges, leaving courses of long bricks and courses of short ones; each brick is
// then shrunk (the long ones less).
tex::Arrangement labelled_bricks_grid();
// Its two stripe families (rows 200 apart labelled h1, h2; columns 120 apart, v1..v4), and
// the two mappers of the wall, shared with the tiled form of the wall (tiled.hpp).
tex::Stripes brick_rows();
tex::Stripes brick_columns();
tex::Curves keep_brick_joints(const tex::Edge& e);
tex::Curves shrink_brick(const tex::Face& f);
tex::Arrangement brick_courses();
tex::Arrangement shrunk_bricks();

// Teaser d, woven hatching: a group of parallel strokes on every cell of a dense uniform
// partition, lying either horizontally or vertically.
tex::Arrangement hatch_cells();
tex::Arrangement woven_hatching(const std::string& dir);

// Teaser e, wheels in a stipple field: wheels on a sparse uniform partition, dot clusters
// on a dense random one, and only the dots lying wholly outside the wheels kept.
tex::Arrangement wheels(const std::string& dir);
tex::Arrangement stipples(const std::string& dir);
tex::Arrangement wheels_in_stipple(const std::string& dir);

// Teaser f, hatched shards: the cells of a sparse random partition, shrunk apart, each
// filled with stripes at its own random angle; the shrunk outlines are then dropped.
tex::Arrangement shards();
tex::Arrangement hatched_shards();

// Teaser g, cracked basket weave: a checkerboard of square cells striped horizontally
// and vertically in turn, the inner stripe lines drawn as cracks.
tex::Arrangement basket_cells();
tex::Arrangement cracked_basket(const std::string& dir);

// Teaser h, plaid: two crossing families of diagonal hatching in bands, over a fine
// vertical hatching in the narrow rows and columns of an uneven grid.
tex::Arrangement plaid();

}  // namespace gallery::teasers
