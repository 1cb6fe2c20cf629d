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

double Region::area() const {
    double a = signed_area(outer_);
    for (const auto& h : holes_) a += signed_area(h);  // holes are clockwise (negative)
    return a;
}

bool point_in_ring(const Point& p, const std::vector<Point>& ring) {
    bool in = false;
    const std::size_t n = ring.size();
    for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
        const Point& a = ring[i];
        const Point& b = ring[j];
        // Both ends above p, or both below it: the segment neither holds p nor crosses its
        // horizontal (the common case, decided without arithmetic).
        const bool a_above = a.y > p.y;
        if (a_above == (b.y > p.y) && (a_above || (a.y < p.y && b.y < p.y))) continue;
        // On the segment: inside.
        if (cross(b - a, p - a) == 0.0 && std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) &&
            std::min(a.y, b.y) <= p.y && p.y <= std::max(a.y, b.y))
            return true;
        if ((a.y > p.y) != (b.y > p.y)) {
            const double x = a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y);
            if (p.x < x) in = !in;
        }
    }
    return in;
}

bool Region::contains(const Point& p) const {
    if (!bbox_.contains(p)) return false;
    if (!point_in_ring(p, outer_)) return false;
    for (const auto& h : holes_) {
        if (point_in_ring(p, h)) {
            // On a hole's boundary still counts as inside the region.
            bool on_edge = false;
            for (std::size_t i = 0, j = h.size() - 1; i < h.size(); j = i++) {
                const Point &a = h[i], &b = h[j];
                if (cross(b - a, p - a) == 0.0 && std::min(a.x, b.x) <= p.x &&
                    p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
                    p.y <= std::max(a.y, b.y))
                    on_edge = true;
            }
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
// the first that finds the polygon meeting the region).
Overlap classify(const std::vector<Point>& poly, const BBox& box, const Region& r, bool only_disjoint) {
    if (!box.intersects(r.bbox())) return Overlap::Disjoint;
    // Any proper crossing between the polygon and a region ring: partial.
    auto crosses_ring = [&](const std::vector<Point>& ring) {
        for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
            const Point &a = ring[j], &b = ring[i];
            BBox eb;
            eb.add(a);
            eb.add(b);
            if (!eb.intersects(box)) continue;
            for (std::size_t k = 0, l = poly.size() - 1; k < poly.size(); l = k++)
                if (segments_cross(a, b, poly[l], poly[k])) return true;
        }
        return false;
    };
    Point c{0, 0};
    for (const auto& p : poly) c += p;
    c = c / double(poly.size());
    // Not Disjoint as soon as one of the three tests below says so: the centre first, the
    // cheapest test and the one that settles the cells inside.
    if (only_disjoint && r.contains(c)) return Overlap::Partial;
    if (crosses_ring(r.outer())) return Overlap::Partial;
    for (const auto& h : r.holes())
        if (crosses_ring(h)) return Overlap::Partial;
    // No crossing: the polygon is inside, outside, or contains parts of the region. Test
    // its centre (inside a convex polygon) and whether a region vertex lies inside it.
    const bool centre_in = !only_disjoint && r.contains(c);
    auto ring_vertex_inside = [&](const std::vector<Point>& ring) {
        for (const auto& p : ring)
            if (box.contains(p) && point_in_ring(p, poly)) {
                // A region vertex on the polygon's own boundary does not make it partial.
                bool on_boundary = false;
                for (std::size_t k = 0, l = poly.size() - 1; k < poly.size(); l = k++) {
                    const Point &a = poly[l], &b = poly[k];
                    if (std::abs(cross(b - a, p - a)) <= 1e-12 * (norm(b - a) * norm(p - a) + 1e-300) &&
                        dot(p - a, p - b) <= 0)
                        on_boundary = true;
                }
                if (!on_boundary) return true;
            }
        return false;
    };
    const bool region_vertex_in = ring_vertex_inside(r.outer()) ||
        std::any_of(r.holes().begin(), r.holes().end(), ring_vertex_inside);
    if (centre_in) return region_vertex_in ? Overlap::Partial : Overlap::Inside;
    return region_vertex_in ? Overlap::Partial : Overlap::Disjoint;
}
}  // namespace

Overlap classify_polygon(const std::vector<Point>& poly, const BBox& box, const Region& r) {
    return classify(poly, box, r, false);
}

bool polygon_meets_region(const std::vector<Point>& poly, const BBox& box, const Region& r) {
    return classify(poly, box, r, true) != Overlap::Disjoint;
}

}  // namespace tex
