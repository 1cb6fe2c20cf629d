// The rock mask's helpers: the non-rock pieces (holes and the open outside) and the user's
// mask layer burnt onto the grid (step 1 of carto/extract.hpp).
#pragma once

#include <string>
#include <vector>

#include "carto/raster.hpp"
#include "grid.hpp"

namespace carto::extraction {

// The 8- (or 4-) connected non-rock pieces: label per cell (-1 on rock), and per piece its
// size and whether it is open (reaches the grid's edge, NoData or the outside of the user's mask)
// rather than a hole in the rock.
struct NonRock {
    std::vector<int> lab;
    std::vector<std::size_t> size;
    std::vector<char> open;
};

NonRock non_rock_pieces(const Grid& g, const std::vector<char>& rock, const std::vector<float>& dem,
                        const std::vector<char>& inside_mask, bool eight);

// The user's mask layer burnt onto the grid (1 inside a polygon).
std::vector<char> rasterize_mask(const std::string& path, const Raster& grid);

// The rock mask generalised at map scale, in place: closed by a disc of `rc` cells (dilation
// then erosion, at least the 4 neighbours): crests and couloir floors are less steep than the
// flanks around them but belong to the rock, and a round window keeps the outline and the
// gaps free of square corners. Then 4-connected rock specks, and non-rock gaps enclosed by
// rock (no NoData, no outside of the user's mask), whose cells cover less than `keep_area`
// (m2) are dropped and filled. `dem`: NaN for NoData.
void close_rock(const Grid& g, std::vector<char>& rock, const std::vector<float>& dem,
                const std::vector<char>& inside_mask, int rc, double cell_area, double keep_area);

// The closed mask's edge moved onto the terrain, in place: within `band` cells of it a cell
// is rock where `fine` says so (the slope and roughness over a small window reach the
// thresholds), farther in rock stays rock and farther out nothing is rock. The wide window
// and the closing place the edge where a mean over 25 m crosses the threshold, a round arc a
// few cells off the wall; the small window puts it on the break of slope at a cliff's foot or
// top, and lets it follow the ribs and gullies of the rock's edge. `dem`: NaN for NoData.
void follow_terrain_edge(const Grid& g, std::vector<char>& rock, const std::vector<char>& fine,
                         const std::vector<float>& dem, int band);

}  // namespace carto::extraction
