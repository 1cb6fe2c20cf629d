// FrayedCrop: a crop whose cut ends are drawn back irregularly from the region's border, so
// that the border is not drawn by the ends of the curves (rock drawing has no outline).
#include <algorithm>
#include <cmath>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "libtex/error.hpp"
#include "libtex/merge.hpp"
#include "libtex/parallel.hpp"
#include "libtex/random.hpp"
#include "libtex/region.hpp"

namespace tex {
namespace {

constexpr std::uint64_t kFrayTag = 0x46524159ULL;
// Halvings of a segment's parameter when an end is placed at its depth: 2^-20 of a segment
// (a few metres on the ground) is far below a printed line's width.
constexpr int kBisections = 20;

// The segments of a region's boundary, each marked "rim" when the drawing ends there: not
// labelled one of the hard labels, and no value of `across` just beyond it (outside is on
// the right of every ring). Bucketed on a grid for distance queries near the border.
class BorderIndex {
public:
    BorderIndex(const Region& r, const std::vector<std::string>& hard, const Field& across, double probe) {
        const Curves edges = r.boundary();
        for (const Curve& c : edges.curves) {
            bool h = false;
            for (const auto& l : hard) h = h || c.labels.has(l);
            const std::size_t n = c.points.size();
            for (std::size_t i = 0; i + 1 < n + (c.closed ? 1 : 0); ++i) {
                const Point a = c.points[i], b = c.points[(i + 1) % n];
                const double l = distance(a, b);
                bool rim = !h && l > 0;
                if (rim) {
                    const Point right{(b - a).y / l, -(b - a).x / l};
                    rim = std::isnan(across((a + b) / 2 + right * probe));
                }
                segs_.push_back({a, b, rim});
            }
        }
        box_ = r.bbox();
        const double side = std::max(box_.width(), box_.height());
        cells_ = std::max(1, std::min(256, int(std::sqrt(double(segs_.size())))));
        cell_ = side > 0 ? side / cells_ : 1.0;
        buckets_.resize(std::size_t(cells_) * std::size_t(cells_));
        rim_buckets_.resize(buckets_.size());
        for (std::size_t k = 0; k < segs_.size(); ++k) {
            const Seg& s = segs_[k];
            const int x0 = col(std::min(s.a.x, s.b.x)), x1 = col(std::max(s.a.x, s.b.x));
            const int y0 = row(std::min(s.a.y, s.b.y)), y1 = row(std::max(s.a.y, s.b.y));
            for (int y = y0; y <= y1; ++y)
                for (int x = x0; x <= x1; ++x) {
                    const std::size_t b = std::size_t(y) * std::size_t(cells_) + std::size_t(x);
                    buckets_[b].push_back(k);
                    if (s.rim) rim_buckets_[b].push_back(k);
                }
            first_.push_back({x0, y0});
        }
    }

    // The distance from p to the nearest segment within `limit` (+inf when none), and
    // whether that segment is rim.
    // Of segments at the same distance, the one met first in the window of buckets read row
    // by row (each bucket's segments in their order): the first bucket of the window that
    // holds a segment is the corner of the overlap of its buckets with the window, so the
    // buckets farther from p than `limit`, which hold no segment within it, are skipped
    // without changing the answer.
    std::pair<double, bool> nearest(const Point& p, double limit) const {
        const Window w = window(p, limit);
        double best = limit * limit;  // squared distances: one square root per query
        bool rim = false, found = false;
        std::size_t best_first = 0, best_k = 0;  // where the best was met first, and its index
        for (int yy = w.y0; yy <= w.y1; ++yy) {
            if (!w.near_row(*this, p, yy)) continue;
            for (int xx = w.x0; xx <= w.x1; ++xx) {
                if (!w.near_col(*this, p, xx)) continue;
                for (std::size_t k : buckets_[std::size_t(yy) * std::size_t(cells_) + std::size_t(xx)]) {
                    const double d = squared_distance_to(p, segs_[k]);
                    if (d > best) continue;
                    const std::size_t first = std::size_t(std::max(first_[k].y, w.y0)) * std::size_t(cells_) +
                                              std::size_t(std::max(first_[k].x, w.x0));
                    if (d < best || !found || first < best_first || (first == best_first && k < best_k)) {
                        best = d;
                        rim = segs_[k].rim;
                        found = true;
                        best_first = first;
                        best_k = k;
                    }
                }
            }
        }
        return {found ? std::sqrt(best) : INFINITY, rim};
    }

