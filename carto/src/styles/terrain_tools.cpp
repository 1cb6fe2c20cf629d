#include "terrain_tools.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>
#include <tuple>

#include "carto/error.hpp"
#include "libtex/parallel.hpp"

namespace carto::terrain {

namespace {
// Sides of the polygon standing for the round dot of a zero-length hatch.
constexpr int kDiscSides = 8;
}  // namespace

Raster cell_mask(const Raster& like, const std::function<bool(int, int)>& keep) {
    Raster m = like;
    tex::parallel_for(std::size_t(like.height), [&](std::size_t row) {
        const int r = int(row);
        for (int c = 0; c < like.width; ++c) m.at(c, r) = std::isnan(like.at(c, r)) ? NAN : (keep(c, r) ? 1.0f : 0.0f);
    });
    return m;
}

RockProximity rock_proximity(const Partition& p, const Raster& elevation, double radius) {
    const int w = elevation.width, h = elevation.height;
    const std::size_t n = std::size_t(w) * std::size_t(h);
    // The rock cells: centres inside a face (each face tested only over its bounding box).
    std::vector<char> rock(n, 0);
    for (const auto& f : p.faces) {
        const tex::BBox b = f.region.bbox();
        const Point a = elevation.to_pixel({b.xmin, b.ymin}), z = elevation.to_pixel({b.xmax, b.ymax});
        const int c0 = std::max(0, int(std::floor(std::min(a.x, z.x)))), c1 = std::min(w - 1, int(std::ceil(std::max(a.x, z.x))));
        const int r0 = std::max(0, int(std::floor(std::min(a.y, z.y)))), r1 = std::min(h - 1, int(std::ceil(std::max(a.y, z.y))));
        for (int r = r0; r <= r1; ++r)
            for (int c = c0; c <= c1; ++c)
                if (!rock[std::size_t(r) * w + c] && f.region.contains(elevation.grid_world(c + 0.5, r + 0.5)))
                    rock[std::size_t(r) * w + c] = 1;
    }
    // The cell offsets within the radius, nearest first (ties in a fixed order): the first
    // offset that lands on rock is the nearest rock cell, found the same way in any window.
    const double hx = elevation.cell_x(), hy = elevation.cell_y();
    const int rc = std::max(0, int(std::floor(radius / hx))), rr = std::max(0, int(std::floor(radius / hy)));
    struct Offset {
        double d2;
        int dc, dr;
    };
    std::vector<Offset> offsets;
    for (int dr = -rr; dr <= rr; ++dr)
        for (int dc = -rc; dc <= rc; ++dc) {
            const double dx = double(dc) * hx, dy = double(dr) * hy, d2 = dx * dx + dy * dy;
            if (d2 <= radius * radius) offsets.push_back({d2, dc, dr});
        }
    std::sort(offsets.begin(), offsets.end(), [](const Offset& a, const Offset& b) {
        return std::tie(a.d2, a.dr, a.dc) < std::tie(b.d2, b.dr, b.dc);
    });
    // Rock cells counted over rectangles (summed-area table): a cell with no rock in the
    // square around it skips the scan.
    std::vector<std::uint32_t> sum(std::size_t(w + 1) * std::size_t(h + 1), 0);
    for (int r = 0; r < h; ++r)
        for (int c = 0; c < w; ++c)
            sum[std::size_t(r + 1) * (w + 1) + c + 1] = sum[std::size_t(r) * (w + 1) + c + 1] +
                                                        sum[std::size_t(r + 1) * (w + 1) + c] -
                                                        sum[std::size_t(r) * (w + 1) + c] + rock[std::size_t(r) * w + c];
    auto count = [&](int c0, int r0, int c1, int r1) {  // inclusive, clamped
        c0 = std::max(c0, 0), r0 = std::max(r0, 0), c1 = std::min(c1, w - 1), r1 = std::min(r1, h - 1);
        if (c0 > c1 || r0 > r1) return 0u;
        const std::size_t W = std::size_t(w) + 1;
        return sum[(r1 + 1) * W + c1 + 1] - sum[r0 * W + c1 + 1] - sum[(r1 + 1) * W + c0] + sum[r0 * W + c0];
    };
    RockProximity out{elevation, elevation};
    tex::parallel_for(std::size_t(h), [&](std::size_t row) {
        const int r = int(row);
        for (int c = 0; c < w; ++c) {
            const std::size_t i = std::size_t(r) * w + c;
            out.distance.data[i] = std::numeric_limits<float>::infinity();
            out.rock_elevation.data[i] = NAN;
            if (count(c - rc, r - rr, c + rc, r + rr) == 0) continue;
            for (const Offset& o : offsets) {
                const int cc = c + o.dc, rw = r + o.dr;
                if (cc < 0 || rw < 0 || cc >= w || rw >= h || !rock[std::size_t(rw) * w + cc]) continue;
                out.distance.data[i] = float(std::sqrt(o.d2));
                out.rock_elevation.data[i] = elevation.data[std::size_t(rw) * w + cc];
                break;
            }
        }
    });
    return out;
}

TileIndex tile_of(const Point& p, double side) {
    return {(long long)std::floor(p.x / side), (long long)std::floor(p.y / side)};
}

tex::BBox tile_box(const TileIndex& t, double side) {
    return {double(t.first) * side, double(t.second) * side, double(t.first + 1) * side, double(t.second + 1) * side};
}

const tex::disc::RegionSet& Placed::tagged(long long tag) const {
    static const tex::disc::RegionSet none;
    const auto it = by_tag.find(tag);
    return it == by_tag.end() ? none : it->second;
}

namespace {
int phase_of(const TileIndex& t) { return int(t.second & 1) * 2 + int(t.first & 1); }
}  // namespace

std::vector<Element> throw_in_phases(std::vector<TileIndex> work, double side, const std::optional<tex::BBox>& window,
                                     bool by_tag, const ThrowTile& throw_tile) {
    std::sort(work.begin(), work.end());
    work.erase(std::unique(work.begin(), work.end()), work.end());
    auto has_work = [&](const TileIndex& t) { return std::binary_search(work.begin(), work.end(), t); };
    // The tiles to throw: all, or the window's own and, transitively, their neighbours of
    // earlier phases (whose elements they see).
    std::set<TileIndex> run, own;
    if (!window) {
        run.insert(work.begin(), work.end());
        own = run;
    } else {
        std::vector<TileIndex> pending;
        for (const TileIndex& t : work) {
            const tex::BBox b = tile_box(t, side);
            if (owns(*window, {0.5 * (b.xmin + b.xmax), 0.5 * (b.ymin + b.ymax)})) {
                own.insert(t), run.insert(t), pending.push_back(t);
            }
        }
        while (!pending.empty()) {
            const TileIndex t = pending.back();
            pending.pop_back();
            for (long long dj = -1; dj <= 1; ++dj)
                for (long long di = -1; di <= 1; ++di) {
                    const TileIndex u{t.first + di, t.second + dj};
                    if (phase_of(u) < phase_of(t) && has_work(u) && run.insert(u).second) pending.push_back(u);
                }
        }
    }
    Placed before;
    // Per element of before.all, in its order: its tag and whether the caller gets it.
    std::vector<long long> tags;
    std::vector<char> kept;
    for (int phase = 0; phase < 4; ++phase) {
        std::vector<TileIndex> tiles;
        for (const TileIndex& t : run)
            if (phase_of(t) == phase) tiles.push_back(t);
        std::vector<std::vector<Element>> thrown(tiles.size());
        tex::parallel_for(tiles.size(), [&](std::size_t k) { thrown[k] = throw_tile(tiles[k], before); });
        std::vector<tex::Region> joined;
        std::map<long long, std::vector<tex::Region>> tagged;
        for (std::size_t k = 0; k < tiles.size(); ++k) {
            const char mine = char(own.count(tiles[k]));
            for (Element& e : thrown[k]) {
                if (by_tag) tagged[e.tag].push_back(e.region);
                tags.push_back(e.tag);
                kept.push_back(mine);
                joined.push_back(std::move(e.region));
            }
        }
        before.all.add(std::move(joined));
        for (auto& [tag, v] : tagged) before.by_tag[tag].add(std::move(v));
    }
    std::vector<Element> out;
    const std::vector<tex::Region>& all = before.all.regions();
    for (std::size_t i = 0; i < all.size(); ++i)
        if (kept[i]) out.push_back({all[i], tags[i]});
    return out;
}

tex::disc::FlowField fall_line(std::shared_ptr<const Raster> elevation, double step) {
    const double hx = elevation->cell_x(), hy = elevation->cell_y();
    return [elevation, step, hx, hy](const Point& p) -> Point {
        const double e = elevation->sample({p.x + hx, p.y}), wv = elevation->sample({p.x - hx, p.y});
        const double nv = elevation->sample({p.x, p.y + hy}), s = elevation->sample({p.x, p.y - hy});
        const double gx = (e - wv) / (2 * hx), gy = (nv - s) / (2 * hy);
        const double g = std::hypot(gx, gy);
        if (!std::isfinite(g) || g < 1e-9) return {0, 0};
        return {-gx / g * step, -gy / g * step};
    };
}

tex::disc::RegionSet hatch_obstacles(const std::vector<Hatch>& rock, double scale, double clearance,
                                     const tex::BBox& near) {
    // Each hatch's pieces are made on their own (in parallel, stored by index) and joined in
    // the order of the hatches, so the set is the same at any thread count; the index is
    // then bulk-loaded in one go.
    std::vector<std::vector<tex::Region>> pieces(rock.size());
    tex::parallel_for(rock.size(), [&](std::size_t k) {
        const Hatch& h = rock[k];
        // Segment by segment: a stroke that folds back on itself has no area as one ring.
        const double w = family_width_mm(h.family) * scale / 1000.0 + 2 * clearance;
        tex::BBox b;
        for (const auto& q : h.points) b.add(q);
        if (!tex::BBox{b.xmin - w, b.ymin - w, b.xmax + w, b.ymax + w}.intersects(near)) return;
        const std::size_t n = h.points.size(), segs = h.closed ? n : n - 1;
        for (std::size_t i = 0; n > 1 && i < segs; ++i) {
            const Point a = h.points[i], z = h.points[(i + 1) % n];
            // A speck of a hatch still inks a dot (round caps): a disc, whose polygon
            // circumscribes the circle of the ink.
            if (tex::distance(a, z) < 1e-6 * w)
                pieces[k].push_back(tex::disc::Translation(
                    tex::disc::BuiltinCircle(w / 2 / std::cos(M_PI / kDiscSides), kDiscSides), a));
            else {
                // Square caps half the width long cover the round caps of the drawn stroke.
                const Point u = (z - a) / tex::distance(a, z) * (w / 2);
                pieces[k].push_back(tex::disc::ApplyThickness({{a - u, z + u}, false}, [w](double) { return w; }));
            }
        }
    });
    std::vector<tex::Region> all;
    for (auto& v : pieces)
        for (auto& r : v) all.push_back(std::move(r));
    tex::disc::RegionSet set;
    set.add(std::move(all));
    return set;
}

double ramp(double v, double lo, double hi) {
    if (std::isnan(v)) return 0;
    if (!(hi > lo)) return v >= hi ? 1.0 : 0.0;
    return std::clamp((v - lo) / (hi - lo), 0.0, 1.0);
}

Weight ground_weight(const Terrain& t, double slope_min, double slope_max, double shade) {
    auto slope = std::make_shared<const Raster>(t.slope), light = std::make_shared<const Raster>(t.hillshade);
    return [=](const Point& q) {
        const double l = light->sample(q), dark = std::isnan(l) ? 0 : 1 - l;
        return (1 - shade) * ramp(slope->sample(q), slope_min, slope_max) + shade * dark;
    };
}

tex::disc::Check all_vertices(tex::disc::PointCheck inside) {
    return [inside](const tex::Region& r) {
        return std::all_of(r.outer().begin(), r.outer().end(), [&](const Point& q) { return inside(q); });
    };
}

void require_order(const char* style, const char* lo_name, double lo, const char* hi_name, double hi) {
    if (lo <= hi) return;
    std::ostringstream m;
    m << "--param " << lo_name << ": must not exceed " << hi_name << " for style '" << style << "'";
    throw Error(Code::Usage, m.str());
}

Hatch ring_hatch(const tex::Region& r, Family f) { return Hatch{r.outer(), true, f}; }

}  // namespace carto::terrain
