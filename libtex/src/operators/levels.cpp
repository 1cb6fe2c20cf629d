// CutAtLevels: curves cut into rows where a field crosses its levels (strokes that hang in
// rows from the level lines of the elevation, as hachures in bands of rock do).
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "libtex/error.hpp"
#include "libtex/merge.hpp"

namespace tex {
namespace {

// Readings of the field that place a cut on its level line (regula falsi).
constexpr int kRefinements = 4;

// A curve's points with their arc length and field value (samples added between the given
// points at most `sampling` apart).
struct Sampled {
    std::vector<Point> pts;
    std::vector<double> s, v;
    std::vector<char> given;  // a point of the curve, not a sample between two
};

// Fills `out` (a buffer kept from curve to curve).
void sample(const Curve& c, const Field& f, double sampling, Sampled& out) {
    out.pts.clear();
    out.s.clear();
    out.v.clear();
    out.given.clear();
    const std::size_t n = c.points.size() + (c.closed && c.points.size() > 2 ? 1 : 0);
    auto pt = [&](std::size_t i) -> const Point& { return c.points[i < c.points.size() ? i : 0]; };
    double s = 0;
    for (std::size_t i = 0; i < n; ++i) {
        if (i > 0) {
            const Point a = pt(i - 1), b = pt(i);
            const double l = distance(a, b);
            const int n = sampling > 0 ? std::max(1, int(std::ceil(l / sampling))) : 1;
            for (int k = 1; k < n; ++k) {
                const Point p = a + (b - a) * (double(k) / n);
                out.pts.push_back(p);
                out.s.push_back(s + l * k / n);
                out.v.push_back(f(p));
                out.given.push_back(0);
            }
            s += l;
        }
        out.pts.push_back(pt(i));
        out.s.push_back(s);
        out.v.push_back(f(pt(i)));
        out.given.push_back(1);
    }
}

// Where f crosses `level` between a and b (g0 = f(a) - level and g1 = f(b) - level of opposite
// signs, or one zero): the parameter t in [0, 1], by regula falsi whose kept end has its value
// halved at each step (so that neither end sticks), a few readings of f: the cut lies on the
// level line whatever the samples around it.
double crossing(const Field& f, const Point& a, const Point& b, double level, double g0, double g1) {
    double t0 = 0, t1 = 1;
    double t = g0 / (g0 - g1);
    for (int k = 0; k < kRefinements && g0 != g1; ++k) {
        t = t0 - g0 * (t1 - t0) / (g1 - g0);
        const double g = f(a + (b - a) * t) - level;
        if (!std::isfinite(g) || g == 0) break;
        if ((g > 0) == (g0 > 0)) {
            t0 = t;
            g0 = g;
            g1 *= 0.5;
        } else {
            t1 = t;
            g1 = g;
            g0 *= 0.5;
        }
    }
    return std::clamp(t, 0.0, 1.0);
}

// The point at arc length t of a sampled curve, and the curve's own points strictly between
// arc lengths a and b.
Point at(const Sampled& c, double t) {
    auto it = std::upper_bound(c.s.begin(), c.s.end(), t);
    if (it == c.s.begin()) return c.pts.front();
    if (it == c.s.end()) return c.pts.back();
    const std::size_t i = std::size_t(it - c.s.begin());
    const double l = c.s[i] - c.s[i - 1];
    return l > 0 ? c.pts[i - 1] + (c.pts[i] - c.pts[i - 1]) * ((t - c.s[i - 1]) / l) : c.pts[i];
}

std::vector<Point> stretch(const Sampled& c, double a, double b) {
    std::vector<Point> out{at(c, a)};
    for (std::size_t i = 0; i < c.s.size(); ++i)
        if (c.given[i] && c.s[i] > a && c.s[i] < b) out.push_back(c.pts[i]);
    out.push_back(at(c, b));
    return out;
}

}  // namespace

Arrangement CutAtLevels(Arrangement a, Field f, double step, double gap, double sampling) {
    if (!(step > 0) || !std::isfinite(step))
        throw Error("CutAtLevels", "the step between levels must be positive and finite (got " +
                                       std::to_string(step) + ")");
    if (!(gap >= 0) || !std::isfinite(gap))
        throw Error("CutAtLevels", "the gap must be 0 or more (got " + std::to_string(gap) + ")");
    if (!(sampling >= 0) || !std::isfinite(sampling))
        throw Error("CutAtLevels", "the sampling must be 0 or more (got " + std::to_string(sampling) + ")");
    return Arrangement([a = std::move(a), f = std::move(f), step, gap, sampling](const Region& r) {
        Curves in = a(r);
        Curves out;
        out.points = std::move(in.points);
        out.origin = std::move(in.origin);
        out.curves.reserve(in.curves.size());
        Sampled sc;
        std::vector<std::pair<double, double>> cuts;
        for (Curve& c : in.curves) {
            if (c.points.size() < 2) {
                out.curves.push_back(std::move(c));
                continue;
            }
            sample(c, f, sampling, sc);
            const double total = sc.s.back();
            // Stretches taken out: the gap on the higher side of each crossing of a level.
            cuts.clear();
            for (std::size_t i = 0; i + 1 < sc.s.size(); ++i) {
                const double v0 = sc.v[i], v1 = sc.v[i + 1];
                if (!std::isfinite(v0) || !std::isfinite(v1) || v0 == v1) continue;
                const double lo = std::min(v0, v1), hi = std::max(v0, v1);
                // The levels k x step with lo < level <= hi: one met exactly at a sample is
                // crossed by the segment that reaches it, not again by the next.
                for (double k = std::floor(lo / step) + 1; k * step <= hi; ++k) {
                    const double level = k * step;
                    const double t = crossing(f, sc.pts[i], sc.pts[i + 1], level, v0 - level, v1 - level);
                    const double at_s = sc.s[i] + (sc.s[i + 1] - sc.s[i]) * t;
                    if (v0 > v1)
                        cuts.push_back({at_s - gap, at_s});  // going down: the gap lies before
                    else
                        cuts.push_back({at_s, at_s + gap});  // going up: after
                }
            }
            if (cuts.empty()) {
                out.curves.push_back(std::move(c));
                continue;
            }
            std::sort(cuts.begin(), cuts.end());
            // The kept stretches between the cuts.
            double from = 0;
            auto keep = [&](double s0, double s1) {
                s0 = std::max(s0, 0.0);
                s1 = std::min(s1, total);
                if (!(s1 > s0)) return;
                Curve k;
                k.points = stretch(sc, s0, s1);
                k.labels = c.labels;
                k.left = c.left;
                k.right = c.right;
                out.curves.push_back(std::move(k));
            };
            for (const auto& [c0, c1] : cuts) {
                keep(from, c0);
                from = std::max(from, c1);
            }
            keep(from, total);
        }
        return out;
    });
}

}  // namespace tex
