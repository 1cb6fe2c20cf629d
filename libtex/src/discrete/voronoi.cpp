// VoronoiCells of a set of regions (seed 004, section 2).
//
// The seed computes generalised Voronoi cells on graphics hardware (a distance field) and
// fits polygons to them. Here they come from CGAL's Delaunay triangulation instead: every
// region boundary is sampled every `spacing`, the Voronoi cell of each sample is the
// polygon of the circumcentres around it, cut to the domain box, and the cells of the
// samples of one region are merged by dropping the edges two of them share. Each cut and
// each circumcentre is computed once, from the same doubles whichever cell asks, so shared
// edges match bit for bit and the merge is a plain edge cancellation, with no polygon
// Boolean operation. The cells tile the domain exactly (they are unions of a tiling); they
// approximate the true region Voronoi cells to within about the sampling step.
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "libtex/discrete.hpp"
#include "libtex/error.hpp"
#include "libtex/parallel.hpp"

namespace tex::disc {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
using Fb = CGAL::Triangulation_face_base_with_info_2<std::size_t, K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Delaunay = CGAL::Delaunay_triangulation_2<K, Tds>;

// Cap on the number of boundary samples (the spacing grows to respect it).
constexpr double kMaxSamples = 2e6;

double perimeter(const std::vector<Point>& ring) {
    double l = 0;
    for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++)
        l += distance(ring[j], ring[i]);
    return l;
}

double region_perimeter(const Region& r) {
    double l = perimeter(r.outer());
    for (const auto& h : r.holes()) l += perimeter(h);
    return l;
}

void sample_ring(const std::vector<Point>& ring, double spacing, int label,
                 std::vector<std::pair<K::Point_2, int>>& out) {
    for (std::size_t i = 0; i < ring.size(); ++i) {
        const Point a = ring[i], b = ring[(i + 1) % ring.size()];
        const int n = std::max(1, int(std::ceil(distance(a, b) / spacing)));
        for (int k = 0; k < n; ++k) {
            const Point p = a + (b - a) * (double(k) / n);
            out.push_back({K::Point_2(p.x, p.y), label});
        }
    }
}

// The intersection of segment pq with the line x = v (axis 0) or y = v (axis 1), computed
// from the endpoints in a fixed order so that both cells of an edge get the same point.
Point cut(Point p, Point q, int axis, double v) {
    if (q < p) std::swap(p, q);
    if (axis == 0) {
        const double t = (v - p.x) / (q.x - p.x);
        return {v, p.y + t * (q.y - p.y)};
    }
    const double t = (v - p.y) / (q.y - p.y);
    return {p.x + t * (q.x - p.x), v};
}

// Sutherland-Hodgman against the four sides of the box.
std::vector<Point> clip(std::vector<Point> poly, const BBox& box) {
    struct Side {
        int axis;
        double v;
        bool keep_above;
    };
    const Side sides[4] = {
        {0, box.xmin, true}, {0, box.xmax, false}, {1, box.ymin, true}, {1, box.ymax, false}};
    for (const auto& s : sides) {
        if (poly.empty()) break;
        auto inside = [&](const Point& p) {
            const double c = s.axis == 0 ? p.x : p.y;
            return s.keep_above ? c >= s.v : c <= s.v;
        };
        std::vector<Point> out;
        for (std::size_t i = 0; i < poly.size(); ++i) {
            const Point& a = poly[(i + poly.size() - 1) % poly.size()];
            const Point& b = poly[i];
            const bool ia = inside(a), ib = inside(b);
            if (ib) {
                if (!ia) out.push_back(cut(a, b, s.axis, s.v));
                out.push_back(b);
            } else if (ia) {
                out.push_back(cut(a, b, s.axis, s.v));
            }
        }
        poly = std::move(out);
    }
    return poly;
}

// The union of cells that tile their union: the directed edges that no other cell runs
// the other way, chained into rings; the largest counter-clockwise ring is the outside.
Region merge_cells(const std::vector<std::vector<Point>>& cells, std::size_t index) {
    std::multimap<std::pair<Point, Point>, int> edges;
    for (const auto& c : cells)
        for (std::size_t i = 0; i < c.size(); ++i) {
            const Point a = c[i], b = c[(i + 1) % c.size()];
            if (a == b) continue;
            const auto twin = edges.find({b, a});
            if (twin != edges.end())
                edges.erase(twin);
            else
                edges.insert({{a, b}, 0});
        }
    std::multimap<Point, Point> next;
    for (const auto& e : edges) next.insert({e.first.first, e.first.second});
    std::vector<std::vector<Point>> rings;
    while (!next.empty()) {
        auto it = next.begin();
        const Point start = it->first;
        std::vector<Point> ring{start};
        Point at = it->second;
        next.erase(it);
        while (at != start) {
            ring.push_back(at);
            auto n = next.find(at);
            if (n == next.end()) break;  // an open chain cannot happen in a tiling; stop safely
            at = n->second;
            next.erase(n);
        }
        if (ring.size() >= 3) rings.push_back(std::move(ring));
    }
    std::size_t outer = rings.size();
    double best = 0;
    for (std::size_t i = 0; i < rings.size(); ++i) {
        const double a = signed_area(rings[i]);
        if (a > best) best = a, outer = i;
    }
    if (outer == rings.size())
        throw Error("VoronoiCells",
                    "region " + std::to_string(index) + " got no cell (is it inside another?)");
    std::vector<std::vector<Point>> holes;
    for (std::size_t i = 0; i < rings.size(); ++i)
        if (i != outer && signed_area(rings[i]) < 0 &&
            point_in_ring(rings[i].front(), rings[outer]))
            holes.push_back(rings[i]);
    return Region(rings[outer], holes, "VoronoiCells");
}

}  // namespace

