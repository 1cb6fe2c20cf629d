// Induction of planar maps (see planar_map.hpp for the model).
//
// Two ways to the same map, both producing a neutral half-edge graph of segments (RawGraph)
// that one common step turns into the thesis's cells:
//
//  - direct: when the curves' segments only meet at shared end points (checked with exact
//    predicates on the doubles) and form one connected drawing, the faces are traced from
//    the segments' exact angular order around each point. This is the common case of
//    partitions and of contours, and needs no construction at all;
//  - CGAL: otherwise, CGAL's Arrangement_2 over an exact-constructions kernel computes the
//    intersections and overlaps. The shape follows CGAL's own examples
//    (consolidated_curve_data.cpp for the curve data, dcel_extension.cpp for indices in the
//    DCEL): every input segment carries one integer, the index of its polyline times two
//    plus a "runs left to right" bit, merged on overlapping pieces.
//
// The common step groups segments into chains (the thesis's edges) between break vertices
// (the thesis's vertices) and numbers every cell in an order that depends only on the
// geometry, so both ways give the same map, byte for byte (tested).
#include "libtex/planar_map.hpp"

#include <CGAL/Arr_consolidated_curve_data_traits_2.h>
#include <CGAL/Arr_extended_dcel.h>
#include <CGAL/Arr_non_caching_segment_traits_2.h>
#include <CGAL/Arr_segment_traits_2.h>
#include <CGAL/Arrangement_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <climits>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <tuple>
#include <unordered_map>

#include "libtex/random.hpp"
#include "geometry/exact_double.hpp"
#include "geometry/segment_index.hpp"

namespace tex {
namespace {

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using KPoint = Kernel::Point_2;
using KSegment = Kernel::Segment_2;
// Two segment traits, as CGAL advises: the caching one precomputes each segment's line,
// which pays off when segments cross a lot; the non-caching one is cheaper per segment when
// they mostly do not (CGAL's documentation, "Arr_non_caching_segment_traits_2").
template <class SegmentTraits>
struct CgalTypes {
    using Traits = CGAL::Arr_consolidated_curve_data_traits_2<SegmentTraits, std::uint32_t>;
    using Dcel = CGAL::Arr_extended_dcel<Traits, int, int, int>;
    using Arr = CGAL::Arrangement_2<Traits, Dcel>;
};
using Caching = CgalTypes<CGAL::Arr_segment_traits_2<Kernel>>;
using NonCaching = CgalTypes<CGAL::Arr_non_caching_segment_traits_2<Kernel>>;
using IK = CGAL::Exact_predicates_inexact_constructions_kernel;

using detail::exact_double;

struct PointHash {
    std::size_t operator()(const Point& p) const { return hash_point(0, p); }
};

// Lexicographic "left to right" order of CGAL's x-monotone curves.
bool left_to_right(const Point& a, const Point& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); }


// A planar map at the level of segments. Half-edges 2k and 2k+1 are twins; a half-edge's
// face lies on its left.
struct RawGraph {
    std::vector<Point> vpt;
    std::vector<int> vrank;       // exact order among vertices with equal doubles
    std::vector<char> visolated;
    std::vector<char> vend;       // the end of an open curve (direct way only; empty otherwise)
    std::vector<int> vout_start;  // outgoing half-edges of each vertex, counter-clockwise
    std::vector<int> vout;
    struct HalfEdge {
        int source, target, next, face;
        bool l2r;
    };
    std::vector<HalfEdge> he;
    std::vector<std::uint32_t> data_start, data;  // curve data of each segment (he / 2)
    struct RawFace {
        bool unbounded = false;
        int outer = -1;
        std::vector<int> inner;
        std::vector<int> isolated;
    };
    std::vector<RawFace> faces;

    std::size_t degree(int v) const { return std::size_t(vout_start[v + 1] - vout_start[v]); }
    template <class F>
    void for_data(int h, F&& f) const {
        const int e = h / 2;
        for (std::uint32_t k = data_start[e]; k < data_start[e + 1]; ++k) f(data[k]);
    }
    // Empty, keeping the vectors' storage for the next map.
    void clear() {
        auto clear_all = [](auto&... v) { (v.clear(), ...); };
        clear_all(vpt, vrank, visolated, vend, vout_start, vout, he, data_start, data, faces);
    }
};

// An end of a segment with its point copied in (no indirection while sorting ends).
struct SegEnd {
    Point p;
    std::uint32_t k;
    bool operator<(const SegEnd& o) const { return p != o.p ? p < o.p : k < o.k; }
};

// The chains of the common step: runs of half-edges between break vertices (the thesis's
// edges), their half-edges kept together in one vector of the scratch.
struct Chain {
    std::size_t hs_begin = 0, hs_end = 0;  // in BuildScratch::chain_hs, in the chain's direction
    std::vector<Point> points;
    bool canon_reversed = false;  // the canonical reading runs from the last point
    int source = -1, target = -1;
};

// The builder's temporary vectors, one set per thread, kept from map to map: a pipeline
// builds tens of thousands of small maps, and these vectors, made afresh for each, were a
// third of the allocations of a run on the sample (heaptrack). Vectors grown beyond
// kKeepElements are freed after the build, so that one huge map does not hold its memory
// for the life of the thread. The builder does not call itself: one set serves each call.
struct BuildScratch {
    static constexpr std::size_t kKeepElements = std::size_t(1) << 16;
    RawGraph g;
    // build_directly
    std::vector<detail::Seg> segs;
    std::vector<BBox> boxes;
    std::vector<SegEnd> ends;
    std::vector<std::uint32_t> first;
    std::vector<int> ids, comp, parent, fill, pos, v0, outer_he, cycle, cycle_start, face_of_cycle, holder;
    std::vector<char> cycle_outer;
    // PlanarMapBuilder::build
    std::vector<Point> curve_ends;
    std::vector<char> is_break;
    std::vector<std::uint32_t> ids_a, ids_b;
    std::vector<Chain> chains;
    std::vector<int> chain_hs, he_chain, breaks, vid, order, eid, side_of, fid, edge_seen, vertex_seen;
    std::vector<std::vector<EdgeSource>> chain_sources;
    std::vector<std::pair<int, int>> fs;
    std::vector<std::vector<Side>> outer_cycle;
    bool busy = false;

    // A chain's half-edges, front and back.
    int hs_front(const Chain& ch) const { return chain_hs[ch.hs_begin]; }
    int hs_back(const Chain& ch) const { return chain_hs[ch.hs_end - 1]; }

