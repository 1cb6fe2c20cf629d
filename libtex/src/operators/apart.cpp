// Apart: curves kept a given distance from other lines (a gap left along them).
#include <algorithm>
#include <cmath>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "libtex/error.hpp"
#include "libtex/merge.hpp"
#include "libtex/parallel.hpp"

namespace tex {
namespace {

// The segments of the lines, bucketed on a grid of eight times the distance: which stretches
// of a segment come within the distance of them.
class NearIndex {
public:
    NearIndex(const Curves& lines, double d) : d_(d), bucket_(8 * d) {
        for (const Curve& c : lines.curves) {
            const std::size_t n = c.points.size();
            if (n == 1) add(c.points[0], c.points[0]);
            for (std::size_t i = 0; i + 1 < n + (c.closed && n > 2 ? 1 : 0); ++i) add(c.points[i], c.points[(i + 1) % n]);
        }
    }
    bool empty() const { return segs_.empty(); }
    // The parameters t in [0, 1] of p + t (q - p) within the distance of a line, as sorted,
    // merged intervals: the line through p and q meets each segment's capsule (a convex set)
    // in one interval, the union of its meetings with the two end discs and the band between.
    // `seen` is the caller's scratch (one per thread).
    std::vector<std::pair<double, double>> near(const Point& p, const Point& q, std::vector<std::size_t>& seen) const {
        std::vector<std::pair<double, double>> out;
        const long long x0 = cell(std::min(p.x, q.x) - d_), x1 = cell(std::max(p.x, q.x) + d_);
        const long long y0 = cell(std::min(p.y, q.y) - d_), y1 = cell(std::max(p.y, q.y) + d_);
        seen.clear();
        const Point v = q - p;
        for (long long y = y0; y <= y1; ++y)
            for (long long x = x0; x <= x1; ++x) {
                const auto it = buckets_.find(key(x, y));
                if (it == buckets_.end()) continue;
                for (std::size_t s : it->second) {
                    const auto& [a, b] = segs_[s];
                    if (std::max(a.x, b.x) + d_ < std::min(p.x, q.x) || std::min(a.x, b.x) - d_ > std::max(p.x, q.x) ||
                        std::max(a.y, b.y) + d_ < std::min(p.y, q.y) || std::min(a.y, b.y) - d_ > std::max(p.y, q.y))
                        continue;
                    if (std::find(seen.begin(), seen.end(), s) != seen.end()) continue;
                    seen.push_back(s);
                    double lo = INFINITY, hi = -INFINITY;
                    capsule(p, v, segs_[s].first, segs_[s].second, lo, hi);
                    lo = std::max(lo, 0.0);
                    hi = std::min(hi, 1.0);
                    if (lo < hi) out.push_back({lo, hi});
                }
            }
        std::sort(out.begin(), out.end());
        std::vector<std::pair<double, double>> merged;
        for (const auto& iv : out) {
            if (!merged.empty() && iv.first <= merged.back().second) merged.back().second = std::max(merged.back().second, iv.second);
            else merged.push_back(iv);
        }
        return merged;
    }

private:
    long long cell(double v) const { return (long long)std::floor(v / bucket_); }
    static long long key(long long x, long long y) { return x * 73856093LL ^ y * 19349663LL; }
    // Widens [lo, hi] by the t where |p + t v - c| < d.
    void disc(const Point& p, const Point& v, const Point& c, double& lo, double& hi) const {
        const Point w = p - c;
        const double a = dot(v, v), b = 2 * dot(v, w), k = dot(w, w) - d_ * d_;
        if (a == 0) {
            if (k < 0) lo = -INFINITY, hi = INFINITY;
            return;
        }
        const double disc = b * b - 4 * a * k;
        if (disc <= 0) return;
        const double r = std::sqrt(disc);
        lo = std::min(lo, (-b - r) / (2 * a));
        hi = std::max(hi, (-b + r) / (2 * a));
    }
    // The t where a linear function f0 + t f1 lies in [a, b], intersected into [lo, hi].
    static void clip(double f0, double f1, double a, double b, double& lo, double& hi) {
        if (f1 == 0) {
            if (f0 < a || f0 > b) lo = INFINITY, hi = -INFINITY;
            return;
        }
        double t0 = (a - f0) / f1, t1 = (b - f0) / f1;
        if (t0 > t1) std::swap(t0, t1);
        lo = std::max(lo, t0);
        hi = std::min(hi, t1);
    }
    void capsule(const Point& p, const Point& v, const Point& a, const Point& b, double& lo, double& hi) const {
        disc(p, v, a, lo, hi);
        disc(p, v, b, lo, hi);
        const double l = distance(a, b);
        if (l == 0) return;
        const Point u = (b - a) * (1 / l), n{-u.y, u.x};
        double blo = -INFINITY, bhi = INFINITY;
        clip(dot(p - a, u), dot(v, u), 0, l, blo, bhi);
        clip(dot(p - a, n), dot(v, n), -d_, d_, blo, bhi);
        if (blo < bhi) lo = std::min(lo, blo), hi = std::max(hi, bhi);
    }
    void add(const Point& a, const Point& b) {
        const std::size_t s = segs_.size();
        segs_.push_back({a, b});
        for (long long y = cell(std::min(a.y, b.y)); y <= cell(std::max(a.y, b.y)); ++y)
            for (long long x = cell(std::min(a.x, b.x)); x <= cell(std::max(a.x, b.x)); ++x) {
                auto& v = buckets_[key(x, y)];
                if (v.empty() || v.back() != s) v.push_back(s);
            }
    }
    double d_, bucket_;
    std::vector<std::pair<Point, Point>> segs_;
    std::unordered_map<long long, std::vector<std::size_t>> buckets_;
};

// The pieces of `c` farther than the index's distance from its lines, appended to `out`
// (c itself, moved, when nothing comes near it).
void keep_apart(Curve& c, const NearIndex& index, std::vector<std::size_t>& seen, Curves& out) {
    const std::size_t n = c.points.size();
    if (n < 2) {
        out.curves.push_back(std::move(c));
        return;
    }
    // The points walked: the curve's own, closed by its first point again when closed.
    std::vector<Point> closed_pts;
    if (c.closed) {
        closed_pts.reserve(n + 1);
        closed_pts = c.points;
        closed_pts.push_back(c.points.front());
    }
    const std::vector<Point>& pts = c.closed ? closed_pts : c.points;
    std::vector<std::vector<Point>> pieces;
    std::vector<Point> run;
    bool cut = false;
    for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
        const Point p = pts[i], q = pts[i + 1];
        const std::vector<std::pair<double, double>> near = index.near(p, q, seen);
        if (!cut) {
            // Until the first cut the run is the curve's points so far: made only when a cut
            // comes (most curves have none and are moved out whole).
            if (near.empty()) continue;
            run.assign(pts.begin(), pts.begin() + std::ptrdiff_t(i) + 1);
        }
        double from = 0;  // the kept stretch of this segment starts here
        for (const auto& [t0, t1] : near) {
            cut = true;
            if (t0 > from) {
                if (run.empty()) run.push_back(p + (q - p) * from);
                run.push_back(p + (q - p) * t0);
            }
            if (run.size() >= 2) pieces.push_back(run);
            run.clear();
            from = t1;
        }
        if (from < 1) {
            if (run.empty()) run.push_back(p + (q - p) * from);
            run.push_back(q);
        }
    }
    if (!cut) {
        out.curves.push_back(std::move(c));  // untouched
        return;
    }
    if (run.size() >= 2) pieces.push_back(run);
    // A closed curve kept through its first point: the pieces before and after that point are
    // one piece (wherever the curve happened to start).
    if (c.closed && pieces.size() >= 2 && pieces.front().front() == pts.front() && pieces.back().back() == pts.back()) {
        std::vector<Point>& last = pieces.back();
        last.insert(last.end(), pieces.front().begin() + 1, pieces.front().end());
        pieces.erase(pieces.begin());
    }
    for (auto& piece : pieces) {
        Curve k;
        k.points = std::move(piece);
        k.labels = c.labels;
        k.left = c.left;
        k.right = c.right;
        out.curves.push_back(std::move(k));
    }
}

}  // namespace

