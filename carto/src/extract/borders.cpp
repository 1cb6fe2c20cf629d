#include "borders.hpp"

#include <algorithm>
#include <cmath>

#include "../corner_cut.hpp"

namespace carto::extraction {

double seg_dist(const Point& p, const Point& a, const Point& b) {
    const Point d = b - a;
    const double l2 = tex::dot(d, d);
    const double t = l2 > 0 ? std::clamp(tex::dot(p - a, d) / l2, 0.0, 1.0) : 0.0;
    return tex::distance(p, a + d * t);
}

void douglas_peucker(const std::vector<Point>& pts, std::size_t a, std::size_t b, double tol,
                     std::vector<char>& keep) {
    if (b <= a + 1) return;
    double best = -1;
    std::size_t idx = a;
    for (std::size_t i = a + 1; i < b; ++i) {
        const double d = seg_dist(pts[i], pts[a], pts[b]);
        if (d > best) {
            best = d;
            idx = i;
        }
    }
    if (best <= tol) return;
    keep[idx] = 1;
    douglas_peucker(pts, a, idx, tol, keep);
    douglas_peucker(pts, idx, b, tol, keep);
}

std::vector<Point> simplify(const std::vector<Point>& pts, bool closed, double tol) {
    std::vector<char> keep(pts.size(), 0);
    keep.front() = keep.back() = 1;
    if (closed) {
        // Fix the start and the corner farthest from it, simplify both halves.
        std::size_t far = 0;
        for (std::size_t i = 0; i < pts.size(); ++i)
            if (tex::distance(pts[i], pts[0]) > tex::distance(pts[far], pts[0])) far = i;
        keep[far] = 1;
        douglas_peucker(pts, 0, far, tol, keep);
        douglas_peucker(pts, far, pts.size() - 1, tol, keep);
    } else {
        douglas_peucker(pts, 0, pts.size() - 1, tol, keep);
    }
    std::vector<Point> out;
    for (std::size_t i = 0; i < pts.size(); ++i)
        if (keep[i]) out.push_back(pts[i]);
    // A closed ring needs at least three distinct corners.
    if (closed && out.size() < 4) return pts;
    return out;
}

std::vector<Point> cut_steps(const std::vector<Point>& cuts, bool closed, const Point& from,
                             const Point& to) {
    std::vector<Point> out;
    out.reserve(cuts.size() + 2);
    if (!closed) out.push_back(from);
    out.insert(out.end(), cuts.begin(), cuts.end());
    if (closed)
        out.push_back(cuts.front());
    else
        out.push_back(to);
    return out;
}

std::vector<Point> generalise(const std::vector<Point>& cut, bool closed, double tol, int rounds) {
    if (cut.size() < 3) return cut;
    return cut_corners(simplify(cut, closed, tol), rounds);
}

std::vector<Chain> trace_chains(const Grid& g, const std::vector<int>& face,
                                const std::vector<int>& kind) {
    auto label = [&](int c, int r) { return g.inside(c, r) ? face[g.at(c, r)] : -1; };
    const int W = g.w + 1, H = g.h + 1;
    // Edge from corner (i, j) in direction d exists when the two cells across it differ.
    auto cells = [&](int i, int j, int d, int& right, int& left, int& rc, int& rr, int& lc,
                     int& lr) {
        switch (d) {
            case 0:
                rc = i, rr = j - 1, lc = i, lr = j;
                break;  // E
            case 1:
                rc = i, rr = j, lc = i - 1, lr = j;
                break;  // S
            case 2:
                rc = i - 1, rr = j, lc = i - 1, lr = j - 1;
                break;  // W
            default:
                rc = i - 1, rr = j - 1, lc = i, lr = j - 1;
                break;  // N
        }
        right = label(rc, rr);
        left = label(lc, lr);
    };
    auto edge_exists = [&](int i, int j, int d) {
        const int ni = i + kCx[d], nj = j + kCy[d];
        if (ni < 0 || nj < 0 || ni >= W || nj >= H) return false;
        int right, left, rc, rr, lc, lr;
        cells(i, j, d, right, left, rc, rr, lc, lr);
        return right != left;
    };
    // Visited edges: horizontal ones keyed by their west corner, vertical ones by their north.
    std::vector<char> hseen(std::size_t(W) * H, 0), vseen(std::size_t(W) * H, 0);
    auto seen = [&](int i, int j, int d) -> char& {
        switch (d) {
            case 0:
                return hseen[std::size_t(j) * W + i];
            case 2:
                return hseen[std::size_t(j) * W + i - 1];
            case 1:
                return vseen[std::size_t(j) * W + i];
            default:
                return vseen[std::size_t(j - 1) * W + i];
        }
    };
    auto degree = [&](int i, int j) {
        int n = 0;
        for (int d = 0; d < 4; ++d) n += edge_exists(i, j, d);
        return n;
    };
    std::vector<Chain> chains;
    auto trace = [&](int i0, int j0, int d0) {
        Chain ch;
        int right, left, rc, rr, lc, lr;
        cells(i0, j0, d0, right, left, rc, rr, lc, lr);
        ch.right = right;
        ch.left = left;
        ch.first_dir = d0;
        ch.start = (long long)j0 * W + i0;
        ch.raw.push_back({double(i0), double(j0)});
        int i = i0, j = j0, d = d0;
        while (true) {
            seen(i, j, d) = 1;
            cells(i, j, d, right, left, rc, rr, lc, lr);
            const int kr = g.inside(rc, rr) ? kind[g.at(rc, rr)] : 0,
                      kl = g.inside(lc, lr) ? kind[g.at(lc, lr)] : 0;
            ch.edges.push_back((unsigned char)((kr == 1 || kl == 1) | ((kr == 2 || kl == 2) << 1)));
            ch.last_dir = d;
            i += kCx[d];
            j += kCy[d];
            ch.raw.push_back({double(i), double(j)});
            if (i == i0 && j == j0) {
                ch.closed = degree(i, j) == 2;
                break;
            }
            if (degree(i, j) != 2) break;
            int next = -1;
            for (int e = 0; e < 4; ++e)
                if (e != (d + 2) % 4 && edge_exists(i, j, e)) next = e;
            d = next;
        }
        ch.end = (long long)j * W + i;
        chains.push_back(std::move(ch));
    };
    for (int j = 0; j < H; ++j)
        for (int i = 0; i < W; ++i)
            if (degree(i, j) > 2)
                for (int d = 0; d < 4; ++d)
                    if (edge_exists(i, j, d) && !seen(i, j, d)) trace(i, j, d);
    // Closed loops without a node: start at their first corner in raster order.
    for (int j = 0; j < H; ++j)
        for (int i = 0; i < W; ++i)
            for (int d = 0; d < 4; ++d)
                if (edge_exists(i, j, d) && !seen(i, j, d)) trace(i, j, d);
    return chains;
}

std::vector<Chain> label_chains(std::vector<Chain> chains, int corner_w, int min_run,
                                bool outline) {
    auto dir_of = [](const Point& a, const Point& b) {
        return b.x > a.x ? 0 : b.y > a.y ? 1 : b.x < a.x ? 2 : 3;
    };
    auto corner = [&](const Point& q) {
        return (long long)std::lround(q.y) * corner_w + std::lround(q.x);
    };
    auto kind_of = [](int l) {
        return l == 1 ? LineKind::Ridge : l == 2 ? LineKind::Valley : LineKind::Other;
    };
    std::vector<Chain> out;
    for (Chain& ch : chains) {
        const std::size_t n = ch.edges.size();
        std::vector<int> lab(n, 0);
        if (outline || (ch.right >= 0 && ch.left >= 0))
            for (std::size_t e = 0; e < n; ++e)
                lab[e] = (ch.edges[e] & 1) ? 1 : (ch.edges[e] & 2) ? 2 : 0;
        // A loop without a node starts where its label changes, so its first and last pieces
        // differ.
        if (ch.closed && lab[n - 1] == lab[0]) {
            std::size_t s = n;  // start of the last run
            while (s > 0 && lab[s - 1] == lab[n - 1]) --s;
            if (s > 0) {
                std::rotate(lab.begin(), lab.begin() + long(s), lab.end());
                std::rotate(ch.edges.begin(), ch.edges.begin() + long(s), ch.edges.end());
                ch.raw.pop_back();
                std::rotate(ch.raw.begin(), ch.raw.begin() + long(s), ch.raw.end());
                ch.raw.push_back(ch.raw.front());
                ch.start = ch.end = corner(ch.raw.front());
                ch.first_dir = dir_of(ch.raw[0], ch.raw[1]);
                ch.last_dir = dir_of(ch.raw[n - 1], ch.raw[n]);
            }
        }
        struct Run {
            int label;
            std::size_t begin, len;
        };
        std::vector<Run> runs;
        for (std::size_t e = 0; e < n; ++e)
            if (runs.empty() || runs.back().label != lab[e])
                runs.push_back({lab[e], e, 1});
            else
                ++runs.back().len;
        auto merge_equal = [&] {
            std::vector<Run> m;
            for (const Run& r : runs)
                if (!m.empty() && m.back().label == r.label)
                    m.back().len += r.len;
                else
                    m.push_back(r);
            runs = std::move(m);
        };
        while (runs.size() > 1) {
            std::size_t k = 0;
            for (std::size_t q = 1; q < runs.size(); ++q)
                if (runs[q].len < runs[k].len) k = q;
            if (int(runs[k].len) >= min_run) break;
            const Run* a = k > 0 ? &runs[k - 1] : nullptr;
            const Run* b = k + 1 < runs.size() ? &runs[k + 1] : nullptr;
            runs[k].label = (!b || (a && a->len >= b->len)) ? a->label : b->label;
            merge_equal();
        }
        if (runs.size() == 1) {
            ch.kind = kind_of(runs[0].label);
            out.push_back(std::move(ch));
            continue;
        }
        for (const Run& r : runs) {
            Chain piece;
            piece.raw.assign(ch.raw.begin() + long(r.begin),
                             ch.raw.begin() + long(r.begin + r.len + 1));
            piece.edges.assign(ch.edges.begin() + long(r.begin),
                               ch.edges.begin() + long(r.begin + r.len));
            piece.right = ch.right;
            piece.left = ch.left;
            piece.first_dir = dir_of(piece.raw[0], piece.raw[1]);
            piece.last_dir = dir_of(piece.raw[piece.raw.size() - 2], piece.raw.back());
            piece.start = corner(piece.raw.front());
            piece.end = corner(piece.raw.back());
            piece.kind = kind_of(r.label);
            out.push_back(std::move(piece));
        }
    }
    return out;
}

}  // namespace carto::extraction
