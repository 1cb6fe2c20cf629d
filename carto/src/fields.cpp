#include "carto/fields.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>


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

Point interior_point(const tex::Region& r) {
    const auto& ring = r.outer();
    Point c{0, 0};
    double a = 0;
    for (std::size_t i = 0, n = ring.size(); i < n; ++i) {
        const double w = tex::cross(ring[i], ring[(i + 1) % n]);
        a += w;
        c += (ring[i] + ring[(i + 1) % n]) * w;
    }
    if (a != 0) c = c / (3 * a);
    if (a != 0 && r.contains(c)) return c;
    // Step inwards from the middle of the longest border segment of the outer ring.
    std::size_t best = 0;
    double len = -1;
    for (std::size_t i = 0; i < ring.size(); ++i) {
        const double l = tex::distance(ring[i], ring[(i + 1) % ring.size()]);
        if (l > len) {
            len = l;
            best = i;
        }
    }
    const Point p = ring[best], q = ring[(best + 1) % ring.size()];
    const Point d = (q - p) / std::max(len, 1e-300);
    const Point inward{-d.y, d.x};  // the outer ring is counter-clockwise: inside on the left
    for (double eps = len * 0.25; eps > len * 1e-6; eps /= 2) {
        const Point x = (p + q) / 2 + inward * eps;
        if (r.contains(x)) return x;
    }
    return (p + q) / 2;
}

namespace {

// Running minimum (or maximum, with `less` reversed) over windows of 2k + 1 values, NaN
// values left out (NaN where a window has none); a monotonic queue, linear time.
template <class Less>
void running_extreme(const float* in, float* out, int n, int stride, int k, Less less) {
    std::vector<int> q(std::size_t(n) + 1);
    int head = 0, tail = 0;
    int next = 0;  // next index to push
    for (int i = 0; i < n; ++i) {
        while (next < n && next <= i + k) {
            const float v = in[std::size_t(next) * stride];
            if (!std::isnan(v)) {
                while (tail > head && !less(in[std::size_t(q[tail - 1]) * stride], v)) --tail;
                q[tail++] = next;
            }
            ++next;
        }
        while (tail > head && q[head] < i - k) ++head;
        out[std::size_t(i) * stride] = tail > head ? in[std::size_t(q[head]) * stride] : NAN;
    }
}

Raster window_extreme(const Raster& z, int kx, int ky, bool max) {
    Raster tmp = z, out = z;
    auto lt = [](float a, float b) { return a < b; };
    auto gt = [](float a, float b) { return a > b; };
    for (int r = 0; r < z.height; ++r) {
        const float* in = z.data.data() + std::size_t(r) * z.width;
        float* o = tmp.data.data() + std::size_t(r) * z.width;
        max ? running_extreme(in, o, z.width, 1, kx, gt) : running_extreme(in, o, z.width, 1, kx, lt);
    }
    for (int c = 0; c < z.width; ++c) {
        const float* in = tmp.data.data() + c;
        float* o = out.data.data() + c;
        max ? running_extreme(in, o, z.height, z.width, ky, gt) : running_extreme(in, o, z.height, z.width, ky, lt);
    }
    return out;
}

}  // namespace

Raster local_relief(const Raster& dem, double radius) {
    const int kx = std::max(1, int(std::ceil(radius / dem.cell_x())));
    const int ky = std::max(1, int(std::ceil(radius / dem.cell_y())));
    const Raster lo = window_extreme(dem, kx, ky, false), hi = window_extreme(dem, kx, ky, true);
    Raster out = dem;
    for (std::size_t i = 0; i < out.data.size(); ++i) {
        const float z = dem.data[i];
        if (std::isnan(z)) continue;
        const float range = hi.data[i] - lo.data[i];
        out.data[i] = range > 0 ? (z - lo.data[i]) / range : 0.5f;
    }
    return out;
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
