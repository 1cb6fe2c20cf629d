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

}  // namespace carto::extraction
