#include "geometry/segment_index.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>
#include <unordered_set>

#include "libtex/merge.hpp"
#include "libtex/planar_map.hpp"
#include "libtex/random.hpp"

namespace tex::detail {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using KP = K::Point_2;
using KS = K::Segment_2;

KP kp(const Point& p) { return KP(p.x, p.y); }

// Liang-Barsky: does segment ab meet the box (closed)? Decided on doubles, so callers
// pass a box grown by a margin.
bool segment_meets_box(const Point& a, const Point& b, const BBox& box) {
    double t0 = 0, t1 = 1;
    const double dx = b.x - a.x, dy = b.y - a.y;
    auto clip = [&](double p, double q) {
        if (p == 0) return q >= 0;
        const double t = q / p;
        if (p < 0) {
            if (t > t1) return false;
            if (t > t0) t0 = t;
        } else {
            if (t < t0) return false;
            if (t < t1) t1 = t;
        }
        return true;
    };
    return clip(-dx, a.x - box.xmin) && clip(dx, box.xmax - a.x) && clip(-dy, a.y - box.ymin) &&
           clip(dy, box.ymax - a.y);
}

struct PointHash {
    std::size_t operator()(const Point& p) const { return hash_point(0, p); }
};

}  // namespace

int orientation(const Point& a, const Point& b, const Point& c) {
    return int(CGAL::orientation(kp(a), kp(b), kp(c)));
}

bool segments_touch(const Point& a, const Point& b, const Point& c, const Point& d) {
    if (a == b) {
        if (c == d) return a == c;
        return CGAL::do_intersect(kp(a), KS(kp(c), kp(d)));
    }
    if (c == d) return CGAL::do_intersect(kp(c), KS(kp(a), kp(b)));
    return CGAL::do_intersect(KS(kp(a), kp(b)), KS(kp(c), kp(d)));
}

// At most this many segments go in one cell: scanning them costs less than bucketing them.
constexpr std::size_t kFewSegments = 16;

SegmentGrid::SegmentGrid(std::vector<Seg> segs) : segs_(std::move(segs)) {
    if (segs_.empty()) return;
    for (const auto& s : segs_) {
        box_.add(s.a);
        box_.add(s.b);
    }
    const double span = std::max(box_.width(), box_.height());
    const double margin = 1e-9 * (1 + span);
    box_ = box_.expanded(margin);
    const double w = box_.width(), h = box_.height();
    const double n = double(segs_.size());
    const double s = std::sqrt(w * h / n);
    // A few segments (a cell of a grid, a small face) are searched one by one: one cell.
    const bool few = segs_.size() <= kFewSegments;
    nx_ = few ? 1 : int(std::clamp(std::ceil(w / s), 1.0, 1024.0));
    ny_ = few ? 1 : int(std::clamp(std::ceil(h / s), 1.0, 1024.0));
    cw_ = w / nx_;
    ch_ = h / ny_;
    if (few) {  // every segment in the one cell, in order (what the passes below would give)
        start_ = {0, std::uint32_t(segs_.size())};
        items_.resize(segs_.size());
        for (std::uint32_t i = 0; i < segs_.size(); ++i) items_[i] = i;
        seen_.assign(segs_.size(), 0);
        return;
    }
    // Two passes: count, then fill (compressed rows).
    std::vector<std::uint32_t> count(std::size_t(nx_) * std::size_t(ny_) + 1, 0);
    auto cells_of = [&](const Seg& sg, auto&& emit) {
        BBox b;
        b.add(sg.a);
        b.add(sg.b);
        const int c0 = col(b.xmin - margin), c1 = col(b.xmax + margin);
        const int r0 = row(b.ymin - margin), r1 = row(b.ymax + margin);
        const bool thin = c0 == c1 || r0 == r1;
        for (int r = r0; r <= r1; ++r)
            for (int c = c0; c <= c1; ++c) {
                if (!thin) {
                    BBox cb;
                    cb.add(Point{box_.xmin + c * cw_, box_.ymin + r * ch_});
                    cb.add(Point{box_.xmin + (c + 1) * cw_, box_.ymin + (r + 1) * ch_});
                    if (!segment_meets_box(sg.a, sg.b, cb.expanded(margin + 1e-9 * (cw_ + ch_)))) continue;
                }
                emit(cell(c, r));
            }
    };
    for (const auto& sg : segs_) cells_of(sg, [&](std::size_t k) { ++count[k + 1]; });
    for (std::size_t k = 1; k < count.size(); ++k) count[k] += count[k - 1];
    start_ = count;
    items_.resize(count.back());
    std::vector<std::uint32_t> fill(count.begin(), count.end() - 1);
    for (std::uint32_t i = 0; i < segs_.size(); ++i) cells_of(segs_[i], [&](std::size_t k) { items_[fill[k]++] = i; });
    seen_.assign(segs_.size(), 0);
}

