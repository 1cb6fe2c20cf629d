#include "libtex/mappers.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "libtex/cells.hpp"
#include "libtex/curves.hpp"
#include "libtex/error.hpp"
#include "libtex/labels.hpp"
#include "libtex/random.hpp"

namespace tex {

EdgeMapper JitterEdges(const std::string& label, double theta, double across, double along, double r, double gap,
                       Field gate, double gate_min) {
    const LabelId id = intern_label(label);
    const Point d{std::cos(theta), std::sin(theta)}, n{-d.y, d.x};
    const double half_across = across * r / 2, half_along = along * r / 2;
    // It reads only its edge: MapToEdges runs it on a partition's edges without the map, and
    // only on those with the label.
    return LocalEdgeMapper(
        [=, gate = std::move(gate)](LocalEdge& e, Curves& out) {
        if (gate_min > 0 && !(gate(LocationAt(e, 0.5)) >= gate_min)) return;
        const Point s = e.source(), t = e.target();
        const Point ms = s + n * RandomAtSource(e, -half_across, half_across, 0) +
                         d * RandomAtSource(e, -half_along, half_along, 1);
        const Point mt = t + n * RandomAtTarget(e, -half_across, half_across, 0) +
                         d * RandomAtTarget(e, -half_along, half_along, 1);
        // One curve, the edge's own (LocalEdgeFn: nothing reads the edge after this), moved
        // and shortened where it lies (MatchPoints then Scale, without the copy each makes).
        Curve& c = out.curves.emplace_back(std::move(e.curve));
        detail::match_points_in_place(c, s, t, ms, mt);
        if (gap < 1) detail::scale_in_place(c, gap);
        },
        id);
}

double ThinRank(long long k) {
    constexpr double phi = 0.6180339887498948482;  // (sqrt(5) - 1) / 2
    const double x = double(k) * phi;
    return x - std::floor(x);
}

EdgeMapper ThinLines(EdgeMapper inner, double theta, double spacing, Field keep, Region owner) {
    if (!inner) throw Error("ThinLines", "no inner mapper");
    if (!(spacing > 0) || !std::isfinite(spacing)) throw Error("ThinLines", "the spacing must be positive and finite");
    if (!std::isfinite(theta)) throw Error("ThinLines", "theta must be finite");
    const Point n{-std::sin(theta), std::cos(theta)};
    const bool owned = !owner.empty();
    return [=, inner = std::move(inner), keep = std::move(keep), owner = std::move(owner)](const Edge& e) -> Curves {
        const Point mid = LocationAt(e, 0.5);
        if (owned && !owner.contains(mid)) return Nothing();
        const double t = (mid.x * n.x + mid.y * n.y) / spacing;
        if (!(std::abs(t) < 1e15)) return Nothing();  // beyond exact integers: no line index
        const double k = keep(mid);
        if (!(ThinRank(std::llround(t)) < k)) return Nothing();
        return inner(e);
    };
}

std::vector<Point> CutCorners(std::vector<Point> pts, int passes) {
    for (int r = 0; r < passes && pts.size() >= 3; ++r) {
        std::vector<Point> next;
        next.reserve(2 * pts.size());
        next.push_back(pts.front());
        for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
            const Point &a = pts[i], &b = pts[i + 1];
            if (i > 0) next.push_back(a * 0.75 + b * 0.25);
            if (i + 2 < pts.size()) next.push_back(a * 0.25 + b * 0.75);
        }
        next.push_back(pts.back());
        pts = std::move(next);
    }
    return pts;
}

Curves MovingAverage(const Curves& c, int half_window) {
    if (half_window < 0) throw Error("MovingAverage", "the half window must not be negative");
    Curves out = c;
    for (Curve& cv : out.curves) {
        const std::vector<Point>& p = c.curves[std::size_t(&cv - out.curves.data())].points;
        const long long n = (long long)p.size();
        for (long long i = 0; i < n; ++i) {
            long long w = half_window;
            if (!cv.closed) w = std::min({w, i, n - 1 - i});
            else w = std::min<long long>(w, (n - 1) / 2);
            Point sum{0, 0};
            for (long long k = i - w; k <= i + w; ++k) sum = sum + p[std::size_t(((k % n) + n) % n)];
            cv.points[std::size_t(i)] = sum * (1.0 / double(2 * w + 1));
        }
    }
    return out;
}

