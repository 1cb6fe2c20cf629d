// Induction of planar maps with CGAL (see planar_map.hpp for the model).
//
// The shape follows CGAL's own examples (consolidated_curve_data.cpp for the curve data,
// dcel_extension.cpp for indices stored in the DCEL): every input segment carries one
// integer, the index of its polyline times two plus a "runs left to right" bit, and the
// sweep of CGAL::insert merges these integers on overlapping pieces.
#include "libtex/planar_map.hpp"

#include <CGAL/Arr_consolidated_curve_data_traits_2.h>
#include <CGAL/Arr_extended_dcel.h>
#include <CGAL/Arr_segment_traits_2.h>
#include <CGAL/Arrangement_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>

#include <algorithm>
#include <climits>
#include <unordered_map>

#include "libtex/random.hpp"

namespace tex {
namespace {

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using SegmentTraits = CGAL::Arr_segment_traits_2<Kernel>;
using Traits = CGAL::Arr_consolidated_curve_data_traits_2<SegmentTraits, std::uint32_t>;
using Dcel = CGAL::Arr_extended_dcel<Traits, int, int, int>;
using Arr = CGAL::Arrangement_2<Traits, Dcel>;
using KPoint = Kernel::Point_2;
using KSegment = Kernel::Segment_2;

struct PointHash {
    std::size_t operator()(const Point& p) const { return hash_point(0, p); }
};

// Lexicographic "left to right" order of CGAL's x-monotone curves.
bool left_to_right(const Point& a, const Point& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); }

}  // namespace

struct PlanarMapBuilder {
    static MapPtr build(const Curves& curves);
};

MapPtr PlanarMap::induce(const Curves& curves) { return PlanarMapBuilder::build(curves); }