    // The distance from p to the nearest rim segment, up to `limit` (limit when none nearer).
    double to_rim(const Point& p, double limit) const {
        const Window w = window(p, limit);
        const double limit2 = limit * limit;
        double best = limit2;
        for (int yy = w.y0; yy <= w.y1; ++yy) {
            if (!w.near_row(*this, p, yy)) continue;
            for (int xx = w.x0; xx <= w.x1; ++xx)
                if (w.near_col(*this, p, xx))
                    for (std::size_t k : rim_buckets_[std::size_t(yy) * std::size_t(cells_) + std::size_t(xx)])
                        best = std::min(best, squared_distance_to(p, segs_[k]));
        }
        return best < limit2 ? std::min(limit, std::sqrt(best)) : limit;
    }

private:
    struct Seg {
        Point a, b;
        bool rim;
    };
    struct Cell {
        int x, y;
    };
    // The buckets within `limit` of p (by ceil(limit / cell) around its own), and whether a
    // row or a column of them may hold a point within `limit` of p: its band, widened by a
    // rounding margin (and without end on the grid's first and last), reaches p's
    // coordinate within `limit`. A segment within `limit` of p holds a point within it, and
    // lies in that point's bucket.
    struct Window {
        int x0, x1, y0, y1;
        double reach;
        bool near_col(const BorderIndex& b, const Point& p, int c) const {
            const double lo = c == 0 ? -INFINITY : b.box_.xmin + c * b.cell_;
            const double hi = c == b.cells_ - 1 ? INFINITY : b.box_.xmin + (c + 1) * b.cell_;
            return p.x >= lo - reach && p.x <= hi + reach;
        }
        bool near_row(const BorderIndex& b, const Point& p, int r) const {
            const double lo = r == 0 ? -INFINITY : b.box_.ymin + r * b.cell_;
            const double hi = r == b.cells_ - 1 ? INFINITY : b.box_.ymin + (r + 1) * b.cell_;
            return p.y >= lo - reach && p.y <= hi + reach;
        }
    };
    Window window(const Point& p, double limit) const {
        const int r = int(std::ceil(limit / cell_));
        const int x = col(p.x), y = row(p.y);
        return {std::max(0, x - r), std::min(cells_ - 1, x + r), std::max(0, y - r), std::min(cells_ - 1, y + r),
                limit + 1e-6 * cell_};
    }
    static double squared_distance_to(const Point& p, const Seg& s) {
        const Point ab = s.b - s.a;
        const double l2 = dot(ab, ab);
        const double t = l2 > 0 ? std::clamp(dot(p - s.a, ab) / l2, 0.0, 1.0) : 0.0;
        const Point d = p - (s.a + ab * t);
        return dot(d, d);
    }
    int col(double x) const { return std::clamp(int((x - box_.xmin) / cell_), 0, cells_ - 1); }
    int row(double y) const { return std::clamp(int((y - box_.ymin) / cell_), 0, cells_ - 1); }

