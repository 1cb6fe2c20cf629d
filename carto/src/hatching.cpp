#include "carto/hatching.hpp"

#include <sstream>

#include "carto/error.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

#include "libtex/random.hpp"

namespace carto {
namespace {

// Parameters t in (0, 1) where segment a-b crosses segment c-d.
void crossings(const Point& a, const Point& b, const Point& c, const Point& d, std::vector<double>& ts) {
    const Point r = b - a, s = d - c;
    const double den = tex::cross(r, s);
    if (den == 0) return;
    const double t = tex::cross(c - a, s) / den;
    const double u = tex::cross(c - a, r) / den;
    if (t > 0 && t < 1 && u >= 0 && u <= 1) ts.push_back(t);
}

// Pieces of `line` inside a region given by its edges and a point test. `edges_near(sb, f)`
// calls f(c, d) for (at least) every edge whose box meets sb. Inside/outside only changes
// where the line meets an edge, so a segment that meets none inherits the status of the
// previous one; the costly point test runs only on pieces next to an edge (and once at the
// start).
template <class EdgesNear, class Inside>
std::vector<Polyline> clip_line(const Polyline& line, const tex::BBox& box, EdgesNear&& edges_near, Inside&& inside) {
    std::vector<Polyline> out;
    Polyline cur;
    std::vector<double> ts;
    int status = -1;  // unknown
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
        const Point& a = line[i];
        const Point& b = line[i + 1];
        tex::BBox sb;
        sb.add(a);
        sb.add(b);
        ts.clear();
        ts.push_back(0);
        bool touched = false;
        if (sb.intersects(box)) {
            edges_near(sb, [&](const Point& c, const Point& d) {
                if (std::max(c.x, d.x) < sb.xmin || std::min(c.x, d.x) > sb.xmax || std::max(c.y, d.y) < sb.ymin ||
                    std::min(c.y, d.y) > sb.ymax)
                    return;
                touched = true;
                crossings(a, b, c, d, ts);
            });
        } else {
            status = 0;  // entirely outside the region's box
        }
        ts.push_back(1);
        if (touched) std::sort(ts.begin(), ts.end());
        for (std::size_t k = 0; k + 1 < ts.size(); ++k) {
            const double t0 = ts[k], t1 = ts[k + 1];
            if (t1 <= t0) continue;
            const Point p0 = a + (b - a) * t0, p1 = a + (b - a) * t1;
            if (touched || status < 0) status = inside(a + (b - a) * ((t0 + t1) / 2)) ? 1 : 0;
            if (status == 1) {
                if (cur.empty()) cur.push_back(p0);
                cur.push_back(p1);
            } else if (!cur.empty()) {
                if (cur.size() >= 2) out.push_back(std::move(cur));
                cur.clear();
            }
        }
    }
    if (cur.size() >= 2) out.push_back(std::move(cur));
    return out;
}

}  // namespace

std::vector<Polyline> clip_to_region(const Polyline& line, const tex::Region& region) {
    return RegionClipper(region).clip(line);
}

RegionClipper::RegionClipper(const tex::Region& region) : region_(region), box_(region.bbox()) {
    auto add = [&](const std::vector<Point>& ring) {
        for (std::size_t k = 0, n = ring.size(); k < n; ++k) edges_.push_back({ring[k], ring[(k + 1) % n]});
    };
    add(region.outer());
    for (const auto& h : region.holes()) add(h);
    // About four edges per cell on average.
    const int side = std::clamp(int(std::sqrt(double(edges_.size()) / 4.0)), 1, 256);
    nx_ = ny_ = side;
    cw_ = std::max(box_.width(), 1e-12) / nx_;
    ch_ = std::max(box_.height(), 1e-12) / ny_;
    cells_.resize(std::size_t(nx_) * ny_);
    for (std::size_t i = 0; i < edges_.size(); ++i) {
        const Edge& e = edges_[i];
        const int x0 = std::clamp(int((std::min(e.a.x, e.b.x) - box_.xmin) / cw_), 0, nx_ - 1);
        const int x1 = std::clamp(int((std::max(e.a.x, e.b.x) - box_.xmin) / cw_), 0, nx_ - 1);
        const int y0 = std::clamp(int((std::min(e.a.y, e.b.y) - box_.ymin) / ch_), 0, ny_ - 1);
        const int y1 = std::clamp(int((std::max(e.a.y, e.b.y) - box_.ymin) / ch_), 0, ny_ - 1);
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) cells_[std::size_t(y) * nx_ + x].push_back(int(i));
    }
}

std::vector<Polyline> RegionClipper::clip(const Polyline& line) const {
    std::vector<int> seen;
    auto near = [&](const tex::BBox& sb, auto&& f) {
        const int x0 = std::clamp(int((sb.xmin - box_.xmin) / cw_), 0, nx_ - 1);
        const int x1 = std::clamp(int((sb.xmax - box_.xmin) / cw_), 0, nx_ - 1);
        const int y0 = std::clamp(int((sb.ymin - box_.ymin) / ch_), 0, ny_ - 1);
        const int y1 = std::clamp(int((sb.ymax - box_.ymin) / ch_), 0, ny_ - 1);
        seen.clear();
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x)
                for (int id : cells_[std::size_t(y) * nx_ + x]) {
                    if (std::find(seen.begin(), seen.end(), id) != seen.end()) continue;  // edge in several cells
                    seen.push_back(id);
                    f(edges_[id].a, edges_[id].b);
                }
    };
    return clip_line(line, box_, near, [&](const Point& p) { return region_.contains(p); });
}

