// Merging operators and the mask they share with the cropping partitions.
//
// A mask is the set of boundaries of the bounded faces of a planar map (or a region's
// rings). Subject curves that meet none of its segments lie in one of its faces: they are
// kept or dropped whole after one exact point location (segment_index.hpp). Of the others,
// only the stretches that meet the mask are inserted, with the pieces of the mask boundary
// they touch, into one exact planar map; the kept pieces of each curve are then joined
// again where the mask does not cut them. The mask boundaries carry
// a reserved marker label on the side of the mask's bounded faces, so each face of that
// joint map knows whether it lies inside as soon as one mask edge bounds it; the other
// faces (bounded only by subject curves) inherit the status of their neighbours, since
// crossing a subject curve does not enter or leave the mask.
#include "libtex/merge.hpp"

#include <deque>
#include <map>
#include <numeric>
#include <type_traits>

#include "geometry/exact_double.hpp"
#include "geometry/segment_index.hpp"

#include "libtex/error.hpp"
#include "libtex/parallel.hpp"

namespace tex {

namespace detail {
namespace {
thread_local bool g_exact_only = false;
thread_local std::uint64_t g_fast_crops = 0;
thread_local bool g_general_only = false;
thread_local std::uint64_t g_polyline_crops = 0;
thread_local bool g_map_only = false;
thread_local std::uint64_t g_exact_crossing_crops = 0;
thread_local std::uint64_t g_pieces_along = 0;
}  // namespace
std::uint64_t fast_crops() { return g_fast_crops; }
bool exact_crops_only() { return g_exact_only; }
ExactCropScope::ExactCropScope() : saved_(g_exact_only) { g_exact_only = true; }
ExactCropScope::~ExactCropScope() { g_exact_only = saved_; }
GeneralCropScope::GeneralCropScope() : saved_(g_general_only) { g_general_only = true; }
GeneralCropScope::~GeneralCropScope() { g_general_only = saved_; }
std::uint64_t polyline_crops() { return g_polyline_crops; }
JointMapScope::JointMapScope() : saved_(g_map_only) { g_map_only = true; }
JointMapScope::~JointMapScope() { g_map_only = saved_; }
std::uint64_t exact_crossing_crops() { return g_exact_crossing_crops; }
std::uint64_t pieces_cut_along_mask() { return g_pieces_along; }
}  // namespace detail

namespace {

LabelId inside_marker() {
    static const LabelId id = intern_label("\x01libtex-inside");
    return id;
}

Curve strip(Curve c) {
    const LabelId in = inside_marker();
    c.left.remove(in);
    c.right.remove(in);
    c.labels.remove(in);
    return c;
}

enum class Status : signed char { Unknown = -1, Out = 0, In = 1 };

// Faces of the joint map inside the mask. Curves with index >= n_subject are mask curves.
std::vector<Status> classify_faces(const PlanarMap& j, std::size_t n_subject) {
    const LabelId in = inside_marker();
    std::vector<Status> status(j.faces().size(), Status::Unknown);
    std::deque<int> queue;
    for (std::size_t f = 0; f < j.faces().size(); ++f) {
        const FaceRec& fr = j.faces()[f];
        bool has_mask = false, inside = false;
        for (const auto& cyc : fr.cycles)
            for (const Side& s : cyc) {
                const EdgeRec& e = j.edges()[s.edge];
                bool mask_edge = false;
                for (const auto& src : e.sources) mask_edge |= src.curve >= n_subject;
                if (!mask_edge) continue;
                has_mask = true;
                if ((s.left ? e.left_labels : e.right_labels).has(in)) inside = true;
            }
        if (has_mask) status[f] = inside ? Status::In : Status::Out;
        else if (fr.unbounded) status[f] = Status::Out;
        if (status[f] != Status::Unknown) queue.push_back(int(f));
    }
    // Flood across subject-only edges.
    while (!queue.empty()) {
        const int f = queue.front();
        queue.pop_front();
        for (const auto& cyc : j.faces()[f].cycles)
            for (const Side& s : cyc) {
                const EdgeRec& e = j.edges()[s.edge];
                const int g = s.left ? e.right : e.left;
                if (status[g] == Status::Unknown) {
                    status[g] = status[f];
                    queue.push_back(g);
                }
            }
    }
    return status;
}

// A subject curve's points for masking: finite, without repeated consecutive points.
std::vector<Point> clean_points(const Curve& c) {
    std::vector<Point> p;
    p.reserve(c.points.size());
    for (const Point& q : c.points) {
        if (!std::isfinite(q.x) || !std::isfinite(q.y)) continue;
        if (p.empty() || p.back() != q) p.push_back(q);
    }
    if (c.closed)
        while (p.size() > 1 && p.front() == p.back()) p.pop_back();
    return p;
}

// A stretch of consecutive segments of one subject curve that all meet the mask (near) or
// all miss it (far).
struct Run {
    std::uint32_t curve;
    std::vector<Point> pts;
    bool closed;
    bool near;
};

// Cuts each subject curve into near and far runs. A far run lies in one face of the mask,
// so one exact point location classifies it; only the near runs go, with the mask
// boundaries, into the exact planar map.
std::vector<Run> split_runs(const Curves& subject, const detail::SegmentGrid& grid, bool only_changing,
                            std::vector<char>& touched) {
    std::vector<Run> runs;
    std::vector<char> near;
    for (std::uint32_t i = 0; i < subject.curves.size(); ++i) {
        std::vector<Point> pts = clean_points(subject.curves[i]);
        const std::size_t n = pts.size();
        if (n < 2) continue;
        const bool closed = subject.curves[i].closed && n >= 3;
        // A curve whose box meets no mask segment's box is one far run, its segments unseen.
        BBox box;
        for (const Point& q : pts) box.add(q);
        if (!grid.box_meets(box, only_changing)) {
            runs.push_back({i, std::move(pts), closed, false});
            continue;
        }
        const std::size_t nseg = closed ? n : n - 1;
        detail::note_segments_searched(nseg);
        near.assign(nseg, 0);
        bool any = false, all = true;
        for (std::size_t k = 0; k < nseg; ++k) {
            near[k] = grid.touches(pts[k], pts[(k + 1) % n], only_changing, &touched);
            any |= near[k] != 0;
            all &= near[k] != 0;
        }
        if (!any || all) {
            runs.push_back({i, std::move(pts), closed, any});
            continue;
        }
        std::size_t k0 = 0;
        if (closed)
            while (near[k0] == near[(k0 + nseg - 1) % nseg]) ++k0;
        for (std::size_t s = 0; s < nseg;) {
            const std::size_t k = (k0 + s) % nseg;
            std::size_t len = 1;
            while (s + len < nseg && near[(k + len) % nseg] == near[k]) ++len;
            Run r{i, {}, false, near[k] != 0};
            r.pts.reserve(len + 1);
            for (std::size_t t = 0; t <= len; ++t) r.pts.push_back(pts[(k + t) % n]);
            runs.push_back(std::move(r));
            s += len;
        }
    }
    return runs;
}

// Joins the kept pieces of one curve that meet end to start away from the mask, so that a
// curve is only cut where it meets the mask. Pieces run in the curve's direction.
void stitch(std::vector<std::vector<Point>>& pieces, const Curve& source, const detail::SegmentGrid& grid,
            Curves& out) {
    const std::size_t n = pieces.size();
    if (n == 1) {  // the common case: one piece, kept as it is (a loop when it closes away from the mask)
        Curve c;
        c.labels = source.labels;
        c.left = source.left;
        c.right = source.right;
        c.points = std::move(pieces[0]);
        const Point p = c.points.front();
        if (c.points.size() > 2 && p == c.points.back() && !grid.touches(p, p, false)) {
            c.points.pop_back();
            c.closed = true;
        }
        out.curves.push_back(std::move(c));
        return;
    }
    std::vector<int> next(n, -1), prev(n, -1);
    {
        std::map<Point, std::vector<int>> starts, ends;
        for (std::size_t i = 0; i < n; ++i) {
            starts[pieces[i].front()].push_back(int(i));
            ends[pieces[i].back()].push_back(int(i));
        }
        for (const auto& [p, e] : ends) {
            auto it = starts.find(p);
            if (e.size() != 1 || it == starts.end() || it->second.size() != 1) continue;
            if (grid.touches(p, p, false)) continue;  // cut by the mask
            next[e[0]] = it->second[0];  // a closed curve kept whole links to itself
            prev[it->second[0]] = e[0];
        }
    }
    std::vector<char> done(n, 0);
    auto emit = [&](std::size_t first, bool cycle) {
        Curve c;
        c.labels = source.labels;
        c.left = source.left;
        c.right = source.right;
        std::size_t i = first;
        do {
            done[i] = 1;
            const auto& p = pieces[i];
            c.points.insert(c.points.end(), p.begin() + (c.points.empty() ? 0 : 1), p.end());
            if (next[i] < 0) break;
            i = std::size_t(next[i]);
        } while (i != first);
        if (cycle && c.points.size() > 2 && c.points.front() == c.points.back()) {
            c.points.pop_back();
            c.closed = true;
        }
        out.curves.push_back(std::move(c));
    };
    for (std::size_t i = 0; i < n; ++i)
        if (prev[i] < 0) emit(i, false);
    for (std::size_t i = 0; i < n; ++i)
        if (!done[i]) emit(i, true);
}

// The mask curves the exact planar map needs: every connected piece of the mask boundary
// that a near run touches. A piece no near run touches lies inside one face of that map and
// changes nothing there, unless some near run lies inside it (then the face would mix both
// sides): in that case every mask curve is used.
std::vector<char> mask_curves_needed(const Curves& mask, const detail::SegmentGrid& grid, const std::vector<Run>& runs,
                                     const std::vector<char>& touched, bool only_changing) {
    const std::size_t n = mask.curves.size();
    // KEEP modes only read the inside: boundaries with the inside on both hands (or on
    // neither) change nothing there and stay out of the exact map.
    const LabelId in = inside_marker();
    auto useful = [&](std::size_t m) {
        return !only_changing || mask.curves[m].left.has(in) != mask.curves[m].right.has(in);
    };
    std::vector<std::size_t> parent(n);
    std::iota(parent.begin(), parent.end(), std::size_t(0));
    auto find = [&](std::size_t i) {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
    };
    std::map<Point, std::size_t> at;
    for (std::size_t m = 0; m < n; ++m) {
        const auto& pts = mask.curves[m].points;
        if (pts.empty()) continue;
        for (const Point& p : {pts.front(), pts.back()}) {
            auto [it, fresh] = at.emplace(p, m);
            if (!fresh) parent[find(m)] = find(it->second);
        }
    }
    std::vector<char> comp_used(n, 0), included(n, 0);
    for (std::size_t m = 0; m < n; ++m)
        if (touched[m]) comp_used[find(m)] = 1;
    bool all = true;
    for (std::size_t m = 0; m < n; ++m) {
        included[m] = comp_used[find(m)] && useful(m);
        all &= included[m] != 0 || !useful(m);
    }
    if (all) return included;
    std::vector<detail::Seg> rest;
    for (const auto& s : grid.segments())
        if (!included[s.owner] && s.changes()) rest.push_back(s);
    if (rest.empty()) return included;
    const detail::SegmentGrid left_out(std::move(rest));
    for (const Run& r : runs)
        if (r.near && left_out.locate(r.pts.front()) != detail::SegmentGrid::Where::Out) {
            for (std::size_t m = 0; m < n; ++m) included[m] = useful(m);
            return included;
        }
    return included;
}

// A proper crossing of a subject segment with a mask segment.
struct Cross {
    double t;           // along the subject segment
    double u;           // along the mask segment
    std::uint32_t seg;  // mask segment (grid index)
    Point x;
};

// The crossings of the subject segment a -> c with the mask's segments, ordered along it,
// appended to `cs`. False when the segment meets the mask in any other way (through a mask
// vertex, along a mask segment, ending on it) or two crossings are too close to order: the
// caller then leaves it to the exact path.
bool segment_crossings(const detail::SegmentGrid& grid, const Point& a, const Point& c, std::vector<Cross>& cs) {
    const auto& msegs = grid.segments();
    const std::size_t first = cs.size();
    BBox sb;
    sb.add(a);
    sb.add(c);
    bool degenerate = false;
    grid.for_each_in(sb, [&](std::uint32_t j) {
        if (degenerate) return;
        const detail::Seg& m = msegs[j];
        if (std::max(m.a.x, m.b.x) < sb.xmin || std::min(m.a.x, m.b.x) > sb.xmax ||
            std::max(m.a.y, m.b.y) < sb.ymin || std::min(m.a.y, m.b.y) > sb.ymax)
            return;
        const int o1 = detail::orientation(m.a, m.b, a), o2 = detail::orientation(m.a, m.b, c);
        if (o1 == o2 && o1 != 0) return;
        const int o3 = detail::orientation(a, c, m.a), o4 = detail::orientation(a, c, m.b);
        if (o3 == o4 && o3 != 0) return;
        if (o1 * o2 >= 0 || o3 * o4 >= 0) {
            degenerate = true;
            return;
        }
        const Point d = c - a, e = m.b - m.a;
        const double den = cross(d, e);
        const double t = cross(m.a - a, e) / den;
        const double u = cross(m.a - a, d) / den;
        // On the mask line up to one rounding (the line may be a neighbour's outline
        // too): the point is computed in extended precision along the mask segment.
        using LD = long double;
        const LD ex = LD(m.b.x) - LD(m.a.x), ey = LD(m.b.y) - LD(m.a.y);
        const LD dx = LD(c.x) - LD(a.x), dy = LD(c.y) - LD(a.y);
        const LD lu = ((LD(m.a.x) - LD(a.x)) * dy - (LD(m.a.y) - LD(a.y)) * dx) / (dx * ey - dy * ex);
        Point x{double(LD(m.a.x) + ex * lu), double(LD(m.a.y) + ey * lu)};
        // A horizontal or vertical subject keeps its coordinate exactly (window
        // outlines, axis-aligned stripes).
        if (a.y == c.y) x.y = a.y;
        if (a.x == c.x) x.x = a.x;
        if (!(t > 0 && t < 1 && u > 0 && u < 1) || x == a || x == c || x == m.a || x == m.b) {
            degenerate = true;
            return;
        }
        cs.push_back({t, u, j, x});
    });
    if (degenerate) return false;
    std::sort(cs.begin() + std::ptrdiff_t(first), cs.end(), [](const Cross& p, const Cross& q) { return p.t < q.t; });
    for (std::size_t i = first + 1; i < cs.size(); ++i)
        if (!(cs[i].t > cs[i - 1].t) || cs[i].x == cs[i - 1].x) return false;
    return true;
}

// CROP of open polylines (each with finite, distinct consecutive points and distinct ends)
// when every contact with the mask is a proper crossing: each curve walked once, cut at its
// crossings, the pieces on the wanted side kept in the curve's order. This is what
// crop_by_crossings makes of such curves (its runs and the stitching of their pieces give
// the same maximal pieces), without its per-curve runs and tables; the crops of a cell's
// jittered lines (two-point curves) are nearly all of this kind. Returns false, leaving
// `out` alone, when a curve is not of this kind or meets the mask otherwise.
// With `movable` (src itself, which the caller gives up), the curves kept whole are moved
// out of it once the crop has succeeded; src is left as it was when it fails.
bool crop_open_polylines(const Curves& src, const detail::SegmentGrid& grid, Status wanted, Curves& out,
                         Curves* movable = nullptr) {
    std::vector<Point> sorted;
    for (const Curve& c : src.curves) {
        if (c.closed || c.points.size() < 2 || c.points.front() == c.points.back()) return false;
        for (std::size_t i = 0; i < c.points.size(); ++i) {
            const Point& p = c.points[i];
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || (i > 0 && p == c.points[i - 1])) return false;
        }
        if (c.points.size() > 3) {  // a curve through one of its points twice: stitched otherwise
            sorted = c.points;
            std::sort(sorted.begin(), sorted.end());
            if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) return false;
        }
    }
    const auto& msegs = grid.segments();
    Curves result;
    result.points = src.points;
    result.curves.reserve(src.curves.size());
    std::vector<Cross> cs;
    std::vector<Point> seen;
    std::vector<std::pair<std::size_t, std::size_t>> whole;  // (piece, curve of src) to move in
    for (const Curve& c : src.curves) {
        const auto where = grid.locate(c.points.front());
        if (where == detail::SegmentGrid::Where::On) return false;
        Status st = where == detail::SegmentGrid::Where::In ? Status::In : Status::Out;
        auto emit = [&](std::vector<Point>&& pts) {
            Curve piece;
            piece.labels = c.labels;
            piece.left = c.left;
            piece.right = c.right;
            piece.points = std::move(pts);
            result.curves.push_back(std::move(piece));
        };
        BBox box;  // a curve whose box meets no mask segment is kept or dropped whole
        for (const Point& q : c.points) box.add(q);
        if (!grid.box_meets(box, false)) {
            if (st == wanted && movable) {
                whole.push_back({result.curves.size(), std::size_t(&c - src.curves.data())});
                emit(std::vector<Point>());
            } else if (st == wanted) {
                emit(std::vector<Point>(c.points));
            }
            continue;
        }
        detail::note_segments_searched(c.points.size() - 1);
        std::vector<Point> cur;
        cur.reserve(c.points.size() + 1);  // a piece has at most the curve's points and a crossing
        cur.push_back(c.points.front());
        // The curve's ends and crossings, which must all differ: crop_by_crossings joins two
        // pieces again where a rounded crossing repeats and misses the mask.
        seen.assign({c.points.front(), c.points.back()});
        for (std::size_t k = 0; k + 1 < c.points.size(); ++k) {
            cs.clear();
            if (!segment_crossings(grid, c.points[k], c.points[k + 1], cs)) return false;
            for (const Cross& x : cs) seen.push_back(x.x);
            for (const Cross& x : cs) {
                // A boundary with the same side on both hands (a slit of the mask): there
                // the pieces may be joined again, by whether the rounded crossing still
                // touches the mask. Left to crop_by_crossings.
                if (!msegs[x.seg].changes()) return false;
                cur.push_back(x.x);
                if (st == wanted) {  // the piece goes out; the next one gets storage of its own
                    emit(std::move(cur));
                    cur = std::vector<Point>();
                    cur.reserve(c.points.size() - k + 1);
                } else {  // the piece is dropped; its storage serves the next one
                    cur.clear();
                }
                cur.push_back(x.x);
                st = st == Status::In ? Status::Out : Status::In;
            }
            cur.push_back(c.points[k + 1]);
        }
        if (st == wanted) emit(std::move(cur));
        if (seen.size() > 2) {
            std::sort(seen.begin(), seen.end());
            if (std::adjacent_find(seen.begin(), seen.end()) != seen.end()) return false;
        }
    }
    for (const auto& [piece, curve] : whole) result.curves[piece].points = std::move(movable->curves[curve].points);
    out = std::move(result);
    return true;
}