MapPtr PlanarMapBuilder::build(const Curves& input) {
    auto map = std::make_shared<PlanarMap>();
    PlanarMap& pm = *map;

    // 1. Segments with their curve data.
    std::vector<Traits::Curve_2> segs;
    std::size_t total = 0;
    for (const auto& c : input.curves) total += c.points.size();
    segs.reserve(total);
    for (std::uint32_t ci = 0; ci < input.curves.size(); ++ci) {
        const Curve& c = input.curves[ci];
        const std::size_t n = c.points.size();
        if (n < 2) continue;
        const std::size_t nseg = c.closed ? n : n - 1;
        for (std::size_t i = 0; i < nseg; ++i) {
            const Point& a = c.points[i];
            const Point& b = c.points[(i + 1) % n];
            if (a == b || !std::isfinite(a.x) || !std::isfinite(a.y) || !std::isfinite(b.x) ||
                !std::isfinite(b.y))
                continue;
            const std::uint32_t data = (ci << 1) | (left_to_right(a, b) ? 1u : 0u);
            segs.emplace_back(KSegment(KPoint(a.x, a.y), KPoint(b.x, b.y)), data);
        }
    }

    Arr arr;
    CGAL::insert(arr, segs.begin(), segs.end());

    // 2. Number the cells in a canonical order that depends only on the geometry: CGAL's
    //    own iteration order may vary with memory layout from run to run, and the order of
    //    cells is the order in which mappers' results are concatenated.
    std::vector<Arr::Vertex_handle> vs;
    vs.reserve(arr.number_of_vertices());
    for (auto v = arr.vertices_begin(); v != arr.vertices_end(); ++v) vs.push_back(v);
    std::vector<Point> approx(vs.size());
    for (std::size_t i = 0; i < vs.size(); ++i) {
        vs[i]->set_data(int(i));
        approx[i] = Point{CGAL::to_double(vs[i]->point().x()), CGAL::to_double(vs[i]->point().y())};
    }
    {
        std::vector<int> order(vs.size());
        for (std::size_t i = 0; i < order.size(); ++i) order[i] = int(i);
        std::sort(order.begin(), order.end(), [&](int a, int b) {
            if (approx[a] != approx[b]) return approx[a] < approx[b];
            return CGAL::compare_xy(vs[a]->point(), vs[b]->point()) == CGAL::SMALLER;
        });
        for (std::size_t i = 0; i < order.size(); ++i) vs[order[i]]->set_data(int(i));
    }
    const int vi = int(vs.size());

    std::vector<std::pair<std::pair<int, int>, Arr::Halfedge_handle>> es;
    es.reserve(arr.number_of_edges());
    for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e) {
        const int a = e->source()->data(), b = e->target()->data();
        es.push_back({{std::min(a, b), std::max(a, b)}, e});
    }
    std::sort(es.begin(), es.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    for (std::size_t i = 0; i < es.size(); ++i) {
        es[i].second->set_data(int(i));
        es[i].second->twin()->set_data(int(i));
    }
    const int ei = int(es.size());

    // A boundary cycle is identified by its smallest (source, target) vertex pair.
    auto cycle_key = [](Arr::Ccb_halfedge_circulator circ) {
        std::pair<int, int> best{INT_MAX, INT_MAX};
        auto first = circ;
        do {
            best = std::min(best, std::make_pair(circ->source()->data(), circ->target()->data()));
        } while (++circ != first);
        return best;
    };
    std::vector<std::pair<std::pair<int, int>, Arr::Face_handle>> fs;
    fs.reserve(arr.number_of_faces());
    for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f)
        fs.push_back({f->is_unbounded() ? std::make_pair(-1, -1) : cycle_key(f->outer_ccb()), f});
    std::sort(fs.begin(), fs.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    for (std::size_t i = 0; i < fs.size(); ++i) fs[i].second->set_data(int(i));
    const int fi = int(fs.size());

    // 3. Vertices.
    std::unordered_map<Point, Labels, PointHash> point_labels;
    for (const auto& lp : input.points) point_labels[lp.point].merge(lp.labels);
    pm.vertices_.resize(vi);
    for (auto v = arr.vertices_begin(); v != arr.vertices_end(); ++v) {
        VertexRec& rec = pm.vertices_[v->data()];
        rec.point = Point{CGAL::to_double(v->point().x()), CGAL::to_double(v->point().y())};
        rec.key = hash_point(0x5645525445ULL, rec.point);
        if (!point_labels.empty()) {
            auto it = point_labels.find(rec.point);
            if (it != point_labels.end()) rec.labels = it->second;
        }
    }

    // 4. Edges, oriented like the first of their source curves.
    pm.edges_.resize(ei);
    std::vector<Arr::Halfedge_handle> oriented(ei);
    for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e) {
        EdgeRec& rec = pm.edges_[e->data()];
        const auto& data = e->curve().data();
        for (std::uint32_t d : data) rec.sources.push_back({d >> 1, (d & 1u) != 0});
        std::sort(rec.sources.begin(), rec.sources.end(),
                  [](const EdgeSource& a, const EdgeSource& b) {
                      return a.curve < b.curve || (a.curve == b.curve && a.forward < b.forward);
                  });
        // Halfedge `e` runs left to right or right to left; pick the one running like the
        // first source (forward = that source runs left to right).
        Arr::Halfedge_handle h = e;
        const bool h_l2r = h->direction() == CGAL::ARR_LEFT_TO_RIGHT;
        if (h_l2r != rec.sources.front().forward) h = h->twin();
        oriented[e->data()] = h;
        rec.source = h->source()->data();
        rec.target = h->target()->data();
        rec.left = h->face()->data();
        rec.right = h->twin()->face()->data();
        const bool l2r = h->direction() == CGAL::ARR_LEFT_TO_RIGHT;
        for (const auto& s : rec.sources) {
            const Curve& c = input.curves[s.curve];
            rec.labels.merge(c.labels);
            if (s.forward == l2r) {
                rec.left_labels.merge(c.left);
                rec.right_labels.merge(c.right);
            } else {
                rec.left_labels.merge(c.right);
                rec.right_labels.merge(c.left);
            }
        }
        const Point& a = pm.vertices_[rec.source].point;
        const Point& b = pm.vertices_[rec.target].point;
        // Key independent of the orientation, so that both directions agree.
        rec.key = left_to_right(a, b) ? hash_point(hash_point(0x45444745ULL, a), b)
                                      : hash_point(hash_point(0x45444745ULL, b), a);
    }

    // 5. Vertex incidences (CGAL circulates clockwise around a vertex; reverse it).
    for (auto v = arr.vertices_begin(); v != arr.vertices_end(); ++v) {
        VertexRec& rec = pm.vertices_[v->data()];
        if (v->is_isolated()) {
            rec.faces.push_back(v->face()->data());
            continue;
        }
        auto circ = v->incident_halfedges();
        auto first = circ;
        do {
            rec.edges.push_back(circ->data());
        } while (++circ != first);
        std::reverse(rec.edges.begin(), rec.edges.end());
        // Start the counter-clockwise turn at the smallest edge id.
        const auto first_edge = std::min_element(rec.edges.begin(), rec.edges.end());
        std::rotate(rec.edges.begin(), first_edge, rec.edges.end());
        rec.faces.clear();
        for (int e : rec.edges) {
            // Faces in the same turn: the face on the counter-clockwise side of each edge.
            const EdgeRec& er = pm.edges_[e];
            const int f = er.source == v->data() ? er.left : er.right;
            if (std::find(rec.faces.begin(), rec.faces.end(), f) == rec.faces.end()) rec.faces.push_back(f);
        }
    }

    // 6. Faces: boundary cycles, incidences, labels rebuilt from the side labels.
    pm.faces_.resize(fi);
    std::vector<int> edge_seen(ei, -1), vertex_seen(vi, -1);
    for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f) {
        FaceRec& rec = pm.faces_[f->data()];
        rec.unbounded = f->is_unbounded();
        if (rec.unbounded) pm.unbounded_ = f->data();
        auto add_cycle = [&](Arr::Ccb_halfedge_circulator circ) {
            // Start the cycle at its smallest (source, target) pair.
            const auto key = cycle_key(circ);
            while (std::make_pair(circ->source()->data(), circ->target()->data()) != key) ++circ;
            std::vector<Side> cycle;
            auto first = circ;
            do {
                const int e = circ->data();
                const bool left = (Arr::Halfedge_handle(circ) == oriented[e]);
                cycle.push_back({e, left});
                const EdgeRec& er = pm.edges_[e];
                rec.labels.merge(left ? er.left_labels : er.right_labels);
            } while (++circ != first);
            return std::make_pair(key, std::move(cycle));
        };
        if (!f->is_unbounded()) rec.cycles.push_back(add_cycle(f->outer_ccb()).second);
        std::vector<std::pair<std::pair<int, int>, std::vector<Side>>> holes;
        for (auto h = f->inner_ccbs_begin(); h != f->inner_ccbs_end(); ++h) holes.push_back(add_cycle(*h));
        std::sort(holes.begin(), holes.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
        for (auto& h : holes) rec.cycles.push_back(std::move(h.second));
        for (const auto& cyc : rec.cycles)
            for (const Side& sd : cyc) {
                if (edge_seen[sd.edge] != f->data()) {
                    edge_seen[sd.edge] = f->data();
                    rec.edges.push_back(sd.edge);
                }
                const EdgeRec& er = pm.edges_[sd.edge];
                const int v = sd.left ? er.source : er.target;
                if (vertex_seen[v] != f->data()) {
                    vertex_seen[v] = f->data();
                    rec.vertices.push_back(v);
                }
            }
        std::vector<int> isolated;
        for (auto iv = f->isolated_vertices_begin(); iv != f->isolated_vertices_end(); ++iv)
            isolated.push_back(iv->data());
        std::sort(isolated.begin(), isolated.end());
        rec.vertices.insert(rec.vertices.end(), isolated.begin(), isolated.end());

        // Key: the outer ring read from its lexicographically smallest vertex, so that the
        // same face gets the same key in any map and whatever its vertex numbering.
        std::uint64_t key = 0x46414345ULL;
        if (!rec.unbounded && !rec.cycles.empty()) {
            const auto& cyc = rec.cycles.front();
            std::size_t start = 0;
            for (std::size_t i = 1; i < cyc.size(); ++i)
                if (pm.side_start(cyc[i]) < pm.side_start(cyc[start])) start = i;
            for (std::size_t i = 0; i < cyc.size(); ++i)
                key = hash_point(key, pm.side_start(cyc[(start + i) % cyc.size()]));
        }
        rec.key = key;
    }
    return map;
}

std::vector<Point> PlanarMap::cycle_points(int face, std::size_t cycle) const {
    std::vector<Point> ring;
    const auto& cyc = faces_[face].cycles.at(cycle);
    ring.reserve(cyc.size());
    for (const Side& s : cyc) ring.push_back(side_start(s));
    return ring;
}

Curve PlanarMap::edge_curve(int e) const {
    const EdgeRec& r = edges_[e];
    Curve c;
    c.points = {vertices_[r.source].point, vertices_[r.target].point};
    c.labels = r.labels;
    c.left = r.left_labels;
    c.right = r.right_labels;
    return c;
}

Curves PlanarMap::edge_curves() const {
    Curves out;
    out.curves.reserve(edges_.size());
    for (std::size_t e = 0; e < edges_.size(); ++e) out.curves.push_back(edge_curve(int(e)));
    for (const auto& v : vertices_)
        if (!v.labels.empty()) out.points.push_back({v.point, v.labels});
    return out;
}

}  // namespace tex
