#include "carto/fields.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <unordered_map>

#include "carto/hatching.hpp"

namespace carto {

Field raster_field(const Raster& r, double offset, double range) {
    return [&r, offset, range](const Point& q) { return (r.sample(q) - offset) / range; };
}

Field face_field(const Partition& p, std::vector<double> values) {
    // A grid of face boxes, so a lookup tests only the faces near the point.
    struct Index {
        tex::BBox box;
        double cell = 1;
        int nx = 1, ny = 1;
        std::vector<std::vector<int>> cells;
        std::vector<double> values;
        const Partition* part;
    };
    auto idx = std::make_shared<Index>();
    idx->part = &p;
    idx->values = std::move(values);
    idx->box = p.bounds();
    const double side = std::sqrt(std::max(1.0, double(p.faces.size())));
    idx->cell = std::max(idx->box.width(), idx->box.height()) / side + 1e-9;
    idx->nx = std::max(1, int(std::ceil(idx->box.width() / idx->cell)));
    idx->ny = std::max(1, int(std::ceil(idx->box.height() / idx->cell)));
    idx->cells.resize(std::size_t(idx->nx) * idx->ny);
    for (std::size_t i = 0; i < p.faces.size(); ++i) {
        const tex::BBox& b = p.faces[i].region.bbox();
        const int x0 = std::clamp(int((b.xmin - idx->box.xmin) / idx->cell), 0, idx->nx - 1);
        const int x1 = std::clamp(int((b.xmax - idx->box.xmin) / idx->cell), 0, idx->nx - 1);
        const int y0 = std::clamp(int((b.ymin - idx->box.ymin) / idx->cell), 0, idx->ny - 1);
        const int y1 = std::clamp(int((b.ymax - idx->box.ymin) / idx->cell), 0, idx->ny - 1);
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) idx->cells[std::size_t(y) * idx->nx + x].push_back(int(i));
    }
    return [idx](const Point& q) {
        if (!idx->box.contains(q)) return std::nan("");
        const int x = std::clamp(int((q.x - idx->box.xmin) / idx->cell), 0, idx->nx - 1);
        const int y = std::clamp(int((q.y - idx->box.ymin) / idx->cell), 0, idx->ny - 1);
        for (int i : idx->cells[std::size_t(y) * idx->nx + x])
            if (idx->part->faces[i].region.contains(q)) return idx->values[i];
        return std::nan("");
    };
}

Field constant_field(double v) {
    return [v](const Point&) { return v; };
}

Point interior_point(const RockFace& f) {
    const Point c = ring_centroid(f.region.outer());
    if (f.region.contains(c)) return c;
    // Step inwards from the middle of the longest border segment of the outer ring.
    const auto& ring = f.region.outer();
    std::size_t best = 0;
    double len = -1;
    for (std::size_t i = 0; i < ring.size(); ++i) {
        const double l = tex::distance(ring[i], ring[(i + 1) % ring.size()]);
        if (l > len) {
            len = l;
            best = i;
        }
    }
    const Point a = ring[best], b = ring[(best + 1) % ring.size()];
    const Point d = (b - a) / std::max(len, 1e-300);
    const Point inward{-d.y, d.x};  // the outer ring is counter-clockwise: inside on the left
    for (double eps = len * 0.25; eps > len * 1e-6; eps /= 2) {
        const Point q = (a + b) / 2 + inward * eps;
        if (f.region.contains(q)) return q;
    }
    return (a + b) / 2;
}

namespace {

// Sample points inside a face (a lattice of about 400 points, no finer than the cells).
template <class F>
void for_face_samples(const RockFace& f, double cell, F&& fn) {
    const tex::BBox& b = f.region.bbox();
    const double step = std::max(cell, std::max(b.width(), b.height()) / 20);
    for (double y = b.ymin + step / 2; y < b.ymax; y += step)
        for (double x = b.xmin + step / 2; x < b.xmax; x += step)
            if (f.region.contains({x, y})) fn(Point{x, y});
}

}  // namespace

std::pair<std::size_t, std::size_t> derive_face_controls(Partition& p, const Terrain& t) {
    std::size_t derived_o = 0, derived_d = 0;
    const double cell = t.elevation.cell_x();
    for (RockFace& f : p.faces) {
        if (!f.orientation) {
            double sx = 0, sy = 0;
            for_face_samples(f, cell, [&](const Point& q) {
                const double a = t.aspect.sample(q), s = t.slope.nearest(q);
                if (std::isnan(a) || std::isnan(s)) return;
                sx += s * std::cos(a);
                sy += s * std::sin(a);
            });
            f.orientation = (sx == 0 && sy == 0) ? 0.0 : std::atan2(sy, sx);
            ++derived_o;
        }
        if (!f.density) {
            double sum = 0;
            int n = 0;
            for_face_samples(f, cell, [&](const Point& q) {
                const double h = t.hillshade.sample(q);
                if (!std::isnan(h)) {
                    sum += h;
                    ++n;
                }
            });
            f.density = n ? std::clamp(1.0 - sum / n, 0.0, 1.0) : 0.5;
            ++derived_d;
        }
    }
    return {derived_o, derived_d};
}

}  // namespace carto