    // Frees each vector grown beyond kKeepElements.
    template <class... V>
    static void trim(V&... v) {
        ((v.capacity() > kKeepElements ? V().swap(v) : void()), ...);
    }
    void trim_all() {
        trim(g.vpt, g.vrank, g.visolated, g.vend, g.vout_start, g.vout, g.he, g.data_start, g.data, g.faces);
        trim(segs, boxes, ends, first, ids, comp, parent, fill, pos, v0, outer_he, cycle, cycle_start, face_of_cycle,
             holder, cycle_outer);
        trim(curve_ends, is_break, ids_a, ids_b, chains, chain_hs, he_chain, breaks, vid, order, eid, side_of, fid,
             edge_seen, vertex_seen, chain_sources, fs, outer_cycle);
    }
};

BuildScratch& build_scratch() {
    thread_local BuildScratch scratch;
    return scratch;
}

// Holds the thread's scratch for one build, and trims it when the build ends (also on an
// exception).
class ScratchLease {
public:
    ScratchLease() : s_(build_scratch()) {
        if (s_.busy) throw std::logic_error("planar map builder: called again while building");
        s_.busy = true;
    }
    ~ScratchLease() {
        s_.trim_all();
        s_.busy = false;
    }
    ScratchLease(const ScratchLease&) = delete;
    ScratchLease& operator=(const ScratchLease&) = delete;
    BuildScratch& operator*() const { return s_; }

private:
    BuildScratch& s_;
};

// ---- Way 1: CGAL ----

template <class Types>
void build_with_cgal(const Curves& input, RawGraph& g) {
    using Traits = typename Types::Traits;
    using Arr = typename Types::Arr;
    std::vector<typename Traits::Curve_2> segs;
    for (const detail::Seg& s : detail::curve_segments(input)) {
        const std::uint32_t d = (s.owner << 1) | (left_to_right(s.a, s.b) ? 1u : 0u);
        segs.emplace_back(KSegment(KPoint(s.a.x, s.a.y), KPoint(s.b.x, s.b.y)), d);
    }
    Arr arr;
    CGAL::insert(arr, segs.begin(), segs.end());

    std::vector<typename Arr::Vertex_handle> vs;
    for (auto v = arr.vertices_begin(); v != arr.vertices_end(); ++v) vs.push_back(v);
    const std::size_t nv = vs.size();
    g.vpt.resize(nv);
    g.visolated.resize(nv);
    for (std::size_t i = 0; i < nv; ++i) {
        vs[i]->set_data(int(i));
        g.vpt[i] = Point{exact_double(vs[i]->point().x()), exact_double(vs[i]->point().y())};
        g.visolated[i] = vs[i]->is_isolated();
    }
    {
        std::vector<int> order(nv);
        std::iota(order.begin(), order.end(), 0);
        std::sort(order.begin(), order.end(), [&](int a, int b) {
            return CGAL::compare_xy(vs[a]->point(), vs[b]->point()) == CGAL::SMALLER;
        });
        g.vrank.resize(nv);
        for (std::size_t i = 0; i < nv; ++i) g.vrank[order[i]] = int(i);
    }
    int k = 0;
    for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e, ++k) {
        e->set_data(2 * k);
        e->twin()->set_data(2 * k + 1);
    }
    int fi = 0;
    for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f) f->set_data(fi++);
    g.he.resize(2 * std::size_t(k));
    g.data_start.assign(std::size_t(k) + 1, 0);
    k = 0;
    for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e, ++k) {
        for (typename Arr::Halfedge_handle h : {typename Arr::Halfedge_handle(e), e->twin()})
            g.he[h->data()] = {h->source()->data(), h->target()->data(), h->next()->data(), h->face()->data(),
                               h->direction() == CGAL::ARR_LEFT_TO_RIGHT};
        for (std::uint32_t d : e->curve().data()) g.data.push_back(d);
        g.data_start[k + 1] = std::uint32_t(g.data.size());
    }
    g.vout_start.assign(nv + 1, 0);
    for (std::size_t i = 0; i < nv; ++i) {
        const std::size_t before = g.vout.size();
        if (!vs[i]->is_isolated()) {
            auto circ = vs[i]->incident_halfedges();  // incoming, clockwise
            const auto first = circ;
            do {
                g.vout.push_back(circ->twin()->data());
            } while (++circ != first);
            std::reverse(g.vout.begin() + std::ptrdiff_t(before), g.vout.end());
        }
        g.vout_start[i + 1] = int(g.vout.size());
    }
    g.faces.resize(std::size_t(fi));
    for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f) {
        RawGraph::RawFace& rf = g.faces[f->data()];
        rf.unbounded = f->is_unbounded();
        if (!rf.unbounded) rf.outer = f->outer_ccb()->data();
        for (auto h = f->inner_ccbs_begin(); h != f->inner_ccbs_end(); ++h) rf.inner.push_back((*h)->data());
        for (auto iv = f->isolated_vertices_begin(); iv != f->isolated_vertices_end(); ++iv)
            rf.isolated.push_back(iv->data());
    }
}

// ---- Way 2: direct, for clean connected drawings ----

IK::Point_2 ik(const Point& p) { return IK::Point_2(p.x, p.y); }

// Counter-clockwise order of directions from p, starting at the +x axis.
bool ccw_before(const Point& p, const Point& a, const Point& b) {
    auto upper = [&](const Point& q) { return q.y > p.y || (q.y == p.y && q.x > p.x); };
    const bool ua = upper(a), ub = upper(b);
    if (ua != ub) return ua;
    return CGAL::orientation(ik(p), ik(a), ik(b)) == CGAL::LEFT_TURN;
}

