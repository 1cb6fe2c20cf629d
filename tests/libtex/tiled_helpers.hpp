// Comparing two sets of curves as drawings: up to the order of the curves, their direction
// and where a straight run is cut into pieces (a tiled map duplicates a line one period at
// a time; the planar-map engine draws it whole).
#pragma once

#include <algorithm>
#include <iterator>
#include <ostream>
#include <cmath>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "libtex/tex.hpp"

namespace th {

// A maximal straight run of the drawing with its labels: the line (direction, offset),
// the interval along it, and the labels (side labels swapped when the run was reversed).
struct Run {
    long long ax, ay, off;  // quantised direction and offset of the line
    long long t0, t1;       // quantised interval along it
    std::string labels;
    bool operator<(const Run& o) const {
        return std::tie(ax, ay, off, labels, t0, t1) < std::tie(o.ax, o.ay, o.off, o.labels, o.t0, o.t1);
    }
    bool operator==(const Run& o) const {
        return std::tie(ax, ay, off, labels, t0, t1) == std::tie(o.ax, o.ay, o.off, o.labels, o.t0, o.t1);
    }
};

inline std::string label_text(const tex::Labels& l) {
    std::string s;
    for (const auto& n : l.names()) s += n + ",";
    return s;
}

// Canonical form: every segment oriented with its direction in the upper half plane,
// grouped by line and labels, overlapping or touching intervals merged.
inline std::vector<Run> runs(const tex::Curves& c, bool with_side_labels = true, double q = 1e-4) {
    auto Q = [q](double v) { return (long long)std::llround(v / q); };
    std::map<std::tuple<long long, long long, long long, std::string>, std::vector<std::pair<double, double>>> lines;
    for (const auto& cv : c.curves) {
        const std::size_t n = cv.points.size();
        const std::size_t segs = cv.closed ? n : (n ? n - 1 : 0);
        for (std::size_t k = 0; k < segs; ++k) {
            tex::Point a = cv.points[k], b = cv.points[(k + 1) % n];
            tex::Labels left = cv.left, right = cv.right;
            tex::Point d = b - a;
            const double len = tex::norm(d);
            if (len < 1e-9) continue;
            d = d / len;
            if (d.y < -1e-12 || (std::abs(d.y) <= 1e-12 && d.x < 0)) {
                std::swap(a, b);
                std::swap(left, right);
                d = -d;
            }
            const double off = tex::cross(d, a);
            std::string lab = label_text(cv.labels);
            if (with_side_labels) lab += "|" + label_text(left) + "|" + label_text(right);
            // Directions quantised coarsely (1e-6) so that float noise does not split a line.
            auto key = std::make_tuple((long long)std::llround(d.x * 1e6), (long long)std::llround(d.y * 1e6), Q(off), lab);
            lines[key].push_back({tex::dot(a, d), tex::dot(b, d)});
        }
    }
    std::vector<Run> out;
    for (auto& [key, iv] : lines) {
        std::sort(iv.begin(), iv.end());
        double s = iv[0].first, e = iv[0].second;
        const auto& k3 = key;  // a structured binding cannot be captured in C++17 (clang refuses it)
        auto flush = [&] {
            out.push_back({std::get<0>(k3), std::get<1>(k3), std::get<2>(k3), Q(s), Q(e), std::get<3>(k3)});
        };
        for (std::size_t k = 1; k < iv.size(); ++k) {
            if (iv[k].first <= e + q) {
                e = std::max(e, iv[k].second);
            } else {
                flush();
                s = iv[k].first;
                e = iv[k].second;
            }
        }
        flush();
    }
    std::sort(out.begin(), out.end());
    return out;
}

inline std::string run_text(const Run& r) {
    return "dir(" + std::to_string(r.ax) + "," + std::to_string(r.ay) + ") off " + std::to_string(r.off) + " [" +
           std::to_string(r.t0) + ", " + std::to_string(r.t1) + "] " + r.labels;
}
inline void PrintTo(const Run& r, std::ostream* os) { *os << run_text(r); }

// The runs of a not in b and of b not in a (at most `n` of each), for failure messages.
inline std::string run_diff(const std::vector<Run>& a, const std::vector<Run>& b, std::size_t n = 8) {
    std::vector<Run> ab, ba;
    std::set_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(ab));
    std::set_difference(b.begin(), b.end(), a.begin(), a.end(), std::back_inserter(ba));
    std::string s = std::to_string(ab.size()) + " only in the first, " + std::to_string(ba.size()) + " only in the second\n";
    for (std::size_t k = 0; k < ab.size() && k < n; ++k) s += "  < " + run_text(ab[k]) + "\n";
    for (std::size_t k = 0; k < ba.size() && k < n; ++k) s += "  > " + run_text(ba[k]) + "\n";
    return s;
}

#define EXPECT_SAME_RUNS(a, b)                          \
    do {                                                \
        const auto ra_ = (a);                           \
        const auto rb_ = (b);                           \
        EXPECT_TRUE(ra_ == rb_) << th::run_diff(ra_, rb_); \
    } while (0)