Arrangement Apart(Arrangement a, Curves lines, double distance) {
    if (!(distance > 0) || !std::isfinite(distance))
        throw Error("Apart", "the distance must be positive and finite (got " + std::to_string(distance) + ")");
    auto lines_ptr = std::make_shared<const Curves>(std::move(lines));
    return Arrangement([a = std::move(a), lines_ptr, distance](const Region& r) {
        Curves in = a(r);
        const NearIndex index(*lines_ptr, distance);
        if (index.empty()) return in;
        // Blocks of curves apart, each with its own query buffer (a face drawn last shares
        // them with the threads that have run out of faces), their pieces kept in order.
        constexpr std::size_t kBlock = 256;
        std::vector<Curves> blocks((in.curves.size() + kBlock - 1) / kBlock);
        parallel_for(blocks.size(), [&](std::size_t b) {
            blocks[b].curves.reserve(std::min(kBlock, in.curves.size() - b * kBlock));  // one piece a curve, mostly
            std::vector<std::size_t> seen;
            for (std::size_t i = b * kBlock; i < std::min(in.curves.size(), (b + 1) * kBlock); ++i)
                keep_apart(in.curves[i], index, seen, blocks[b]);
        });
        Curves out;
        out.points = std::move(in.points);
        out.origin = std::move(in.origin);
        std::size_t total = 0;
        for (const Curves& b : blocks) total += b.curves.size();
        out.curves.reserve(total);
        for (Curves& b : blocks)
            for (Curve& c : b.curves) out.curves.push_back(std::move(c));
        return out;
    });
}

}  // namespace tex