// The common case of a crop, without the exact planar map: every contact between the
// near runs and the mask is a proper crossing of two segments (decided with exact
// predicates), so each curve is cut at its crossing points, computed once in doubles and
// shared by the subject piece and the mask piece that meet there, and the inside flips at
// each crossing of a boundary that changes it. Returns false, leaving `out` alone, as
// soon as anything else happens (a curve through a mask vertex, along a mask segment,
// ending on the mask, two crossings too close to order): the exact path handles those.
bool crop_by_crossings(const Curves& src, const Curves& mask, const detail::SegmentGrid& grid,
                       const std::vector<Run>& runs, Border b, Status wanted, Curves& out, std::vector<char>& hard) {
    // With CROP alone, a curve that meets the mask in a degenerate way is left to the exact
    // path on its own (`hard`); the mask's own pieces (CROP_ADD_BOUNDARY) are cut by every
    // curve, so there any degeneracy sends the whole crop to the exact path.
    const bool per_curve = b == Border::CROP;
    hard.assign(src.curves.size(), 0);
    const auto& msegs = grid.segments();
    // Crossings of each near run, segment by segment, and of each mask segment.
    std::vector<std::vector<std::vector<Cross>>> run_cross(runs.size());
    std::vector<std::vector<std::pair<double, Point>>> on_mask(msegs.size());
    for (std::size_t r = 0; r < runs.size(); ++r) {
        if (!runs[r].near) continue;
        const auto& pts = runs[r].pts;
        const std::size_t n = pts.size();
        const std::size_t nseg = runs[r].closed ? n : n - 1;
        auto& per_seg = run_cross[r];
        per_seg.resize(nseg);
        for (std::size_t k = 0; k < nseg; ++k) {
            if (!segment_crossings(grid, pts[k], pts[(k + 1) % n], per_seg[k])) {
                if (!per_curve) return false;
                hard[runs[r].curve] = 1;
                break;
            }
        }
    }
    if (!per_curve)
        for (std::size_t r = 0; r < runs.size(); ++r)
            for (const auto& cs : run_cross[r])
                for (const Cross& x : cs) on_mask[x.seg].push_back({x.u, x.x});
    for (auto& v : on_mask) {
        std::sort(v.begin(), v.end(), [](const auto& p, const auto& q) { return p.first < q.first; });
        for (std::size_t i = 1; i < v.size(); ++i)
            if (!(v[i].first > v[i - 1].first) || v[i].second == v[i - 1].second) return false;
    }
    // The subject's kept pieces, run by run, in the curve's direction.
    std::vector<std::vector<std::vector<Point>>> pieces(src.curves.size());
    for (std::size_t r = 0; r < runs.size(); ++r) {
        const Run& run = runs[r];
        if (hard[run.curve]) continue;
        const auto where = grid.locate(run.pts.front());
        if (where == detail::SegmentGrid::Where::On) {
            if (!per_curve) return false;
            hard[run.curve] = 1;
            pieces[run.curve].clear();
            continue;
        }
        Status st = where == detail::SegmentGrid::Where::In ? Status::In : Status::Out;
        auto& kept = pieces[run.curve];
        if (!run.near) {
            if (st != wanted) continue;
            std::vector<Point> p = run.pts;
            if (run.closed) p.push_back(p.front());
            kept.push_back(std::move(p));
            continue;
        }
        const std::size_t n = run.pts.size();
        std::vector<Point> cur{run.pts.front()};
        for (std::size_t k = 0; k < run_cross[r].size(); ++k) {
            for (const Cross& x : run_cross[r][k]) {
                cur.push_back(x.x);
                if (st == wanted) kept.push_back(std::move(cur));
                cur = {x.x};
                if (msegs[x.seg].changes()) st = st == Status::In ? Status::Out : Status::In;
            }
            cur.push_back(run.pts[(k + 1) % n]);
        }
        if (st == wanted) kept.push_back(std::move(cur));
    }
    const LabelId in = inside_marker();
    Curves result;
    result.points = src.points;
    result.curves.reserve(src.curves.size() + (b == Border::CROP_ADD_BOUNDARY ? 2 * msegs.size() : 0));
    for (std::size_t i = 0; i < src.curves.size(); ++i)
        if (!pieces[i].empty() && !hard[i]) stitch(pieces[i], src.curves[i], grid, result);
    if (b == Border::CROP_ADD_BOUNDARY) {
        // The mask's bounded boundaries, cut where the subject crosses them. Segments of one
        // mask curve are consecutive in the grid, in the curve's order.
        std::size_t j = 0;
        for (std::uint32_t m = 0; m < mask.curves.size(); ++m) {
            const Curve& mc = mask.curves[m];
            const std::size_t first = j;
            while (j < msegs.size() && msegs[j].owner == m) ++j;
            if (!(mc.left.has(in) || mc.right.has(in)) || first == j) continue;
            std::vector<std::vector<Point>> parts;
            std::vector<Point> cur{msegs[first].a};
            for (std::size_t k = first; k < j; ++k) {
                if (msegs[k].a != cur.back()) {  // a point left out of the mask curve
                    parts.push_back(std::move(cur));
                    cur = {msegs[k].a};
                }
                for (const auto& [u, x] : on_mask[k]) {
                    cur.push_back(x);
                    parts.push_back(std::move(cur));
                    cur = {x};
                }
                cur.push_back(msegs[k].b);
            }
            parts.push_back(std::move(cur));
            Curve base = strip(mc);
            base.points.clear();
            const bool closed = mc.closed && msegs[j - 1].b == msegs[first].a;
            if (closed && parts.size() == 1) {
                base.points = std::move(parts[0]);
                base.points.pop_back();
                base.closed = true;
                result.curves.push_back(std::move(base));
                continue;
            }
            base.closed = false;
            if (closed) {  // the last part runs on into the first
                parts.front().insert(parts.front().begin(), parts.back().begin(), parts.back().end() - 1);
                parts.pop_back();
            }
            for (auto& p : parts) {
                Curve c = base;
                c.points = std::move(p);
                result.curves.push_back(std::move(c));
            }
        }
    }
    out = std::move(result);
    return true;
}

