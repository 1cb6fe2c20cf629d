#include "terrain.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "carto/error.hpp"
#include "libtex/parallel.hpp"

namespace carto::terrain {

namespace {
// Sides of the polygon standing for the round dot of a zero-length hatch.
constexpr int kDiscSides = 8;
}  // namespace

Raster cell_mask(const Raster& like, const std::function<bool(int, int)>& keep) {
    Raster m = like;
    for (int r = 0; r < like.height; ++r)
        for (int c = 0; c < like.width; ++c)
            m.at(c, r) = std::isnan(like.at(c, r)) ? NAN : (keep(c, r) ? 1.0f : 0.0f);
    return m;
}

RockProximity rock_proximity(const Partition& p, const Raster& elevation) {
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
                if (!rock[std::size_t(r) * w + c] && f.region.contains(elevation.to_world(c + 0.5, r + 0.5)))
                    rock[std::size_t(r) * w + c] = 1;
    }
    // Nearest rock cell by two raster sweeps (each cell takes the best source of the
    // neighbours already swept), repeated once to settle the corners.
    constexpr long long kNone = -1;
    std::vector<long long> src(n, kNone);
    for (std::size_t i = 0; i < n; ++i)
        if (rock[i]) src[i] = (long long)i;
    auto dist2 = [&](std::size_t i, long long s) {
        if (s < 0) return std::numeric_limits<double>::infinity();
        const double dx = (double(i % w) - double(s % w)) * elevation.cell_x();
        const double dy = (double(i / w) - double(s / w)) * elevation.cell_y();
        return dx * dx + dy * dy;
    };
    auto relax = [&](int c, int r, int dc, int dr) {
        const int cc = c + dc, rr = r + dr;
        if (cc < 0 || rr < 0 || cc >= w || rr >= h) return;
        const std::size_t i = std::size_t(r) * w + c, j = std::size_t(rr) * w + cc;
        if (src[j] != kNone && dist2(i, src[j]) < dist2(i, src[i])) src[i] = src[j];
    };
    for (int round = 0; round < 2; ++round) {
        for (int r = 0; r < h; ++r)
            for (int c = 0; c < w; ++c) {
                relax(c, r, -1, -1), relax(c, r, 0, -1), relax(c, r, 1, -1), relax(c, r, -1, 0);
            }
        for (int r = h - 1; r >= 0; --r)
            for (int c = w - 1; c >= 0; --c) {
                relax(c, r, 1, 1), relax(c, r, 0, 1), relax(c, r, -1, 1), relax(c, r, 1, 0);
            }
    }
    RockProximity out{elevation, elevation};
    for (std::size_t i = 0; i < n; ++i) {
        out.distance.data[i] = float(std::sqrt(dist2(i, src[i])));
        out.rock_elevation.data[i] = src[i] == kNone ? NAN : elevation.data[std::size_t(src[i])];
    }
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

tex::Region frame(const Raster& r) {
    const tex::BBox b = r.bounds();
    return tex::Region({{b.xmin, b.ymin}, {b.xmax, b.ymin}, {b.xmax, b.ymax}, {b.xmin, b.ymax}});
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