// Whole curves, compared up to order and direction only: each curve as text (its points
// rounded to q, its labels, its side labels swapped when it is read backwards; a closed
// curve from its smallest point), the texts sorted.
inline std::vector<std::string> whole_curves(const tex::Curves& c, double q = 1e-4) {
    auto Q = [q](double v) { return (long long)std::llround(v / q); };
    std::vector<std::string> out;
    for (const auto& cv : c.curves) {
        std::vector<std::pair<long long, long long>> pts;
        for (const auto& p : cv.points) pts.emplace_back(Q(p.x), Q(p.y));
        auto text = [&](const std::vector<std::pair<long long, long long>>& v, const tex::Labels& l,
                        const tex::Labels& r) {
            std::string s = std::string(cv.closed ? "closed " : "open ") + label_text(cv.labels) + "|" +
                            label_text(l) + "|" + label_text(r) + " ";
            for (const auto& [x, y] : v) s += "(" + std::to_string(x) + "," + std::to_string(y) + ")";
            return s;
        };
        auto rev = pts;
        std::reverse(rev.begin(), rev.end());
        if (cv.closed && !pts.empty()) {
            std::rotate(pts.begin(), std::min_element(pts.begin(), pts.end()), pts.end());
            std::rotate(rev.begin(), std::min_element(rev.begin(), rev.end()), rev.end());
        }
        out.push_back(std::min(text(pts, cv.left, cv.right), text(rev, cv.right, cv.left)));
    }
    std::sort(out.begin(), out.end());
    return out;
}

inline std::string curve_diff(const std::vector<std::string>& a, const std::vector<std::string>& b,
                              std::size_t n = 6) {
    std::vector<std::string> ab, ba;
    std::set_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(ab));
    std::set_difference(b.begin(), b.end(), a.begin(), a.end(), std::back_inserter(ba));
    std::string s = std::to_string(a.size()) + " and " + std::to_string(b.size()) + " curves; " +
                    std::to_string(ab.size()) + " only in the first, " + std::to_string(ba.size()) +
                    " only in the second\n";
    for (std::size_t k = 0; k < ab.size() && k < n; ++k) s += "  < " + ab[k] + "\n";
    for (std::size_t k = 0; k < ba.size() && k < n; ++k) s += "  > " + ba[k] + "\n";
    return s;
}

// The same whole curves (not only the same drawing: a line cut in two differs).
#define EXPECT_SAME_CURVES(a, b)                                            \
    do {                                                                    \
        const auto ca_ = th::whole_curves(a);                               \
        const auto cb_ = th::whole_curves(b);                               \
        EXPECT_TRUE(ca_ == cb_) << th::curve_diff(ca_, cb_);                \
    } while (0)

// The curves whose every point lies inside the box.
inline tex::Curves inside_box(const tex::Curves& c, const tex::BBox& b) {
    tex::Curves out;
    for (const auto& cv : c.curves) {
        bool in = true;
        for (const auto& p : cv.points) in = in && b.contains(p);
        if (in) out.curves.push_back(cv);
    }
    return out;
}

// The open curves cut at every point of `at` that lies on them (within tol) other than at
// their ends; closed curves as they are. For comparisons where a split at such a point is a
// degenerate case decided by rounding (a line through a shape's corner).
inline tex::Curves split_at_points(const tex::Curves& c, const std::vector<tex::Point>& at, double tol = 1e-6) {
    tex::Curves out;
    out.points = c.points;
    for (const auto& cv : c.curves) {
        if (cv.closed || cv.points.size() < 2) {
            out.curves.push_back(cv);
            continue;
        }
        tex::Curve piece = cv;
        piece.points.assign(1, cv.points.front());
        auto cut = [&](const tex::Point& p) {
            if (tex::distance(p, piece.points.back()) <= tol) return;  // the same point twice
            piece.points.push_back(p);
            out.curves.push_back(piece);
            piece.points.assign(1, p);
        };
        for (std::size_t k = 1; k < cv.points.size(); ++k) {
            const tex::Point a = cv.points[k - 1], b = cv.points[k], d = b - a;
            const double l2 = tex::dot(d, d);
            std::vector<std::pair<double, tex::Point>> on;
            for (const auto& p : at) {
                const double t = l2 > 0 ? tex::dot(p - a, d) / l2 : 0.0;
                if (t <= 0 || t >= 1 || tex::distance(p, a + d * t) > tol) continue;
                if (tex::distance(p, a) <= tol || tex::distance(p, b) <= tol) continue;
                on.emplace_back(t, p);
            }
            std::sort(on.begin(), on.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
            for (const auto& [t, p] : on) cut(p);
            const bool last = k + 1 == cv.points.size();
            bool corner = false;
            for (const auto& p : at) corner = corner || tex::distance(p, b) <= tol;
            if (!last && corner) cut(b);
            else piece.points.push_back(b);
        }
        out.curves.push_back(piece);
    }
    return out;
}

}  // namespace th
