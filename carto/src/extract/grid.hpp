// The extraction's raster grid: cell indexing, the eight neighbours, connected components,
// window means and the progress steps, shared by its units (carto/extract.hpp).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "carto/error.hpp"
#include "carto/control_fields.hpp"
#include "carto/pipeline.hpp"

namespace carto::extraction {

// The eight neighbours (rows go south): E, SE, S, SW, W, NW, N, NE.
constexpr int kDc[8] = {1, 1, 0, -1, -1, -1, 0, 1};

constexpr int kDr[8] = {0, 1, 1, 1, 0, -1, -1, -1};

struct Grid {
    int w = 0, h = 0;
    std::size_t size() const { return std::size_t(w) * h; }
    bool inside(int c, int r) const { return c >= 0 && r >= 0 && c < w && r < h; }
    std::size_t at(int c, int r) const { return std::size_t(r) * w + c; }
};

// Pixel positions in the whole raster's grid. The extraction may run on a window of a
// larger raster (a tile of a tiled extraction: Raster::col0, row0): it indexes cells in the
// window, but places every point of a border or line in the whole raster's pixel grid, the
// window's integer offset added before any fraction of a cell, so that each point gets the
// bits a whole run gives it (Raster::to_world, from the window's own origin, and a fraction
// added to a window coordinate would both round differently).
inline Point window_offset(const Raster& r) { return {double(r.col0), double(r.row0)}; }

// World coordinates of a position in the whole raster's pixel grid.
inline Point whole_pixel_to_world(const Raster& r, const Point& p) {
    const auto& gt = r.grid_gt ? *r.grid_gt : r.gt;
    return {gt[0] + p.x * gt[1] + p.y * gt[2], gt[3] + p.x * gt[4] + p.y * gt[5]};
}

inline void step(const Progress& p, double f, const std::string& stage) {
    if (p && !p(f, stage)) throw Error(Code::Cancelled, "cancelled during " + stage);
}

// NoData-aware window mean (carto/fields.hpp) on the extraction's grid.
inline std::vector<float> box_mean(const Grid& g, const std::vector<float>& v, int radius) {
    return carto::box_mean(v, g.w, g.h, radius);
}

// Connected components of the cells where on[i] is true (4- or 8-connected), numbered from 0
// in raster order; -1 elsewhere.
inline std::vector<int> components(const Grid& g, const std::vector<char>& on, bool eight,
                                   int& count) {
    std::vector<int> lab(g.size(), -1);
    std::vector<std::size_t> stack;
    count = 0;
    for (std::size_t s = 0; s < g.size(); ++s) {
        if (!on[s] || lab[s] >= 0) continue;
        lab[s] = count;
        stack.push_back(s);
        while (!stack.empty()) {
            const std::size_t i = stack.back();
            stack.pop_back();
            const int c = int(i % g.w), r = int(i / g.w);
            for (int k = 0; k < 8; k += eight ? 1 : 2) {
                const int cc = c + kDc[k], rr = r + kDr[k];
                if (!g.inside(cc, rr)) continue;
                const std::size_t j = g.at(cc, rr);
                if (on[j] && lab[j] < 0) {
                    lab[j] = count;
                    stack.push_back(j);
                }
            }
        }
        ++count;
    }
    return lab;
}

}  // namespace carto::extraction