// The phases of build_directly, in their order. Each reads and fills the vectors of the
// scratch (the raw graph `sc.g` above all).
namespace direct {

// The grid index of the segments, built the first time a phase needs it (at most once per
// map).
const detail::SegmentGrid& lazy_grid(std::optional<detail::SegmentGrid>& grid_store,
                                     const std::vector<detail::Seg>& segs) {
    if (!grid_store) grid_store.emplace(segs);
    return *grid_store;
}

// Clean: two segments meet only at a common end point, without overlapping. Otherwise,
// count the segments that cross another one (not overlaps) to choose the CGAL traits, and
// stop (false, with `many_crossings`) as soon as a tenth of them do.
bool is_clean(BuildScratch& sc, std::optional<detail::SegmentGrid>& grid_store, bool& many_crossings) {
    const std::vector<detail::Seg>& segs = sc.segs;
    // The grid index pays off from a few dozen segments on; the maps of small cells (a
    // polygon and a few chords) compare every pair directly, and build the grid only if
    // they need it to place their pieces.
    constexpr std::size_t kSmall = 48;
    bool clean = true;
    const std::size_t enough = segs.size() / 10 + 1;
    std::size_t crossings = 0;
    // Each segment's box once: most pairs are told apart by their boxes alone.
    std::vector<BBox>& boxes = sc.boxes;
    boxes.assign(segs.size(), BBox{});
    for (std::size_t i = 0; i < segs.size(); ++i) {
        boxes[i].add(segs[i].a);
        boxes[i].add(segs[i].b);
    }
    for (std::uint32_t i = 0; i < segs.size(); ++i) {
        const detail::Seg& s = segs[i];
        const BBox& b = boxes[i];
        bool crossing = false;
        auto visit = [&](std::uint32_t j) {
            if (crossing || j <= i) return;
            const detail::Seg& t = segs[j];
            const BBox& tb = boxes[j];
            if (tb.xmax < b.xmin || tb.xmin > b.xmax || tb.ymax < b.ymin || tb.ymin > b.ymax) return;
            const bool sa = s.a == t.a || s.a == t.b, sb = s.b == t.a || s.b == t.b;
            if (sa && sb) {
                clean = false;  // the same segment twice
            } else if (sa || sb) {
                const Point& p = sa ? s.a : s.b;           // shared
                const Point& q = sa ? s.b : s.a;           // s's other end
                const Point& r = (t.a == p) ? t.b : t.a;   // t's other end
                if (CGAL::orientation(ik(p), ik(q), ik(r)) == CGAL::COLLINEAR && dot(q - p, r - p) > 0)
                    clean = false;
            } else if (detail::segments_touch(s.a, s.b, t.a, t.b)) {
                clean = false;
                crossing = CGAL::orientation(ik(s.a), ik(s.b), ik(t.a)) != CGAL::COLLINEAR ||
                           CGAL::orientation(ik(s.a), ik(s.b), ik(t.b)) != CGAL::COLLINEAR;
            }
        };
        if (segs.size() <= kSmall) {
            for (std::uint32_t j = i + 1; j < segs.size() && !crossing; ++j) visit(j);
        } else {
            lazy_grid(grid_store, segs).for_each_in(b, visit);
        }
        if (crossing && ++crossings >= enough) {
            many_crossings = true;
            return false;
        }
    }
    return clean;
}

// The half-edges and curve data of every segment, and its two vertices, numbered in the
// order their points first appear. `slot(k, e)` is where the vertex id of end e of segment
// k is kept, shared by every end at that vertex.
template <class Slot>
void number_segments(const std::vector<detail::Seg>& segs, RawGraph& g, Slot&& slot) {
    const std::size_t ns = segs.size();
    g.he.resize(2 * ns);
    g.data_start.resize(ns + 1);
    g.data.resize(ns);
    g.vpt.reserve(2 * ns);
    for (std::size_t k = 0; k < ns; ++k) {
        int uv[2];
        for (std::uint32_t e = 0; e < 2; ++e) {
            int& v = slot(k, e);
            if (v < 0) {
                v = int(g.vpt.size());
                g.vpt.push_back(e ? segs[k].b : segs[k].a);
            }
            uv[e] = v;
        }
        const bool l2r = left_to_right(segs[k].a, segs[k].b);
        g.he[2 * k] = {uv[0], uv[1], -1, -1, l2r};
        g.he[2 * k + 1] = {uv[1], uv[0], -1, -1, !l2r};
        g.data_start[k] = std::uint32_t(k);
        g.data[k] = (segs[k].owner << 1) | (l2r ? 1u : 0u);
    }
}

// Vertices (numbered in the order their points first appear) and segments: the ends at
// one vertex are those the caller names alike (`known`), or else those with equal points.
void number_vertices(BuildScratch& sc, const detail::KnownVertices* known) {
    RawGraph& g = sc.g;
    const std::vector<detail::Seg>& segs = sc.segs;
    const std::size_t ns = segs.size();
    if (known) {
        // Vertices named by the caller.
        std::vector<int>& id = sc.ids;
        id.assign(known->count, -1);
        number_segments(segs, g, [&](std::size_t k, std::uint32_t e) -> int& {
            return id[std::size_t(known->ends[k][e])];
        });
    } else {
        auto end_point = [&](std::uint32_t k) -> const Point& { return (k & 1u) ? segs[k >> 1].b : segs[k >> 1].a; };
        // The ends sorted by point, then by index.
        std::vector<SegEnd>& ends = sc.ends;
        ends.resize(2 * ns);
        for (std::uint32_t k = 0; k < 2 * ns; ++k) ends[k] = {end_point(k), k};
        std::sort(ends.begin(), ends.end());
        std::vector<std::uint32_t>& first = sc.first;  // the first end at the same point
        first.resize(2 * ns);
        for (std::size_t i = 0; i < ends.size(); ++i)
            first[ends[i].k] = (i > 0 && ends[i].p == ends[i - 1].p) ? first[ends[i - 1].k] : ends[i].k;
        std::vector<int>& id = sc.ids;
        id.assign(2 * ns, -1);
        number_segments(segs, g, [&](std::size_t k, std::uint32_t e) -> int& { return id[first[2 * k + e]]; });
    }
    g.data_start[ns] = std::uint32_t(ns);
}

// The ends of open curves: the first and last segment kept of each (segments of a curve
// are consecutive).
void mark_open_ends(const Curves& input, BuildScratch& sc) {
    RawGraph& g = sc.g;
    const std::vector<detail::Seg>& segs = sc.segs;
    const std::size_t ns = segs.size();
    const std::size_t nv = g.vpt.size();
    g.vend.assign(nv, 0);
    for (std::size_t k = 0; k < ns; ++k) {
        const std::uint32_t owner = segs[k].owner;
        if (input.curves[owner].closed) continue;
        if (k == 0 || segs[k - 1].owner != owner) g.vend[std::size_t(g.he[2 * k].source)] = 1;
        if (k + 1 == ns || segs[k + 1].owner != owner) g.vend[std::size_t(g.he[2 * k].target)] = 1;
    }
}

// Connected pieces of the drawing: the piece of each vertex (sc.comp), numbered in the
// order of their first vertex; returns their number.
int connected_pieces(BuildScratch& sc) {
    const RawGraph& g = sc.g;
    const std::size_t ns = sc.segs.size();
    const std::size_t nv = g.vpt.size();
    std::vector<int>& comp = sc.comp;
    comp.resize(nv);
    int ncomp = 0;
    std::vector<int>& parent = sc.parent;
    parent.resize(nv);
    std::iota(parent.begin(), parent.end(), 0);
    auto find = [&](int x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    };
    for (std::size_t k = 0; k < ns; ++k) {
        const int a = find(g.he[2 * k].source), b = find(g.he[2 * k].target);
        if (a != b) parent[a] = b;
    }
    std::vector<int>& id = sc.ids;
    id.assign(nv, -1);
    for (std::size_t v = 0; v < nv; ++v) {
        int& c = id[find(int(v))];
        if (c < 0) c = ncomp++;
        comp[v] = c;
    }
    return ncomp;
}

// The outgoing half-edges of each vertex, in counter-clockwise order (sc.pos: the place of
// each half-edge in that order). No vertex is isolated and no two have the same point, so
// every rank and isolation flag is zero.
void sort_around_vertices(BuildScratch& sc) {
    RawGraph& g = sc.g;
    const std::size_t nv = g.vpt.size();
    g.vrank.assign(nv, 0);
    g.visolated.assign(nv, 0);
    g.vout_start.assign(nv + 1, 0);
    for (const auto& h : g.he) ++g.vout_start[h.source + 1];
    for (std::size_t v = 0; v < nv; ++v) g.vout_start[v + 1] += g.vout_start[v];
    g.vout.resize(g.he.size());
    {
        std::vector<int>& fill = sc.fill;
        fill.assign(g.vout_start.begin(), g.vout_start.end() - 1);
        for (std::size_t h = 0; h < g.he.size(); ++h) g.vout[fill[g.he[h].source]++] = int(h);
    }
    std::vector<int>& pos = sc.pos;
    pos.resize(g.he.size());
    for (std::size_t v = 0; v < nv; ++v) {
        const auto b = g.vout.begin() + g.vout_start[v], e = g.vout.begin() + g.vout_start[v + 1];
        const Point& p = g.vpt[v];
        std::sort(b, e, [&](int x, int y) { return ccw_before(p, g.vpt[g.he[x].target], g.vpt[g.he[y].target]); });
        for (int i = g.vout_start[v]; i < g.vout_start[v + 1]; ++i) pos[g.vout[i]] = i;
    }
}

// The next half-edge of each: the face on the left of u -> v goes on along the edge leaving
// v just clockwise of v -> u.
void link_next(BuildScratch& sc) {
    RawGraph& g = sc.g;
    const std::vector<int>& pos = sc.pos;
    for (std::size_t h = 0; h < g.he.size(); ++h) {
        const int v = g.he[h].target;
        const int twin = int(h ^ 1);
        const int s = g.vout_start[v], n = g.vout_start[v + 1] - s;
        g.he[h].next = g.vout[s + (pos[twin] - s + n - 1) % n];
    }
}

// Cycles. In each connected piece, the outer one lies left of the most counter-clockwise
// edge leaving the piece's lexicographically smallest vertex.
void trace_cycles(BuildScratch& sc, int ncomp) {
    const RawGraph& g = sc.g;
    const std::vector<int>& comp = sc.comp;
    const std::size_t nv = g.vpt.size();
    std::vector<int>& v0 = sc.v0;
    v0.assign(std::size_t(ncomp), -1);
    for (std::size_t v = 0; v < nv; ++v) {
        int& m = v0[std::size_t(comp[v])];
        if (m < 0 || g.vpt[v] < g.vpt[m]) m = int(v);
    }
    std::vector<int>& outer_he = sc.outer_he;
    outer_he.assign(std::size_t(ncomp), -1);
    for (int c = 0; c < ncomp; ++c) {
        const int v = v0[c];
        const Point& p = g.vpt[v];
        int o = g.vout[g.vout_start[v + 1] - 1];
        for (int i = g.vout_start[v]; i < g.vout_start[v + 1]; ++i) {
            const Point& q = g.vpt[g.he[g.vout[i]].target];
            if (q.y > p.y || (q.y == p.y && q.x > p.x)) o = g.vout[i];
        }
        outer_he[c] = o;
    }
    std::vector<int>& cycle = sc.cycle;
    std::vector<int>& cycle_start = sc.cycle_start;
    std::vector<char>& cycle_outer = sc.cycle_outer;
    cycle.assign(g.he.size(), -1);
    cycle_start.clear();
    cycle_outer.clear();
    for (std::size_t h = 0; h < g.he.size(); ++h) {
        if (cycle[h] >= 0) continue;
        const int id = int(cycle_start.size());
        cycle_start.push_back(int(h));
        bool outer = false;
        int cur = int(h);
        do {
            cycle[cur] = id;
            outer |= cur == outer_he[comp[g.he[cur].source]];
            cur = g.he[cur].next;
        } while (cur != int(h));
        cycle_outer.push_back(outer);
    }
}

// Faces: one per inner cycle, plus the unbounded face. Each piece's outer cycle is a hole
// of the face holding the piece: the face below the first segment of another piece met
// by a ray going up from the piece's smallest vertex (exact predicates).
void assign_faces(BuildScratch& sc, int ncomp, std::optional<detail::SegmentGrid>& grid_store) {
    RawGraph& g = sc.g;
    const std::vector<int>& comp = sc.comp;
    const std::vector<int>& v0 = sc.v0;
    const std::vector<int>& cycle = sc.cycle;
    const std::vector<int>& cycle_start = sc.cycle_start;
    const std::vector<char>& cycle_outer = sc.cycle_outer;
    const std::size_t ns = sc.segs.size();
    const std::size_t nv = g.vpt.size();
    std::vector<int>& face_of_cycle = sc.face_of_cycle;
    face_of_cycle.assign(cycle_start.size(), -1);
    g.faces.emplace_back();
    g.faces[0].unbounded = true;
    for (std::size_t c = 0; c < cycle_start.size(); ++c)
        if (!cycle_outer[c]) {
            face_of_cycle[c] = int(g.faces.size());
            g.faces.emplace_back();
            g.faces.back().outer = cycle_start[c];
        }
    std::vector<int>& holder = sc.holder;
    holder.assign(std::size_t(ncomp), -2);  // face holding each piece
    auto holding = [&](auto&& self, int c) -> int {
        if (holder[c] != -2) return holder[c];
        // One piece, or no cycle at all (a forest: as many vertices as segments plus
        // pieces): the unbounded face is the only face.
        if (ncomp == 1 || nv == ns + std::size_t(ncomp)) return holder[c] = 0;
        bool on = false;
        const int k = lazy_grid(grid_store, sc.segs).first_above(g.vpt[v0[c]], [&](std::uint32_t i) {
            return comp[g.he[2 * i].source] != c;
        }, on);
        if (k < 0) return holder[c] = 0;
        const int below = g.he[2 * k].l2r ? 2 * k + 1 : 2 * k;  // runs right to left
        const int cyc = cycle[below];
        if (!cycle_outer[cyc]) return holder[c] = face_of_cycle[cyc];
        return holder[c] = self(self, comp[g.he[below].source]);
    };
    for (std::size_t c = 0; c < cycle_start.size(); ++c) {
        if (!cycle_outer[c]) continue;
        const int f = holding(holding, comp[g.he[cycle_start[c]].source]);
        face_of_cycle[c] = f;
        g.faces[f].inner.push_back(cycle_start[c]);
    }
    for (std::size_t h = 0; h < g.he.size(); ++h) g.he[h].face = face_of_cycle[cycle[h]];
}

}  // namespace direct

