// Plain double geometry used for placing elements and for output.
//
// Topology is never decided on these types: planar maps are induced with CGAL's exact
// kernel (planar_map.hpp). Doubles are what mappers see and what affine placement uses
// (ARCHITECTURE.md, "right tool per step").
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace tex {

inline constexpr double pi = 3.14159265358979323846;

struct Point {
    double x = 0.0;
    double y = 0.0;

    Point() = default;
    Point(double x_, double y_) : x(x_), y(y_) {}

    Point operator+(const Point& o) const { return {x + o.x, y + o.y}; }
    Point operator-(const Point& o) const { return {x - o.x, y - o.y}; }
    Point operator*(double s) const { return {x * s, y * s}; }
    Point operator/(double s) const { return {x / s, y / s}; }
    Point operator-() const { return {-x, -y}; }
    Point& operator+=(const Point& o) { x += o.x; y += o.y; return *this; }
    Point& operator-=(const Point& o) { x -= o.x; y -= o.y; return *this; }
    bool operator==(const Point& o) const { return x == o.x && y == o.y; }
    bool operator!=(const Point& o) const { return !(*this == o); }
    bool operator<(const Point& o) const { return x < o.x || (x == o.x && y < o.y); }
};

inline Point operator*(double s, const Point& p) { return p * s; }
inline double dot(const Point& a, const Point& b) { return a.x * b.x + a.y * b.y; }
inline double cross(const Point& a, const Point& b) { return a.x * b.y - a.y * b.x; }
inline double norm(const Point& a) { return std::hypot(a.x, a.y); }
inline double distance(const Point& a, const Point& b) { return norm(a - b); }

// Axis-aligned bounding box; empty until a point is added.
struct BBox {
    double xmin = std::numeric_limits<double>::infinity();
    double ymin = std::numeric_limits<double>::infinity();
    double xmax = -std::numeric_limits<double>::infinity();
    double ymax = -std::numeric_limits<double>::infinity();

    bool empty() const { return xmin > xmax; }
    void add(const Point& p) {
        if (p.x < xmin) xmin = p.x;
        if (p.x > xmax) xmax = p.x;
        if (p.y < ymin) ymin = p.y;
        if (p.y > ymax) ymax = p.y;
    }
    void add(const BBox& b) {
        if (b.empty()) return;
        add(Point{b.xmin, b.ymin});
        add(Point{b.xmax, b.ymax});
    }
    double width() const { return empty() ? 0.0 : xmax - xmin; }
    double height() const { return empty() ? 0.0 : ymax - ymin; }
    Point center() const { return empty() ? Point{} : Point{(xmin + xmax) / 2, (ymin + ymax) / 2}; }
    bool intersects(const BBox& b) const {
        return !(b.xmin > xmax || b.xmax < xmin || b.ymin > ymax || b.ymax < ymin);
    }
    bool contains(const Point& p) const {
        return p.x >= xmin && p.x <= xmax && p.y >= ymin && p.y <= ymax;
    }
    // The common part (xmin > xmax or ymin > ymax when the boxes do not meet).
    BBox intersection(const BBox& b) const {
        return {std::max(xmin, b.xmin), std::max(ymin, b.ymin), std::min(xmax, b.xmax), std::min(ymax, b.ymax)};
    }
    BBox expanded(double m) const {
        BBox r = *this;
        r.xmin -= m; r.ymin -= m; r.xmax += m; r.ymax += m;
        return r;
    }
};

// 2x3 affine map p -> (a*x + b*y + c, d*x + e*y + f).
struct Affine {
    double a = 1, b = 0, c = 0, d = 0, e = 1, f = 0;

    Point operator()(const Point& p) const { return {a * p.x + b * p.y + c, d * p.x + e * p.y + f}; }
    // (*this)(o(p))
    Affine then_after(const Affine& o) const {
        return {a * o.a + b * o.d, a * o.b + b * o.e, a * o.c + b * o.f + c,
                d * o.a + e * o.d, d * o.b + e * o.e, d * o.c + e * o.f + f};
    }
    double determinant() const { return a * e - b * d; }

    static Affine translation(const Point& v) { return {1, 0, v.x, 0, 1, v.y}; }
    static Affine scaling(double sx, double sy, const Point& about) {
        return {sx, 0, about.x - sx * about.x, 0, sy, about.y - sy * about.y};
    }
    static Affine rotation(double angle, const Point& about) {
        const double cs = std::cos(angle), sn = std::sin(angle);
        return {cs, -sn, about.x - cs * about.x + sn * about.y,
                sn, cs, about.y - sn * about.x - cs * about.y};
    }
};

// Signed area of a closed ring (positive when counter-clockwise in a y-up frame).
double signed_area(const std::vector<Point>& ring);

}  // namespace tex