namespace {
// The points of a curve in order, a closed one ending on its first point again.
std::vector<Point> open_points(const Curve& c) {
    std::vector<Point> pts = c.points;
    if (c.closed && !pts.empty()) pts.push_back(pts.front());
    return pts;
}

// The curve from its canonical start in its canonical direction (an open one from the
// smaller of its ends, a closed one from its smallest point towards the smaller of that
// point's neighbours), and whether it was turned round: two faces that see one border in
// opposite directions smooth the same line.
Curve canonical(const Curve& c, bool& reversed) {
    Curve out = c;
    reversed = false;
    std::vector<Point>& p = out.points;
    if (p.size() < 2) return out;
    if (!c.closed) {
        if (p.back() < p.front()) {
            std::reverse(p.begin(), p.end());
            reversed = true;
        }
        return out;
    }
    std::rotate(p.begin(), std::min_element(p.begin(), p.end()), p.end());
    if (p.size() > 2 && p.back() < p[1]) {
        std::reverse(p.begin() + 1, p.end());
        reversed = true;
    }
    return out;
}

Curve smoothed(const Curve& in, double step) {
    constexpr int kPasses = 3;  // three rounds: the curvature varies smoothly at the step's scale
    bool reversed = false;
    const Curve c = canonical(in, reversed);
    const std::vector<Point> pts = open_points(c);
    Curve out;
    out.labels = c.labels;
    if (pts.size() < 2) {
        out.points = pts;
        return out;
    }
    // Points every `step` of length from the first (seed 004's regular pinning along a curve).
    std::vector<Point> samples = PointsAlong(pts, false, 1 / step);
    // The last point kept, a sample too close to it dropped (it would make a kink there).
    if (samples.size() > 1 && distance(samples.back(), pts.back()) < step / 2) samples.pop_back();
    samples.push_back(pts.back());
    out.points = CutCorners(std::move(samples), kPasses);
    if (reversed) std::reverse(out.points.begin(), out.points.end());
    return out;
}

// The points along one curve every `spacing`, from half a spacing on (MapAlong).
Curves map_along(const Curve& c, double spacing, const AlongMapper& f) {
    const std::vector<Point> pts = open_points(c);
    double total = 0;
    for (std::size_t i = 0; i + 1 < pts.size(); ++i) total += distance(pts[i], pts[i + 1]);
    Curves out;
    double walked = 0, next = spacing / 2;  // length before segment i, and of the next point
    long long k = 0;
    for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
        const Point a = pts[i], b = pts[i + 1];
        const double l = distance(a, b);
        if (l == 0) continue;
        const Point t = (b - a) * (1 / l);
        for (; next <= walked + l && next <= total; next = (k + 0.5) * spacing) {
            out.append(f(a + (b - a) * ((next - walked) / l), t, k, total - next));
            ++k;
        }
        walked += l;
    }
    return out;
}

}  // namespace

Curves Smoothed(const Curves& c, double step) {
    if (!(step > 0) || !std::isfinite(step)) throw Error("Smoothed", "the step must be positive and finite");
    Curves out = c;
    for (Curve& cv : out.curves) cv = smoothed(cv, step);
    return out;
}

Curves MapAlong(const Curves& c, double spacing, const AlongMapper& f) {
    if (!(spacing > 0) || !std::isfinite(spacing)) throw Error("MapAlong", "the spacing must be positive and finite");
    if (!f) throw Error("MapAlong", "no mapper");
    Curves out;
    for (const Curve& cv : c.curves) out.append(map_along(cv, spacing, f));
    return out;
}

}  // namespace tex
