#include "libtex/curves.hpp"

#include <algorithm>

#include "libtex/error.hpp"

namespace tex {

double signed_area(const std::vector<Point>& ring) {
    double a = 0.0;
    const std::size_t n = ring.size();
    for (std::size_t i = 0; i < n; ++i) a += cross(ring[i], ring[(i + 1) % n]);
    return a / 2;
}

BBox Curves::bbox() const {
    BBox b;
    for (const auto& c : curves)
        for (const auto& p : c.points) b.add(p);
    return b;
}

void Curves::append(const Curves& other) {
    curves.insert(curves.end(), other.curves.begin(), other.curves.end());
    points.insert(points.end(), other.points.begin(), other.points.end());
    if (origin.empty()) origin = other.origin;
}

void Curves::append(Curves&& other) {
    if (curves.empty()) {
        curves = std::move(other.curves);
    } else {
        curves.insert(curves.end(), std::make_move_iterator(other.curves.begin()),
                      std::make_move_iterator(other.curves.end()));
    }
    points.insert(points.end(), other.points.begin(), other.points.end());
    if (origin.empty()) origin = std::move(other.origin);
}

void Curves::transform(const Affine& m) {
    const bool mirror = m.determinant() < 0;
    for (auto& c : curves) {
        for (auto& p : c.points) p = m(p);
        if (mirror) std::swap(c.left, c.right);  // a mirror swaps the sides of a curve
    }
    for (auto& lp : points) lp.point = m(lp.point);
}

Curves Nothing() { return Curves{}; }

Curves Append(const Curves& c1, const Curves& c2) {
    Curves out = c1;
    out.append(c2);
    return out;
}

double BBoxWidth(const Curves& c) { return c.bbox().width(); }
double BBoxHeight(const Curves& c) { return c.bbox().height(); }
Point BBoxCenter(const Curves& c) { return c.bbox().center(); }

static Curves transformed(const Curves& c, const Affine& m) {
    Curves out = c;
    out.transform(m);
    return out;
}

Curves Scale(const Curves& c, double s) { return Scale(c, s, s); }

Curves Scale(const Curves& c, double sx, double sy) {
    return transformed(c, Affine::scaling(sx, sy, BBoxCenter(c)));
}

void detail::scale_in_place(Curves& c, double s) { c.transform(Affine::scaling(s, s, BBoxCenter(c))); }

void detail::scale_in_place(Curve& c, double s) {
    BBox b;  // as Curves::bbox of curves holding c alone
    for (const Point& p : c.points) b.add(p);
    const Affine m = Affine::scaling(s, s, b.center());
    for (Point& p : c.points) p = m(p);
    if (m.determinant() < 0) std::swap(c.left, c.right);
}

Curves Rotate(const Curves& c, double a) {
    return transformed(c, Affine::rotation(a, BBoxCenter(c)));
}

Curves Translate(const Curves& c, const Point& v) {
    return transformed(c, Affine::translation(v));
}

// Applies m, sending the points equal to a source exactly onto its target (rounding would
// leave them a few ulps away, and a curve meant to end on a vertex would then miss it).
static Point map_onto(const Point& p, const Affine& m, const Point* s, const Point* t, std::size_t n) {
    for (std::size_t k = 0; k < n; ++k)
        if (p == s[k]) return t[k];
    return m(p);
}
static void transform_onto(Curve& cv, const Affine& m, const Point* s, const Point* t, std::size_t n) {
    for (auto& p : cv.points) p = map_onto(p, m, s, t, n);
    if (m.determinant() < 0) std::swap(cv.left, cv.right);
}
static void transform_onto(Curves& c, const Affine& m, const Point* s, const Point* t, std::size_t n) {
    for (auto& cv : c.curves) transform_onto(cv, m, s, t, n);
    for (auto& lp : c.points) lp.point = map_onto(lp.point, m, s, t, n);
}

Curves MatchPoint(const Curves& c, const Point& s, const Point& t) {
    Curves out = c;
    transform_onto(out, Affine::translation(t - s), &s, &t, 1);
    return out;
}

// The similarity sending s1 to t1 and s2 to t2.
static Affine similarity(const Point& s1, const Point& s2, const Point& t1, const Point& t2) {
    const Point ds = s2 - s1, dt = t2 - t1;
    const double ls = dot(ds, ds);
    if (ls == 0.0) throw Error("MatchPoints", "the two source points coincide");
    // Complex-number similarity z -> t1 + (dt / ds) * (z - s1).
    const double ra = (dt.x * ds.x + dt.y * ds.y) / ls;
    const double rb = (dt.y * ds.x - dt.x * ds.y) / ls;
    Affine m{ra, -rb, 0, rb, ra, 0};
    m.c = t1.x - (ra * s1.x - rb * s1.y);
    m.f = t1.y - (rb * s1.x + ra * s1.y);
    return m;
}

void detail::match_points_in_place(Curves& c, const Point& s1, const Point& s2, const Point& t1, const Point& t2) {
    const Point src[2] = {s1, s2}, dst[2] = {t1, t2};
    transform_onto(c, similarity(s1, s2, t1, t2), src, dst, 2);
}

void detail::match_points_in_place(Curve& c, const Point& s1, const Point& s2, const Point& t1, const Point& t2) {
    const Point src[2] = {s1, s2}, dst[2] = {t1, t2};
    transform_onto(c, similarity(s1, s2, t1, t2), src, dst, 2);
}

Curves MatchPoints(const Curves& c, const Point& s1, const Point& s2, const Point& t1,
                   const Point& t2) {
    Curves out = c;
    detail::match_points_in_place(out, s1, s2, t1, t2);
    return out;
}

static std::string origin_of(const Curves& c) {
    return c.origin.empty() ? std::string("curves") : "'" + c.origin + "'";
}

Point PointLabeled(const Curves& c, const std::string& l) {
    for (const auto& lp : c.points)
        if (lp.labels.has(l)) return lp.point;
    throw Error("PointLabeled", "no point labelled '" + l + "' in " + origin_of(c));
}

Curves CurveLabeled(const Curves& c, const std::string& l) {
    Curves out;
    out.origin = c.origin;
    for (const auto& cv : c.curves)
        if (cv.labels.has(l)) out.curves.push_back(cv);
    if (out.curves.empty())
        throw Error("CurveLabeled", "no curve labelled '" + l + "' in " + origin_of(c));
    return out;
}

Curves Polyline(std::vector<Point> pts, bool closed) {
    Curves out;
    Curve c;
    c.points = std::move(pts);
    c.closed = closed;
    out.curves.push_back(std::move(c));
    return out;
}

Curves Labelled(const Curves& c, const std::string& l) {
    Curves out = c;
    const LabelId id = intern_label(l);
    for (auto& cv : out.curves) cv.labels.add(id);
    return out;
}

std::vector<Point> PointsAlong(const std::vector<Point>& points, bool closed, double density) {
    const double step = 1.0 / density;
    std::vector<Point> pts = points;
    if (closed) pts.push_back(pts.front());
    std::vector<Point> out{pts.front()};
    double to_next = step;  // length left before the next point
    for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
        const Point a = pts[i], b = pts[i + 1];
        const double l = distance(a, b);
        double at = 0;
        while (l - at >= to_next) {
            at += to_next;
            out.push_back(a + (b - a) * (at / l));
            to_next = step;
        }
        to_next -= l - at;
    }
    // A closed curve must not get its first point twice.
    if (closed && out.size() > 1 && distance(out.back(), out.front()) < 1e-9 * step) out.pop_back();
    return out;
}

}  // namespace tex
