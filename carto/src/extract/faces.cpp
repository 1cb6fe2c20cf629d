#include "faces.hpp"

#include <algorithm>
#include <map>

namespace carto::extraction {

namespace {

constexpr int kMaxMergePasses =
    50;  // rounds of merging small faces (each merges a face at most once)

}  // namespace

std::vector<int> face_grid(const Grid& g, const std::vector<char>& rock,
                           const std::vector<int>& line_cells, double cell_area, double min_area,
                           int& nfaces) {
    std::vector<char> free_cell(g.size());
    for (std::size_t i = 0; i < g.size(); ++i) free_cell[i] = rock[i] && line_cells[i] == 0;
    nfaces = 0;
    std::vector<int> face = components(g, free_cell, false, nfaces);
    // Line cells join a 4-neighbouring face, wave by wave (the smallest face index wins).
    while (true) {
        std::vector<std::pair<std::size_t, int>> wave;
        for (int r = 0; r < g.h; ++r)
            for (int c = 0; c < g.w; ++c) {
                const std::size_t i = g.at(c, r);
                if (!rock[i] || face[i] >= 0) continue;
                int best = -1;
                for (int k = 0; k < 8; k += 2) {
                    const int cc = c + kDc[k], rr = r + kDr[k];
                    if (!g.inside(cc, rr)) continue;
                    const int f = face[g.at(cc, rr)];
                    if (f >= 0 && (best < 0 || f < best)) best = f;
                }
                if (best >= 0) wave.push_back({i, best});
            }
        if (wave.empty()) break;
        for (auto [i, f] : wave) face[i] = f;
    }
    // Rock made only of line cells (narrow ribs): faces of their own.
    for (std::size_t i = 0; i < g.size(); ++i)
        if (rock[i] && face[i] < 0) {
            std::vector<char> rest(g.size());
            for (std::size_t j = 0; j < g.size(); ++j) rest[j] = rock[j] && face[j] < 0;
            int n = 0;
            const std::vector<int> lab = components(g, rest, false, n);
            for (std::size_t j = 0; j < g.size(); ++j)
                if (lab[j] >= 0) face[j] = nfaces + lab[j];
            nfaces += n;
            break;
        }
    // Small faces merge into the neighbour they share most border with, smallest first.
    for (int pass = 0; pass < kMaxMergePasses; ++pass) {
        std::vector<std::size_t> area(std::size_t(nfaces), 0);
        std::map<std::pair<int, int>, int> shared;
        for (int r = 0; r < g.h; ++r)
            for (int c = 0; c < g.w; ++c) {
                const int f = face[g.at(c, r)];
                if (f < 0) continue;
                ++area[f];
                for (int k : {0, 2}) {  // east and south neighbours
                    const int cc = c + kDc[k], rr = r + kDr[k];
                    if (!g.inside(cc, rr)) continue;
                    const int e = face[g.at(cc, rr)];
                    if (e >= 0 && e != f) {
                        ++shared[{f, e}];
                        ++shared[{e, f}];
                    }
                }
            }
        std::vector<int> order;
        for (int f = 0; f < nfaces; ++f)
            if (area[f] > 0 && double(area[f]) * cell_area < min_area) order.push_back(f);
        std::stable_sort(order.begin(), order.end(),
                         [&](int a, int b) { return area[a] < area[b]; });
        std::vector<int> target(std::size_t(nfaces), -1);
        std::vector<char> touched(std::size_t(nfaces), 0);
        bool merged = false;
        for (int f : order) {
            if (touched[f]) continue;
            int best = -1, most = 0;
            for (auto it = shared.lower_bound({f, -1}); it != shared.end() && it->first.first == f;
                 ++it)
                if (it->second > most && !touched[it->first.second]) {
                    most = it->second;
                    best = it->first.second;
                }
            if (best < 0) continue;
            target[f] = best;
            touched[f] = touched[best] = 1;
            merged = true;
        }
        if (!merged) break;
        for (int& f : face)
            if (f >= 0 && target[f] >= 0) f = target[f];
    }
    // Compact numbering in raster order of the faces' first cells.
    {
        std::vector<int> renum(std::size_t(nfaces), -1);
        int n = 0;
        for (int& f : face)
            if (f >= 0) {
                if (renum[f] < 0) renum[f] = n++;
                f = renum[f];
            }
        nfaces = n;
    }
    return face;
}

}  // namespace carto::extraction