// Returns false when the drawing is not clean; `many_crossings` then tells whether at least
// a tenth of the segments cross another one, to choose the CGAL traits.
//
// With `known` (detail::induce_clean_complex), the caller vouches that the drawing is clean
// and names the vertex of each segment end: the exact check and the sort of the ends that
// finds equal points are skipped, and the vertices are numbered in the same order (first
// appearance), so the graph is the one the check and the sort would have produced.
bool build_directly(const Curves& input, BuildScratch& sc, bool& many_crossings,
                    const detail::KnownVertices* known = nullptr) {
    detail::curve_segments(input, sc.segs);
    if (sc.segs.empty()) return false;
    if (known && known->ends.size() != sc.segs.size()) return false;  // a segment left out
    std::optional<detail::SegmentGrid> grid;  // built on first use (direct::lazy_grid)
    if (!known && !direct::is_clean(sc, grid, many_crossings)) return false;
    direct::number_vertices(sc, known);
    direct::mark_open_ends(input, sc);
    const int ncomp = direct::connected_pieces(sc);
    direct::sort_around_vertices(sc);
    direct::link_next(sc);
    direct::trace_cycles(sc, ncomp);
    direct::assign_faces(sc, ncomp, grid);
    return true;
}

}  // namespace

enum class Way { Any, CgalCaching, CgalNonCaching };

