// Apart: curves kept a given distance from other lines (a gap left along them).
#include <algorithm>
#include <cmath>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "libtex/error.hpp"
#include "libtex/merge.hpp"

namespace tex {
namespace {

// The segments of the lines, bucketed on a grid of the distance for "is any within d" queries.
class NearIndex {
public:
    NearIndex(const Curves& lines, double d) : d_(d) {
        for (const Curve& c : lines.curves) {
            const std::size_t n = c.points.size();
            if (n == 1) add(c.points[0], c.points[0]);
            for (std::size_t i = 0; i + 1 < n + (c.closed && n > 2 ? 1 : 0); ++i) add(c.points[i], c.points[(i + 1) % n]);
        }
    }
    bool near(const Point& p) const {
        const long long cx = cell(p.x), cy = cell(p.y);
        for (long long y = cy - 1; y <= cy + 1; ++y)
            for (long long x = cx - 1; x <= cx + 1; ++x) {
                const auto it = buckets_.find(key(x, y));
                if (it == buckets_.end()) continue;
                for (std::size_t s : it->second)
                    if (dist2(p, segs_[s].first, segs_[s].second) < d_ * d_) return true;
            }
        return false;
    }

private:
    long long cell(double v) const { return (long long)std::floor(v / d_); }
    static long long key(long long x, long long y) { return x * 73856093LL ^ y * 19349663LL; }
    static double dist2(const Point& p, const Point& a, const Point& b) {
        const Point ab = b - a;
        const double l2 = dot(ab, ab);
        const double t = l2 > 0 ? std::clamp(dot(p - a, ab) / l2, 0.0, 1.0) : 0.0;
        const Point q = a + ab * t - p;
        return dot(q, q);
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
    double d_;
    std::vector<std::pair<Point, Point>> segs_;
    std::unordered_map<long long, std::vector<std::size_t>> buckets_;
};

}  // namespace

Arrangement Apart(Arrangement a, Curves lines, double distance) {
    if (!(distance > 0) || !std::isfinite(distance))
        throw Error("Apart", "the distance must be positive and finite (got " + std::to_string(distance) + ")");
    auto index = std::make_shared<const NearIndex>(lines, distance);
    return Arrangement([a = std::move(a), index, distance](const Region& r) {
        Curves in = a(r), out;
        out.points = in.points;
        out.origin = in.origin;
        const double step = distance / 8;
        for (const Curve& c : in.curves) {
            const std::size_t n = c.points.size();
            if (n < 2) {
                out.curves.push_back(c);
                continue;
            }
            std::vector<Point> pts = c.points;
            if (c.closed) pts.push_back(pts.front());
            std::vector<std::vector<Point>> pieces;
            std::vector<Point> run;
            bool was_near = index->near(pts[0]);
            if (!was_near) run.push_back(pts[0]);
            auto close_run = [&] {
                if (run.size() >= 2) pieces.push_back(run);
                run.clear();
            };
            for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
                const Point p = pts[i], q = pts[i + 1];
                const int k = std::max(1, int(std::ceil(tex::distance(p, q) / step)));
                Point prev = p;
                for (int j = 1; j <= k; ++j) {
                    const Point s = j == k ? q : p + (q - p) * (double(j) / k);
                    const bool now_near = index->near(s);
                    if (now_near != was_near) {
                        const Point cut = (prev + s) / 2;
                        if (now_near) {
                            run.push_back(cut);
                            close_run();
                        } else {
                            run.push_back(cut);
                        }
                    }
                    if (!now_near && j == k) run.push_back(s);
                    was_near = now_near;
                    prev = s;
                }
            }
            close_run();
            if (pieces.size() == 1 && c.closed && pieces[0].size() == pts.size()) {
                out.curves.push_back(c);  // untouched
                continue;
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
        return out;
    });
}

}  // namespace tex
