#include "flow.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <queue>

#include "borders.hpp"

namespace carto::extraction {

namespace {
// Multiple flow directions (Freeman 1991): each lower neighbour gets a share of the area in
// proportion to slope^1.1 (dimensionless exponent).
constexpr double kFreemanExponent = 1.1;
// Cells between diagonal neighbours, in units of the cell size (the walks' steepness).
constexpr double kDiagonalCells = 1.4142135623730951;
}  // namespace

Flow flow(const Grid& g, const std::vector<float>& z, double dx, double dy, double max_fill) {
    const std::size_t n = g.size();
    std::vector<float> filled(z);
    std::vector<int> flooder(n, -1);
    std::vector<std::size_t> order(n, 0);  // pop order of the flood
    std::vector<char> seen(n, 0);
    using Item = std::pair<float, std::size_t>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> pq;
    for (int r = 0; r < g.h; ++r)
        for (int c = 0; c < g.w; ++c) {
            const std::size_t i = g.at(c, r);
            if (std::isnan(z[i])) continue;
            bool border = false;
            for (int k = 0; k < 8 && !border; ++k) {
                const int cc = c + kDc[k], rr = r + kDr[k];
                border = !g.inside(cc, rr) || std::isnan(z[g.at(cc, rr)]);
            }
            if (border) {
                seen[i] = 1;
                pq.push({z[i], i});
            }
        }
    std::size_t popped = 0;
    while (!pq.empty()) {
        const auto [level, i] = pq.top();
        pq.pop();
        order[i] = popped++;
        const int c = int(i % g.w), r = int(i / g.w);
        for (int k = 0; k < 8; ++k) {
            const int cc = c + kDc[k], rr = r + kDr[k];
            if (!g.inside(cc, rr)) continue;
            const std::size_t j = g.at(cc, rr);
            if (seen[j] || std::isnan(z[j])) continue;
            seen[j] = 1;
            filled[j] = std::max(z[j], level);
            flooder[j] = int(i);
            pq.push({filled[j], j});
        }
    }
    // Depressions (8-connected raised cells): shallow ones stay filled, deep ones are restored.
    std::vector<char> raised(n);
    for (std::size_t i = 0; i < n; ++i) raised[i] = !std::isnan(z[i]) && filled[i] > z[i];
    int ndep = 0;
    const std::vector<int> dep = components(g, raised, true, ndep);
    std::vector<float> depth(std::size_t(ndep), 0.0f);
    for (std::size_t i = 0; i < n; ++i)
        if (dep[i] >= 0) depth[dep[i]] = std::max(depth[dep[i]], filled[i] - z[i]);
    std::vector<float> s(filled);
    for (std::size_t i = 0; i < n; ++i)
        if (dep[i] >= 0 && depth[dep[i]] > max_fill) s[i] = z[i];

    // Highest first; on equal heights the later-flooded first (it drains to its flooder).
    std::vector<std::size_t> idx;
    idx.reserve(n);
    for (std::size_t i = 0; i < n; ++i)
        if (!std::isnan(z[i])) idx.push_back(i);
    std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) {
        return s[a] != s[b] ? s[a] > s[b] : order[a] > order[b];
    });
    Flow f;
    f.down.assign(n, -1);
    f.area.assign(n, 0.0);
    const double cell_area = dx * dy, diag = std::hypot(dx, dy);
    for (std::size_t i : idx) {
        f.area[i] += cell_area;
        const int c = int(i % g.w), r = int(i / g.w);
        double best = 0, wsum = 0, w[8];
        for (int k = 0; k < 8; ++k) {
            w[k] = 0;
            const int cc = c + kDc[k], rr = r + kDr[k];
            if (!g.inside(cc, rr)) continue;
            const std::size_t j = g.at(cc, rr);
            if (std::isnan(z[j]) || !(s[j] < s[i])) continue;
            const double dist = (kDc[k] && kDr[k]) ? diag : (kDc[k] ? dx : dy);
            const double slope = (double(s[i]) - s[j]) / dist;
            w[k] = std::pow(slope, kFreemanExponent);
            wsum += w[k];
            if (slope > best) {
                best = slope;
                f.down[i] = int(j);
            }
        }
        if (wsum > 0) {
            for (int k = 0; k < 8; ++k)
                if (w[k] > 0) f.area[g.at(c + kDc[k], r + kDr[k])] += f.area[i] * w[k] / wsum;
        } else if (flooder[i] >= 0 && !(dep[i] >= 0 && depth[dep[i]] > max_fill) &&
                   s[flooder[i]] <= s[i]) {
            f.down[i] = flooder[i];  // a flat (or a filled depression) draining out
            f.area[std::size_t(flooder[i])] += f.area[i];
        }
    }
    return f;
}

double convergence(const Grid& g, const Flow& f, std::size_t i) {
    if (f.down[i] < 0) return 0;
    const int c = int(i % g.w), r = int(i / g.w);
    const int dc = f.down[i] % g.w - c, dr = f.down[i] / g.w - r;
    double sides = 0;
    for (int side : {-1, 1}) {
        const int cc = c - side * dr, rr = r + side * dc;
        sides += g.inside(cc, rr) ? f.area[g.at(cc, rr)] : 0.0;
    }
    return sides > 0 ? 2 * f.area[i] / sides : 1e9;
}