// ---- The steps of mask_core

Curves mask_core(const Curves& subject, const Curves& mask, MaskSide side, Border b, Curves* movable = nullptr);

// The mask's segments, each knowing on which of its sides the mask's inside lies.
std::vector<detail::Seg> inside_marked_segments(const Curves& mask, LabelId in) {
    std::vector<detail::Seg> mask_segs = detail::curve_segments(mask);
    for (auto& sg : mask_segs) {
        const Curve& mc = mask.curves[sg.owner];
        sg.in_left = mc.left.has(in);
        sg.in_right = mc.right.has(in);
    }
    return mask_segs;
}

// CROP of open polylines by their crossings with the mask alone (counted); false when that
// cannot decide.
bool crop_polylines_fast(const Curves& subject, const detail::SegmentGrid& grid, Status wanted, Curves& fast,
                         Curves* movable) {
    if (!crop_open_polylines(subject, grid, wanted, fast, movable)) return false;
    ++detail::g_fast_crops;
    ++detail::g_polyline_crops;
    return true;
}

// CROP by the crossings with the mask (counted), the curves that meet the mask degenerately
// cropped on the exact path; false when the crossings cannot decide.
bool crop_by_crossings_fast(const Curves& src, const Curves& mask, const detail::SegmentGrid& grid,
                            const std::vector<Run>& runs, MaskSide side, Border b, Status wanted, Curves& fast) {
    std::vector<char> hard;
    if (!crop_by_crossings(src, mask, grid, runs, b, wanted, fast, hard)) return false;
    ++detail::g_fast_crops;
    Curves rest;  // the curves that meet the mask degenerately: exact path
    for (std::size_t i = 0; i < src.curves.size(); ++i)
        if (hard[i]) rest.curves.push_back(src.curves[i]);
    if (!rest.curves.empty()) {
        detail::ExactCropScope exact;
        Curves cut = mask_core(rest, mask, side, b);
        for (auto& c : cut.curves) fast.curves.push_back(std::move(c));
    }
    return true;
}

