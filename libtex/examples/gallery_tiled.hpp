// Tiled planar maps (thesis Fig. 4.5) with the project's own elements: one regular wall of
// bricks, stored once per period, then made semi-regular at conversion by ghost mappers.
#pragma once

#include <string>

#include "libtex/tex.hpp"

namespace gallery::tiled {

// The regular wall: long and short bricks (teaser c's rules) shrunk, a pebble in each
// long one. No Random: a tiled map.
tex::TiledMap wall(const std::string& dir);

// (a) The wall as it is.
tex::Arrangement regular_wall(const std::string& dir);
// (b) Each brick scaled, turned and moved at random by a ghost mapper.
tex::Arrangement jittered_wall(const std::string& dir);
// (c) About a third of the bricks deleted at random by a ghost mapper.
tex::Arrangement thinned_wall(const std::string& dir);
// (d) Clusters: bricks kept where a smooth field of their position, blurred by a random
// amount per brick, is high; smaller towards the clusters' edges.
tex::Arrangement clustered_wall(const std::string& dir);

}  // namespace gallery::tiled
