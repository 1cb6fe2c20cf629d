// Induction of planar maps with CGAL (see planar_map.hpp for the model).
//
// The shape follows CGAL's own examples (consolidated_curve_data.cpp for the curve data,
// dcel_extension.cpp for indices stored in the DCEL): every input segment carries one
// integer, the index of its polyline times two plus a "runs left to right" bit, and the
// sweep of CGAL::insert merges these integers on overlapping pieces. CGAL's halfedges are
// then grouped into chains (the thesis's edges) between break vertices (the thesis's
// vertices), and every cell is numbered in an order that depends only on the geometry.
#include "libtex/planar_map.hpp"

#include <CGAL/Arr_consolidated_curve_data_traits_2.h>
#include <CGAL/Arr_extended_dcel.h>
#include <CGAL/Arr_segment_traits_2.h>
#include <CGAL/Arrangement_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>

#include <algorithm>
#include <climits>
#include <unordered_map>
#include <unordered_set>

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
using Halfedge = Arr::Halfedge_handle;

struct PointHash {
    std::size_t operator()(const Point& p) const { return hash_point(0, p); }
};

// Lexicographic "left to right" order of CGAL's x-monotone curves.
bool left_to_right(const Point& a, const Point& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); }

Point approx(const KPoint& p) { return Point{CGAL::to_double(p.x()), CGAL::to_double(p.y())}; }

// The sorted, distinct ids of the curves a CGAL edge comes from.
void curve_ids(Halfedge h, std::vector<std::uint32_t>& out) {
    out.clear();
    for (std::uint32_t d : h->curve().data()) out.push_back(d >> 1);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
}

// The chain's polyline read in one direction, for ordering and keys: the direction that
// starts at the smaller end point, or for a loop the one whose second point is smaller.
std::vector<Point> canonical_points(const std::vector<Point>& pts) {
    std::vector<Point> rev(pts.rbegin(), pts.rend());
    return std::lexicographical_compare(rev.begin(), rev.end(), pts.begin(), pts.end()) ? rev : pts;
}

struct Chain {
    std::vector<Halfedge> hs;  // in the chain's direction
    std::vector<Point> points;
    std::vector<Point> canon;
    int source = -1, target = -1;  // break-vertex ids
};

}  // namespace

struct PlanarMapBuilder {
    static MapPtr build(const Curves& curves);
};

MapPtr PlanarMap::induce(const Curves& curves) { return PlanarMapBuilder::build(curves); }