// Where the subject's runs lie: a far run located at once by one point; the near runs, with
// the mask curves they need, in one exact planar map whose faces are classified.
struct JointMap {
    std::vector<Status> run_status;        // of the far runs (Unknown for the near ones)
    Curves joint;                          // the near runs, then the mask curves included
    std::vector<std::uint32_t> joint_run;  // the run of each subject curve of `joint`
    std::size_t n_subject = 0;             // curves of `joint` from the subject
    MapPtr jm;                             // none without near runs
    std::vector<Status> status;            // of jm's faces
};

// Locates the runs of `src` against the mask.
JointMap joint_map(const Curves& src, const Curves& mask, const detail::SegmentGrid& grid, const std::vector<Run>& runs,
                   const std::vector<char>& included, const std::vector<char>* to_map = nullptr) {
    JointMap j;
    j.run_status.assign(runs.size(), Status::Unknown);
    for (std::uint32_t r = 0; r < runs.size(); ++r) {
        if (!runs[r].near) {
            j.run_status[r] =
                grid.locate(runs[r].pts.front()) == detail::SegmentGrid::Where::In ? Status::In : Status::Out;
            continue;
        }
        if (to_map && !(*to_map)[r]) continue;  // cut without the map
        const Curve& c = src.curves[runs[r].curve];
        Curve jc;
        jc.points = runs[r].pts;
        jc.closed = runs[r].closed;
        jc.labels = c.labels;
        jc.left = c.left;
        jc.right = c.right;
        j.joint.curves.push_back(std::move(jc));
        j.joint_run.push_back(r);
    }
    j.n_subject = j.joint.curves.size();
    if (j.n_subject > 0) {
        for (std::size_t m = 0; m < mask.curves.size(); ++m)
            if (included[m]) j.joint.curves.push_back(mask.curves[m]);
        j.jm = PlanarMap::induce(j.joint);
        j.status = classify_faces(*j.jm, j.n_subject);
    }
    return j;
}

// KEEP modes: whole edges, kept by the status of all their pieces (KEEP_INSIDE) or of any
// one (KEEP_OUTSIDE); a piece lying on the mask boundary counts for both sides.
struct KeepVotes {
    std::vector<char> any, all, seen;
    explicit KeepVotes(std::size_t n) : any(n, 0), all(n, 1), seen(n, 0) {}
    void note(std::uint32_t curve, bool ok) {
        seen[curve] = 1;
        any[curve] |= ok;
        all[curve] &= ok;
    }
    void forget(std::uint32_t curve) {
        seen[curve] = any[curve] = 0;
        all[curve] = 1;
    }
    bool keep(std::size_t curve, Border b) const { return b == Border::KEEP_INSIDE ? (seen[curve] && all[curve]) : any[curve]; }
};

// The votes of the pieces of `runs` (those the joint map `j` was made of).
void vote_from_joint_map(const std::vector<Run>& runs, const JointMap& j, Status wanted, KeepVotes& v) {
    for (std::uint32_t r = 0; r < runs.size(); ++r)
        if (!runs[r].near && j.run_status[r] != Status::Unknown) v.note(runs[r].curve, j.run_status[r] == wanted);
    if (j.jm)
        for (const EdgeRec& e : j.jm->edges()) {
            bool on_mask = false;
            for (const auto& s : e.sources) on_mask |= s.curve >= j.n_subject;
            const bool ok = on_mask ? (j.status[e.left] == wanted || j.status[e.right] == wanted)
                                    : j.status[e.left] == wanted;
            for (const auto& s : e.sources)
                if (s.curve < j.n_subject) v.note(runs[j.joint_run[s.curve]].curve, ok);
        }
}

// KEEP modes without the exact planar map: a run is located by its first point and its
// status flips at each proper crossing of a boundary across which the inside changes
// (exact predicates), so every piece votes. A curve with any other contact with the
// mask (through a mask vertex, along a segment, ending on it, crossings too close to
// order) is marked `hard` and left to the joint map; its votes so far are forgotten.
void keep_by_crossings(const detail::SegmentGrid& grid, const std::vector<Run>& runs, Status wanted, KeepVotes& v,
                       std::vector<char>& hard) {
    const auto& msegs = grid.segments();
    std::vector<Cross> cs;
    for (const Run& run : runs) {
        if (hard[run.curve]) continue;
        const auto where = grid.locate(run.pts.front());
        if (where == detail::SegmentGrid::Where::On) {
            hard[run.curve] = 1;
            v.forget(run.curve);
            continue;
        }
        Status st = where == detail::SegmentGrid::Where::In ? Status::In : Status::Out;
        if (run.near) {
            const std::size_t n = run.pts.size(), nseg = run.closed ? n : n - 1;
            bool plain = true;
            for (std::size_t k = 0; plain && k < nseg; ++k) {
                cs.clear();
                plain = segment_crossings(grid, run.pts[k], run.pts[(k + 1) % n], cs);
                for (const Cross& x : cs)
                    if (plain && msegs[x.seg].changes()) {
                        v.note(run.curve, st == wanted);
                        st = st == Status::In ? Status::Out : Status::In;
                    }
            }
            if (!plain) {
                hard[run.curve] = 1;
                v.forget(run.curve);
                continue;
            }
        }
        v.note(run.curve, st == wanted);
    }
}

// KEEP modes: each whole edge kept by the votes of its pieces, decided by the crossings
// where they can (keep_by_crossings), by the joint map of the other curves' runs alone.
void keep_whole_edges(const Curves& src, const Curves& mask, const detail::SegmentGrid& grid,
                      const std::vector<Run>& runs, Border b, Status wanted, Curves& out) {
    KeepVotes votes(src.curves.size());
    std::vector<char> hard(src.curves.size(), detail::exact_crops_only() ? 1 : 0);
    if (!detail::exact_crops_only()) keep_by_crossings(grid, runs, wanted, votes, hard);
    std::vector<Run> hard_runs;
    for (const Run& r : runs)
        if (hard[r.curve]) hard_runs.push_back(r);
    if (!hard_runs.empty()) {
        std::vector<char> touched(mask.curves.size(), 0);
        for (const Run& r : hard_runs)
            if (r.near) {
                const std::size_t n = r.pts.size(), nseg = r.closed ? n : n - 1;
                for (std::size_t k = 0; k < nseg; ++k) grid.touches(r.pts[k], r.pts[(k + 1) % n], true, &touched);
            }
        const std::vector<char> included = mask_curves_needed(mask, grid, hard_runs, touched, true);
        vote_from_joint_map(hard_runs, joint_map(src, mask, grid, hard_runs, included), wanted, votes);
    }
    for (std::size_t i = 0; i < src.curves.size(); ++i)
        if (votes.keep(i, b)) out.curves.push_back(src.curves[i]);
}

