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

}  // namespace carto