int SegmentGrid::col(double x) const {
    if (nx_ == 1) return 0;
    const double t = std::floor((x - box_.xmin) / cw_);
    return int(std::clamp(t, 0.0, double(nx_ - 1)));
}

int SegmentGrid::row(double y) const {
    if (ny_ == 1) return 0;
    const double t = std::floor((y - box_.ymin) / ch_);
    return int(std::clamp(t, 0.0, double(ny_ - 1)));
}

bool SegmentGrid::touches(const Point& p, const Point& q, bool only_changing, std::vector<char>* owners) const {
    BBox b;
    b.add(p);
    b.add(q);
    bool hit = false;
    for_each_in(b, [&](std::uint32_t i) {
        const Seg& s = segs_[i];
        if (hit && (!owners || (*owners)[s.owner])) return;
        if (only_changing && !s.changes()) return;
        if (std::max(s.a.x, s.b.x) < b.xmin || std::min(s.a.x, s.b.x) > b.xmax ||
            std::max(s.a.y, s.b.y) < b.ymin || std::min(s.a.y, s.b.y) > b.ymax)
            return;
        if (segments_touch(p, q, s.a, s.b)) {
            hit = true;
            if (owners) (*owners)[s.owner] = 1;
        }
    });
    return hit;
}

bool SegmentGrid::box_meets(const BBox& b, bool only_changing) const {
    if (segs_.empty() || b.empty() || !b.intersects(box_)) return false;
    const int c0 = col(b.xmin), c1 = col(b.xmax), r0 = row(b.ymin), r1 = row(b.ymax);
    // Segments are clipped against the box grown by a rounding margin (Liang-Barsky decides
    // on doubles): a segment that misses it misses the box.
    const BBox grown = b.expanded(1e-9 * (1 + std::max(b.width(), b.height())));
    for (int r = r0; r <= r1; ++r)
        for (int c = c0; c <= c1; ++c)
            for (std::uint32_t k = start_[cell(c, r)]; k < start_[cell(c, r) + 1]; ++k) {
                const Seg& s = segs_[items_[k]];
                if (only_changing && !s.changes()) continue;
                if (!(std::max(s.a.x, s.b.x) < grown.xmin || std::min(s.a.x, s.b.x) > grown.xmax ||
                      std::max(s.a.y, s.b.y) < grown.ymin || std::min(s.a.y, s.b.y) > grown.ymax) &&
                    segment_meets_box(s.a, s.b, grown))
                    return true;
            }
    return false;
}

template <class Use>
int SegmentGrid::first_above_with(const Point& p, const Use& use, bool& on) const {
    on = false;
    if (segs_.empty() || p.x < box_.xmin || p.x > box_.xmax || p.y > box_.ymax) return -1;
    const int c = col(p.x);
    const int r_start = p.y < box_.ymin ? 0 : row(p.y);
    const KP kpp = kp(p);
    int best = -1;
    KS best_seg;
    ++stamp_;
    for (int r = r_start; r < ny_; ++r) {
        for (std::uint32_t k = start_[cell(c, r)]; k < start_[cell(c, r) + 1]; ++k) {
            const std::uint32_t i = items_[k];
            if (seen_[i] == stamp_) continue;
            seen_[i] = stamp_;
            if (!use(i)) continue;
            const Seg& s = segs_[i];
            const Point& L = s.a < s.b ? s.a : s.b;
            const Point& R = s.a < s.b ? s.b : s.a;
            if (L.x == R.x) {
                if (p.x == L.x && p.y >= L.y && p.y <= R.y) {
                    on = true;
                    return int(i);
                }
                continue;
            }
            if (!(L.x <= p.x && p.x < R.x)) {
                if (p == R) {
                    on = true;
                    return int(i);
                }
                continue;
            }
            const KS seg(kp(L), kp(R));
            const auto o = CGAL::orientation(kp(L), kp(R), kpp);
            if (o == CGAL::COLLINEAR) {
                on = true;
                return int(i);
            }
            if (o == CGAL::LEFT_TURN) continue;  // p above the segment
            bool lower = best < 0;
            if (!lower) {
                const auto cmp = CGAL::compare_y_at_x(kpp, seg, best_seg);
                if (cmp == CGAL::SMALLER) lower = true;
                else if (cmp == CGAL::EQUAL)
                    lower = CGAL::orientation(seg.source(), seg.target(), best_seg.target()) == CGAL::LEFT_TURN;
            }
            if (lower) {
                best = int(i);
                best_seg = seg;
            }
        }
        if (best >= 0) {
            const Point L = {best_seg.source().x(), best_seg.source().y()};
            const Point R = {best_seg.target().x(), best_seg.target().y()};
            const double y = L.y + (R.y - L.y) * ((p.x - L.x) / (R.x - L.x));
            if (y < box_.ymin + (r + 1) * ch_ - 1e-9 * ch_) break;
        }
    }
    return best;
}