// The kept pieces of each curve, per curve and in its direction.
using CurvePieces = std::vector<std::vector<std::vector<Point>>>;

// The far runs kept, as pieces of their curves (a closed run closed by its first point).
void add_far_pieces(const std::vector<Run>& runs, const JointMap& j, Status wanted, CurvePieces& pieces) {
    for (std::uint32_t r = 0; r < runs.size(); ++r)
        if (!runs[r].near && j.run_status[r] == wanted) {
            std::vector<Point> p = runs[r].pts;
            if (runs[r].closed) p.push_back(p.front());
            pieces[runs[r].curve].push_back(std::move(p));
        }
}

// A kept edge of the joint map as a curve with the labels of the piece's own side: the
// subject's for a piece of it (lying on the mask or not), the mask's for a piece of the
// mask's boundary alone.
Curve joint_edge_piece(const JointMap& j, std::size_t ei, bool on_subject) {
    const EdgeRec& e = j.jm->edges()[ei];
    Curve c = j.jm->edge_curve(int(ei));
    c.labels = Labels{};
    c.left = Labels{};
    c.right = Labels{};
    for (const auto& src_ref : e.sources) {
        if ((src_ref.curve < j.n_subject) != on_subject) continue;
        const Curve& from = j.joint.curves[src_ref.curve];
        c.labels.merge(from.labels);
        c.left.merge(src_ref.forward ? from.left : from.right);
        c.right.merge(src_ref.forward ? from.right : from.left);
    }
    return strip(std::move(c));
}

// The kept edges of the joint map: an edge of one subject curve alone as a piece of that
// curve, the others (on the mask or shared by several curves) as loose curves.
void add_joint_pieces(const std::vector<Run>& runs, const JointMap& j, Border b, Status wanted, LabelId in,
                      CurvePieces& pieces, Curves& loose) {
    for (std::size_t ei = 0; ei < j.jm->edges().size(); ++ei) {
        const EdgeRec& e = j.jm->edges()[ei];
        bool on_mask = false, on_subject = false, mask_bounded = false;
        for (const auto& s : e.sources) {
            if (s.curve >= j.n_subject) {
                on_mask = true;
                const Curve& mc = j.joint.curves[s.curve];
                mask_bounded |= mc.left.has(in) || mc.right.has(in);
            } else {
                on_subject = true;
            }
        }
        bool keep = false;
        if (on_subject)
            keep = on_mask ? (j.status[e.left] == wanted || j.status[e.right] == wanted) : j.status[e.left] == wanted;
        if (keep && !on_mask && e.sources.size() == 1) {
            std::vector<Point> p = e.points;
            if (!e.sources[0].forward) std::reverse(p.begin(), p.end());
            pieces[runs[j.joint_run[e.sources[0].curve]].curve].push_back(std::move(p));
            continue;
        }
        if (!keep && on_mask && b == Border::CROP_ADD_BOUNDARY) keep = mask_bounded;
        if (!keep) continue;
        loose.curves.push_back(joint_edge_piece(j, ei, on_subject));
    }
}

// CROP: the kept pieces of each curve, in its direction, then joined where the mask
// does not cut them; the loose pieces and (CROP_ADD_BOUNDARY) the mask's boundaries after.
void crop_pieces(const Curves& src, const Curves& mask, const detail::SegmentGrid& grid, const std::vector<Run>& runs,
                 const std::vector<char>& included, const JointMap& j, Border b, Status wanted, LabelId in,
                 Curves& out, CurvePieces* cut = nullptr) {
    CurvePieces pieces(src.curves.size());
    Curves loose;  // pieces on the mask or shared by several curves
    add_far_pieces(runs, j, wanted, pieces);
    if (cut)  // the near runs cut without the map (exact_crossing_pieces)
        for (std::size_t i = 0; i < pieces.size(); ++i)
            for (auto& p : (*cut)[i]) pieces[i].push_back(std::move(p));
    if (j.jm) add_joint_pieces(runs, j, b, wanted, in, pieces, loose);
    if (j.jm && b == Border::CROP_ADD_BOUNDARY)  // the boundaries that met no subject curve
        for (std::size_t m = 0; m < mask.curves.size(); ++m)
            if (!included[m] && (mask.curves[m].left.has(in) || mask.curves[m].right.has(in)))
                loose.curves.push_back(strip(mask.curves[m]));
    for (std::size_t i = 0; i < src.curves.size(); ++i)
        if (!pieces[i].empty()) stitch(pieces[i], src.curves[i], grid, out);
    for (auto& c : loose.curves) out.curves.push_back(std::move(c));
    if (!j.jm && b == Border::CROP_ADD_BOUNDARY)
        for (const Curve& mc : mask.curves)
            if (mc.left.has(in) || mc.right.has(in)) out.curves.push_back(strip(mc));
}

// The near runs of a CROP cut at their exact crossings, without the joint map: what the
// map gives for every curve whose near runs meet the mask and each other only simply.
// Simple contacts are a proper crossing of a mask segment or of a near run (this one
// included), at an exact point the map would round to the nearest doubles
// (detail::exact_double); a segment lying along the mask from end to end (its pieces, kept
// whatever the side, come after the curves as the map's edges on the mask do); an inner
// point of the run inside a mask segment, where it touches, crosses, joins or leaves the
// mask; an end of the curve on the mask; an end of a near run inside another near run's
// segment, or shared with another run's end. A run is cut at those points (in their exact
// order along it, each rounded as the map rounds its vertices), and each piece off the mask
// keeps the side of one of the run's own points located exactly (or of the point after it
// leaves the mask, or before it joins it), turned over at each crossing of a boundary
// across which the inside changes. A curve's kept pieces come after its far pieces in the
// order of the map's edges: by their end vertices (by point, then by exact point), then by
// their points read from the smaller end. Any other contact (a run through a mask vertex,
// an overlap of part of a segment, two cuts at one exact point, a closed near run) leaves
// the curve to the joint map, with every curve whose near runs touch its own, so that the
// map's cuts are all there; and all of them when a piece along the mask was cut here.
struct ExactPieces {
    std::vector<char> to_map;  // per run: a near run left to the joint map
    CurvePieces pieces;        // per curve: the kept pieces of its near runs cut here
    Curves along;              // the pieces along the mask, in the map's order (no run left to the map)
    bool any = false;          // some curve was cut here
};

