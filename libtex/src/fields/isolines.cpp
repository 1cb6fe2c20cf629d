// IsoLines: the level sets of a control field by marching squares on a global lattice.
#include <cmath>
#include <map>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "libtex/error.hpp"
#include "libtex/fields.hpp"
#include "lattice.hpp"

namespace tex {
namespace {

// A lattice edge: from node (i, j) to (i + 1, j) (horizontal) or to (i, j + 1).
struct EdgeKey {
    long long i, j;
    int vertical;
    bool operator<(const EdgeKey& o) const { return std::tie(i, j, vertical) < std::tie(o.i, o.j, o.vertical); }
    bool operator==(const EdgeKey& o) const { return i == o.i && j == o.j && vertical == o.vertical; }
};

struct Segment {
    EdgeKey from, to;
    Point a, b;
};

}  // namespace

Arrangement IsoLines(Field f, double level, double cell) {
    if (!(cell > 0) || !std::isfinite(cell))
        throw Error("IsoLines", "cell must be a positive number (got " + std::to_string(cell) + ")");
    if (!std::isfinite(level)) throw Error("IsoLines", "level must be a finite number");
    return Arrangement([f = std::move(f), level, cell](const Region& r) {
        // The field at every node of the lattice over the region's box.
        const detail::LatticeWindow w(f, r.bbox(), cell, 0, "IsoLines");
        const long long i0 = w.i0, i1 = w.i1, j0 = w.j0, j1 = w.j1;
        auto val = [&](long long i, long long j) { return w.at(i, j); };
        auto node = [&](long long i, long long j) { return Point{double(i) * cell, double(j) * cell}; };
        // Where the level crosses a lattice edge, interpolated from its lower node: the same
        // point from both squares that share the edge.
        auto cross_at = [&](const EdgeKey& e) {
            const long long i2 = e.vertical ? e.i : e.i + 1, j2 = e.vertical ? e.j + 1 : e.j;
            const double va = val(e.i, e.j), vb = val(i2, j2);
            const double t = (level - va) / (vb - va);
            const Point a = node(e.i, e.j), b = node(i2, j2);
            return a + (b - a) * t;
        };
        std::vector<Segment> segs;
        for (long long j = j0; j < j1; ++j)
            for (long long i = i0; i < i1; ++i) {
                const double c[4] = {val(i, j), val(i + 1, j), val(i + 1, j + 1), val(i, j + 1)};
                if (std::isnan(c[0]) || std::isnan(c[1]) || std::isnan(c[2]) || std::isnan(c[3])) continue;
                bool high[4];
                int n_high = 0;
                for (int k = 0; k < 4; ++k) n_high += high[k] = c[k] >= level;
                if (n_high == 0 || n_high == 4) continue;
                // Edge k runs from corner k to corner k + 1.
                const EdgeKey edge[4] = {{i, j, 0}, {i + 1, j, 1}, {i, j + 1, 0}, {i, j, 1}};
                // A segment across edges ea and eb with the high side on its left: it runs from
                // the edge where the corners (counter-clockwise) go from high to low, to the
                // one where they go from low to high (decided on the corners, not on the
                // points, which coincide where a node lies on the level).
                auto add = [&](int ea, int eb) {
                    if (!high[ea] || high[(ea + 1) % 4]) std::swap(ea, eb);
                    segs.push_back({edge[ea], edge[eb], cross_at(edge[ea]), cross_at(edge[eb])});
                };
                const bool saddle = n_high == 2 && high[0] == high[2];
                if (!saddle) {
                    // One segment: across the two edges whose corners differ.
                    int e[2], m = 0;
                    for (int k = 0; k < 4; ++k)
                        if (high[k] != high[(k + 1) % 4]) e[m++] = k;
                    add(e[0], e[1]);
                } else {
                    // Two segments, each cutting off one corner: the low ones when the
                    // centre is high (the high corners join through it), else the high ones.
                    const bool centre_high = (c[0] + c[1] + c[2] + c[3]) / 4 >= level;
                    for (int k = 0; k < 4; ++k) {
                        if (high[k] == centre_high) continue;
                        // Corner k lies between edge k - 1 and edge k.
                        add((k + 3) % 4, k);
                    }
                }
            }
        // Chain the segments: each crossing is the end of at most one segment and the start
        // of at most one; lines start where nothing ends (the box's edge), then the loops.
        std::map<EdgeKey, std::size_t> starting;
        std::map<EdgeKey, int> ending;
        for (std::size_t k = 0; k < segs.size(); ++k) {
            starting[segs[k].from] = k;
            ++ending[segs[k].to];
        }
        std::vector<char> used(segs.size(), 0);
        Curves out;
        auto follow = [&](std::size_t k) {
            std::vector<Point> pts{segs[k].a};
            bool closed = false;
            while (true) {
                used[k] = 1;
                pts.push_back(segs[k].b);
                const auto next = starting.find(segs[k].to);
                if (next == starting.end()) break;
                if (used[next->second]) {
                    closed = true;
                    break;
                }
                k = next->second;
            }
            if (closed) pts.pop_back();
            Curve c;
            c.points = std::move(pts);
            c.closed = closed && c.points.size() >= 3;
            out.curves.push_back(std::move(c));
        };
        for (std::size_t k = 0; k < segs.size(); ++k)
            if (!used[k] && !ending.count(segs[k].from)) follow(k);
        for (std::size_t k = 0; k < segs.size(); ++k)
            if (!used[k]) follow(k);
        return out;
    });
}

}  // namespace tex
