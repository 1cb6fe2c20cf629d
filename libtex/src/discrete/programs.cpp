// The programs of seed 004 (sections 3.1 and 3.3): greedy distribution, relaxation,
// stream lines, and the tangent flow field they follow.
#include <algorithm>
#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>
#include <cmath>
#include <unordered_map>

#include "geometry/segment_index.hpp"
#include "libtex/discrete.hpp"
#include "libtex/error.hpp"

namespace tex::disc {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;

long long greedy_distribution(RegionSet& out, const Condition& loop, const Pinning& pinning,
                              const Shaping& shaping, const Check& check) {
    if (!loop || !pinning || !shaping || !check)
        throw Error("greedy_distribution",
                    "the loop condition, pinning, shaping and check must all be given");
    out.clear();
    long long thrown = 0;
    while (loop()) {
        ++thrown;
        Region r = shaping(pinning());
        if (!r.empty() && check(r)) out.add(std::move(r));
    }
    return thrown;
}

void relaxation(const RegionSet& in, RegionSet& out, const Condition& loop,
                const Reshaping& reshaping, const Repinning& repinning) {
    if (!loop || !reshaping || !repinning)
        throw Error("relaxation", "the loop condition, reshaping and repinning must all be given");
    // The seed writes the new set as Translation(s) applied to the pins; we read it as
    // Lloyd's step: each element goes to the pin of its reshaped cell (moving the cells to
    // their own centroids would leave them where they are).
    std::vector<Region> cur = in.regions();
    while (loop()) {
        const std::vector<Region> shapes = reshaping(cur);
        if (shapes.size() != cur.size())
            throw Error("relaxation", "the reshaping returned " + std::to_string(shapes.size()) +
                                          " shapes for " + std::to_string(cur.size()) +
                                          " elements");
        std::vector<Region> next;
        next.reserve(cur.size());
        for (std::size_t i = 0; i < cur.size(); ++i)
            next.push_back(Translation(cur[i], repinning(shapes[i])));
        cur = std::move(next);
    }
    out.clear();
    for (auto& r : cur) out.add(std::move(r));
}

// ---- Tangent flow field ----

namespace {

using BPoint = bg::model::point<double, 2, bg::cs::cartesian>;
using Sample = std::pair<BPoint, std::size_t>;

struct TangentSample {
    Point tangent;  // unit
    std::size_t region;
};

struct FlowIndex {
    bgi::rtree<Sample, bgi::rstar<16>> tree;
    std::vector<TangentSample> samples;
};

// Regions averaged at a point, and candidates asked of the tree to find them.
constexpr std::size_t kRegionsAveraged = 3;
constexpr unsigned kCandidates = 24;

}  // namespace

FlowField TangentFlowField(const RegionSet& regions, double step) {
    if (regions.empty()) throw Error("TangentFlowField", "needs at least one region");
    if (!(step > 0) || !std::isfinite(step))
        throw Error("TangentFlowField",
                    "the step must be a positive number (got " + std::to_string(step) + ")");
    auto index = std::make_shared<FlowIndex>();
    std::vector<Sample> entries;
    auto add_ring = [&](const std::vector<Point>& ring, std::size_t id) {
        for (std::size_t i = 0; i < ring.size(); ++i) {
            const Point a = ring[i], b = ring[(i + 1) % ring.size()];
            const double l = distance(a, b);
            if (l == 0) continue;
            const int n = std::max(1, int(std::ceil(l / step)));
            for (int k = 0; k < n; ++k) {
                const Point p = a + (b - a) * ((k + 0.5) / n);
                entries.push_back({BPoint(p.x, p.y), index->samples.size()});
                index->samples.push_back({(b - a) / l, id});
            }
        }
    };
    for (std::size_t i = 0; i < regions.size(); ++i) {
        add_ring(regions[i].outer(), i);
        for (const auto& h : regions[i].holes()) add_ring(h, i);
    }
    index->tree = bgi::rtree<Sample, bgi::rstar<16>>(entries.begin(), entries.end());
    return [index, step](const Point& p) -> Point {
        // Nearest sample of each of the nearest regions; tangents are axes, so they are
        // averaged as doubled angles (a tangent and its opposite count the same).
        std::vector<std::pair<double, std::size_t>> near;
        for (auto it = index->tree.qbegin(bgi::nearest(BPoint(p.x, p.y), kCandidates));
             it != index->tree.qend(); ++it)
            near.push_back(
                {distance(p, Point{bg::get<0>(it->first), bg::get<1>(it->first)}), it->second});
        std::sort(near.begin(), near.end());
        std::vector<std::size_t> seen;
        double sx = 0, sy = 0;
        for (const auto& [d, i] : near) {
            const TangentSample& s = index->samples[i];
            if (std::find(seen.begin(), seen.end(), s.region) != seen.end()) continue;
            seen.push_back(s.region);
            const double w = 1.0 / (d * d + 1e-12 * step * step);
            sx += w * (s.tangent.x * s.tangent.x - s.tangent.y * s.tangent.y);
            sy += w * (2 * s.tangent.x * s.tangent.y);
            if (seen.size() == kRegionsAveraged) break;
        }
        if (std::hypot(sx, sy) == 0) return {0, 0};
        const double a = 0.5 * std::atan2(sy, sx);
        return {step * std::cos(a), step * std::sin(a)};
    };
}

// ---- Stream lines ----

namespace {
// Upper bound on the steps of one line (a field of tiny steps must not run forever).
constexpr int kMaxSteps = 100000;

// The segments of a line being traced, in a hash grid, so that a new step can be refused
// when it would cross or touch an earlier, non-adjacent segment (a curve of the seed is
// never self-intersecting). Decided with the exact segment test.
class TracedSegments {
public:
    explicit TracedSegments(double cell) : cell_(cell) {}

