#include "geometry/segment_index.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>
#include <unordered_set>

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
    nx_ = int(std::clamp(std::ceil(w / s), 1.0, 1024.0));
    ny_ = int(std::clamp(std::ceil(h / s), 1.0, 1024.0));
    cw_ = w / nx_;
    ch_ = h / ny_;
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
    const double t = std::floor((x - box_.xmin) / cw_);
    return int(std::clamp(t, 0.0, double(nx_ - 1)));
}

int SegmentGrid::row(double y) const {
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

int SegmentGrid::first_above(const Point& p, const std::function<bool(std::uint32_t)>& use, bool& on) const {
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

SegmentGrid::Where SegmentGrid::locate(const Point& p) const {
    // Shoot a ray upwards and read the side of the lowest boundary segment it meets.
    bool on = false;
    const int best = first_above(p, [&](std::uint32_t i) { return segs_[i].changes(); }, on);
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

void curve_segments(const Curves& c, std::vector<Seg>& out) {
    out.clear();
    std::size_t most = 0;
    for (const Curve& cv : c.curves) most += cv.points.size();
    out.reserve(most);
    for (std::uint32_t ci = 0; ci < c.curves.size(); ++ci) {
        const Curve& cv = c.curves[ci];
        const std::size_t n = cv.points.size();
        if (n < 2) continue;
        const std::size_t nseg = cv.closed ? n : n - 1;
        for (std::size_t i = 0; i < nseg; ++i) {
            const Point& a = cv.points[i];
            const Point& b = cv.points[(i + 1) % n];
            if (a == b || !std::isfinite(a.x) || !std::isfinite(a.y) || !std::isfinite(b.x) || !std::isfinite(b.y))
                continue;
            Seg s;
            s.a = a;
            s.b = b;
            s.owner = ci;
            out.push_back(s);
        }
    }
}

Curves maximal_edges(const Curves& c) {
    const std::vector<Seg> segs = curve_segments(c);
    // Position of each segment along its curve, and the number of segments per curve.
    std::vector<std::uint32_t> pos(segs.size()), nseg(c.curves.size(), 0);
    for (std::size_t i = 0; i < segs.size(); ++i) pos[i] = nseg[segs[i].owner]++;
    std::vector<char> busy(c.curves.size(), 0);
    // A labelled point inside a curve is a vertex of it.
    if (!c.points.empty()) {
        std::unordered_set<Point, PointHash> labelled;
        for (const auto& lp : c.points) labelled.insert(lp.point);
        for (std::size_t ci = 0; ci < c.curves.size(); ++ci) {
            const auto& pts = c.curves[ci].points;
            if (pts.size() < 2) continue;
            // The ends of an open curve are vertices anyway.
            const std::size_t first = c.curves[ci].closed ? 0 : 1;
            const std::size_t last = c.curves[ci].closed ? pts.size() : pts.size() - 1;
            for (std::size_t k = first; k < last; ++k)
                if (labelled.count(pts[k])) busy[ci] = 1;
        }
    }
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
    for (std::size_t ci = 0; ci < c.curves.size(); ++ci) {
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