int SegmentGrid::first_above(const Point& p, const std::function<bool(std::uint32_t)>& use, bool& on) const {
    return first_above_with(p, use, on);
}

SegmentGrid::Where SegmentGrid::locate(const Point& p) const {
    // Shoot a ray upwards and read the side of the lowest boundary segment it meets.
    bool on = false;
    const int best = first_above_with(p, [&](std::uint32_t i) { return segs_[i].changes(); }, on);
    if (on) return Where::On;
    if (best < 0) return Where::Out;
    const Seg& s = segs_[best];
    // Below a left-to-right segment is its right side.
    const bool in = s.a < s.b ? s.in_right : s.in_left;
    return in ? Where::In : Where::Out;
}

std::vector<Seg> curve_segments(const Curves& c) {
    std::vector<Seg> out;
    curve_segments(c, out);
    return out;
}

namespace {

// Appends the segments of one curve (zero-length and non-finite ones left out).
void append_segments(const Curve& cv, std::uint32_t owner, std::vector<Seg>& out) {
    const std::size_t n = cv.points.size();
    if (n < 2) return;
    const std::size_t nseg = cv.closed ? n : n - 1;
    for (std::size_t i = 0; i < nseg; ++i) {
        const Point& a = cv.points[i];
        const Point& b = cv.points[(i + 1) % n];
        if (a == b || !std::isfinite(a.x) || !std::isfinite(a.y) || !std::isfinite(b.x) || !std::isfinite(b.y))
            continue;
        Seg s;
        s.a = a;
        s.b = b;
        s.owner = owner;
        out.push_back(s);
    }
}

// Whether every segment of the curve turns the same way around c (exact orientation, never
// collinear with c) and the angles they sweep sum to less than a full turn (an open curve)
// or to one full turn (a closed one). Then each ray from c meets the curve at most once
// (the curve is star-shaped from c), so it is simple.
bool star_shaped_from(const std::vector<Point>& p, bool closed, const Point& c) {
    const std::size_t n = p.size(), nseg = closed ? n : n - 1;
    int side = 0;
    double swept = 0;
    for (std::size_t i = 0; i < nseg; ++i) {
        const Point& a = p[i];
        const Point& b = p[(i + 1) % n];
        const int o = CGAL::orientation(kp(c), kp(a), kp(b));
        if (o == 0 || (side != 0 && o != side)) return false;
        side = o;
        const Point u = a - c, v = b - c;
        swept += std::atan2(cross(u, v), dot(u, v));
    }
    return closed ? std::abs(swept) < 3 * pi : std::abs(swept) < 2 * pi - 1e-6;
}

// Whether a curve is shown simple in O(n): an open chain running forward along its chord
// all the way, or a curve star-shaped from its vertices' mean or (open) from a point off its
// chord's middle. Nearly collinear points (a flattened arc, a straight stretch with points
// along it) do not spoil it. False means "not shown", and the segment search decides.
bool plainly_simple(const Curve& cv) {
    const auto& p = cv.points;
    const std::size_t n = p.size();
    if (n < 2) return false;
    for (std::size_t i = 0; i < n; ++i) {
        if (!std::isfinite(p[i].x) || !std::isfinite(p[i].y)) return false;
        if ((i + 1 < n || cv.closed) && p[i] == p[(i + 1) % n]) return false;
    }
    if (!cv.closed && n == 2) return true;
    if (cv.closed && n < 3) return false;
    Point mean{0, 0};
    for (const Point& q : p) mean = mean + q;
    mean = mean / double(n);
    if (cv.closed) return star_shaped_from(p, true, mean);
    // Forward along the chord, with a margin for the rounding of the dot products.
    const Point d = p.back() - p.front();
    const double ld = norm(d);
    bool forward = ld > 0;
    for (std::size_t i = 0; forward && i + 1 < n; ++i) {
        const Point e = p[i + 1] - p[i];
        forward = dot(e, d) > 1e-9 * norm(e) * ld;
    }
    if (forward) return true;
    if (star_shaped_from(p, false, mean)) return true;
    if (ld == 0) return false;
    const Point mid = (p.front() + p.back()) / 2, off{-d.y, d.x};
    return star_shaped_from(p, false, mid + off) || star_shaped_from(p, false, mid - off);
}

// Curves whose boxes (closed, grown by a rounding margin) meet another's box, or that
// cover too many cells of the boxes' grid to be checked pair by pair (those are marked
// too: they go to the segment search, which is exact).
std::vector<char> crowded_curves(const std::vector<BBox>& box, const std::vector<char>& usable) {
    const std::size_t n = box.size();
    std::vector<char> crowded(n, 0);
    BBox all;
    std::size_t m = 0;
    for (std::size_t i = 0; i < n; ++i)
        if (usable[i]) {
            all.add(Point{box[i].xmin, box[i].ymin});
            all.add(Point{box[i].xmax, box[i].ymax});
            ++m;
        }
    if (m < 2) return crowded;
    const double span = std::max(all.width(), all.height());
    const double margin = 1e-9 * (1 + span);
    all = all.expanded(2 * margin);
    const double w = all.width(), h = all.height();
    const double s = std::max(std::sqrt(w * h / double(m)), span / 1024);
    const int nx = int(std::clamp(std::ceil(w / s), 1.0, 1024.0)), ny = int(std::clamp(std::ceil(h / s), 1.0, 1024.0));
    const double cw = w / nx, ch = h / ny;
    auto col = [&](double x) { return int(std::clamp(std::floor((x - all.xmin) / cw), 0.0, double(nx - 1))); };
    auto row = [&](double y) { return int(std::clamp(std::floor((y - all.ymin) / ch), 0.0, double(ny - 1))); };
    constexpr int kMostCells = 64;
    constexpr std::size_t kMostPerCell = 32;
    std::vector<std::vector<std::uint32_t>> cells(std::size_t(nx) * std::size_t(ny));
    std::vector<BBox> grown(n);
    for (std::size_t i = 0; i < n; ++i) {
        if (!usable[i]) continue;
        grown[i] = box[i].expanded(margin);
        const int c0 = col(grown[i].xmin), c1 = col(grown[i].xmax), r0 = row(grown[i].ymin), r1 = row(grown[i].ymax);
        if ((c1 - c0 + 1) * (r1 - r0 + 1) > kMostCells) {
            crowded[i] = 1;
            continue;
        }
        for (int r = r0; r <= r1; ++r)
            for (int c = c0; c <= c1; ++c) cells[std::size_t(r) * std::size_t(nx) + std::size_t(c)].push_back(std::uint32_t(i));
    }
    // A curve too large for the cells still meets the others' boxes: found from its side.
    for (std::size_t i = 0; i < n; ++i) {
        if (!crowded[i]) continue;
        const int c0 = col(grown[i].xmin), c1 = col(grown[i].xmax), r0 = row(grown[i].ymin), r1 = row(grown[i].ymax);
        for (int r = r0; r <= r1; ++r)
            for (int c = c0; c <= c1; ++c)
                for (std::uint32_t j : cells[std::size_t(r) * std::size_t(nx) + std::size_t(c)])
                    if (grown[i].intersects(grown[j])) crowded[j] = 1;
    }
    for (const auto& cell : cells) {
        if (cell.size() > kMostPerCell) {
            for (std::uint32_t i : cell) crowded[i] = 1;
            continue;
        }
        for (std::size_t a = 0; a < cell.size(); ++a)
            for (std::size_t b = a + 1; b < cell.size(); ++b)
                if (grown[cell[a]].intersects(grown[cell[b]])) crowded[cell[a]] = crowded[cell[b]] = 1;
    }
    return crowded;
}

}  // namespace