    // Whether segment ab meets a segment stored before the last one (the one ending at a).
    bool meets(const Point& a, const Point& b) const {
        bool hit = false;
        visit(a, b, [&](std::size_t i) {
            if (!hit && i + 1 < segs_.size() &&
                tex::detail::segments_touch(a, b, segs_[i].first, segs_[i].second))
                hit = true;
        });
        return hit;
    }
    void add(const Point& a, const Point& b) {
        const std::size_t i = segs_.size();
        segs_.push_back({a, b});
        for_cells(a, b, [&](long long key) { grid_[key].push_back(i); });
    }

private:
    template <class F>
    void for_cells(const Point& a, const Point& b, F&& f) const {
        const long long x0 = cell_of(std::min(a.x, b.x)), x1 = cell_of(std::max(a.x, b.x));
        const long long y0 = cell_of(std::min(a.y, b.y)), y1 = cell_of(std::max(a.y, b.y));
        for (long long x = x0; x <= x1; ++x)
            for (long long y = y0; y <= y1; ++y) f(x * 0x100000000LL + y);
    }
    template <class F>
    void visit(const Point& a, const Point& b, F&& f) const {
        for_cells(a, b, [&](long long key) {
            const auto it = grid_.find(key);
            if (it != grid_.end())
                for (std::size_t i : it->second) f(i);
        });
    }
    long long cell_of(double v) const { return (long long)std::floor(v / cell_); }

    double cell_;
    std::vector<std::pair<Point, Point>> segs_;
    std::unordered_map<long long, std::vector<std::size_t>> grid_;
};
}  // namespace

Polyline trace_stream(const Point& start, const FlowField& flow, const PointCheck& check,
                      double length) {
    if (!flow || !check) throw Error("stream_line", "the flow field and the check must be given");
    if (!(length >= 0) || !std::isfinite(length))
        throw Error("stream_line",
                    "the length must be finite and >= 0 (got " + std::to_string(length) + ")");
    Polyline line;
    line.points.push_back(start);
    Point prev = flow(start);
    if (!(norm(prev) > 0) || !std::isfinite(prev.x + prev.y)) return line;
    if (!check(start + prev)) prev = -prev;  // the first step decides the way
    double done = 0;
    Point cur = start;
    TracedSegments traced(norm(prev));
    for (int i = 0; i < kMaxSteps; ++i) {
        Point v = flow(cur);
        const double l = norm(v);
        if (!(l > 0) || !std::isfinite(l) || done + l > length) break;
        if (dot(v, prev) < 0) v = -v;  // a tangent has no sign: keep going the same way
        const Point next = cur + v;
        if (!check(next) || traced.meets(cur, next)) break;
        traced.add(cur, next);
        line.points.push_back(next);
        done += l;
        cur = next;
        prev = v;
    }
    return line;
}

Region stream_line(const Point& start, const FlowField& flow, const PointCheck& check,
                   double length, const ThicknessFn& thickness, double min_length) {
    if (!thickness) throw Error("stream_line", "the thickness function must be given");
    const Polyline line = trace_stream(start, flow, check, length);
    double l = 0;
    for (std::size_t i = 1; i < line.points.size(); ++i)
        l += distance(line.points[i - 1], line.points[i]);
    if (line.points.size() < 3 || l < min_length || l == 0) return Region();
    return ApplyThickness(Interpolation(line.points), thickness);
}

Shaping stream_line(FlowField flow, PointCheck check, double length, ThicknessFn thickness,
                    double min_length) {
    if (!flow || !check || !thickness)
        throw Error("stream_line", "the flow field, the check and the thickness must be given");
    if (!(length >= 0) || !std::isfinite(length))
        throw Error("stream_line",
                    "the length must be finite and >= 0 (got " + std::to_string(length) + ")");
    return
        [=](const Point& p) { return stream_line(p, flow, check, length, thickness, min_length); };
}

}  // namespace tex::disc
