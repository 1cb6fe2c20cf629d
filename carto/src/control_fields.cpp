#include "carto/control_fields.hpp"
#include "carto/partition.hpp"
#include "libtex/parallel.hpp"

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

std::vector<float> box_mean(const std::vector<float>& v, int width, int height, int radius) {
    const auto at = [width](int c, int r) { return std::size_t(r) * std::size_t(width) + std::size_t(c); };
    std::vector<double> sum(v.size(), 0.0), cnt(v.size(), 0.0);
    for (int r = 0; r < height; ++r)
        for (int c = 0; c < width; ++c) {
            double s = 0, n = 0;
            for (int k = std::max(0, c - radius); k <= std::min(width - 1, c + radius); ++k) {
                const float x = v[at(k, r)];
                if (!std::isnan(x)) s += x, n += 1;
            }
            sum[at(c, r)] = s;
            cnt[at(c, r)] = n;
        }
    std::vector<float> out(v.size(), NAN);
    for (int r = 0; r < height; ++r)
        for (int c = 0; c < width; ++c) {
            if (std::isnan(v[at(c, r)])) continue;
            double s = 0, n = 0;
            for (int k = std::max(0, r - radius); k <= std::min(height - 1, r + radius); ++k) {
                s += sum[at(c, k)];
                n += cnt[at(c, k)];
            }
            out[at(c, r)] = float(s / n);
        }
    return out;
}

namespace {
// The window of a ground radius, in cells (at least one).
int radius_cells(const Raster& r, double radius) {
    return std::max(1, int(std::lround(radius / std::max(r.cell_x(), r.cell_y()))));
}
}  // namespace

Field fall_line_field(const Terrain& t, double radius) {
    const int k = radius_cells(t.slope, radius);
    std::vector<float> gx(t.slope.data.size(), NAN), gy(t.slope.data.size(), NAN);
    for (std::size_t i = 0; i < gx.size(); ++i) {
        const float s = t.slope.data[i], a = t.aspect.data[i];
        if (std::isnan(s)) continue;
        gx[i] = std::isnan(a) ? 0.0f : float(s * std::cos(a));  // flat cells pull towards no direction
        gy[i] = std::isnan(a) ? 0.0f : float(s * std::sin(a));
    }
    auto x = std::make_shared<Raster>(t.slope), y = std::make_shared<Raster>(t.slope);
    x->data = box_mean(gx, t.slope.width, t.slope.height, k);
    y->data = box_mean(gy, t.slope.width, t.slope.height, k);
    return tex::Combine(raster_field(std::shared_ptr<const Raster>(x)), raster_field(std::shared_ptr<const Raster>(y)),
                        [](double vx, double vy) { return vx == 0 && vy == 0 ? NAN : std::atan2(vy, vx); });
}

Field shade_field(const Terrain& t, double radius) {
    auto s = std::make_shared<Raster>(t.hillshade);
    s->data = box_mean(t.hillshade.data, t.hillshade.width, t.hillshade.height, radius_cells(t.hillshade, radius));
    return raster_field(std::shared_ptr<const Raster>(s), 1.0, -1.0);  // (h - 1) / -1 = 1 - h
}

Field elevation_field(const Terrain& t, double radius) {
    auto z = std::make_shared<Raster>(t.elevation);
    const int k = radius_cells(t.elevation, radius);
    z->data = box_mean(box_mean(t.elevation.data, z->width, z->height, k), z->width, z->height, k);
    return raster_field(std::shared_ptr<const Raster>(z));
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
    for (const RockFace& f : p.faces) {
        derived_o += !f.orientation;
        derived_d += !f.density;
    }
    const double cell = t.elevation.cell_x();
    // Face by face, each on its own (a work item of parallel_for): the sums run in the
    // same order whatever the thread count.
    tex::parallel_for(p.faces.size(), [&](std::size_t i) {
        RockFace& f = p.faces[i];
        if (!f.orientation) {
            double sx = 0, sy = 0;
            for_face_samples(f, cell, [&](const Point& q) {
                const double a = t.aspect.sample(q), s = t.slope.nearest(q);
                if (std::isnan(a) || std::isnan(s)) return;
                sx += s * std::cos(a);
                sy += s * std::sin(a);
            });
            f.orientation = (sx == 0 && sy == 0) ? 0.0 : std::atan2(sy, sx);
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
        }
    });
    return {derived_o, derived_d};
}

}  // namespace carto