std::vector<Polyline> clip_to_convex(const Polyline& line, const std::vector<Point>& convex) {
    tex::BBox box;
    for (const auto& p : convex) box.add(p);
    auto all_edges = [&](const tex::BBox&, auto&& f) {
        for (std::size_t k = 0, n = convex.size(); k < n; ++k) f(convex[k], convex[(k + 1) % n]);
    };
    return clip_line(line, box, all_edges, [&](const Point& p) {
        for (std::size_t k = 0, n = convex.size(); k < n; ++k)
            if (tex::cross(convex[(k + 1) % n] - convex[k], p - convex[k]) < 0) return false;
        return true;
    });
}

std::vector<Point> clip_polygon_convex(const std::vector<Point>& subject, const std::vector<Point>& convex) {
    std::vector<Point> out = subject;
    for (std::size_t k = 0, n = convex.size(); k < n && !out.empty(); ++k) {
        const Point a = convex[k], b = convex[(k + 1) % n];
        const Point e = b - a;
        std::vector<Point> in;
        in.swap(out);
        for (std::size_t i = 0, m = in.size(); i < m; ++i) {
            const Point p = in[i], q = in[(i + 1) % m];
            const double sp = tex::cross(e, p - a), sq = tex::cross(e, q - a);
            if (sp >= 0) out.push_back(p);
            if ((sp >= 0) != (sq >= 0)) out.push_back(p + (q - p) * (sp / (sp - sq)));
        }
    }
    return out;
}

Point jitter_at(const Point& p, std::uint64_t seed, std::uint64_t stream) {
    // Round to a millimetre so that positions computed along different paths agree.
    std::uint64_t h = tex::hash_combine(tex::mix64(seed ^ 0x4a495454ULL), stream);
    h = tex::hash_combine(h, std::uint64_t(std::llround(p.x * 1000)));
    h = tex::hash_combine(h, std::uint64_t(std::llround(p.y * 1000)));
    const double u = tex::unit_from_hash(h), v = tex::unit_from_hash(tex::mix64(h));
    return {2 * u - 1, 2 * v - 1};
}

std::vector<Polyline> jittered_lines(const tex::BBox& box, double angle, double spacing, double length,
                                     double jitter_across, double jitter_along, std::uint64_t seed,
                                     std::uint64_t stream) {
    const Point d{std::cos(angle), std::sin(angle)}, n{-d.y, d.x};
    // Lines one spacing beyond the box across, break points one length beyond it along.
    const Point corners[4] = {{box.xmin, box.ymin}, {box.xmax, box.ymin}, {box.xmax, box.ymax}, {box.xmin, box.ymax}};
    double tlo = 1e300, thi = -1e300, slo = 1e300, shi = -1e300;
    for (const auto& c : corners) {
        tlo = std::min(tlo, tex::dot(c, n));
        thi = std::max(thi, tex::dot(c, n));
        slo = std::min(slo, tex::dot(c, d));
        shi = std::max(shi, tex::dot(c, d));
    }
    const double k0d = std::floor(tlo / spacing) - 1, k1d = std::ceil(thi / spacing) + 1;
    const double j0d = std::floor(slo / length) - 1, j1d = std::ceil(shi / length) + 1;
    if (!((k1d - k0d + 1) * (j1d - j0d + 1) <= 50e6)) {
        std::ostringstream m;
        m << "hatch spacing " << spacing << " and length " << length << " are too small for an area of "
          << box.width() << " x " << box.height() << " (more than 50 million break points)";
        throw Error(Code::Usage, m.str());
    }
    const long long k0 = (long long)k0d, k1 = (long long)k1d, j0 = (long long)j0d, j1 = (long long)j1d;
    std::vector<Polyline> out;
    out.reserve(std::size_t(k1 - k0 + 1));
    for (long long k = k0; k <= k1; ++k) {
        Polyline line;
        line.reserve(std::size_t(j1 - j0 + 1));
        for (long long j = j0; j <= j1; ++j) {
            const Point p = n * (double(k) * spacing) + d * (double(j) * length);
            const Point jt = jitter_at(p, seed, stream);
            line.push_back(p + n * (jt.x * jitter_across * spacing / 2) + d * (jt.y * jitter_along * length / 2));
        }
        out.push_back(std::move(line));
    }
    return out;
}

std::vector<Polyline> split_strokes(const Polyline& line, double gap) {
    std::vector<Polyline> out;
    if (gap >= 1) {
        out.push_back(line);
        return out;
    }
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
        const Point m = (line[i] + line[i + 1]) / 2;
        out.push_back({m + (line[i] - m) * gap, m + (line[i + 1] - m) * gap});
    }
    return out;
}

Point ring_centroid(const std::vector<Point>& ring) {
    double a = 0, cx = 0, cy = 0;
    for (std::size_t i = 0, n = ring.size(); i < n; ++i) {
        const Point& p = ring[i];
        const Point& q = ring[(i + 1) % n];
        const double w = tex::cross(p, q);
        a += w;
        cx += (p.x + q.x) * w;
        cy += (p.y + q.y) * w;
    }
    if (a == 0) {
        Point s{0, 0};
        for (const auto& p : ring) s += p;
        return ring.empty() ? s : s / double(ring.size());
    }
    return {cx / (3 * a), cy / (3 * a)};
}

std::vector<Point> scale_ring(const std::vector<Point>& ring, double s) {
    const Point c = ring_centroid(ring);
    std::vector<Point> out;
    out.reserve(ring.size());
    for (const auto& p : ring) out.push_back(c + (p - c) * s);
    return out;
}

}  // namespace carto