// Builds a PlanarMap in steps, one function each, run in the order of `build`: the raw graph
// of segments (direct or CGAL), the ends of open curves, then the common step's eight
// steps. The steps share the thread's scratch; the last ones fill the map's tables.
struct PlanarMapBuilder {
    static MapPtr build(const Curves& curves, Way way, const detail::KnownVertices* known = nullptr);

private:
    using PointLabels = std::unordered_map<Point, Labels, PointHash>;

    static void build_raw_graph(const Curves& input, Way way, const detail::KnownVertices* known, BuildScratch& sc);
    static void collect_curve_ends(const Curves& input, BuildScratch& sc);
    static void mark_breaks(const PointLabels& point_labels, BuildScratch& sc);                     // 1
    static void walk_chains(BuildScratch& sc);                                                      // 2
    static void orient_chains(BuildScratch& sc);                                                    // 3
    static void number_vertices(const PointLabels& point_labels, BuildScratch& sc, PlanarMap& pm);  // 4
    static void number_edges(BuildScratch& sc, PlanarMap& pm);                                      // 5
    static void number_faces(BuildScratch& sc, PlanarMap& pm);                                      // 6
    static void fill_edge_records(const Curves& input, BuildScratch& sc, PlanarMap& pm);            // 6
    static void vertex_incidences(const BuildScratch& sc, PlanarMap& pm);                           // 7
    static void fill_face_records(BuildScratch& sc, PlanarMap& pm);                                 // 8
    static std::pair<int, std::vector<Side>> boundary_cycle(const BuildScratch& sc, int start);
    static std::uint64_t face_key(const std::vector<EdgeRec>& edges, const FaceRec& rec);
};

MapPtr PlanarMap::induce(const Curves& curves) { return PlanarMapBuilder::build(curves, Way::Any); }

namespace detail {
MapPtr induce_with_cgal(const Curves& curves, bool caching) {
    return PlanarMapBuilder::build(curves, caching ? Way::CgalCaching : Way::CgalNonCaching);
}
thread_local std::uint64_t t_direct = 0;
thread_local std::uint64_t t_complex = 0;
std::uint64_t direct_inductions() { return t_direct; }
std::uint64_t complex_inductions() { return t_complex; }
MapPtr induce_clean_complex(const Curves& curves, const KnownVertices& known) {
    return PlanarMapBuilder::build(curves, Way::Any, &known);
}
std::uint64_t vertex_key(const Point& p) { return hash_point(0x5645525445ULL, p); }
std::vector<Point> canonical_points(const std::vector<Point>& pts) {
    std::vector<Point> rev(pts.rbegin(), pts.rend());
    return std::lexicographical_compare(rev.begin(), rev.end(), pts.begin(), pts.end()) ? rev : pts;
}
std::uint64_t edge_key(const std::vector<Point>& points, bool reversed) {
    std::uint64_t key = 0x45444745ULL;
    if (reversed)
        for (auto it = points.rbegin(); it != points.rend(); ++it) key = hash_point(key, *it);
    else
        for (const Point& p : points) key = hash_point(key, p);
    return key;
}
std::uint64_t edge_key(const std::vector<Point>& points) {
    return edge_key(points, std::lexicographical_compare(points.rbegin(), points.rend(), points.begin(), points.end()));
}
}  // namespace detail

MapPtr PlanarMapBuilder::build(const Curves& input, Way way, const detail::KnownVertices* known) {
    auto map = std::make_shared<PlanarMap>();
    PlanarMap& pm = *map;

    PointLabels point_labels;
    for (const auto& lp : input.points) point_labels[lp.point].merge(lp.labels);

    ScratchLease lease;
    BuildScratch& sc = *lease;
    build_raw_graph(input, way, known, sc);
    collect_curve_ends(input, sc);
    mark_breaks(point_labels, sc);          // 1
    walk_chains(sc);                        // 2
    orient_chains(sc);                      // 3
    number_vertices(point_labels, sc, pm);  // 4
    number_edges(sc, pm);                   // 5
    number_faces(sc, pm);                   // 6
    fill_edge_records(input, sc, pm);       // 6
    vertex_incidences(sc, pm);              // 7
    fill_face_records(sc, pm);              // 8
    return map;
}

// The raw graph of segments: traced directly when the drawing is clean (and `way` allows
// it), else through CGAL's arrangement with the traits `way` asks for, or that suit the
// number of crossings.
void PlanarMapBuilder::build_raw_graph(const Curves& input, Way way, const detail::KnownVertices* known,
                                       BuildScratch& sc) {
    RawGraph& g = sc.g;
    g.clear();
    bool many_crossings = false;
    if (known && build_directly(input, sc, many_crossings, known)) {
        ++detail::t_direct;
        ++detail::t_complex;
    } else if (way == Way::Any && build_directly(input, sc, many_crossings)) {
        ++detail::t_direct;
    } else {
        g.clear();
        // Few crossings for the number of segments: the non-caching traits are faster.
        const bool caching = way == Way::Any ? many_crossings : way == Way::CgalCaching;
        if (caching) build_with_cgal<Caching>(input, g);
        else build_with_cgal<NonCaching>(input, g);
    }
}

