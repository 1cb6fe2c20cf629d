#include "libtex/region.hpp"

#include <algorithm>
#include <cmath>

#include "libtex/curves.hpp"
#include "libtex/error.hpp"

namespace tex {
namespace {

// Removes repeated consecutive points and a closing point equal to the first.
std::vector<Point> clean_ring(std::vector<Point> ring) {
    std::vector<Point> out;
    out.reserve(ring.size());
    for (const auto& p : ring) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y)) continue;
        if (out.empty() || out.back() != p) out.push_back(p);
    }
    while (out.size() > 1 && out.front() == out.back()) out.pop_back();
    return out;
}

// p on the closed segment ab (collinear in doubles and within its box).
inline bool on_segment(const Point& p, const Point& a, const Point& b) {
    return cross(b - a, p - a) == 0.0 && std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) &&
           std::min(a.y, b.y) <= p.y && p.y <= std::max(a.y, b.y);
}

bool segments_cross(const Point& a, const Point& b, const Point& c, const Point& d) {
    const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
    const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
    return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

}  // namespace

Region::Region(std::vector<Point> outer, std::vector<std::vector<Point>> holes,
               const std::string& op) {
    outer_ = clean_ring(std::move(outer));
    if (outer_.size() < 3 || signed_area(outer_) == 0.0)
        throw Error(op, "empty region (the outer ring has " + std::to_string(outer_.size()) +
                            " distinct points and no area)");
    if (signed_area(outer_) < 0) std::reverse(outer_.begin(), outer_.end());
    for (auto& h : holes) {
        auto ring = clean_ring(std::move(h));
        if (ring.size() < 3 || signed_area(ring) == 0.0) continue;  // degenerate hole: no effect
        if (signed_area(ring) > 0) std::reverse(ring.begin(), ring.end());
        holes_.push_back(std::move(ring));
    }
    for (const auto& p : outer_) bbox_.add(p);
}

Region Region::rectangle(double xmin, double ymin, double xmax, double ymax) {
    return Region({{xmin, ymin}, {xmax, ymin}, {xmax, ymax}, {xmin, ymax}}, {}, "Region.rectangle");
}

namespace {

// Twice the signed area's sum, halved: the shoelace over the ring as given.
double ring_area(const std::vector<Point>& ring) {
    double a = 0;
    for (std::size_t i = 0, n = ring.size(); i < n; ++i) a += cross(ring[i], ring[(i + 1) % n]);
    return a / 2;
}

// The ring clipped by the convex polygon `clip` (Sutherland-Hodgman); its area is exact for a
// ring of any shape, though the result may run along the clip's edges more than once. Two
// buffers serve every clip edge (the ring itself is read, not copied): a tone budget calls
// this for every face and grid cell, and a vector per edge made it a style's most frequent
// allocation.
std::vector<Point> clip_ring(const std::vector<Point>& ring, const std::vector<Point>& clip) {
    const double side = ring_area(clip) >= 0 ? 1.0 : -1.0;
    std::vector<Point> cur, out;
    const std::vector<Point>* in = &ring;
    for (std::size_t i = 0, n = clip.size(); i < n && !in->empty(); ++i) {
        const Point a = clip[i], b = clip[(i + 1) % n];
        auto inside = [&](const Point& q) { return side * cross(b - a, q - a) >= 0; };
        out.clear();
        out.reserve(in->size() + 2);
        for (std::size_t k = 0, m = in->size(); k < m; ++k) {
            const Point p = (*in)[k], q = (*in)[(k + 1) % m];
            const bool pin = inside(p), qin = inside(q);
            if (pin) out.push_back(p);
            if (pin != qin) {
                const double dp = cross(b - a, p - a), dq = cross(b - a, q - a);
                out.push_back(p + (q - p) * (dp / (dp - dq)));
            }
        }
        std::swap(cur, out);
        in = &cur;
    }
    return in == &ring ? ring : cur;
}

}  // namespace

double Region::area_within(const Region& convex) const {
    double a = std::abs(ring_area(clip_ring(outer_, convex.outer())));
    for (const auto& h : holes_) a -= std::abs(ring_area(clip_ring(h, convex.outer())));
    return std::max(a, 0.0);
}

double Region::area() const {
    double a = signed_area(outer_);
    for (const auto& h : holes_) a += signed_area(h);  // holes are clockwise (negative)
    return a;
}

