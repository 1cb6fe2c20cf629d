#include "carto/fields.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>

#include "carto/hatching.hpp"

namespace carto {

namespace {

// A raster read in place: no copy of its cells.
class RasterFieldImpl : public tex::FieldImpl {
public:
    RasterFieldImpl(std::shared_ptr<const Raster> r, double offset, double range)
        : r_(std::move(r)), offset_(offset), range_(range) {}
    double eval(const Point& q) const override { return (r_->sample(q) - offset_) / range_; }
    std::optional<tex::BBox> domain() const override { return r_->bounds(); }
    const char* kind() const override { return "raster"; }

private:
    std::shared_ptr<const Raster> r_;
    double offset_, range_;
};

}  // namespace

Field raster_field(const Raster& r, double offset, double range) {
    // The caller keeps the raster alive (a non-owning pointer).
    return raster_field(std::shared_ptr<const Raster>(std::shared_ptr<const Raster>(), &r), offset, range);
}

Field raster_field(std::shared_ptr<const Raster> r, double offset, double range) {
    return Field(std::make_shared<RasterFieldImpl>(std::move(r), offset, range));
}

Field face_field(const Partition& p, std::vector<double> values) {
    std::vector<tex::Region> regions;
    regions.reserve(p.faces.size());
    for (const auto& f : p.faces) regions.push_back(f.region);
    return tex::RegionField(std::move(regions), std::move(values));
}

Field constant_field(double v) { return tex::ConstantField(v); }

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