MapPtr PlanarMapBuilder::build(const Curves& input) {
    auto map = std::make_shared<PlanarMap>();
    PlanarMap& pm = *map;

    // 1. Segments with their curve data; the end points of open curves.
    std::vector<Traits::Curve_2> segs;
    std::unordered_set<Point, PointHash> ends;
    std::size_t total = 0;
    for (const auto& c : input.curves) total += c.points.size();
    segs.reserve(total);
    for (std::uint32_t ci = 0; ci < input.curves.size(); ++ci) {
        const Curve& c = input.curves[ci];
        const std::size_t n = c.points.size();
        if (n < 2) continue;
        const std::size_t nseg = c.closed ? n : n - 1;
        bool first = true;
        Point last;
        for (std::size_t i = 0; i < nseg; ++i) {
            const Point& a = c.points[i];
            const Point& b = c.points[(i + 1) % n];
            if (a == b || !std::isfinite(a.x) || !std::isfinite(a.y) || !std::isfinite(b.x) ||
                !std::isfinite(b.y))
                continue;
            const std::uint32_t data = (ci << 1) | (left_to_right(a, b) ? 1u : 0u);
            segs.emplace_back(KSegment(KPoint(a.x, a.y), KPoint(b.x, b.y)), data);
            if (!c.closed && first) ends.insert(a);
            first = false;
            last = b;
        }
        if (!c.closed && !first) ends.insert(last);
    }
    std::unordered_map<Point, Labels, PointHash> point_labels;
    for (const auto& lp : input.points) point_labels[lp.point].merge(lp.labels);

    Arr arr;
    CGAL::insert(arr, segs.begin(), segs.end());

    // 2. Break vertices: curve ends, labelled points, degree other than two, and points
    //    where the set of source curves changes.
    std::vector<Arr::Vertex_handle> vs;
    vs.reserve(arr.number_of_vertices());
    for (auto v = arr.vertices_begin(); v != arr.vertices_end(); ++v) vs.push_back(v);
    std::vector<Point> vpt(vs.size());
    std::vector<char> is_break(vs.size(), 0);
    {
        std::vector<std::uint32_t> ids_a, ids_b;
        for (std::size_t i = 0; i < vs.size(); ++i) {
            const auto v = vs[i];
            v->set_data(int(i));
            vpt[i] = approx(v->point());
            bool brk = v->is_isolated() || v->degree() != 2 || ends.count(vpt[i]) || point_labels.count(vpt[i]);
            if (!brk) {
                auto circ = v->incident_halfedges();
                const Halfedge a = circ;
                ++circ;
                const Halfedge b = circ;
                const auto& da = a->curve().data();
                const auto& db = b->curve().data();
                if (da.size() == 1 && db.size() == 1) {
                    brk = (*da.begin() >> 1) != (*db.begin() >> 1);
                } else {
                    curve_ids(a, ids_a);
                    curve_ids(b, ids_b);
                    brk = ids_a != ids_b;
                }
            }
            is_break[i] = brk;
        }
    }
    for (auto h = arr.halfedges_begin(); h != arr.halfedges_end(); ++h) h->set_data(-1);

    // 3. Chains: walk from every break vertex along degree-two vertices; what is left are
    //    closed curves meeting nothing, which start at their smallest point.
    std::vector<Chain> chains;
    auto walk = [&](Halfedge start) {
        Chain ch;
        Halfedge cur = start;
        for (;;) {
            ch.hs.push_back(cur);
            cur->set_data(0);
            cur->twin()->set_data(0);
            if (is_break[cur->target()->data()]) break;
            cur = cur->next();
        }
        chains.push_back(std::move(ch));
    };
    for (std::size_t i = 0; i < vs.size(); ++i) {
        if (!is_break[i] || vs[i]->is_isolated()) continue;
        auto circ = vs[i]->incident_halfedges();
        const auto first = circ;
        do {
            const Halfedge out = circ->twin();
            if (out->data() == -1) walk(out);
        } while (++circ != first);
    }
    for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e) {
        if (e->data() != -1) continue;
        Halfedge start = e, cur = e;
        do {
            if (vpt[cur->source()->data()] < vpt[start->source()->data()]) start = cur;
            cur = cur->next();
        } while (cur != Halfedge(e));
        is_break[start->source()->data()] = 1;
        walk(start);
    }

    // 4. Orient each chain like its first source curve; its polyline.
    std::vector<std::vector<EdgeSource>> chain_sources(chains.size());
    for (std::size_t k = 0; k < chains.size(); ++k) {
        Chain& ch = chains[k];
        const Halfedge h0 = ch.hs.front();
        const bool h0_l2r = h0->direction() == CGAL::ARR_LEFT_TO_RIGHT;
        auto& src = chain_sources[k];
        for (std::uint32_t d : h0->curve().data()) src.push_back({d >> 1, ((d & 1u) != 0) == h0_l2r});
        std::sort(src.begin(), src.end(), [](const EdgeSource& a, const EdgeSource& b) {
            return a.curve < b.curve || (a.curve == b.curve && a.forward > b.forward);
        });
        for (const Halfedge& h : ch.hs) ch.points.push_back(vpt[h->source()->data()]);
        ch.points.push_back(vpt[ch.hs.back()->target()->data()]);
        bool flip = !src.front().forward;
        // The first curve running both ways along the chain: keep the canonical direction.
        if (src.size() > 1 && src[1].curve == src[0].curve) flip = canonical_points(ch.points) != ch.points;
        if (flip) {
            std::reverse(ch.hs.begin(), ch.hs.end());
            for (auto& h : ch.hs) h = h->twin();
            std::reverse(ch.points.begin(), ch.points.end());
            for (auto& s : src) s.forward = !s.forward;
            std::sort(src.begin(), src.end(), [](const EdgeSource& a, const EdgeSource& b) {
                return a.curve < b.curve || (a.curve == b.curve && a.forward > b.forward);
            });
        }
        ch.canon = canonical_points(ch.points);
    }

    // 5. Vertices: the break vertices, in the order of their points.
    std::vector<int> breaks;
    for (std::size_t i = 0; i < vs.size(); ++i)
        if (is_break[i]) breaks.push_back(int(i));
    std::sort(breaks.begin(), breaks.end(), [&](int a, int b) {
        if (vpt[a] != vpt[b]) return vpt[a] < vpt[b];
        return CGAL::compare_xy(vs[a]->point(), vs[b]->point()) == CGAL::SMALLER;
    });
    std::vector<int> vid(vs.size(), -1);
    for (std::size_t i = 0; i < breaks.size(); ++i) vid[breaks[i]] = int(i);
    pm.vertices_.resize(breaks.size());
    for (std::size_t i = 0; i < breaks.size(); ++i) {
        VertexRec& rec = pm.vertices_[i];
        rec.point = vpt[breaks[i]];
        rec.key = hash_point(0x5645525445ULL, rec.point);
        if (!point_labels.empty()) {
            auto it = point_labels.find(rec.point);
            if (it != point_labels.end()) rec.labels = it->second;
        }
    }

    // 6. Edges: chains ordered by their end vertices, then by their polylines.
    for (auto& ch : chains) {
        ch.source = vid[ch.hs.front()->source()->data()];
        ch.target = vid[ch.hs.back()->target()->data()];
    }
    std::vector<int> order(chains.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = int(i);
    std::sort(order.begin(), order.end(), [&](int a, int b) {
        const Chain& x = chains[a];
        const Chain& y = chains[b];
        const auto kx = std::minmax(x.source, x.target), ky = std::minmax(y.source, y.target);
        if (kx != ky) return kx < ky;
        return std::lexicographical_compare(x.canon.begin(), x.canon.end(), y.canon.begin(), y.canon.end());
    });
    pm.edges_.resize(chains.size());
    std::vector<int> eid(chains.size());
    for (std::size_t i = 0; i < order.size(); ++i) eid[order[i]] = int(i);
    for (std::size_t k = 0; k < chains.size(); ++k) {
        const int id = eid[k];
        for (const Halfedge& h : chains[k].hs) {
            h->set_data(2 * id);             // runs along the edge
            h->twin()->set_data(2 * id + 1); // runs against it
        }
    }

    // 7. Faces: boundary cycles as sides of edges, ordered by their smallest side.
    auto cycle_of = [&](Arr::Ccb_halfedge_circulator circ) {
        std::vector<Side> cycle;
        int best = INT_MAX;
        std::size_t best_at = 0;
        const auto first = circ;
        do {
            if (is_break[circ->source()->data()]) {
                const int d = circ->data();
                if (d < best) {
                    best = d;
                    best_at = cycle.size();
                }
                cycle.push_back({d / 2, (d & 1) == 0});
            }
        } while (++circ != first);
        std::rotate(cycle.begin(), cycle.begin() + std::ptrdiff_t(best_at), cycle.end());
        return std::make_pair(best, std::move(cycle));
    };
    std::vector<std::pair<int, Arr::Face_handle>> fs;
    fs.reserve(arr.number_of_faces());
    for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f)
        fs.push_back({f->is_unbounded() ? -1 : cycle_of(f->outer_ccb()).first, f});
    std::sort(fs.begin(), fs.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    for (std::size_t i = 0; i < fs.size(); ++i) fs[i].second->set_data(int(i));
    pm.faces_.resize(fs.size());

    // Edge records (faces are numbered now).
    for (std::size_t k = 0; k < chains.size(); ++k) {
        const Chain& ch = chains[k];
        EdgeRec& rec = pm.edges_[eid[k]];
        rec.source = ch.source;
        rec.target = ch.target;
        rec.points = ch.points;
        rec.left = ch.hs.front()->face()->data();
        rec.right = ch.hs.front()->twin()->face()->data();
        rec.sources = chain_sources[k];
        for (const auto& s : rec.sources) {
            const Curve& c = input.curves[s.curve];
            rec.labels.merge(c.labels);
            rec.left_labels.merge(s.forward ? c.left : c.right);
            rec.right_labels.merge(s.forward ? c.right : c.left);
        }
        // Key of the geometry, whatever the orientation and the numbering.
        std::uint64_t key = 0x45444745ULL;
        for (const Point& p : ch.canon) key = hash_point(key, p);
        rec.key = key;
    }

    // 8. Vertex incidences (CGAL turns clockwise around a vertex; reverse it).
    for (std::size_t i = 0; i < breaks.size(); ++i) {
        const auto v = vs[breaks[i]];
        VertexRec& rec = pm.vertices_[i];
        if (v->is_isolated()) {
            rec.faces.push_back(v->face()->data());
            continue;
        }
        std::vector<Halfedge> in;
        auto circ = v->incident_halfedges();
        const auto first = circ;
        do {
            in.push_back(circ);
        } while (++circ != first);
        std::reverse(in.begin(), in.end());
        std::size_t start = 0;
        for (std::size_t k = 1; k < in.size(); ++k)
            if (in[k]->data() / 2 < in[start]->data() / 2) start = k;
        std::rotate(in.begin(), in.begin() + std::ptrdiff_t(start), in.end());
        for (const Halfedge& h : in) {
            rec.edges.push_back(h->data() / 2);
            // The face on the counter-clockwise side of the edge leaving the vertex.
            const int f = h->twin()->face()->data();
            if (std::find(rec.faces.begin(), rec.faces.end(), f) == rec.faces.end()) rec.faces.push_back(f);
        }
    }

    // 9. Face records: cycles, incidences, labels rebuilt from the side labels.
    std::vector<int> edge_seen(chains.size(), -1), vertex_seen(breaks.size(), -1);
    for (const auto& [key_unused, f] : fs) {
        (void)key_unused;
        FaceRec& rec = pm.faces_[f->data()];
        rec.unbounded = f->is_unbounded();
        if (rec.unbounded) pm.unbounded_ = f->data();
        if (!f->is_unbounded()) rec.cycles.push_back(cycle_of(f->outer_ccb()).second);
        std::vector<std::pair<int, std::vector<Side>>> holes;
        for (auto h = f->inner_ccbs_begin(); h != f->inner_ccbs_end(); ++h) holes.push_back(cycle_of(*h));
        std::sort(holes.begin(), holes.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
        for (auto& h : holes) rec.cycles.push_back(std::move(h.second));
        for (const auto& cyc : rec.cycles)
            for (const Side& sd : cyc) {
                const EdgeRec& er = pm.edges_[sd.edge];
                rec.labels.merge(sd.left ? er.left_labels : er.right_labels);
                if (edge_seen[sd.edge] != f->data()) {
                    edge_seen[sd.edge] = f->data();
                    rec.edges.push_back(sd.edge);
                }
                const int v = sd.left ? er.source : er.target;
                if (vertex_seen[v] != f->data()) {
                    vertex_seen[v] = f->data();
                    rec.vertices.push_back(v);
                }
            }
        std::vector<int> isolated;
        for (auto iv = f->isolated_vertices_begin(); iv != f->isolated_vertices_end(); ++iv)
            isolated.push_back(vid[iv->data()]);
        std::sort(isolated.begin(), isolated.end());
        rec.vertices.insert(rec.vertices.end(), isolated.begin(), isolated.end());

        // Key: the outer ring read from its lexicographically smallest point, so that the
        // same face gets the same key in any map and whatever its numbering.
        std::uint64_t key = 0x46414345ULL;
        if (!rec.unbounded && !rec.cycles.empty()) {
            const std::vector<Point> ring = pm.cycle_points(f->data(), 0);
            std::size_t start = 0;
            for (std::size_t i = 1; i < ring.size(); ++i)
                if (ring[i] < ring[start]) start = i;
            for (std::size_t i = 0; i < ring.size(); ++i) key = hash_point(key, ring[(start + i) % ring.size()]);
        }
        rec.key = key;
    }
    return map;
}

std::vector<Point> PlanarMap::cycle_points(int face, std::size_t cycle) const {
    std::vector<Point> ring;
    const auto& cyc = faces_[face].cycles.at(cycle);
    for (const Side& s : cyc) {
        const std::vector<Point>& p = edges_[s.edge].points;
        if (s.left) ring.insert(ring.end(), p.begin(), p.end() - 1);
        else ring.insert(ring.end(), p.rbegin(), p.rend() - 1);
    }
    return ring;
}

Curve PlanarMap::edge_curve(int e) const {
    const EdgeRec& r = edges_[e];
    Curve c;
    c.points = r.points;
    if (r.source == r.target && c.points.size() > 2) {
        c.points.pop_back();
        c.closed = true;
    }
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