std::vector<Region> VoronoiCells(const std::vector<Region>& regions, const BBox& domain,
                                 double spacing) {
    if (regions.size() < 2)
        throw Error("VoronoiCells",
                    "needs at least two regions (got " + std::to_string(regions.size()) + ")");
    if (domain.empty() || !(domain.width() > 0) || !(domain.height() > 0) ||
        !std::isfinite(domain.width()) || !std::isfinite(domain.height()))
        throw Error("VoronoiCells", "the domain is empty");
    if (!(spacing >= 0) || !std::isfinite(spacing))
        throw Error("VoronoiCells",
                    "the spacing must be finite and >= 0 (got " + std::to_string(spacing) + ")");
    double total = 0, narrowest = std::numeric_limits<double>::infinity();
    for (const auto& r : regions) {
        if (r.empty()) throw Error("VoronoiCells", "an empty region has no cell");
        const double p = region_perimeter(r);
        total += p;
        narrowest = std::min(narrowest, 2 * r.area() / p);  // the radius for a disc
    }
    if (spacing == 0) spacing = narrowest / 5;
    spacing = std::max(spacing, total / kMaxSamples);

    std::vector<std::pair<K::Point_2, int>> samples;
    for (std::size_t i = 0; i < regions.size(); ++i) {
        sample_ring(regions[i].outer(), spacing, int(i), samples);
        for (const auto& h : regions[i].holes()) sample_ring(h, spacing, int(i), samples);
    }
    // Four far points (label -1) enclose every sample, so every sample's cell is bounded.
    BBox all = domain;
    for (const auto& s : samples) all.add(Point{s.first.x(), s.first.y()});
    const double far = 10 * (all.width() + all.height());
    const Point c = all.center();
    for (const Point d : {Point{-1, -1}, Point{1, -1}, Point{1, 1}, Point{-1, 1}})
        samples.push_back({K::Point_2(c.x + d.x * far, c.y + d.y * far), -1});

    // One point at a time, in boundary order, each located from the previous one: the
    // range insert would shuffle the points with CGAL's shared random state, and with the
    // many cocircular samples of circles the triangulation (so the bytes) would change.
    Delaunay dt;
    Delaunay::Vertex_handle hint;
    for (const auto& s : samples) {
        const std::size_t before = dt.number_of_vertices();
        hint = dt.insert(
            s.first, hint == Delaunay::Vertex_handle() ? Delaunay::Face_handle() : hint->face());
        if (dt.number_of_vertices() > before)
            hint->info() = s.second;  // a repeated point keeps its first label
    }
    std::vector<Point> centres;
    for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) {
        f->info() = centres.size();
        const K::Point_2 cc = dt.circumcenter(f);
        centres.push_back({cc.x(), cc.y()});
    }
    // The clipped cell of every sample, grouped by region.
    std::vector<std::vector<std::vector<Point>>> cells(regions.size());
    for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) {
        if (v->info() < 0) continue;
        std::vector<Point> poly;
        auto f = dt.incident_faces(v), done = f;
        do {
            if (dt.is_infinite(f)) {
                poly.clear();
                break;
            }
            poly.push_back(centres[f->info()]);
        } while (++f != done);
        poly = clip(std::move(poly), domain);
        if (poly.size() >= 3) cells[std::size_t(v->info())].push_back(std::move(poly));
    }
    std::vector<Region> out(regions.size());
    parallel_for(regions.size(), [&](std::size_t i) { out[i] = merge_cells(cells[i], i); });
    return out;
}

Reshaping VoronoiCells(const BBox& domain, double spacing) {
    if (domain.empty()) throw Error("VoronoiCells", "the domain is empty");
    return [domain, spacing](const std::vector<Region>& rs) {
        return VoronoiCells(rs, domain, spacing);
    };
}

}  // namespace tex::disc
