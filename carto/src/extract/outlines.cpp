#include "outlines.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "../gdal_scope.hpp"

namespace carto::extraction {

Outlines face_outlines(std::vector<Chain>& chains, int nfaces, const BorderPlaces& places,
                       const Raster& grid, const OutlineOptions& o) {
    const std::size_t nf = std::size_t(std::max(0, nfaces));
    // Cut points per chain: below the cell size (levels 0 to 2) and at the middles of the cell
    // edges (level 3); the chains' ends are placed once per node (NodePlaces).
    std::vector<std::vector<Point>> fine(chains.size()), middles(chains.size());
    NodePlaces nodes;
    for (std::size_t k = 0; k < chains.size(); ++k) {
        // Places in the whole raster's grid (cut() shifts its own; grid.hpp says why).
        const std::vector<Point>& raw = chains[k].raw;
        for (std::size_t i = 0; i + 1 < raw.size(); ++i) {
            fine[k].push_back(places.cut(raw[i], raw[i + 1], chains[k].kind));
            middles[k].push_back((raw[i] + raw[i + 1]) / 2 + places.offset);
        }
        if (!chains[k].closed) {
            nodes.add(chains[k].start, raw.front() + places.offset, middles[k].front());
            nodes.add(chains[k].end, raw.back() + places.offset, middles[k].back());
        }
    }
    auto shape_chain = [&](std::size_t k) {
        Chain& c = chains[k];
        const Point from = nodes.place(c.start), to = nodes.place(c.end);
        const std::vector<Point> cut = cut_steps(fine[k], c.closed, from, to);
        std::vector<Point> edges = c.raw;
        for (Point& q : edges) q = q + places.offset;
        if (!c.closed) {
            edges.front() = from;
            edges.back() = to;
        }
        c.shapes = {generalise(cut, c.closed, o.simplify, o.smooth_rounds),
                    generalise(cut, c.closed, kHalfCell, 1), cut,
                    cut_steps(middles[k], c.closed, from, to), std::move(edges)};
    };
    std::vector<std::vector<int>> of_face(nf);
    std::multimap<long long, int> at_node;  // the open chains ending at each node
    for (std::size_t k = 0; k < chains.size(); ++k) {
        shape_chain(k);
        const Chain& c = chains[k];
        if (c.right >= 0) of_face[std::size_t(c.right)].push_back(int(k));
        if (c.left >= 0) of_face[std::size_t(c.left)].push_back(int(k));
        if (!c.closed) {
            at_node.insert({c.start, int(k)});
            if (c.end != c.start) at_node.insert({c.end, int(k)});
        }
    }
    Outlines out;
    out.faces.resize(nf);
    std::vector<char> redo(nf, 1), degraded(nf, 0);
    const QuietGdal quiet;  // IsValid reports each crossing it finds as a warning
    auto acceptable = [&](const std::vector<FacePolygon>& polys) {
        if (polys.size() != 1) return false;
        for (const FacePolygon& fp : polys) {
            if (!to_ogr(fp)->IsValid()) return false;
            // Rounding takes area from small faces and holes: one under the minimum area
            // (which its cells reach) keeps its cell edges instead of becoming a speck.
            if (std::abs(tex::signed_area(fp.outer)) < o.min_area) return false;
            for (const auto& h : fp.holes)
                if (std::abs(tex::signed_area(h)) < o.min_area) return false;
        }
        return true;
    };
    auto redo_faces_of = [&](int k) {
        if (chains[std::size_t(k)].right >= 0) redo[std::size_t(chains[std::size_t(k)].right)] = 1;
        if (chains[std::size_t(k)].left >= 0) redo[std::size_t(chains[std::size_t(k)].left)] = 1;
    };
    // A few rounds more than the levels settle the faces across the ones that stepped back.
    constexpr int kRounds = Chain::kLevels + 4;
    for (int round = 0; round <= kRounds; ++round) {
        std::vector<char> bad(nf, 0);
        bool any = false;
        for (std::size_t f = 0; f < nf; ++f) {
            if (!redo[f]) continue;
            out.faces[f] = face_polygons(chains, of_face[f], int(f), grid);
            if (!acceptable(out.faces[f]) && round < kRounds) bad[f] = 1, any = true;
        }
        if (!any) break;
        std::fill(redo.begin(), redo.end(), 0);
        for (std::size_t f = 0; f < nf; ++f) {
            if (!bad[f]) continue;
            degraded[f] = 1;
            const bool last = std::all_of(of_face[f].begin(), of_face[f].end(), [&](int k) {
                return chains[std::size_t(k)].level == Chain::kLevels - 1;
            });
            for (int k : of_face[f]) {
                Chain& c = chains[std::size_t(k)];
                if (!last) {
                    c.level = std::min(c.level + 1, Chain::kLevels - 1);
                    redo_faces_of(k);
                    continue;
                }
                if (c.closed) continue;
                for (const long long node : {c.start, c.end}) {
                    nodes.pin(node);
                    for (auto [it, stop] = at_node.equal_range(node); it != stop; ++it) {
                        shape_chain(std::size_t(it->second));
                        redo_faces_of(it->second);
                    }
                }
            }
        }
    }
    if (const auto n = std::count(degraded.begin(), degraded.end(), 1)) {
        std::array<int, Chain::kLevels> at_level{};
        for (const Chain& c : chains) ++at_level[std::size_t(c.level)];
        out.note = "kept the borders of " + std::to_string(n) +
                   " narrow or small faces closer to the cell edges (generalised, they would cross or "
                   "fall under the minimum area): " +
                   std::to_string(at_level[1]) + " borders lightly generalised, " +
                   std::to_string(at_level[2] + at_level[3]) + " on the cut steps, " +
                   std::to_string(at_level[4]) + " on the cell edges";
    }
    return out;
}

}  // namespace carto::extraction