namespace {

// One segment's share of the even-odd test of p against a ring, for a = ring[i] and
// b = ring[i - 1]: true when p lies on the segment (inside, whatever the rest says), else
// `in` flips when the segment crosses p's horizontal right of p.
inline bool ring_step(const Point& p, const Point& a, const Point& b, bool& in) {
    // Both ends above p, or both below it: the segment neither holds p nor crosses its
    // horizontal (the common case, decided without arithmetic).
    const bool a_above = a.y > p.y;
    if (a_above == (b.y > p.y) && (a_above || (a.y < p.y && b.y < p.y))) return false;
    if (on_segment(p, a, b)) return true;
    if ((a.y > p.y) != (b.y > p.y)) {
        const double x = a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y);
        if (p.x < x) in = !in;
    }
    return false;
}

}  // namespace

bool point_in_ring(const Point& p, const std::vector<Point>& ring) {
    bool in = false;
    const std::size_t n = ring.size();
    for (std::size_t i = 0, j = n - 1; i < n; j = i++)
        if (ring_step(p, ring[i], ring[j], in)) return true;
    return in;
}

bool Region::contains(const Point& p) const {
    if (!bbox_.contains(p)) return false;
    if (!point_in_ring(p, outer_)) return false;
    for (const auto& h : holes_) {
        if (point_in_ring(p, h)) {
            // On a hole's boundary still counts as inside the region.
            bool on_edge = false;
            for (std::size_t i = 0, j = h.size() - 1; i < h.size() && !on_edge; j = i++)
                on_edge = on_segment(p, h[i], h[j]);
            if (!on_edge) return false;
        }
    }
    return true;
}

Region Region::with_edges(Curves edges) const {
    Region r = *this;
    r.edges_ = std::make_shared<const Curves>(std::move(edges));
    return r;
}

Curves Region::boundary() const {
    if (edges_) return *edges_;
    Curves out;
    auto add = [&](const std::vector<Point>& ring) {
        Curve c;
        c.points = ring;
        c.closed = true;
        out.curves.push_back(std::move(c));
    };
    add(outer_);
    for (const auto& h : holes_) add(h);
    return out;
}

namespace {
// classify_polygon, or with `only_disjoint` just whether the polygon is Disjoint (then
// Partial stands for any other answer: KEEP_OUTSIDE asks no more, so the tests can stop at
// the first that finds the polygon meeting the region). The region is asked through
// `contains(p)`, `any_segment(box, f)` (f(a, b) on the ring segments a -> b whose box meets
// `box`, until one returns true) and `any_vertex(box, f)` (the same for the rings' vertices
// in `box`): a plain region answers by scanning its rings, a prepared one by its slabs.
template <class Contains, class AnySegment, class AnyVertex>
Overlap classify(const std::vector<Point>& poly, const BBox& box, const Region& r, bool only_disjoint,
                 const Contains& contains, const AnySegment& any_segment, const AnyVertex& any_vertex) {
    if (!box.intersects(r.bbox())) return Overlap::Disjoint;
    Point c{0, 0};
    for (const auto& p : poly) c += p;
    c = c / double(poly.size());
    // Not Disjoint as soon as one of the three tests below says so: the centre first, the
    // cheapest test and the one that settles the cells inside.
    if (only_disjoint && contains(c)) return Overlap::Partial;
    // Any proper crossing between the polygon and a region ring: partial.
    const bool crossing = any_segment(box, [&](const Point& a, const Point& b) {
        for (std::size_t k = 0, l = poly.size() - 1; k < poly.size(); l = k++)
            if (segments_cross(a, b, poly[l], poly[k])) return true;
        return false;
    });
    if (crossing) return Overlap::Partial;
    // No crossing: the polygon is inside, outside, or contains parts of the region. Test
    // its centre (inside a convex polygon) and whether a region vertex lies inside it.
    const bool centre_in = !only_disjoint && contains(c);
    const bool region_vertex_in = any_vertex(box, [&](const Point& p) {
        if (!point_in_ring(p, poly)) return false;
        // A region vertex on the polygon's own boundary does not make it partial.
        for (std::size_t k = 0, l = poly.size() - 1; k < poly.size(); l = k++) {
            const Point &a = poly[l], &b = poly[k];
            if (std::abs(cross(b - a, p - a)) <= 1e-12 * (norm(b - a) * norm(p - a) + 1e-300) && dot(p - a, p - b) <= 0)
                return false;
        }
        return true;
    });
    if (centre_in) return region_vertex_in ? Overlap::Partial : Overlap::Inside;
    return region_vertex_in ? Overlap::Partial : Overlap::Disjoint;
}

Overlap classify_plain(const std::vector<Point>& poly, const BBox& box, const Region& r, bool only_disjoint) {
    auto rings = [&](auto&& per_ring) {
        if (per_ring(r.outer())) return true;
        for (const auto& h : r.holes())
            if (per_ring(h)) return true;
        return false;
    };
    auto any_segment = [&](const BBox& near, const auto& f) {
        return rings([&](const std::vector<Point>& ring) {
            for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
                BBox eb;
                eb.add(ring[j]);
                eb.add(ring[i]);
                if (eb.intersects(near) && f(ring[j], ring[i])) return true;
            }
            return false;
        });
    };
    auto any_vertex = [&](const BBox& near, const auto& f) {
        return rings([&](const std::vector<Point>& ring) {
            for (const auto& p : ring)
                if (near.contains(p) && f(p)) return true;
            return false;
        });
    };
    return classify(poly, box, r, only_disjoint, [&](const Point& p) { return r.contains(p); }, any_segment,
                    any_vertex);
}
}  // namespace