std::vector<char> channels(const Grid& g, const Flow& f, double threshold, double converge,
                           const std::vector<char>& edge, int near) {
    std::vector<char> ch(g.size(), 0);
    for (int r = 0; r < g.h; ++r)
        for (int c = 0; c < g.w; ++c) {
            const std::size_t i = g.at(c, r);
            if (!(f.area[i] >= threshold) || f.down[i] < 0 || ch[i] || edge[i]) continue;
            bool crest = convergence(g, f, i) >= converge;
            // Not a side line along a bigger one: no cell within `near` carries twice the area.
            for (int rr = std::max(0, r - near); crest && rr <= std::min(g.h - 1, r + near); ++rr)
                for (int cc = std::max(0, c - near); crest && cc <= std::min(g.w - 1, c + near);
                     ++cc)
                    if (f.area[g.at(cc, rr)] > 2 * f.area[i]) crest = false;
            if (!crest) continue;
            // Into the border band for a few cells only: the line reaches the edge of the DEM
            // without running along it.
            int band = 0;
            for (std::size_t j = i; f.area[j] >= threshold && !ch[j] && (band += edge[j]) <= 3;) {
                ch[j] = 1;
                if (f.down[j] < 0) break;
                j = std::size_t(f.down[j]);
            }
        }
    return ch;
}

void prune_spurs(const Grid& g, const Flow& f, std::vector<char>& ch, int min_cells, int near) {
    std::vector<int> ups(g.size(), 0);
    for (std::size_t i = 0; i < g.size(); ++i)
        if (ch[i] && f.down[i] >= 0 && ch[f.down[i]]) ++ups[f.down[i]];
    std::vector<std::size_t> heads;
    for (std::size_t i = 0; i < g.size(); ++i)
        if (ch[i] && ups[i] == 0) heads.push_back(i);
    std::vector<int> owner(g.size(), -1);
    std::vector<std::vector<std::size_t>> paths;
    for (std::size_t h : heads) {
        std::vector<std::size_t> path;
        for (std::size_t j = h;;) {
            path.push_back(j);
            const int d = f.down[j];
            if (d < 0 || !ch[d] || ups[d] > 1) break;
            j = std::size_t(d);
        }
        for (std::size_t j : path) owner[j] = int(paths.size());
        paths.push_back(std::move(path));
    }
    std::vector<std::size_t> drop;
    for (std::size_t k = 0; k < paths.size(); ++k) {
        const auto& path = paths[k];
        bool remove = int(path.size()) < min_cells;
        if (!remove) {
            std::size_t beside = 0;
            for (std::size_t i : path) {
                const int c = int(i % g.w), r = int(i / g.w);
                bool found = false;
                for (int rr = std::max(0, r - near); !found && rr <= std::min(g.h - 1, r + near);
                     ++rr)
                    for (int cc = std::max(0, c - near);
                         !found && cc <= std::min(g.w - 1, c + near); ++cc) {
                        const std::size_t j = g.at(cc, rr);
                        found = ch[j] && owner[j] != int(k) && f.area[j] > f.area[i];
                    }
                beside += found;
            }
            remove = 10 * beside > 7 * path.size();
        }
        if (remove) drop.insert(drop.end(), path.begin(), path.end());
    }
    for (std::size_t i : drop) ch[i] = 0;
}

std::vector<float> concavity(const Grid& g, const std::vector<float>& z, double dx, double dy,
                             double dist) {
    std::vector<float> out(g.size(), NAN);
    auto at = [&](double c, double r) -> double {  // bilinear at cell coordinates (centres at .5)
        const double fx = c - 0.5, fy = r - 0.5;
        const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
        const double tx = fx - x0, ty = fy - y0;
        double s = 0;
        for (int k = 0; k < 4; ++k) {
            const int x = x0 + (k & 1), y = y0 + (k >> 1);
            if (!g.inside(x, y) || std::isnan(z[g.at(x, y)])) return NAN;
            s += z[g.at(x, y)] * ((k & 1) ? tx : 1 - tx) * ((k >> 1) ? ty : 1 - ty);
        }
        return s;
    };
    for (int r = 1; r + 1 < g.h; ++r)
        for (int c = 1; c + 1 < g.w; ++c) {
            const double gx = (double(z[g.at(c + 1, r)]) - z[g.at(c - 1, r)]) / (2 * dx);
            const double gy = (double(z[g.at(c, r + 1)]) - z[g.at(c, r - 1)]) / (2 * dy);
            const double n = std::hypot(gx, gy);
            if (!(n > 0)) continue;
            // Contour direction in cell units (perpendicular to the gradient).
            const double ux = -gy / n * dist / dx, uy = gx / n * dist / dy;
            const double a = at(c + 0.5 + ux, r + 0.5 + uy), b = at(c + 0.5 - ux, r + 0.5 - uy);
            out[g.at(c, r)] = float(z[g.at(c, r)] - (a + b) / 2);
        }
    return out;
}