namespace {
thread_local std::uint64_t g_searched = 0;
}  // namespace
void note_segments_searched(std::size_t n) { g_searched += n; }
std::uint64_t segments_searched() { return g_searched; }

void curve_segments(const Curves& c, std::vector<Seg>& out) {
    out.clear();
    std::size_t most = 0;
    for (const Curve& cv : c.curves) most += cv.points.size();
    out.reserve(most);
    for (std::uint32_t ci = 0; ci < c.curves.size(); ++ci) append_segments(c.curves[ci], ci, out);
}

Curves maximal_edges(const Curves& c) {
    const std::size_t ncurves = c.curves.size();
    std::vector<char> busy(ncurves, 0);
    // A labelled point inside a curve is a vertex of it.
    if (!c.points.empty()) {
        std::unordered_set<Point, PointHash> labelled;
        for (const auto& lp : c.points) labelled.insert(lp.point);
        for (std::size_t ci = 0; ci < ncurves; ++ci) {
            const auto& pts = c.curves[ci].points;
            if (pts.size() < 2) continue;
            // The ends of an open curve are vertices anyway.
            const std::size_t first = c.curves[ci].closed ? 0 : 1;
            const std::size_t last = c.curves[ci].closed ? pts.size() : pts.size() - 1;
            for (std::size_t k = first; k < last; ++k)
                if (labelled.count(pts[k])) busy[ci] = 1;
        }
    }
    // Whole curves first: one whose box meets no other curve's box and that is plainly
    // simple is an edge on its own, without a look at its segments. The others (crowded)
    // are searched segment by segment.
    std::vector<BBox> box(ncurves);
    std::vector<char> usable(ncurves, 0);
    for (std::size_t ci = 0; ci < ncurves; ++ci) {
        for (const Point& q : c.curves[ci].points)
            if (std::isfinite(q.x) && std::isfinite(q.y)) box[ci].add(q);
        usable[ci] = c.curves[ci].points.size() >= 2 && !box[ci].empty();
    }
    std::vector<char> crowded = crowded_curves(box, usable);
    for (std::size_t ci = 0; ci < ncurves; ++ci)
        if (usable[ci] && !crowded[ci] && !plainly_simple(c.curves[ci])) crowded[ci] = 1;
    std::vector<Seg> segs;
    for (std::uint32_t ci = 0; ci < ncurves; ++ci)
        if (crowded[ci]) append_segments(c.curves[ci], ci, segs);
    note_segments_searched(segs.size());
    // Position of each segment along its curve, and the number of segments per curve.
    std::vector<std::uint32_t> pos(segs.size()), nseg(ncurves, 0);
    for (std::size_t i = 0; i < segs.size(); ++i) pos[i] = nseg[segs[i].owner]++;
    for (std::size_t ci = 0; ci < ncurves; ++ci)
        if (usable[ci] && !crowded[ci]) nseg[ci] = std::uint32_t(c.curves[ci].points.size());  // any nonzero count
    const SegmentGrid grid(segs);
    for (std::uint32_t i = 0; i < segs.size(); ++i) {
        const Seg& s = segs[i];
        BBox b;
        b.add(s.a);
        b.add(s.b);
        grid.for_each_in(b, [&](std::uint32_t j) {
            if (j <= i) return;
            const Seg& t = segs[j];
            if (busy[s.owner] && busy[t.owner]) return;
            if (std::max(t.a.x, t.b.x) < b.xmin || std::min(t.a.x, t.b.x) > b.xmax ||
                std::max(t.a.y, t.b.y) < b.ymin || std::min(t.a.y, t.b.y) > b.ymax)
                return;
            if (s.owner == t.owner) {
                const std::uint32_t n = nseg[s.owner];
                const bool closed = c.curves[s.owner].closed;
                const bool next = pos[j] == pos[i] + 1;
                const bool wrap = closed && pos[i] == 0 && pos[j] == n - 1;
                if (next || wrap) {
                    // Consecutive segments share a point; they only meet elsewhere when
                    // the curve folds back on itself.
                    const Point& shared = next ? s.b : s.a;
                    const Point& p = next ? s.a : s.b;
                    const Point& q = next ? t.b : t.a;
                    const bool folds = CGAL::orientation(kp(p), kp(shared), kp(q)) == CGAL::COLLINEAR &&
                                       dot(p - shared, q - shared) > 0;
                    const bool two_closed = closed && n == 2;
                    if (folds || two_closed || (next && wrap)) busy[s.owner] = 1;
                    return;
                }
            }
            if (segments_touch(s.a, s.b, t.a, t.b)) busy[s.owner] = busy[t.owner] = 1;
        });
    }
    Curves out, cluster;
    out.points = c.points;
    for (std::size_t ci = 0; ci < ncurves; ++ci) {
        if (nseg[ci] == 0) continue;
        if (busy[ci]) cluster.curves.push_back(c.curves[ci]);
        else out.curves.push_back(c.curves[ci]);
    }
    if (!cluster.curves.empty()) {
        cluster.points = c.points;
        Curves edges = PlanarMap::induce(cluster)->edge_curves();
        for (auto& e : edges.curves) out.curves.push_back(std::move(e));
    }
    return out;
}

}  // namespace tex::detail