ExactPieces exact_crossing_pieces(const Curves& src, const detail::SegmentGrid& grid, const std::vector<Run>& runs,
                                  Status wanted) {
    using FT = mpq_class;
    struct Cut {
        FT key;      // exact position along the segment (growing in its direction)
        Point p;     // rounded
        int id;      // the crossing (its exact point) when p is rounded, else -1
        bool flip;   // a crossing of a boundary across which the inside changes
    };
    struct NearSeg {
        std::uint32_t run, k;
        std::vector<Cut> cuts;
        // Lying along the mask: the collinear mask segments and the ends of theirs strictly
        // inside this one, by key; the covered length is checked to be all of it.
        std::vector<std::uint32_t> along;
        std::vector<std::pair<double, Point>> mask_points;
        // Mask segments (not collinear) through the segment's first and last points.
        std::vector<std::uint32_t> at_a, at_b;
    };
    ExactPieces res;
    res.to_map.assign(runs.size(), 0);
    std::vector<std::uint32_t> first_run(src.curves.size(), UINT32_MAX), last_run(src.curves.size(), 0);
    for (std::uint32_t r = 0; r < runs.size(); ++r) {
        first_run[runs[r].curve] = std::min(first_run[runs[r].curve], r);
        last_run[runs[r].curve] = std::max(last_run[runs[r].curve], r);
    }
    std::vector<char> hard(runs.size(), 0);  // a contact the cut cannot follow
    std::vector<NearSeg> near;
    std::vector<detail::Seg> segs;
    std::vector<std::uint32_t> seg0(runs.size(), 0);  // the run's first segment in `near`
    for (std::uint32_t r = 0; r < runs.size(); ++r) {
        if (!runs[r].near) continue;
        if (runs[r].closed || src.curves[runs[r].curve].closed) hard[r] = 1;
        seg0[r] = std::uint32_t(near.size());
        const auto& pts = runs[r].pts;
        for (std::uint32_t k = 0; k + 1 < pts.size(); ++k) {
            near.push_back({r, k, {}, {}, {}, {}, {}});
            detail::Seg sg;
            sg.a = pts[k];
            sg.b = pts[k + 1];
            sg.owner = std::uint32_t(near.size() - 1);
            segs.push_back(sg);
        }
    }
    if (near.empty()) return res;
    // The exact points of the rounded crossings.
    std::vector<std::pair<FT, FT>> exact;
    // Position along a -> b of a point (x, y) on its line: the coordinate that changes more
    // (doubles or exact numbers alike).
    auto along = [](const Point& a, const Point& b, const auto& x, const auto& y) {
        using T = std::decay_t<decltype(x)>;
        const double dx = b.x - a.x, dy = b.y - a.y;
        if (std::abs(dx) >= std::abs(dy)) return dx > 0 ? T(x) : T(-x);
        return dy > 0 ? T(y) : T(-y);
    };
    auto along_key = [&](const Point& a, const Point& b, const Point& q) { return along(a, b, q.x, q.y); };
    auto crossing = [&](const Point& a, const Point& b, const Point& c, const Point& d, bool flip_ab,
                        std::vector<Cut>& on_ab, std::vector<Cut>* on_cd) {
        const FT ax(a.x), ay(a.y), bx(b.x), by(b.y), cx(c.x), cy(c.y), dx(d.x), dy(d.y);
        const FT den = (bx - ax) * (dy - cy) - (by - ay) * (dx - cx);
        const FT num = (cx - ax) * (dy - cy) - (cy - ay) * (dx - cx);
        const FT t = num / den;
        const FT x = ax + (bx - ax) * t, y = ay + (by - ay) * t;
        const Point p{detail::exact_double(x), detail::exact_double(y)};
        int id = -1;
        if (!(FT(p.x) == x && FT(p.y) == y)) {
            id = int(exact.size());
            exact.push_back({x, y});
        }
        on_ab.push_back({along(a, b, x, y), p, id, flip_ab});
        if (on_cd) on_cd->push_back({along(c, d, x, y), p, id, false});
    };
    auto at_point = [&](const Point& a, const Point& b, const Point& q) {
        return Cut{along(a, b, FT(q.x), FT(q.y)), q, -1, false};
    };
    const auto& msegs = grid.segments();
    // The mask.
    for (NearSeg& ns : near) {
        const Run& run = runs[ns.run];
        if (hard[ns.run]) continue;
        const Point a = run.pts[ns.k], b = run.pts[ns.k + 1];
        BBox sb;
        sb.add(a);
        sb.add(b);
        bool ok = true;
        grid.for_each_in(sb, [&](std::uint32_t j) {
            if (!ok) return;
            const detail::Seg& m = msegs[j];
            if (std::max(m.a.x, m.b.x) < sb.xmin || std::min(m.a.x, m.b.x) > sb.xmax ||
                std::max(m.a.y, m.b.y) < sb.ymin || std::min(m.a.y, m.b.y) > sb.ymax)
                return;
            if (!detail::segments_touch(a, b, m.a, m.b)) return;
            const int o1 = detail::orientation(m.a, m.b, a), o2 = detail::orientation(m.a, m.b, b);
            const int o3 = detail::orientation(a, b, m.a), o4 = detail::orientation(a, b, m.b);
            if (o1 * o2 < 0 && o3 * o4 < 0) {
                crossing(a, b, m.a, m.b, m.changes(), ns.cuts, nullptr);
            } else if (o1 == 0 && o2 == 0) {
                // Along m: the part they share must have a length; m's ends inside are points.
                const double ka = along_key(a, b, a), kb = along_key(a, b, b);
                const double k1 = along_key(a, b, m.a), k2 = along_key(a, b, m.b);
                if (!(std::min(kb, std::max(k1, k2)) > std::max(ka, std::min(k1, k2)))) {
                    ok = false;  // an end against an end
                    return;
                }
                ns.along.push_back(j);
                for (const Point& q : {m.a, m.b}) {
                    const double kq = along_key(a, b, q);
                    if (kq > ka && kq < kb) ns.mask_points.push_back({kq, q});
                }
            } else if (o1 == 0) {
                ns.at_a.push_back(j);  // a on m, the segment leaving m's line
            } else if (o2 == 0) {
                ns.at_b.push_back(j);
            } else {
                ok = false;  // m's end inside the segment, m leaving its line: a mask vertex
            }
        });
        if (!ok) {
            hard[ns.run] = 1;
            continue;
        }
        if (!ns.along.empty()) {
            // All of the segment along the mask: the covering segments' ends inside it each
            // shared by two of them, so that the cover has no gap.
            std::sort(ns.mask_points.begin(), ns.mask_points.end(),
                      [](const auto& x, const auto& y) { return x.first < y.first; });
            double covered_lo = INFINITY, covered_hi = -INFINITY;
            const double ka = along_key(a, b, a), kb = along_key(a, b, b);
            for (std::uint32_t j : ns.along) {
                const double k1 = along_key(a, b, msegs[j].a), k2 = along_key(a, b, msegs[j].b);
                covered_lo = std::min(covered_lo, std::min(k1, k2));
                covered_hi = std::max(covered_hi, std::max(k1, k2));
                if (!msegs[j].changes()) hard[ns.run] = 1;  // a slit: kept by the side
            }
            if (!(covered_lo <= ka && covered_hi >= kb) || !ns.cuts.empty()) hard[ns.run] = 1;
            for (std::size_t i = 0; i < ns.mask_points.size(); ++i) {
                // Each inner end twice (two collinear mask segments meet there), no more.
                const bool twice = (i + 1 < ns.mask_points.size() && ns.mask_points[i + 1].second == ns.mask_points[i].second) ||
                                   (i > 0 && ns.mask_points[i - 1].second == ns.mask_points[i].second);
                const bool thrice = i + 2 < ns.mask_points.size() && ns.mask_points[i + 2].second == ns.mask_points[i].second;
                if (!twice || thrice) hard[ns.run] = 1;
            }
            ns.mask_points.erase(std::unique(ns.mask_points.begin(), ns.mask_points.end(),
                                             [](const auto& x, const auto& y) { return x.second == y.second; }),
                                 ns.mask_points.end());
        }
    }
    // The near runs among themselves; runs that touch go to the map together, or not at all.
    std::vector<std::uint32_t> group(runs.size());
    std::iota(group.begin(), group.end(), 0u);
    auto find = [&](std::uint32_t x) {
        while (group[x] != x) x = group[x] = group[group[x]];
        return x;
    };
    auto unite = [&](std::uint32_t x, std::uint32_t y) { group[find(x)] = find(y); };
    for (std::uint32_t r = 0; r < runs.size(); ++r)
        if (runs[r].near && first_run[runs[r].curve] != r) unite(r, first_run[runs[r].curve]);
    const detail::SegmentGrid index(segs);
    auto run_end = [&](std::uint32_t r, std::uint32_t k, const Point& q) {
        const auto& pts = runs[r].pts;
        return (k == 0 && q == pts.front()) || (k + 2 == pts.size() && q == pts.back());
    };
    for (std::uint32_t g = 0; g < near.size(); ++g) {
        const Point a = segs[g].a, b = segs[g].b;
        BBox sb;
        sb.add(a);
        sb.add(b);
        index.for_each_in(sb, [&](std::uint32_t h) {
            if (h <= g) return;
            const Point c = segs[h].a, d = segs[h].b;
            const NearSeg &s = near[g], &t = near[h];
            if (s.run == t.run && h == g + 1) {
                // Neighbours along the run share b = c: they may not fold back onto each other.
                if (detail::orientation(a, b, d) == 0 && dot(a - b, d - b) > 0) hard[s.run] = 1;
                return;
            }
            if (!detail::segments_touch(a, b, c, d)) return;
            unite(s.run, t.run);
            const int o1 = detail::orientation(a, b, c), o2 = detail::orientation(a, b, d);
            const int o3 = detail::orientation(c, d, a), o4 = detail::orientation(c, d, b);
            if (o1 * o2 < 0 && o3 * o4 < 0) {
                crossing(a, b, c, d, false, near[g].cuts, &near[h].cuts);
                return;
            }
            if (o1 == 0 && o2 == 0) {  // on one line
                hard[s.run] = 1;
                return;
            }
            // One point in common, an end of one of them at least.
            if (a == c || a == d || b == c || b == d) {
                const Point q = (a == c || a == d) ? a : b;
                if (!run_end(s.run, s.k, q) || !run_end(t.run, t.k, q)) hard[s.run] = 1;
                return;
            }
            if (o1 == 0 && run_end(t.run, t.k, c)) near[g].cuts.push_back(at_point(a, b, c));
            else if (o2 == 0 && run_end(t.run, t.k, d)) near[g].cuts.push_back(at_point(a, b, d));
            else if (o3 == 0 && run_end(s.run, s.k, a)) near[h].cuts.push_back(at_point(c, d, a));
            else if (o4 == 0 && run_end(s.run, s.k, b)) near[h].cuts.push_back(at_point(c, d, b));
            else hard[s.run] = 1;
        });
    }
    for (NearSeg& ns : near) {
        if (!ns.along.empty() && !ns.cuts.empty()) hard[ns.run] = 1;  // a run across or ending on a stretch along the mask
        std::sort(ns.cuts.begin(), ns.cuts.end(), [](const Cut& x, const Cut& y) { return x.key < y.key; });
        for (std::size_t i = 1; i < ns.cuts.size(); ++i)
            if (!(ns.cuts[i - 1].key < ns.cuts[i].key)) hard[ns.run] = 1;  // two cuts at one point
    }
    // The pieces of each run, in order. A piece's ends are the map's vertices: a point of
    // the run (a double) or a rounded crossing (known by its exact point).
    struct End {
        Point p;
        int id;  // the crossing, -1 for a double
    };
    struct Piece {
        std::uint32_t curve, run;
        std::vector<Point> pts;
        End front, back;
        bool on;          // along the mask
        std::size_t chain;  // the stretch off the mask it belongs to
        bool parity;      // boundaries crossed since the chain's start
    };
    std::vector<Piece> all;
    std::vector<int> chain_status;  // -1 unknown, else the status at the chain's start (0 out, 1 in)
    auto side_status = [&](const detail::Seg& m, const Point& q) -> int {  // q off m's line
        const int o = detail::orientation(m.a, m.b, q);
        return (o > 0 ? m.in_left : m.in_right) ? 1 : 0;
    };
    for (std::uint32_t r = 0; r < runs.size(); ++r) {
        const Run& run = runs[r];
        if (!run.near || hard[r]) continue;
        const auto& pts = run.pts;
        const std::size_t n = pts.size();
        const NearSeg* sg = near.data() + seg0[r];
        const std::size_t begin = all.size();
        bool bad = false;
        std::vector<Point> cur{pts.front()};
        End from{pts.front(), -1};
        bool on = sg[0].along.size() > 0, parity = false;
        chain_status.push_back(-1);
        std::size_t chain = chain_status.size() - 1;
        auto finish = [&](const End& to) {
            all.push_back({run.curve, r, std::move(cur), from, to, on, chain, parity});
            cur = {to.p};
            from = to;
        };
        auto know = [&](int status_here) {  // the status just here, off the mask
            const int at_start = status_here ^ int(parity);
            if (chain_status[chain] >= 0 && chain_status[chain] != at_start) bad = true;
            chain_status[chain] = at_start;
        };
        // A point of the run off the mask, located (once a chain).
        auto locate_here = [&](const Point& q) {
            if (chain_status[chain] >= 0) return;
            const auto w = grid.locate(q);
            if (w == detail::SegmentGrid::Where::On) bad = true;
            else know(w == detail::SegmentGrid::Where::In ? 1 : 0);
        };
        if (!on && sg[0].at_a.empty()) locate_here(pts.front());
        if (!on && !sg[0].at_a.empty() && !(first_run[run.curve] == r)) bad = true;  // only the curve's end
        for (std::size_t k = 0; k + 1 < n && !bad; ++k) {
            const NearSeg& s = sg[k];
            if (s.along.empty()) {
                for (const Cut& c : s.cuts) {
                    cur.push_back(c.p);
                    finish({c.p, c.id});
                    parity ^= c.flip;
                }
            } else {
                for (const auto& mp : s.mask_points) cur.push_back(mp.second);
            }
            cur.push_back(pts[k + 1]);
            if (k + 2 == n) break;
            // The inner point v = pts[k + 1], between s and the next segment t.
            const NearSeg& t = sg[k + 1];
            const Point v = pts[k + 1];
            const bool on_s = !s.along.empty(), on_t = !t.along.empty();
            // The mask segments through v, other than those along s or t.
            std::vector<std::uint32_t> through;
            for (std::uint32_t j : s.at_b)
                if (std::find(t.along.begin(), t.along.end(), j) == t.along.end()) through.push_back(j);
            for (std::uint32_t j : t.at_a)
                if (std::find(s.along.begin(), s.along.end(), j) == s.along.end() &&
                    std::find(through.begin(), through.end(), j) == through.end())
                    through.push_back(j);
            if (on_s && on_t) {
                if (!through.empty()) bad = true;  // another mask segment at v
                continue;  // on along the mask, v one of the piece's points
            }
            if (!on_s && !on_t) {
                if (through.empty()) {
                    locate_here(v);
                    continue;
                }
                // Touching or crossing inside one mask segment: a vertex of the map.
                if (through.size() != 1) {
                    bad = true;
                    break;
                }
                const detail::Seg& m = msegs[through[0]];
                if (v == m.a || v == m.b) {
                    bad = true;
                    break;
                }
                finish({v, -1});
                const int before = detail::orientation(m.a, m.b, pts[k]), after = detail::orientation(m.a, m.b, pts[k + 2]);
                if (before == 0 || after == 0) {
                    bad = true;
                    break;
                }
                parity ^= before != after && m.changes();
                continue;
            }
            // Joining or leaving the mask at v, inside the mask segment along the other side.
            const std::vector<std::uint32_t>& at = on_s ? s.along : t.along;
            std::uint32_t mj = UINT32_MAX;
            for (std::uint32_t j : at) {
                const detail::Seg& m = msegs[j];
                if (detail::orientation(m.a, m.b, v) == 0 && std::min(m.a, m.b) < v && v < std::max(m.a, m.b)) mj = j;
            }
            if (mj == UINT32_MAX || !through.empty()) {
                bad = true;  // at a mask vertex
                break;
            }
            const detail::Seg& m = msegs[mj];
            if (on_s) {  // leaving: the next point tells the side
                finish({v, -1});
                on = false;
                parity = false;
                chain_status.push_back(-1);
                chain = chain_status.size() - 1;
                know(side_status(m, pts[k + 2]));
            } else {  // joining: the point before tells the side
                know(side_status(m, pts[k]));
                finish({v, -1});
                on = true;
            }
        }
        if (!bad) {
            if (!on && sg[n - 2].at_b.empty()) locate_here(pts.back());
            if (!on && !sg[n - 2].at_b.empty() && !(last_run[run.curve] == r)) bad = true;
            finish({pts.back(), -1});
        }
        for (std::size_t i = begin; i < all.size() && !bad; ++i)
            bad = !all[i].on && chain_status[all[i].chain] < 0;  // a stretch whose side is not known
        if (bad) {
            hard[r] = 1;
            all.resize(begin);
        }
    }
    // The groups with a hard run go to the map; so do all runs when the map is needed and a
    // piece along the mask was cut here (the map's edges on the mask come in its order).
    std::vector<char> group_hard(runs.size(), 0);
    for (std::uint32_t r = 0; r < runs.size(); ++r)
        if (runs[r].near && hard[r]) group_hard[find(r)] = 1;
    bool any_map = false, any_along = false;
    for (std::uint32_t r = 0; r < runs.size(); ++r)
        if (runs[r].near && group_hard[find(r)]) res.to_map[r] = 1, any_map = true;
    for (const Piece& pc : all) any_along = any_along || (pc.on && !res.to_map[pc.run]);
    if (any_map && any_along) return res;  // `any` stays false: all to the map
    // A curve's pieces in the order of the map's edges.
    auto exact_of = [&](const End& e) -> std::pair<FT, FT> {
        return e.id < 0 ? std::pair<FT, FT>{FT(e.p.x), FT(e.p.y)} : exact[std::size_t(e.id)];
    };
    auto vless = [&](const End& x, const End& y) {
        if (x.p != y.p) return x.p < y.p;
        if (x.id == y.id) return false;
        const auto ex = exact_of(x), ey = exact_of(y);
        return ex.first < ey.first || (ex.first == ey.first && ex.second < ey.second);
    };
    auto edge_order = [&](const Piece& x, const Piece& y) {
        const End& x0 = vless(x.back, x.front) ? x.back : x.front;
        const End& x1 = vless(x.back, x.front) ? x.front : x.back;
        const End& y0 = vless(y.back, y.front) ? y.back : y.front;
        const End& y1 = vless(y.back, y.front) ? y.front : y.back;
        if (vless(x0, y0) || vless(y0, x0)) return vless(x0, y0);
        if (vless(x1, y1) || vless(y1, x1)) return vless(x1, y1);
        return detail::canonical_points(x.pts) < detail::canonical_points(y.pts);
    };
    std::vector<Piece> kept, on_mask;
    for (Piece& pc : all) {
        if (res.to_map[pc.run]) continue;
        if (pc.on) {
            if (pc.front.p == pc.back.p) return ExactPieces{std::vector<char>(runs.size(), 1), {}, {}, false};
            on_mask.push_back(std::move(pc));
        } else if (((chain_status[pc.chain] ^ int(pc.parity)) ? Status::In : Status::Out) == wanted) {
            kept.push_back(std::move(pc));
        }
    }
    std::stable_sort(kept.begin(), kept.end(), [&](const Piece& x, const Piece& y) {
        if (x.curve != y.curve) return x.curve < y.curve;
        return edge_order(x, y);
    });
    std::stable_sort(on_mask.begin(), on_mask.end(), edge_order);
    res.pieces.resize(src.curves.size());
    for (Piece& pc : kept) res.pieces[pc.curve].push_back(std::move(pc.pts));
    for (Piece& pc : on_mask) {
        const Curve& from = src.curves[pc.curve];
        Curve c;
        c.points = std::move(pc.pts);
        c.labels.merge(from.labels);
        c.left.merge(from.left);
        c.right.merge(from.right);
        res.along.curves.push_back(strip(std::move(c)));
        ++detail::g_pieces_along;
    }
    for (std::uint32_t r = 0; r < runs.size(); ++r) res.any = res.any || (runs[r].near && !res.to_map[r]);
    return res;
}