void extend_heads(const Grid& g, std::vector<int>& down, std::vector<char>& ch,
                  std::vector<char>& straight, const std::vector<float>& z,
                  const std::vector<float>& conc, double depth, const std::vector<char>& stop,
                  const std::vector<char>& rock, const std::vector<char>& open, int max_cells,
                  int finish) {
    std::vector<char> has_up(g.size(), 0);
    for (std::size_t i = 0; i < g.size(); ++i)
        if (ch[i] && down[i] >= 0) has_up[down[i]] = 1;
    std::vector<std::size_t> heads;
    for (std::size_t i = 0; i < g.size(); ++i)
        if (ch[i] && !has_up[i]) heads.push_back(i);
    std::vector<std::size_t> path;
    std::vector<char> steep;  // per step of the path: taken by the steepest finish
    auto keep = [&](std::size_t marked) {
        for (std::size_t k = 1; k < marked; ++k) {
            ch[path[k]] = 1;
            down[path[k]] = int(path[k - 1]);
            straight[path[k]] = k < steep.size() && steep[k];
        }
    };
    for (std::size_t h : heads) {
        path.assign(1, h);
        steep.assign(1, 0);
        int weak = 0, finishing = -1;
        bool in_rock = rock[h] || open[h];
        std::size_t fallback =
            0;  // the steps kept if the walk, having entered a hole, gets nowhere
        while (int(path.size()) <= max_cells) {
            const std::size_t i = path.back();
            const int c = int(i % g.w), r = int(i / g.w);
            int best = -1, edge = -1;
            double key = 0;
            for (int k = 0; k < 8; ++k) {
                const int cc = c + kDc[k], rr = r + kDr[k];
                if (!g.inside(cc, rr)) continue;
                const std::size_t j = g.at(cc, rr);
                if (rock[j] && (cc == 0 || rr == 0 || cc == g.w - 1 || rr == g.h - 1) && edge < 0)
                    edge = int(j);
                if (!(z[j] > z[i]) || std::isnan(conc[j])) continue;
                // Along the floor: the most concave; finishing: the steepest.
                const double v =
                    finishing < 0 ? conc[j] : -(z[j] - z[i]) / ((kDc[k] && kDr[k]) ? kDiagonalCells : 1.0);
                if (best < 0 || v < key) best = int(j), key = v;
            }
            if (in_rock && edge >= 0 &&
                path.size() > 1) {  // at the grid's edge: the edge cell ends the line
                path.push_back(std::size_t(edge));
                steep.push_back(finishing >= 0);
                keep(path.size());
                fallback = 0;
                break;
            }
            if (best < 0) break;
            if (stop[best] || (in_rock && open[best])) {
                path.push_back(std::size_t(best));
                keep(path.size() - 1);
                fallback = 0;
                break;
            }
            // Into a hole of the rock: crossed (ending there seldom cuts the face), but the
            // steps so far are kept if nothing better is reached.
            if (in_rock && !rock[best] && !fallback && rock[i]) fallback = path.size();
            in_rock = in_rock || rock[best];
            if (finishing < 0) {
                weak = conc[best] <= -depth ? 0 : weak + 1;
                if (weak > 2) finishing = 0;
            } else if (++finishing > finish) {
                break;
            }
            path.push_back(std::size_t(best));
            steep.push_back(finishing >= 0);
        }
        if (fallback) keep(fallback);
    }
}

std::vector<LabelledLine> trace_network(const Grid& g, const std::vector<int>& down,
                                        const std::vector<char>& ch, const std::vector<char>& rock,
                                        LineKind kind, const Raster& grid, double tol) {
    std::vector<char> has_up(g.size(), 0), done(g.size(), 0);
    for (std::size_t i = 0; i < g.size(); ++i)
        if (ch[i] && rock[i] && down[i] >= 0) has_up[down[i]] = 1;
    std::vector<LabelledLine> out;
    auto run = [&](std::size_t start) {
        std::vector<Point> pts;
        for (std::size_t j = start;;) {
            pts.push_back({j % g.w + 0.5, j / g.w + 0.5});
            if (done[j]) break;
            done[j] = 1;
            const int d = down[j];
            if (d < 0 || !ch[d] || !rock[d]) break;
            j = std::size_t(d);
        }
        if (pts.size() < 2) return;
        LabelledLine l;
        l.kind = kind;
        for (const Point& q : simplify(pts, false, tol))
            l.points.push_back(whole_pixel_to_world(grid, q + window_offset(grid)));
        out.push_back(std::move(l));
    };
    for (std::size_t i = 0; i < g.size(); ++i)
        if (ch[i] && rock[i] && !has_up[i]) run(i);
    for (std::size_t i = 0; i < g.size(); ++i)  // loops without a head (none expected)
        if (ch[i] && rock[i] && !done[i]) run(i);
    return out;
}

}  // namespace carto::extraction
