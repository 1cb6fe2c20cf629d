// The faces on the grid (step 3 of carto/extract.hpp): the rock cut by the ridge and thalweg
// cells into 4-connected pieces, the line cells given to a neighbouring face, faces smaller
// than the minimum area merged into the neighbour they share most border with.
#pragma once

#include <vector>

#include "grid.hpp"

namespace carto::extraction {

// Face index per cell (-1 outside the rock), numbered in raster order of the faces' first
// cells; `nfaces` is set to their count. line_cells: 0 none, 1 ridge, 2 thalweg; areas in m2.
std::vector<int> face_grid(const Grid& g, const std::vector<char>& rock,
                           const std::vector<int>& line_cells, double cell_area, double min_area,
                           int& nfaces);

}  // namespace carto::extraction