// The end points of open curves: vertices whatever their degree, like labelled points
// (the direct way marked them in the graph; then sc.curve_ends stays empty).
void PlanarMapBuilder::collect_curve_ends(const Curves& input, BuildScratch& sc) {
    const RawGraph& g = sc.g;
    std::vector<Point>& ends = sc.curve_ends;
    ends.clear();
    for (const Curve& c : input.curves) {
        if (!g.vend.empty()) break;
        if (c.closed) continue;
        const Point* first = nullptr;
        const Point* last = nullptr;
        for (std::size_t i = 0; i + 1 < c.points.size(); ++i) {
            const Point& a = c.points[i];
            const Point& b = c.points[i + 1];
            if (a == b || !std::isfinite(a.x) || !std::isfinite(a.y) || !std::isfinite(b.x) || !std::isfinite(b.y))
                continue;
            if (!first) first = &a;
            last = &b;
        }
        if (first) {
            ends.push_back(*first);
            ends.push_back(*last);
        }
    }
    std::sort(ends.begin(), ends.end());
}

// 1. Break vertices: curve ends, labelled points, degree other than two, and points
//    where the set of source curves changes.
void PlanarMapBuilder::mark_breaks(const PointLabels& point_labels, BuildScratch& sc) {
    const RawGraph& g = sc.g;
    const std::size_t nv = g.vpt.size();
    const std::vector<Point>& ends = sc.curve_ends;
    auto is_end = [&](int v) {
        if (!g.vend.empty()) return g.vend[std::size_t(v)] != 0;
        return std::binary_search(ends.begin(), ends.end(), g.vpt[v]);
    };
    std::vector<char>& is_break = sc.is_break;
    is_break.assign(nv, 0);
    std::vector<std::uint32_t>& ids_a = sc.ids_a;
    std::vector<std::uint32_t>& ids_b = sc.ids_b;
    auto ids = [&](int h, std::vector<std::uint32_t>& out) {
        out.clear();
        g.for_data(h, [&](std::uint32_t d) { out.push_back(d >> 1); });
        std::sort(out.begin(), out.end());
        out.erase(std::unique(out.begin(), out.end()), out.end());
    };
    for (std::size_t v = 0; v < nv; ++v) {
        bool brk = g.visolated[v] || g.degree(int(v)) != 2 || is_end(int(v)) ||
                   (!point_labels.empty() && point_labels.count(g.vpt[v]));
        if (!brk) {
            ids(g.vout[g.vout_start[v]], ids_a);
            ids(g.vout[g.vout_start[v] + 1], ids_b);
            brk = ids_a != ids_b;
        }
        is_break[v] = brk;
    }
}

// 2. Chains: walk from every break vertex along degree-two vertices; what is left are
//    closed curves meeting nothing, which start at their smallest point (made a break).
void PlanarMapBuilder::walk_chains(BuildScratch& sc) {
    const RawGraph& g = sc.g;
    const std::size_t nv = g.vpt.size();
    const std::size_t nh = g.he.size();
    std::vector<char>& is_break = sc.is_break;
    std::vector<Chain>& chains = sc.chains;
    chains.clear();
    chains.reserve(nh / 2);
    std::vector<int>& chain_hs = sc.chain_hs;
    chain_hs.clear();
    chain_hs.reserve(nh / 2);
    std::vector<int>& he_chain = sc.he_chain;
    he_chain.assign(nh, -1);
    auto walk = [&](int start) {
        Chain ch;
        ch.hs_begin = chain_hs.size();
        int cur = start;
        for (;;) {
            chain_hs.push_back(cur);
            he_chain[cur] = he_chain[cur ^ 1] = int(chains.size());
            if (is_break[g.he[cur].target]) break;
            cur = g.he[cur].next;
        }
        ch.hs_end = chain_hs.size();
        chains.push_back(std::move(ch));
    };
    for (std::size_t v = 0; v < nv; ++v) {
        if (!is_break[v]) continue;
        for (int i = g.vout_start[v]; i < g.vout_start[v + 1]; ++i)
            if (he_chain[g.vout[i]] < 0) walk(g.vout[i]);
    }
    for (std::size_t h = 0; h < nh; h += 2) {
        if (he_chain[h] >= 0) continue;
        int start = int(h), cur = int(h);
        do {
            if (g.vpt[g.he[cur].source] < g.vpt[g.he[start].source]) start = cur;
            cur = g.he[cur].next;
        } while (cur != int(h));
        is_break[g.he[start].source] = 1;
        walk(start);
    }
}

// 3. Orient each chain like its first source curve; its polyline.
void PlanarMapBuilder::orient_chains(BuildScratch& sc) {
    const RawGraph& g = sc.g;
    std::vector<Chain>& chains = sc.chains;
    std::vector<int>& chain_hs = sc.chain_hs;
    auto by_curve = [](const EdgeSource& a, const EdgeSource& b) {
        return a.curve < b.curve || (a.curve == b.curve && a.forward > b.forward);
    };
    std::vector<std::vector<EdgeSource>>& chain_sources = sc.chain_sources;
    chain_sources.clear();
    chain_sources.resize(chains.size());
    for (std::size_t k = 0; k < chains.size(); ++k) {
        Chain& ch = chains[k];
        const auto hs_b = chain_hs.begin() + std::ptrdiff_t(ch.hs_begin);
        const auto hs_e = chain_hs.begin() + std::ptrdiff_t(ch.hs_end);
        const int h0 = *hs_b;
        const bool h0_l2r = g.he[h0].l2r;
        auto& src = chain_sources[k];
        g.for_data(h0, [&](std::uint32_t d) { src.push_back({d >> 1, ((d & 1u) != 0) == h0_l2r}); });
        std::sort(src.begin(), src.end(), by_curve);
        ch.points.reserve(ch.hs_end - ch.hs_begin + 1);
        for (auto it = hs_b; it != hs_e; ++it) ch.points.push_back(g.vpt[g.he[*it].source]);
        ch.points.push_back(g.vpt[g.he[*(hs_e - 1)].target]);
        bool flip = !src.front().forward;
        // The first curve running both ways along the chain: keep the canonical direction.
        if (src.size() > 1 && src[1].curve == src[0].curve) flip = detail::canonical_points(ch.points) != ch.points;
        if (flip) {
            std::reverse(hs_b, hs_e);
            for (auto it = hs_b; it != hs_e; ++it) *it ^= 1;
            std::reverse(ch.points.begin(), ch.points.end());
            for (auto& s : src) s.forward = !s.forward;
            std::sort(src.begin(), src.end(), by_curve);
        }
        ch.canon_reversed = std::lexicographical_compare(ch.points.rbegin(), ch.points.rend(), ch.points.begin(),
                                                         ch.points.end());
    }
}

