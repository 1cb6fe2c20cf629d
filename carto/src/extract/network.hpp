// Step 2 of carto/extract.hpp: the ridge and thalweg network of the rock, from flow on the
// smoothed DEM and on its inverse (extract/flow.hpp), as line cells and traced polylines.
#pragma once

#include <vector>

#include "carto/extract.hpp"
#include "carto/partition.hpp"
#include "carto/raster.hpp"
#include "grid.hpp"

namespace carto::extraction {

struct Network {
    std::vector<char> ridge, valley;  // line cells (1 on a line)
    // Cells of the ridges' steepest finishes: they cut the rock but follow no crest, so the
    // borders along them are not labelled.
    std::vector<char> straight;
    std::vector<float> z;             // the smoothed DEM the flow ran on
    std::vector<LabelledLine> lines;  // the network traced inside the rock, ridges first
};

// `rock`: the rock cells (step 1); `inside_mask`: the user's mask burnt on the grid, or empty.
// Reads the options' smooth, thalweg_area, ridge_area, converge, max_fill and extend_ridges.
Network find_network(const Grid& g, const Raster& dem, const std::vector<char>& rock,
                     const std::vector<char>& inside_mask, const ExtractOptions& o);

}  // namespace carto::extraction