Overlap classify_polygon(const std::vector<Point>& poly, const BBox& box, const Region& r) {
    return classify_plain(poly, box, r, false);
}

bool polygon_meets_region(const std::vector<Point>& poly, const BBox& box, const Region& r) {
    return classify_plain(poly, box, r, true) != Overlap::Disjoint;
}

// ---- PreparedRegion ----

int PreparedRegion::Slabs::slab(double y) const {
    const double k = std::floor((y - y0) / height);
    if (!(k > 0)) return 0;
    return k >= double(n - 1) ? n - 1 : int(k);
}

namespace {

PreparedRegion::Slabs make_slabs(const std::vector<Point>& ring) {
    PreparedRegion::Slabs s;
    const std::size_t n = ring.size();
    double ymin = ring[0].y, ymax = ring[0].y;
    for (const auto& p : ring) {
        ymin = std::min(ymin, p.y);
        ymax = std::max(ymax, p.y);
    }
    // About four segments a slab when they are spread evenly over the height.
    s.n = int(std::clamp<std::size_t>(n / 4, 1, 1u << 16));
    s.y0 = ymin;
    s.height = ymax > ymin ? (ymax - ymin) / s.n : 1.0;
    if (!(s.height > 0)) s.n = 1, s.height = 1.0;  // a height too small to divide
    // Counting sort: segment i (ring[i - 1] to ring[i]) into every slab its heights span,
    // vertex i into the slab of its height.
    s.seg_start.assign(std::size_t(s.n) + 1, 0);
    s.vertex_start.assign(std::size_t(s.n) + 1, 0);
    auto span = [&](std::size_t i) {
        const Point& a = ring[i];
        const Point& b = ring[i ? i - 1 : n - 1];
        return std::make_pair(s.slab(std::min(a.y, b.y)), s.slab(std::max(a.y, b.y)));
    };
    for (std::size_t i = 0; i < n; ++i) {
        const auto [lo, hi] = span(i);
        for (int k = lo; k <= hi; ++k) ++s.seg_start[std::size_t(k) + 1];
        ++s.vertex_start[std::size_t(s.slab(ring[i].y)) + 1];
    }
    for (int k = 0; k < s.n; ++k) {
        s.seg_start[std::size_t(k) + 1] += s.seg_start[std::size_t(k)];
        s.vertex_start[std::size_t(k) + 1] += s.vertex_start[std::size_t(k)];
    }
    s.segs.resize(s.seg_start.back());
    s.vertices.resize(s.vertex_start.back());
    std::vector<std::uint32_t> fill_s(s.seg_start.begin(), s.seg_start.end() - 1);
    std::vector<std::uint32_t> fill_v(s.vertex_start.begin(), s.vertex_start.end() - 1);
    for (std::size_t i = 0; i < n; ++i) {
        const auto [lo, hi] = span(i);
        for (int k = lo; k <= hi; ++k) s.segs[fill_s[std::size_t(k)]++] = std::uint32_t(i);
        s.vertices[fill_v[std::size_t(s.slab(ring[i].y))]++] = std::uint32_t(i);
    }
    return s;
}

// point_in_ring over the segments of p's slab: the others lie wholly above or below p,
// which point_in_ring skips without arithmetic. `on` tells whether p is on the ring.
bool in_ring(const PreparedRegion::Slabs& s, const std::vector<Point>& ring, const Point& p, bool* on = nullptr) {
    const std::size_t n = ring.size();
    const int k = s.slab(p.y);
    bool in = false;
    for (std::uint32_t q = s.seg_start[std::size_t(k)]; q < s.seg_start[std::size_t(k) + 1]; ++q) {
        const std::size_t i = s.segs[q];
        if (ring_step(p, ring[i], ring[i ? i - 1 : n - 1], in)) {
            if (on) *on = true;
            return true;
        }
    }
    return in;
}

}  // namespace