// 4. Vertices: the break vertices, in the order of their points.
void PlanarMapBuilder::number_vertices(const PointLabels& point_labels, BuildScratch& sc, PlanarMap& pm) {
    const RawGraph& g = sc.g;
    const std::size_t nv = g.vpt.size();
    const std::vector<char>& is_break = sc.is_break;
    std::vector<int>& breaks = sc.breaks;
    breaks.clear();
    breaks.reserve(nv);
    for (std::size_t v = 0; v < nv; ++v)
        if (is_break[v]) breaks.push_back(int(v));
    std::sort(breaks.begin(), breaks.end(), [&](int a, int b) {
        if (g.vpt[a] != g.vpt[b]) return g.vpt[a] < g.vpt[b];
        return g.vrank[a] < g.vrank[b];
    });
    std::vector<int>& vid = sc.vid;
    vid.assign(nv, -1);
    for (std::size_t i = 0; i < breaks.size(); ++i) vid[breaks[i]] = int(i);
    pm.vertices_.resize(breaks.size());
    for (std::size_t i = 0; i < breaks.size(); ++i) {
        VertexRec& rec = pm.vertices_[i];
        rec.point = g.vpt[breaks[i]];
        rec.key = detail::vertex_key(rec.point);
        if (!point_labels.empty()) {
            auto it = point_labels.find(rec.point);
            if (it != point_labels.end()) rec.labels = it->second;
        }
    }
}

// 5. Edges: chains ordered by their end vertices, then by their polylines; each half-edge
//    as a side of its edge.
void PlanarMapBuilder::number_edges(BuildScratch& sc, PlanarMap& pm) {
    const RawGraph& g = sc.g;
    const std::size_t nh = g.he.size();
    std::vector<Chain>& chains = sc.chains;
    const std::vector<int>& chain_hs = sc.chain_hs;
    const std::vector<int>& vid = sc.vid;
    for (auto& ch : chains) {
        ch.source = vid[g.he[sc.hs_front(ch)].source];
        ch.target = vid[g.he[sc.hs_back(ch)].target];
    }
    std::vector<int>& order = sc.order;
    order.resize(chains.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int a, int b) {
        const Chain& x = chains[a];
        const Chain& y = chains[b];
        const auto kx = std::minmax(x.source, x.target), ky = std::minmax(y.source, y.target);
        if (kx != ky) return kx < ky;
        auto lex = [](const auto& a0, const auto& a1, const auto& b0, const auto& b1) {
            return std::lexicographical_compare(a0, a1, b0, b1);
        };
        const auto& p = x.points;
        const auto& q = y.points;
        if (!x.canon_reversed && !y.canon_reversed) return lex(p.begin(), p.end(), q.begin(), q.end());
        if (!x.canon_reversed) return lex(p.begin(), p.end(), q.rbegin(), q.rend());
        if (!y.canon_reversed) return lex(p.rbegin(), p.rend(), q.begin(), q.end());
        return lex(p.rbegin(), p.rend(), q.rbegin(), q.rend());
    });
    pm.edges_.resize(chains.size());
    std::vector<int>& eid = sc.eid;
    eid.resize(chains.size());
    for (std::size_t i = 0; i < order.size(); ++i) eid[order[i]] = int(i);
    // Each half-edge as a side: 2 * edge id, plus one when it runs against the edge.
    std::vector<int>& side_of = sc.side_of;
    side_of.resize(nh);
    for (std::size_t k = 0; k < chains.size(); ++k)
        for (std::size_t i = chains[k].hs_begin; i < chains[k].hs_end; ++i) {
            const int h = chain_hs[i];
            side_of[h] = 2 * eid[k];
            side_of[h ^ 1] = 2 * eid[k] + 1;
        }
}

// The boundary cycle through half-edge `start`, as sides of edges from its smallest side,
// with that side's number (2 * edge id, plus one against the edge).
std::pair<int, std::vector<Side>> PlanarMapBuilder::boundary_cycle(const BuildScratch& sc, int start) {
    const RawGraph& g = sc.g;
    const std::vector<char>& is_break = sc.is_break;
    const std::vector<int>& side_of = sc.side_of;
    std::vector<Side> cycle;
    cycle.reserve(8);  // most faces have a few sides: one allocation, not four
    int best = INT_MAX;
    std::size_t best_at = 0;
    int cur = start;
    do {
        if (is_break[g.he[cur].source]) {
            const int d = side_of[cur];
            if (d < best) {
                best = d;
                best_at = cycle.size();
            }
            cycle.push_back({d / 2, (d & 1) == 0});
        }
        cur = g.he[cur].next;
    } while (cur != start);
    std::rotate(cycle.begin(), cycle.begin() + std::ptrdiff_t(best_at), cycle.end());
    return std::make_pair(best, std::move(cycle));
}

// 6. Faces: boundary cycles as sides of edges, ordered by their smallest side.
void PlanarMapBuilder::number_faces(BuildScratch& sc, PlanarMap& pm) {
    const RawGraph& g = sc.g;
    const std::size_t nf = g.faces.size();
    std::vector<std::pair<int, int>>& fs = sc.fs;  // (key, raw face)
    fs.resize(nf);
    std::vector<std::vector<Side>>& outer_cycle = sc.outer_cycle;  // kept for the face records (step 8)
    outer_cycle.clear();
    outer_cycle.resize(nf);
    for (std::size_t f = 0; f < nf; ++f) {
        int key = -1;
        if (!g.faces[f].unbounded) std::tie(key, outer_cycle[f]) = boundary_cycle(sc, g.faces[f].outer);
        fs[f] = {key, int(f)};
    }
    std::sort(fs.begin(), fs.end());
    std::vector<int>& fid = sc.fid;
    fid.resize(nf);
    for (std::size_t i = 0; i < nf; ++i) fid[fs[i].second] = int(i);
    pm.faces_.resize(nf);
}