    std::vector<Seg> segs_;
    BBox box_;
    int cells_ = 1;
    double cell_ = 1;
    std::vector<std::vector<std::size_t>> buckets_;
    std::vector<std::vector<std::size_t>> rim_buckets_;  // the rim segments of each bucket, for to_rim
    std::vector<Cell> first_;                            // each segment's first bucket (lowest row and column)
};

// The polyline pts from its start drawn back to the first point at least `depth` from the rim
// (sampled every depth / 4 along it, then bisected); empty when it never gets that far.
std::vector<Point> draw_back(std::vector<Point> pts, double depth, const BorderIndex& border) {
    const double step = depth / 4;
    auto far_enough = [&](const Point& q) { return border.to_rim(q, depth) >= depth; };
    for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
        const Point a = pts[i], b = pts[i + 1];
        const double l = distance(a, b);
        const int n = std::max(1, int(std::ceil(l / step)));
        double lo = 0;
        for (int k = 1; k <= n; ++k) {
            const double t = double(k) / n;
            if (!far_enough(a + (b - a) * t)) {
                lo = t;
                continue;
            }
            // The first sample far enough: bisect between the last one too close and it.
            double hi = t;
            for (int it = 0; it < kBisections; ++it) {
                const double m = (lo + hi) / 2;
                (far_enough(a + (b - a) * m) ? hi : lo) = m;
            }
            pts[i] = a + (b - a) * hi;
            pts.erase(pts.begin(), pts.begin() + std::ptrdiff_t(i));
            return pts;
        }
    }
    return {};
}

// An end is drawn on past the rim only where its stroke crosses the rim steeply, at 60
// degrees or more: continued at a slant, a stroke runs along the outside of the rim and the
// rock's edge grows hairs. It then lies `depth` beyond the rim within depth / sin 60 degrees.
constexpr double kSteepestTravel = 1.1547005383792515;  // 1 / sin(60 degrees)

// The polyline pts drawn on past the rim from its end: its last segment continued straight
// until the end lies `depth` beyond the rim, outside the region (bisected to that depth),
// at most kSteepestTravel (depth + inset) beyond the old end, `inset` being how far inside
// the rim that end lies. False, pts untouched, when the way goes back into the region, onto
// another face (a value of `across`) or not that far from the rim within that travel (a
// slanting stroke).
bool draw_on(std::vector<Point>& pts, double depth, double inset, const PreparedRegion& region,
             const Field& across, const BorderIndex& border) {
    const Point end = pts.back(), from = pts[pts.size() - 2];
    const double l = distance(from, end);
    if (!(l > 0)) return false;
    const Point dir = (end - from) / l;
    const double step = depth / 8, reach = kSteepestTravel * (depth + inset);
    auto deep_enough = [&](const Point& q) { return border.to_rim(q, depth) >= depth; };
    auto beyond = [&](double t) {
        const Point q = end + dir * t;
        return !region.contains(q) && deep_enough(q);
    };
    bool out = false;
    for (double lo = 0, t = step;; lo = t, t += step) {
        if (t > reach) {
            if (lo >= reach) return false;
            t = reach;  // the last probe at the travel's limit itself
        }
        const Point q = end + dir * t;
        if (!std::isnan(across(q))) return false;
        const bool inside = region.contains(q);
        if (inside && (out || t > depth + inset)) return false;
        out = out || !inside;
        if (inside || !deep_enough(q)) continue;  // beyond(t), the containment already known
        double hi = t;
        for (int it = 0; it < kBisections; ++it) {
            const double m = (lo + hi) / 2;
            (beyond(m) ? hi : lo) = m;
        }
        pts.back() = end + dir * hi;
        return true;
    }
    return false;
}

// The checks of both forms of FrayedCrop.
void check_fray(double min, double max, double beyond) {
    if (!(min >= 0) || !(max >= min) || !std::isfinite(max))
        throw Error("FrayedCrop", "the band must be 0 <= min <= max (got " + std::to_string(min) + ", " +
                                      std::to_string(max) + ")");
    if (!(beyond >= 0 && beyond <= 1))
        throw Error("FrayedCrop", "the share of ends drawn on past the rim must be in [0, 1] (got " +
                                      std::to_string(beyond) + ")");
}

// FrayedCrop on curves already cut to the region, with the operator's stream.
Curves fray_ends(Curves in, const Region& r, double min, double max, const Field& across,
                 const std::vector<std::string>& hard, double beyond, std::uint64_t stream) {
    if (in.curves.empty()) return in;
    const double eps = 1e-7 * std::max({r.bbox().width(), r.bbox().height(), 1.0});
    // Another face across is looked for a little beyond the border.
    const BorderIndex border(r, hard, across, 4 * eps + 0.05 * max);
    const std::uint64_t key = hash_combine(hash_combine(kFrayTag, stream), GetSeed());
    // An end within `min` of the border whose nearest border is rim is drawn back to a
    // depth in [min, max] from the rim (0: it stays).
    const double near = std::max(eps, min);
    // Also how far inside the rim the end lies.
    auto depth_at = [&](const Point& p) -> std::pair<double, double> {
        const auto [d, rim] = border.nearest(p, near);
        if (!rim || !(d <= near)) return {0.0, 0.0};
        return {min + (max - min) * unit_from_hash(hash_point(key, p)), d};
    };
    // Whether an end goes on past the rim (a draw of its own, keyed as its depth is).
    const std::uint64_t side_key = hash_combine(key, 1);
    auto onward = [&](const Point& p) { return beyond > 0 && unit_from_hash(hash_point(side_key, p)) < beyond; };
    // The region prepared once, by the first end that needs it (ends are drawn in parallel).
    std::optional<PreparedRegion> prepared;
    std::once_flag prepare_once;
    auto region = [&]() -> const PreparedRegion& {
        std::call_once(prepare_once, [&] { prepared.emplace(r); });
        return *prepared;
    };
    // Each curve's ends alone: blocks of curves in parallel (a face drawn last shares them
    // with the threads that have run out of faces), the curves kept in their order.
    std::vector<char> keep(in.curves.size(), 1);
    auto fray = [&](Curve& c) -> bool {
        if (c.closed || c.points.size() < 2) return true;
        const Point first = c.points.front(), last = c.points.back();
        const auto [head, head_inset] = depth_at(first);
        const auto [tail, tail_inset] = depth_at(last);
        std::vector<Point> pts = std::move(c.points);
        // Each end on past the rim when its draw says so and the way is free, else back.
        if (head > 0) {
            std::reverse(pts.begin(), pts.end());
            const bool on = onward(first) && draw_on(pts, head, head_inset, region(), across, border);
            std::reverse(pts.begin(), pts.end());
            if (!on) pts = draw_back(std::move(pts), head, border);
        }
        if (tail > 0 && pts.size() >= 2 &&
            !(onward(last) && draw_on(pts, tail, tail_inset, region(), across, border))) {
            std::reverse(pts.begin(), pts.end());
            pts = draw_back(std::move(pts), tail, border);
            std::reverse(pts.begin(), pts.end());
        }
        if (pts.size() < 2) return false;
        c.points = std::move(pts);
        return true;
    };
    constexpr std::size_t kBlock = 256;
    parallel_for((in.curves.size() + kBlock - 1) / kBlock, [&](std::size_t b) {
        for (std::size_t i = b * kBlock; i < std::min(in.curves.size(), (b + 1) * kBlock); ++i)
            keep[i] = fray(in.curves[i]);
    });
    Curves out;
    out.points = std::move(in.points);
    out.origin = std::move(in.origin);
    out.curves.reserve(in.curves.size());
    for (std::size_t i = 0; i < in.curves.size(); ++i)
        if (keep[i]) out.curves.push_back(std::move(in.curves[i]));
    return out;
}

}  // namespace

Arrangement FrayedCrop(Arrangement a, double min, double max, Field across, std::vector<std::string> hard,
                       double beyond) {
    check_fray(min, max, beyond);
    // The stream is fixed now, when the operator is created (random.hpp, "Streams").
    const std::uint64_t stream = NextStream();
    return Arrangement([a = std::move(a), min, max, across = std::move(across), hard = std::move(hard), beyond,
                        stream](const Region& r) {
        return fray_ends(apply_mask(a(r), r, CROP), r, min, max, across, hard, beyond, stream);
    });
}

Curves FrayedCrop(Curves curves, const Region& r, double min, double max, Field across, std::vector<std::string> hard,
                  double beyond) {
    check_fray(min, max, beyond);
    const std::uint64_t stream = NextStream();
    return fray_ends(apply_mask(std::move(curves), r, CROP), r, min, max, across, hard, beyond, stream);
}

}  // namespace tex
