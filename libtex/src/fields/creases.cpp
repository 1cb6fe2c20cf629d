// Creases: the ridge and valley lines of a surface (height ridges) on a global lattice.
//
// At each lattice node the surface's gradient and Hessian are read by central differences
// over the neighbouring nodes. A ridge point is where the surface is highest across its
// sharpest downward bend: the derivative along the Hessian's eigenvector of the most negative
// eigenvalue vanishes there. That derivative changes sign along a lattice edge where the line
// crosses it; the eigenvector's sense is arbitrary, so the edge's far end is turned to agree
// with its near one before the signs are compared (a rule of the edge alone, so both squares
// that share an edge agree on its crossing).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "libtex/error.hpp"
#include "libtex/fields.hpp"
#include "lattice.hpp"

namespace tex {
namespace {

struct Node {
    bool valid = false;
    double slope_along = 0;  // gradient . e
    double bend = 0;         // -eigenvalue (ridge) or eigenvalue (valley): > 0 where it bends that way
    bool dominant = false;   // that bend is the stronger of the two
    Point e;                 // unit eigenvector across the line
};

struct Key {
    long long i, j;
    int vertical;
    bool operator==(const Key& o) const { return i == o.i && j == o.j && vertical == o.vertical; }
};

// The crease lines of one kind through the lattice window w (read one node beyond the
// squares it traces).
Curves trace(const detail::LatticeWindow& w, CreaseKind kind, double cell, double min_bend) {
    const long long i0 = w.i0, i1 = w.i1, j0 = w.j0, j1 = w.j1;
    auto zat = [&](long long i, long long j) { return w.at(i, j); };
    const long long mx = i1 - i0 + 1, my = j1 - j0 + 1;
    std::vector<Node> nodes(std::size_t(mx * my));
    const double h2 = cell * cell;
    for (long long j = j0; j <= j1; ++j)
        for (long long i = i0; i <= i1; ++i) {
            const double c = zat(i, j), xm = zat(i - 1, j), xp = zat(i + 1, j), ym = zat(i, j - 1),
                         yp = zat(i, j + 1), pp = zat(i + 1, j + 1), pm = zat(i + 1, j - 1),
                         mp = zat(i - 1, j + 1), mm = zat(i - 1, j - 1);
            Node& n = nodes[std::size_t((j - j0) * mx + (i - i0))];
            if (std::isnan(c) || std::isnan(xm) || std::isnan(xp) || std::isnan(ym) || std::isnan(yp) ||
                std::isnan(pp) || std::isnan(pm) || std::isnan(mp) || std::isnan(mm))
                continue;
            const double gx = (xp - xm) / (2 * cell), gy = (yp - ym) / (2 * cell);
            const double a = (xp - 2 * c + xm) / h2, d = (yp - 2 * c + ym) / h2, b = (pp - pm - mp + mm) / (4 * h2);
            // Eigenvalues m -/+ s of [[a, b], [b, d]]; the eigenvector of m + s at angle phi.
            const double m = (a + d) / 2, s = std::hypot((a - d) / 2, b);
            const double phi = 0.5 * std::atan2(2 * b, a - d);
            const bool ridge = kind == CreaseKind::Ridge;
            const double angle = ridge ? phi + pi / 2 : phi;
            n.valid = true;
            n.e = {std::cos(angle), std::sin(angle)};
            n.slope_along = gx * n.e.x + gy * n.e.y;
            n.bend = ridge ? -(m - s) : m + s;
            n.dominant = ridge ? m <= 0 : m >= 0;
        }
    auto node_at = [&](long long i, long long j) -> const Node& {
        return nodes[std::size_t((j - j0) * mx + (i - i0))];
    };
    // The crossing of a lattice edge, if the line crosses it where it bends enough: each edge
    // read once, its crossing numbered in the order found (-2 not read yet, -1 none). An index,
    // not a pointer: the crossings of a square's later edges may move the vector.
    std::vector<int> crossing_id(std::size_t(mx * my) * 2, -2);
    std::vector<Point> crossings;
    auto edge_of = [&](const Key& k) { return std::size_t((k.j - j0) * mx + (k.i - i0)) * 2 + std::size_t(k.vertical); };
    auto crossing = [&](const Key& k) -> int {
        int& id = crossing_id[edge_of(k)];
        if (id != -2) return id;
        id = -1;
        const long long i2 = k.vertical ? k.i : k.i + 1, j2 = k.vertical ? k.j + 1 : k.j;
        const Node &a = node_at(k.i, k.j), &b = node_at(i2, j2);
        if (!a.valid || !b.valid || !a.dominant || !b.dominant) return -1;
        const double ga = a.slope_along, gb = (dot(a.e, b.e) >= 0 ? 1.0 : -1.0) * b.slope_along;
        if ((ga >= 0) == (gb >= 0)) return -1;
        const double t = ga / (ga - gb);
        const double bend = a.bend + (b.bend - a.bend) * t;
        if (!(bend > min_bend) || a.bend <= 0 || b.bend <= 0) return -1;
        // The derivative falls across the line as the bend says (not a sign flip of a
        // vanishing derivative, as on the flank of a cone, where every radius would pass).
        const Point pa{double(k.i) * cell, double(k.j) * cell}, pb{double(i2) * cell, double(j2) * cell};
        const double across = std::abs(k.vertical ? a.e.y : a.e.x) * cell;
        if (std::abs(ga - gb) < 0.5 * bend * across) return -1;
        id = int(crossings.size());
        crossings.push_back(pa + (pb - pa) * t);
        return id;
    };
    // Segments inside each square between its crossings: two join; four pair off the
    // shorter way; three (the eigenvector turned round inside the square) keep the
    // closest pair; one is a line's end.
    struct Seg {
        Key a, b;
    };
    std::vector<Seg> segs;
    for (long long j = j0; j < j1; ++j)
        for (long long i = i0; i < i1; ++i) {
            const Key edge[4] = {{i, j, 0}, {i + 1, j, 1}, {i, j + 1, 0}, {i, j, 1}};
            int on[4], n = 0, c[4];
            for (int k = 0; k < 4; ++k)
                if ((c[k] = crossing(edge[k])) >= 0) on[n++] = k;
            auto p = [&](int k) -> const Point& { return crossings[std::size_t(c[k])]; };
            if (n == 2) {
                segs.push_back({edge[on[0]], edge[on[1]]});
            } else if (n == 4) {
                const double around = distance(p(0), p(1)) + distance(p(2), p(3));
                const double other = distance(p(1), p(2)) + distance(p(3), p(0));
                if (around <= other) {
                    segs.push_back({edge[0], edge[1]});
                    segs.push_back({edge[2], edge[3]});
                } else {
                    segs.push_back({edge[1], edge[2]});
                    segs.push_back({edge[3], edge[0]});
                }
            } else if (n == 3) {
                int best = 0;
                double shortest = INFINITY;
                for (int k = 0; k < 3; ++k) {
                    const double l = distance(p(on[k]), p(on[(k + 1) % 3]));
                    if (l < shortest) shortest = l, best = k;
                }
                segs.push_back({edge[on[best]], edge[on[(best + 1) % 3]]});
            }
        }
    // Chain the segments: every crossing ends at most two of them (the two squares
    // sharing its edge); lines start at crossings that end one, then the loops.
    struct Ends {
        std::size_t seg[2];
        int n = 0;
        const std::size_t* begin() const { return seg; }
        const std::size_t* end() const { return seg + n; }
        std::size_t size() const { return std::size_t(n); }
    };
    std::vector<Ends> ends(crossings.size());
    auto at = [&](const Key& k) -> Ends& { return ends[std::size_t(crossing_id[edge_of(k)])]; };
    auto point_of = [&](const Key& k) { return crossings[std::size_t(crossing_id[edge_of(k)])]; };
    for (std::size_t s = 0; s < segs.size(); ++s)
        for (const Key& k : {segs[s].a, segs[s].b}) {
            Ends& e = at(k);
            if (e.n < 2) e.seg[e.n++] = s;  // always: the two squares sharing the edge
        }
    std::vector<char> used(segs.size(), 0);
    Curves out;
    auto follow = [&](Key from, std::size_t s) {
        Curve c;
        c.points.push_back(point_of(from));
        bool closed = false;
        while (true) {
            used[s] = 1;
            from = segs[s].a == from ? segs[s].b : segs[s].a;
            c.points.push_back(point_of(from));
            std::size_t next = segs.size();
            for (std::size_t t : at(from))
                if (!used[t]) next = t;
            if (next == segs.size()) {
                for (std::size_t t : at(from))
                    if (t != s && used[t]) closed = true;
                break;
            }
            s = next;
        }
        if (closed && c.points.size() >= 4) {
            c.points.pop_back();
            c.closed = true;
        }
        out.curves.push_back(std::move(c));
    };
    for (std::size_t s = 0; s < segs.size(); ++s) {
        if (used[s]) continue;
        if (at(segs[s].a).size() == 1) follow(segs[s].a, s);
        else if (at(segs[s].b).size() == 1) follow(segs[s].b, s);
    }
    for (std::size_t s = 0; s < segs.size(); ++s)
        if (!used[s]) follow(segs[s].a, s);
    return out;
}

}  // namespace

Arrangement Creases(Field f, CreaseKind kind, double cell, double min_bend) {
    if (!(cell > 0) || !std::isfinite(cell))
        throw Error("Creases", "cell must be a positive number (got " + std::to_string(cell) + ")");
    if (!(min_bend >= 0) || !std::isfinite(min_bend))
        throw Error("Creases", "min_bend must be a non-negative number (got " + std::to_string(min_bend) + ")");
    return Arrangement([f = std::move(f), kind, cell, min_bend](const Region& r) {
        // The surface on the nodes of the squares meeting the box and one ring around them
        // (the differences at the box's nodes read their neighbours), sampled once for both
        // kinds.
        const detail::LatticeWindow w(f, r.bbox(), cell, 1, "Creases");
        if (kind != CreaseKind::Both) return trace(w, kind, cell, min_bend);
        Curves out = trace(w, CreaseKind::Ridge, cell, min_bend);
        for (Curve& c : out.curves) c.labels.add("ridge");
        Curves valleys = trace(w, CreaseKind::Valley, cell, min_bend);
        for (Curve& c : valleys.curves) c.labels.add("valley");
        out.append(std::move(valleys));
        return out;
    });
}

}  // namespace tex