// Distinct exact points of the planar map may round to the same doubles: no piece keeps
// a repeated point (a zero-length segment), none is left with fewer than two points.
void drop_repeated_points(Curves& out) {
    std::size_t kept = 0;
    for (std::size_t i = 0; i < out.curves.size(); ++i) {
        Curve& c = out.curves[i];
        c.points = clean_points(c);
        if (c.points.size() < 2) continue;
        if (kept != i) out.curves[kept] = std::move(c);
        ++kept;
    }
    out.curves.resize(kept);
}

// `movable`: subject itself, given up by the caller (the fast crop moves whole curves).
Curves mask_core(const Curves& subject, const Curves& mask, MaskSide side, Border b, Curves* movable) {
    const LabelId in = inside_marker();
    const bool keep_whole = (b == Border::KEEP_INSIDE || b == Border::KEEP_OUTSIDE);
    const bool want_in = side == MaskSide::Inside;
    const Status wanted = want_in ? Status::In : Status::Out;
    const detail::SegmentGrid grid(inside_marked_segments(mask, in));

    if (b == Border::CROP && !detail::exact_crops_only() && !detail::g_general_only) {
        Curves fast;
        if (crop_polylines_fast(subject, grid, wanted, fast, movable)) return fast;
    }

    // KEEP modes decide on the edges of the subject's own planar map; CROP on its curves.
    Curves edges;
    if (keep_whole) edges = detail::maximal_edges(subject);
    const Curves& src = keep_whole ? edges : subject;
    // KEEP modes only care where the inside changes; CROP also cuts at inner boundaries.
    std::vector<char> touched(mask.curves.size(), 0);
    const std::vector<Run> runs = split_runs(src, grid, keep_whole, touched);
    Curves out;
    out.points = subject.points;
    if (keep_whole) {
        keep_whole_edges(src, mask, grid, runs, b, wanted, out);
        return out;
    }
    const std::vector<char> included = mask_curves_needed(mask, grid, runs, touched, keep_whole);
    if (!detail::exact_crops_only()) {
        Curves fast;
        if (crop_by_crossings_fast(src, mask, grid, runs, side, b, wanted, fast)) return fast;
    }

    if (b == Border::CROP && !detail::g_map_only) {
        ExactPieces cut = exact_crossing_pieces(src, grid, runs, wanted);
        if (cut.any) {
            ++detail::g_exact_crossing_crops;
            const JointMap j = joint_map(src, mask, grid, runs, included, &cut.to_map);
            crop_pieces(src, mask, grid, runs, included, j, b, wanted, in, out, &cut.pieces);
            for (Curve& c : cut.along.curves) out.curves.push_back(std::move(c));
            drop_repeated_points(out);
            return out;
        }
    }
    const JointMap j = joint_map(src, mask, grid, runs, included);
    crop_pieces(src, mask, grid, runs, included, j, b, wanted, in, out);
    drop_repeated_points(out);
    return out;
}

}  // namespace

