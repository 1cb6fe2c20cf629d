#include "polygons.hpp"

#include <algorithm>
#include <map>

#include "carto/error.hpp"

namespace carto::extraction {

std::vector<std::vector<Point>> face_rings(const std::vector<Chain>& chains,
                                           const std::vector<int>& mine, int f) {
    std::vector<OrientedChain> oc;
    for (int k : mine) {
        if (chains[k].right == f) oc.push_back({k, false});
        if (chains[k].left == f) oc.push_back({k, true});
    }
    auto pts = [&](const OrientedChain& o) {
        const Chain& c = chains[o.chain];
        std::vector<Point> p = c.shape();
        if (o.reversed) std::reverse(p.begin(), p.end());
        return p;
    };
    auto start = [&](const OrientedChain& o) {
        return o.reversed ? chains[o.chain].end : chains[o.chain].start;
    };
    auto end = [&](const OrientedChain& o) {
        return o.reversed ? chains[o.chain].start : chains[o.chain].end;
    };
    auto first_dir = [&](const OrientedChain& o) {
        return o.reversed ? (chains[o.chain].last_dir + 2) % 4 : chains[o.chain].first_dir;
    };
    auto last_dir = [&](const OrientedChain& o) {
        return o.reversed ? (chains[o.chain].first_dir + 2) % 4 : chains[o.chain].last_dir;
    };
    std::multimap<long long, int> from;
    for (std::size_t k = 0; k < oc.size(); ++k)
        if (!chains[oc[k].chain].closed) from.insert({start(oc[k]), int(k)});
    std::vector<char> used(oc.size(), 0);
    std::vector<std::vector<Point>> rings;
    for (std::size_t k = 0; k < oc.size(); ++k) {
        if (used[k]) continue;
        used[k] = 1;
        std::vector<Point> ring = pts(oc[k]);
        if (chains[oc[k].chain].closed) {
            rings.push_back(std::move(ring));
            continue;
        }
        const long long ring_start = start(oc[k]);
        std::size_t cur = k;
        while (end(oc[cur]) != ring_start) {
            int pick = -1;
            const int din = last_dir(oc[cur]);
            auto range = from.equal_range(end(oc[cur]));
            for (auto it = range.first; it != range.second; ++it) {
                if (used[it->second]) continue;
                const int dout = first_dir(oc[it->second]);
                // Join turn: the left turn in grid coordinates (cross product > 0).
                const int cross = kCx[din] * kCy[dout] - kCy[din] * kCx[dout];
                if (pick < 0 || cross > 0) pick = it->second;
            }
            if (pick < 0)
                throw Error(Code::Failure,
                            "face " + std::to_string(f + 1) + ": its border does not close");
            used[pick] = 1;
            const std::vector<Point> more = pts(oc[pick]);
            ring.insert(ring.end(), more.begin() + 1, more.end());
            cur = std::size_t(pick);
        }
        rings.push_back(std::move(ring));
    }
    return rings;
}

std::unique_ptr<OGRPolygon> to_ogr(const FacePolygon& fp) {
    auto poly = std::make_unique<OGRPolygon>();
    auto add = [&](const std::vector<Point>& ring) {
        OGRLinearRing lr;
        for (const Point& p : ring) lr.addPoint(p.x, p.y);
        lr.closeRings();
        poly->addRing(&lr);
    };
    add(fp.outer);
    for (const auto& h : fp.holes) add(h);
    return poly;
}

std::vector<FacePolygon> face_polygons(const std::vector<Chain>& chains,
                                       const std::vector<int>& mine, int f, const Raster& grid) {
    std::vector<std::vector<Point>> rings = face_rings(chains, mine, f);
    for (auto& ring : rings)
        for (Point& p : ring) p = whole_pixel_to_world(grid, p);
    std::vector<FacePolygon> out;
    std::vector<std::vector<Point>> holes;
    for (auto& ring : rings) {
        if (tex::signed_area(ring) > 0)
            out.push_back({std::move(ring), {}});
        else
            holes.push_back(std::move(ring));
    }
    for (auto& h : holes) {
        // A hole touches its shell at most at corners: test the middle of its first edge.
        const Point probe = (h[0] + h[1]) / 2;
        std::size_t best = 0;
        for (std::size_t k = 0; k < out.size(); ++k)
            if (tex::point_in_ring(probe, out[k].outer)) best = k;
        if (!out.empty()) out[best].holes.push_back(std::move(h));
    }
    return out;
}

}  // namespace carto::extraction