// 6, continued. Edge records: ends, faces on each side, sources and their labels, key,
// polyline (moved out of the chain).
void PlanarMapBuilder::fill_edge_records(const Curves& input, BuildScratch& sc, PlanarMap& pm) {
    const RawGraph& g = sc.g;
    std::vector<Chain>& chains = sc.chains;
    const std::vector<int>& eid = sc.eid;
    const std::vector<int>& fid = sc.fid;
    std::vector<std::vector<EdgeSource>>& chain_sources = sc.chain_sources;
    for (std::size_t k = 0; k < chains.size(); ++k) {
        Chain& ch = chains[k];
        EdgeRec& rec = pm.edges_[eid[k]];
        rec.source = ch.source;
        rec.target = ch.target;
        rec.left = fid[g.he[sc.hs_front(ch)].face];
        rec.right = fid[g.he[sc.hs_front(ch) ^ 1].face];
        rec.sources = std::move(chain_sources[k]);
        for (const auto& s : rec.sources) {
            const Curve& c = input.curves[s.curve];
            rec.labels.merge(c.labels);
            rec.left_labels.merge(s.forward ? c.left : c.right);
            rec.right_labels.merge(s.forward ? c.right : c.left);
        }
        // Key of the geometry, whatever the orientation and the numbering.
        rec.key = detail::edge_key(ch.points, ch.canon_reversed);
        rec.points = std::move(ch.points);  // the chain is not read after this
    }
}

// 7. Vertex incidences, counter-clockwise from the smallest edge id.
void PlanarMapBuilder::vertex_incidences(const BuildScratch& sc, PlanarMap& pm) {
    const RawGraph& g = sc.g;
    const std::size_t nf = g.faces.size();
    const std::vector<int>& breaks = sc.breaks;
    const std::vector<int>& side_of = sc.side_of;
    const std::vector<int>& fid = sc.fid;
    for (std::size_t i = 0; i < breaks.size(); ++i) {
        const int v = breaks[i];
        VertexRec& rec = pm.vertices_[i];
        if (g.visolated[v]) {
            for (std::size_t f = 0; f < nf; ++f)
                for (int iv : g.faces[f].isolated)
                    if (iv == v) rec.faces.push_back(fid[f]);
            continue;
        }
        const int s = g.vout_start[v], n = g.vout_start[v + 1] - s;
        rec.edges.reserve(std::size_t(n));
        rec.faces.reserve(std::size_t(n));
        int start = 0;
        for (int k = 1; k < n; ++k)
            if (side_of[g.vout[s + k]] / 2 < side_of[g.vout[s + start]] / 2) start = k;
        for (int k = 0; k < n; ++k) {
            const int out = g.vout[s + (start + k) % n];
            rec.edges.push_back(side_of[out] / 2);
            // The face on the counter-clockwise side of the edge leaving the vertex.
            const int f = fid[g.he[out].face];
            if (std::find(rec.faces.begin(), rec.faces.end(), f) == rec.faces.end()) rec.faces.push_back(f);
        }
    }
}

// 8. Face records: cycles, incidences, labels rebuilt from the side labels, key.
void PlanarMapBuilder::fill_face_records(BuildScratch& sc, PlanarMap& pm) {
    const RawGraph& g = sc.g;
    const std::size_t nf = g.faces.size();
    const std::vector<std::pair<int, int>>& fs = sc.fs;
    std::vector<std::vector<Side>>& outer_cycle = sc.outer_cycle;
    const std::vector<int>& vid = sc.vid;
    std::vector<int>& edge_seen = sc.edge_seen;
    std::vector<int>& vertex_seen = sc.vertex_seen;
    edge_seen.assign(sc.chains.size(), -1);
    vertex_seen.assign(sc.breaks.size(), -1);
    for (std::size_t i = 0; i < nf; ++i) {
        const RawGraph::RawFace& rf = g.faces[fs[i].second];
        const int f = int(i);
        FaceRec& rec = pm.faces_[i];
        rec.unbounded = rf.unbounded;
        if (rec.unbounded) pm.unbounded_ = f;
        rec.cycles.reserve(rf.inner.size() + (rf.unbounded ? 0 : 1));
        if (!rf.unbounded) rec.cycles.push_back(std::move(outer_cycle[std::size_t(fs[i].second)]));
        std::vector<std::pair<int, std::vector<Side>>> holes;
        for (int h : rf.inner) holes.push_back(boundary_cycle(sc, h));
        std::sort(holes.begin(), holes.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
        for (auto& h : holes) rec.cycles.push_back(std::move(h.second));
        std::size_t sides = 0;
        for (const auto& cyc : rec.cycles) sides += cyc.size();
        rec.edges.reserve(sides);
        rec.vertices.reserve(sides + rf.isolated.size());
        for (const auto& cyc : rec.cycles)
            for (const Side& sd : cyc) {
                const EdgeRec& er = pm.edges_[sd.edge];
                rec.labels.merge(sd.left ? er.left_labels : er.right_labels);
                if (edge_seen[sd.edge] != f) {
                    edge_seen[sd.edge] = f;
                    rec.edges.push_back(sd.edge);
                }
                const int v = sd.left ? er.source : er.target;
                if (vertex_seen[v] != f) {
                    vertex_seen[v] = f;
                    rec.vertices.push_back(v);
                }
            }
        std::vector<int> isolated;
        for (int iv : rf.isolated) isolated.push_back(vid[iv]);
        std::sort(isolated.begin(), isolated.end());
        rec.vertices.insert(rec.vertices.end(), isolated.begin(), isolated.end());
        rec.key = face_key(pm.edges_, rec);
    }
    if (pm.unbounded_ < 0) pm.unbounded_ = 0;
}

// Key of a face record: its outer ring read from its lexicographically smallest point, so
// that the same face gets the same key in any map and whatever its numbering.
// (The ring is walked in place: cycle_points would copy it first.)
std::uint64_t PlanarMapBuilder::face_key(const std::vector<EdgeRec>& edges, const FaceRec& rec) {
    std::uint64_t key = 0x46414345ULL;
    if (!rec.unbounded && !rec.cycles.empty()) {
        const std::vector<Side>& outer = rec.cycles[0];
        // Point k of side i (its polyline without its last point, in the side's direction).
        auto side_len = [&](const Side& sd) { return edges[sd.edge].points.size() - 1; };
        auto side_point = [&](const Side& sd, std::size_t k) -> const Point& {
            const std::vector<Point>& p = edges[sd.edge].points;
            return sd.left ? p[k] : p[p.size() - 1 - k];
        };
        std::size_t best_side = 0, best_k = 0;
        for (std::size_t i = 0; i < outer.size(); ++i)
            for (std::size_t k = 0, n = side_len(outer[i]); k < n; ++k)
                if (side_point(outer[i], k) < side_point(outer[best_side], best_k)) {
                    best_side = i;
                    best_k = k;
                }
        std::size_t i = best_side, k = best_k;
        for (std::size_t done = 0; done < outer.size() + 1; ++done) {
            const std::size_t n = side_len(outer[i]);
            // The first side is read from best_k, and read again up to best_k at the end.
            const std::size_t stop = (done == outer.size()) ? best_k : n;
            for (; k < stop; ++k) key = hash_point(key, side_point(outer[i], k));
            if (done == outer.size()) break;
            i = (i + 1) % outer.size();
            k = 0;
        }
    }
    return key;
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