Curves apply_mask(const Curves& subject, const PlanarMap& mask_map, MaskSide side, Border b) {
    const LabelId in = inside_marker();
    Curves mask;
    mask.curves.reserve(mask_map.edges().size());
    for (const EdgeRec& e : mask_map.edges()) {
        const bool left_in = !mask_map.faces()[e.left].unbounded;
        const bool right_in = !mask_map.faces()[e.right].unbounded;
        if (!left_in && !right_in) continue;  // a dangling edge in the unbounded face
        // The mask's own labels ride along, for the boundaries CROP_ADD_BOUNDARY adds.
        Curve c = mask_map.edge_curve(int(&e - mask_map.edges().data()));
        if (left_in) c.left.add(in);
        if (right_in) c.right.add(in);
        mask.curves.push_back(std::move(c));
    }
    return mask_core(subject, mask, side, b);
}

Curves apply_mask(const Curves& subject, const Region& region, Border b) {
    return detail::crop_to_region(subject, region, b, std::nullopt);
}

Curves apply_mask(Curves&& subject, const Region& region, Border b) {
    return detail::crop_to_region(subject, region, b, std::nullopt, &subject);
}

Curves detail::crop_to_region(const Curves& subject, const Region& region, Border b, std::optional<LabelId> outline,
                              Curves* movable) {
    Curves mask = region.boundary();
    for (auto& c : mask.curves) {
        c.left.add(inside_marker());
        if (outline) c.labels.add(*outline);
    }
    return mask_core(subject, mask, MaskSide::Inside, b, movable);
}

void detail::label_outline_pieces(Curves& cropped, LabelId outline,
                                  const std::function<std::optional<Labels>(const Point&, const Point&)>& inner) {
    for (auto& c : cropped.curves) {
        if (!c.labels.has(outline)) continue;
        c.labels.remove(outline);
        c.left = Labels{};
        c.right = Labels{};
        if (c.points.size() < 2) continue;
        const Point mid = (c.points[0] + c.points[1]) / 2;
        const Point d = c.points[1] - c.points[0];
        const double len = norm(d);
        if (len == 0) continue;
        if (auto l = inner(mid + Point{-d.y, d.x} * (1e-7 / len * std::max(1.0, len)), mid)) c.left = std::move(*l);
    }
}

Arrangement Union(Arrangement a1, Arrangement a2) {
    return Arrangement([a1 = std::move(a1), a2 = std::move(a2)](const Region& r) {
        Curves parts[2];
        parallel_for(2, [&](std::size_t i) { parts[i] = i == 0 ? a1(r) : a2(r); });
        parts[0].append(std::move(parts[1]));
        return std::move(parts[0]);
    });
}

static Arrangement masked(Arrangement a1, Arrangement a2, Border b, MaskSide side) {
    return Arrangement([a1 = std::move(a1), a2 = std::move(a2), b, side](const Region& r) {
        Curves subject;
        MapPtr mask;
        parallel_for(2, [&](std::size_t i) {
            if (i == 0) subject = a1(r);
            else mask = a2.induce(r);
        });
        return apply_mask(subject, *mask, side, b);
    });
}

Arrangement Inside(Arrangement a1, Arrangement a2, Border b) {
    return masked(std::move(a1), std::move(a2), b, MaskSide::Inside);
}

Arrangement Outside(Arrangement a1, Arrangement a2, Border b) {
    return masked(std::move(a1), std::move(a2), b, MaskSide::Outside);
}

Arrangement Outline() {
    return Arrangement([](const Region& r) { return r.boundary(); });
}

Arrangement Crop(Arrangement a, Border b) {
    return Arrangement([a = std::move(a), b](const Region& r) { return apply_mask(a(r), r, b); });
}

}  // namespace tex