bool PreparedRegion::worth_preparing(const Region& r) {
    constexpr std::size_t kManyPoints = 32;
    std::size_t points = r.outer().size();
    for (const auto& h : r.holes()) points += h.size();
    return points > kManyPoints;
}

PreparedRegion::PreparedRegion(const Region& r) : r_(&r) {
    if (r.empty()) return;
    outer_ = make_slabs(r.outer());
    holes_.reserve(r.holes().size());
    for (const auto& h : r.holes()) holes_.push_back(make_slabs(h));
}

bool PreparedRegion::contains(const Point& p) const {
    const Region& r = *r_;
    if (r.empty() || !r.bbox().contains(p)) return false;
    if (!in_ring(outer_, r.outer(), p)) return false;
    for (std::size_t h = 0; h < holes_.size(); ++h) {
        bool on = false;
        // On a hole's boundary still counts as inside the region.
        if (in_ring(holes_[h], r.holes()[h], p, &on) && !on) return false;
    }
    return true;
}

Overlap PreparedRegion::classify_polygon(const std::vector<Point>& poly, const BBox& box) const {
    return classify_as(poly, box, false);
}

bool PreparedRegion::polygon_meets_region(const std::vector<Point>& poly, const BBox& box) const {
    return classify_as(poly, box, true) != Overlap::Disjoint;
}

Overlap PreparedRegion::classify_as(const std::vector<Point>& poly, const BBox& box, bool only_disjoint) const {
    const Region& r = *r_;
    auto slabs_of = [&](auto&& per_ring) {
        if (per_ring(outer_, r.outer())) return true;
        for (std::size_t h = 0; h < holes_.size(); ++h)
            if (per_ring(holes_[h], r.holes()[h])) return true;
        return false;
    };
    auto any_segment = [&](const BBox& near, const auto& f) {
        return slabs_of([&](const Slabs& s, const std::vector<Point>& ring) {
            const std::size_t n = ring.size();
            const int k1 = s.slab(near.ymax);
            for (int k = s.slab(near.ymin); k <= k1; ++k)
                for (std::uint32_t q = s.seg_start[std::size_t(k)]; q < s.seg_start[std::size_t(k) + 1]; ++q) {
                    const std::size_t i = s.segs[q];
                    const Point& a = ring[i ? i - 1 : n - 1];
                    BBox eb;
                    eb.add(a);
                    eb.add(ring[i]);
                    if (eb.intersects(near) && f(a, ring[i])) return true;
                }
            return false;
        });
    };
    auto any_vertex = [&](const BBox& near, const auto& f) {
        return slabs_of([&](const Slabs& s, const std::vector<Point>& ring) {
            const int k1 = s.slab(near.ymax);
            for (int k = s.slab(near.ymin); k <= k1; ++k)
                for (std::uint32_t q = s.vertex_start[std::size_t(k)]; q < s.vertex_start[std::size_t(k) + 1]; ++q) {
                    const Point& p = ring[s.vertices[q]];
                    if (near.contains(p) && f(p)) return true;
                }
            return false;
        });
    };
    return classify(poly, box, r, only_disjoint, [&](const Point& p) { return contains(p); }, any_segment,
                    any_vertex);
}

Point InteriorPoint(const Region& r) {
    const auto& ring = r.outer();
    Point c{0, 0};
    double a = 0;
    for (std::size_t i = 0, n = ring.size(); i < n; ++i) {
        const double w = cross(ring[i], ring[(i + 1) % n]);
        a += w;
        c += (ring[i] + ring[(i + 1) % n]) * w;
    }
    if (a != 0) c = c / (3 * a);
    if (a != 0 && r.contains(c)) return c;
    // Step inwards from the middle of the longest border segment of the outer ring.
    std::size_t best = 0;
    double len = -1;
    for (std::size_t i = 0; i < ring.size(); ++i) {
        const double l = distance(ring[i], ring[(i + 1) % ring.size()]);
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

}  // namespace tex
