// Elements of the discrete operator set (seed 004, section 2): contact and distance tests,
// transformations, construction operators and scalar generators.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "geometry/segment_index.hpp"
#include "element_view.hpp"
#include "libtex/error.hpp"
#include "libtex/random.hpp"
#include "libtex/svg.hpp"

namespace tex::disc {
namespace detail {
namespace {

void add_ring(ElementView& v, const std::vector<Point>& ring, bool closed) {
    for (std::size_t i = 0; i + 1 < ring.size(); ++i) v.segs.emplace_back(ring[i], ring[i + 1]);
    if (closed && ring.size() > 2) v.segs.emplace_back(ring.back(), ring.front());
    for (const auto& p : ring) v.box.add(p);
}

BBox seg_box(const std::pair<Point, Point>& s) {
    BBox b;
    b.add(s.first);
    b.add(s.second);
    return b;
}

double point_segment(const Point& p, const Point& a, const Point& b) {
    const Point ab = b - a;
    const double l2 = dot(ab, ab);
    if (l2 == 0) return distance(p, a);
    const double t = std::clamp(dot(p - a, ab) / l2, 0.0, 1.0);
    return distance(p, a + ab * t);
}

double segment_segment(const std::pair<Point, Point>& s, const std::pair<Point, Point>& t) {
    if (tex::detail::segments_touch(s.first, s.second, t.first, t.second)) return 0;
    return std::min(std::min(point_segment(s.first, t.first, t.second),
                             point_segment(s.second, t.first, t.second)),
                    std::min(point_segment(t.first, s.first, s.second),
                             point_segment(t.second, s.first, s.second)));
}

bool contains(const ElementView& v, const Point& p) {
    return v.solid && v.solid->contains(p);
}

}  // namespace

ElementView view_of(const Point& p) {
    ElementView v;
    v.segs.emplace_back(p, p);
    v.probe = p;
    v.box.add(p);
    return v;
}

ElementView view_of(const Polyline& c) {
    if (c.points.empty()) throw Error("Polyline", "a curve needs at least one point");
    ElementView v;
    if (c.points.size() == 1) return view_of(c.points[0]);
    add_ring(v, c.points, c.closed);
    v.probe = c.points.front();
    return v;
}

ElementView view_of(const Region& r) {
    if (r.empty()) throw Error("Region", "an empty region is not an element");
    ElementView v;
    add_ring(v, r.outer(), true);
    for (const auto& h : r.holes()) add_ring(v, h, true);
    v.probe = r.outer().front();
    v.solid = &r;
    return v;
}

// The two tests below visit the segments of `a` whose box meets the other element's box,
// and for each the segments of `b` that meet `a`'s box, in the order of the segments, without
// collecting them first: the elements of a dart throwing have a handful of segments and
// millions of tests run, so a list per test cost more than the tests.
bool overlap(const ElementView& a, const ElementView& b) {
    if (!a.box.intersects(b.box)) return false;
    // Boundary contacts, decided exactly; only the segments inside the other's box can meet.
    for (const auto& s : a.segs) {
        const BBox bs = seg_box(s);
        if (!bs.intersects(b.box)) continue;
        for (const auto& t : b.segs) {
            const BBox bt = seg_box(t);
            if (bt.intersects(a.box) && bs.intersects(bt) &&
                tex::detail::segments_touch(s.first, s.second, t.first, t.second))
                return true;
        }
    }
    // No contact: one lies wholly inside the other or they are apart.
    return contains(b, a.probe) || contains(a, b.probe);
}

double distance(const ElementView& a, const ElementView& b, double stop) {
    if (overlap(a, b)) return 0;
    double best = std::numeric_limits<double>::infinity();
    // With a stop distance only the segments within it of the other element can matter.
    const double reach = stop > 0 ? stop : best;
    const BBox near_a = b.box.expanded(reach), near_b = a.box.expanded(reach);
    for (const auto& s : a.segs) {
        const BBox bs = seg_box(s);
        if (!bs.intersects(near_a)) continue;
        for (const auto& t : b.segs) {
            const BBox bt = seg_box(t);
            if (!bt.intersects(near_b)) continue;
            // The gap between the boxes bounds the distance from below.
            const double gx = std::max({0.0, bt.xmin - bs.xmax, bs.xmin - bt.xmax});
            const double gy = std::max({0.0, bt.ymin - bs.ymax, bs.ymin - bt.ymax});
            // Squared: this test runs for every pair of nearby segments, hypot per pair cost
            // a fifth of a slope-hachure run.
            if (gx * gx + gy * gy >= best * best) continue;
            best = std::min(best, segment_segment(s, t));
            if (best < stop) return best;
        }
    }
    return best;
}

}  // namespace detail

using detail::view_of;

// ---- Operators as values ----

Pinning Sequence(std::vector<Point> points) {
    auto next = std::make_shared<std::size_t>(0);
    auto pts = std::make_shared<const std::vector<Point>>(std::move(points));
    return [pts, next]() -> Point {
        if (*next >= pts->size())
            throw Error("Sequence", "all " + std::to_string(pts->size()) + " points were used");
        return (*pts)[(*next)++];
    };
}

// ---- Construction ----

namespace {

// The generator of a random operator created now: its own stream under the global seed.
std::shared_ptr<KeyedRng> new_rng() {
    return std::make_shared<KeyedRng>(hash_combine(NextStream(), GetSeed()));
}

void check_region(const Region& r, const char* op) {
    if (r.empty() || !(r.area() > 0)) throw Error(op, "the region is empty");
}

// Rejection sampling tries before giving up on a region or density.
constexpr int kMaxTries = 1000000;

}  // namespace

Pinning RandomPinning(const Region& region) {
    return RandomPinning(region, Field(1.0));
}

namespace {
// One try of the rejection sampling: a point of r's box, kept when it lies in r and passes
// the density (a uniform draw below it).
std::optional<Point> try_point(KeyedRng& rng, const Region& r, const Field& density) {
    const BBox& b = r.bbox();
    const Point p{rng.uniform(b.xmin, b.xmax), rng.uniform(b.ymin, b.ymax)};
    const double keep = rng.uniform();
    if (!r.contains(p)) return std::nullopt;
    const double d = density(p);
    if (std::isfinite(d) && keep < std::clamp(d, 0.0, 1.0)) return p;
    return std::nullopt;
}

Error no_point_found(const char* what) {
    return Error("RandomPinning", "no point found in " + std::to_string(kMaxTries) + " tries (" +
                                      what + " nearly empty)");
}
}  // namespace

Pinning RandomPinning(const Region& region, Field density) {
    check_region(region, "RandomPinning");
    auto rng = new_rng();
    return [region, density, rng]() -> Point {
        for (int i = 0; i < kMaxTries; ++i)
            if (const auto p = try_point(*rng, region, density)) return *p;
        throw no_point_found("the region or its density is");
    };
}

Pinning RandomPinning(const std::vector<Region>& pieces, Field density) {
    if (pieces.empty()) throw Error("RandomPinning", "no piece to pin in");
    // Cumulative areas: a piece is drawn with probability proportional to its area, then a
    // point by rejection in its box, so a program pinning in scattered patches (the cells of
    // a mask) does not throw most of its points into the space between them.
    auto cumulative = std::make_shared<std::vector<double>>();
    for (const Region& r : pieces) {
        check_region(r, "RandomPinning");
        cumulative->push_back((cumulative->empty() ? 0.0 : cumulative->back()) + r.area());
    }
    auto shared = std::make_shared<const std::vector<Region>>(pieces);
    auto rng = new_rng();
    return [shared, cumulative, density, rng]() -> Point {
        const std::vector<double>& c = *cumulative;
        for (int i = 0; i < kMaxTries; ++i) {
            const double at = rng->uniform(0.0, c.back());
            const std::size_t k = std::min<std::size_t>(
                std::upper_bound(c.begin(), c.end(), at) - c.begin(), c.size() - 1);
            if (const auto p = try_point(*rng, (*shared)[k], density)) return *p;
        }
        throw no_point_found("the pieces or their density are");
    };
}

std::vector<Point> RegularPinning(const Region& region, int nx, int ny) {
    check_region(region, "RegularPinning");
    if (nx < 1 || ny < 1)
        throw Error("RegularPinning", "the grid needs nx, ny >= 1 (got " + std::to_string(nx) +
                                          ", " + std::to_string(ny) + ")");
    const BBox& b = region.bbox();
    std::vector<Point> out;
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const Point p{b.xmin + (i + 0.5) * b.width() / nx,
                          b.ymin + (j + 0.5) * b.height() / ny};
            if (region.contains(p)) out.push_back(p);
        }
    return out;
}

std::vector<Point> RegularPinning1D(const Polyline& curve, double density) {
    if (!(density > 0) || !std::isfinite(density))
        throw Error("RegularPinning1D",
                    "density must be a positive number (got " + std::to_string(density) + ")");
    if (curve.points.empty()) throw Error("RegularPinning1D", "the curve has no point");
    return PointsAlong(curve.points, curve.closed, density);
}

std::vector<Point> RegularPinning1D(const std::vector<Polyline>& curves, double density) {
    std::vector<Point> out;
    for (const auto& c : curves) {
        const auto p = RegularPinning1D(c, density);
        out.insert(out.end(), p.begin(), p.end());
    }
    return out;
}

Point Centroid(const Region& r) {
    check_region(r, "Centroid");
    // Signed sums over every ring: holes are clockwise, so they subtract themselves.
    double a = 0, cx = 0, cy = 0;
    const Point o = r.outer().front();  // origin shift keeps the sums well conditioned
    auto ring = [&](const std::vector<Point>& pts) {
        for (std::size_t i = 0, j = pts.size() - 1; i < pts.size(); j = i++) {
            const Point p = pts[j] - o, q = pts[i] - o;
            const double w = cross(p, q);
            a += w;
            cx += (p.x + q.x) * w;
            cy += (p.y + q.y) * w;
        }
    };
    ring(r.outer());
    for (const auto& h : r.holes()) ring(h);
    return o + Point{cx, cy} / (3 * a);
}

Point Centroid(const Polyline& c) {
    if (c.points.empty()) throw Error("Centroid", "the curve has no point");
    Point s;
    for (const auto& p : c.points) s += p;
    return s / double(c.points.size());
}

Polyline Contour(const Region& r) {
    check_region(r, "Contour");
    return {r.outer(), true};
}

std::vector<Polyline> Contour(const RegionSet& s) {
    std::vector<Polyline> out;
    for (const auto& r : s.regions()) out.push_back(Contour(r));
    return out;
}

Polyline Interpolation(const std::vector<Point>& points, int subdivisions) {
    if (points.empty()) throw Error("Interpolation", "no point to interpolate");
    if (subdivisions < 1)
        throw Error("Interpolation",
                    "subdivisions must be >= 1 (got " + std::to_string(subdivisions) + ")");
    Polyline out;
    const std::size_t n = points.size();
    if (subdivisions == 1 || n < 3) {
        out.points = points;
        return out;
    }
    // Uniform Catmull-Rom: passes through every point, tangent (p[i+1] - p[i-1]) / 2.
    for (std::size_t i = 0; i + 1 < n; ++i) {
        const Point p0 = points[i == 0 ? 0 : i - 1], p1 = points[i], p2 = points[i + 1],
                    p3 = points[i + 2 < n ? i + 2 : n - 1];
        for (int s = 0; s < subdivisions; ++s) {
            const double t = double(s) / subdivisions, t2 = t * t, t3 = t2 * t;
            out.points.push_back(0.5 *
                                 ((2 * p1) + (p2 - p0) * t + (2 * p0 - 5 * p1 + 4 * p2 - p3) * t2 +
                                  (3 * p1 - p0 - 3 * p2 + p3) * t3));
        }
    }
    out.points.push_back(points.back());
    return out;
}

Region ApplyThickness(const Polyline& curve, const ThicknessFn& thickness) {
    std::vector<Point> pts;
    for (const auto& p : curve.points)
        if (pts.empty() || pts.back() != p) pts.push_back(p);
    if (curve.closed && pts.size() > 1 && pts.front() == pts.back()) pts.pop_back();
    if (pts.size() < 2) throw Error("ApplyThickness", "the curve needs two distinct points");
    const std::size_t n = pts.size();
    const bool closed = curve.closed && n > 2;
    std::vector<double> at(n, 0.0);  // arc length at each point
    for (std::size_t i = 1; i < n; ++i) at[i] = at[i - 1] + distance(pts[i - 1], pts[i]);
    const double total = closed ? at.back() + distance(pts.back(), pts.front()) : at.back();
    auto unit_normal = [](const Point& a, const Point& b) {
        const Point d = b - a;
        return Point{-d.y, d.x} / norm(d);
    };
    std::vector<Point> left, right;
    for (std::size_t i = 0; i < n; ++i) {
        const bool has_prev = closed || i > 0, has_next = closed || i + 1 < n;
        const Point np = has_prev ? unit_normal(pts[(i + n - 1) % n], pts[i]) : Point{};
        const Point nn = has_next ? unit_normal(pts[i], pts[(i + 1) % n]) : Point{};
        Point m = np + nn;
        const double ml = norm(m);
        m = ml > 1e-12 ? m / ml : (has_next ? nn : np);
        // Miter: keep the sides parallel to both segments, but never more than twice as far.
        const double c = std::max(0.5, dot(m, has_next ? nn : np));
        const double w = thickness(total > 0 ? at[i] / total : 0.0);
        if (!std::isfinite(w) || w < 0)
            throw Error("ApplyThickness",
                        "the thickness must be finite and >= 0 (got " + std::to_string(w) + ")");
        left.push_back(pts[i] + m * (0.5 * w / c));
        right.push_back(pts[i] - m * (0.5 * w / c));
    }
    if (closed) {
        // The outer side is the left one of a clockwise curve and the right one of a
        // counter-clockwise curve (the direction Contour gives): the other side is the hole.
        if (signed_area(pts) > 0) return Region(right, {left}, "ApplyThickness");
        return Region(left, {right}, "ApplyThickness");
    }
    std::vector<Point> ring = left;
    ring.insert(ring.end(), right.rbegin(), right.rend());
    return Region(ring, {}, "ApplyThickness");
}

// ---- Transformations ----

namespace {

std::vector<Point> mapped(const std::vector<Point>& pts, const Affine& m) {
    std::vector<Point> out;
    out.reserve(pts.size());
    for (const auto& p : pts) out.push_back(m(p));
    return out;
}

Region mapped(const Region& r, const Affine& m) {
    std::vector<std::vector<Point>> holes;
    for (const auto& h : r.holes()) holes.push_back(mapped(h, m));
    return Region(mapped(r.outer(), m), std::move(holes), "Transformation");
}

void check_finite(double v, const char* op, const char* what) {
    if (!std::isfinite(v)) throw Error(op, std::string(what) + " must be finite");
}

}  // namespace

Region Translation(const Region& r, const Point& p) {
    check_finite(p.x + p.y, "Translation", "the location");
    return mapped(r, Affine::translation(p - Centroid(r)));
}
Polyline Translation(const Polyline& c, const Point& p) {
    check_finite(p.x + p.y, "Translation", "the location");
    return {mapped(c.points, Affine::translation(p - Centroid(c))), c.closed};
}
Point Translation(const Point&, const Point& p) {
    return p;
}

Region Rotation(const Region& r, double angle) {
    check_finite(angle, "Rotation", "the angle");
    return mapped(r, Affine::rotation(angle, Centroid(r)));
}
Polyline Rotation(const Polyline& c, double angle) {
    check_finite(angle, "Rotation", "the angle");
    return {mapped(c.points, Affine::rotation(angle, Centroid(c))), c.closed};
}
Point Rotation(const Point& v, double angle) {
    check_finite(angle, "Rotation", "the angle");
    return Affine::rotation(angle, Point{})(v);
}

namespace {
void check_scale(double s) {
    if (!(s > 0) || !std::isfinite(s))
        throw Error("Scale",
                    "the factor must be a positive number (got " + std::to_string(s) + ")");
}
}  // namespace

Region Scale(const Region& r, double s) {
    check_scale(s);
    return mapped(r, Affine::scaling(s, s, Centroid(r)));
}
Polyline Scale(const Polyline& c, double s) {
    check_scale(s);
    return {mapped(c.points, Affine::scaling(s, s, Centroid(c))), c.closed};
}
Point Scale(const Point& v, double s) {
    check_finite(s, "Scale", "the factor");
    return v * s;
}
std::vector<Region> Scale(const std::vector<Region>& rs, double s) {
    std::vector<Region> out;
    for (const auto& r : rs) out.push_back(Scale(r, s));
    return out;
}

namespace {
// A generator argument that must be there ("no ... generator given" otherwise).
template <class F>
F given(F f, const char* op, const char* what) {
    if (!f) throw Error(op, std::string("no ") + what + " generator given");
    return f;
}
// The generator of op(element, parameter), each drawn anew at every call, the element first.
template <class E, class P, class Op>
RegionGen generated(E element, P parameter, Op op) {
    return [element = std::move(element), parameter = std::move(parameter), op] {
        Region e = element();
        return op(e, parameter());
    };
}
}  // namespace

RegionGen Translation(const Region& r, Pinning p) {
    return Translation(RegionGen(Const(r)), std::move(p));
}
RegionGen Translation(RegionGen r, const Point& p) {
    check_finite(p.x + p.y, "Translation", "the location");
    return Translation(std::move(r), Pinning(Const(p)));
}
RegionGen Translation(RegionGen r, Pinning p) {
    return generated(given(std::move(r), "Translation", "element"), given(std::move(p), "Translation", "location"),
                     [](const Region& e, const Point& q) { return Translation(e, q); });
}
RegionGen Rotation(const Region& r, RealGen angle) {
    return Rotation(RegionGen(Const(r)), std::move(angle));
}
RegionGen Rotation(RegionGen r, double angle) {
    check_finite(angle, "Rotation", "the angle");
    return Rotation(std::move(r), RealGen(Const(angle)));
}
RegionGen Rotation(RegionGen r, RealGen angle) {
    return generated(given(std::move(r), "Rotation", "element"), given(std::move(angle), "Rotation", "angle"),
                     [](const Region& e, double a) { return Rotation(e, a); });
}
RegionGen Scale(const Region& r, RealGen factor) {
    return Scale(RegionGen(Const(r)), std::move(factor));
}
RegionGen Scale(RegionGen r, double factor) {
    check_scale(factor);
    return Scale(std::move(r), RealGen(Const(factor)));
}
RegionGen Scale(RegionGen r, RealGen factor) {
    return generated(given(std::move(r), "Scale", "element"), given(std::move(factor), "Scale", "factor"),
                     [](const Region& e, double f) { return Scale(e, f); });
}

Shaping Translation(Region r) {
    check_region(r, "Translation");
    return [r](const Point& p) { return Translation(r, p); };
}
Shaping Translation(std::function<Region()> gen) {
    if (!gen) throw Error("Translation", "no element generator given");
    return [gen](const Point& p) { return Translation(gen(), p); };
}
Rotator Rotation(double angle) {
    check_finite(angle, "Rotation", "the angle");
    return {Const(angle)};
}
Rotator Rotation(RealGen angle) {
    if (!angle) throw Error("Rotation", "no angle generator given");
    return {std::move(angle)};
}
Scaler Scale(double factor) {
    check_scale(factor);
    return {Const(factor)};
}
Scaler Scale(RealGen factor) {
    if (!factor) throw Error("Scale", "no factor generator given");
    return {std::move(factor)};
}

// ---- Scalars ----

Condition CountUpTo(long long n) {
    if (n < 0) throw Error("CountUpTo", "the count must be >= 0 (got " + std::to_string(n) + ")");
    auto left = std::make_shared<long long>(n);
    return [left] { return (*left)-- > 0; };
}

RealGen RandomR(double a, double b) {
    if (!std::isfinite(a) || !std::isfinite(b) || b < a)
        throw Error("RandomR", "needs finite a <= b (got " + std::to_string(a) + ", " +
                                   std::to_string(b) + ")");
    auto rng = new_rng();
    return [rng, a, b] { return rng->uniform(a, b); };
}

double Distance(const Point& a, const Point& b) {
    return distance(a, b);
}
double Distance(const Point& a, const Polyline& b) {
    return detail::distance(view_of(a), view_of(b));
}
double Distance(const Point& a, const Region& b) {
    return detail::distance(view_of(a), view_of(b));
}
double Distance(const Polyline& a, const Polyline& b) {
    return detail::distance(view_of(a), view_of(b));
}
double Distance(const Polyline& a, const Region& b) {
    return detail::distance(view_of(a), view_of(b));
}
double Distance(const Region& a, const Region& b) {
    return detail::distance(view_of(a), view_of(b));
}

// ---- Input / output ----

Region Image(double width, double height) {
    if (!(width > 0) || !(height > 0) || !std::isfinite(width) || !std::isfinite(height))
        throw Error("Image", "width and height must be positive (got " + std::to_string(width) +
                                 " x " + std::to_string(height) + ")");
    return Region::rectangle(0, 0, width, height);
}

Region BuiltinHatch(double length, double width) {
    if (!(length > 0) || !(width > 0))
        throw Error("BuiltinHatch", "length and width must be positive");
    return Region::rectangle(-length / 2, -width / 2, length / 2, width / 2);
}

Region BuiltinRectangle(double width, double height) {
    if (!(width > 0) || !(height > 0))
        throw Error("BuiltinRectangle", "width and height must be positive");
    return Region::rectangle(-width / 2, -height / 2, width / 2, height / 2);
}

Region BuiltinCircle(double radius, int segments) {
    if (!(radius > 0) || !std::isfinite(radius))
        throw Error("BuiltinCircle", "the radius must be positive");
    if (segments < 3) throw Error("BuiltinCircle", "a circle needs at least 3 segments");
    std::vector<Point> ring;
    for (int i = 0; i < segments; ++i) {
        const double a = 2 * pi * i / segments;
        ring.push_back({radius * std::cos(a), radius * std::sin(a)});
    }
    return Region(ring, {}, "BuiltinCircle");
}

Region UserRegion(const Curves& curves) {
    return FrameRegion(curves, "UserRegion");
}

Curves ToCurves(const Region& r) {
    Curves c;
    if (r.empty()) return c;
    c.curves.push_back({r.outer(), true, {}, {}, {}});
    for (const auto& h : r.holes()) c.curves.push_back({h, true, {}, {}, {}});
    return c;
}
Curves ToCurves(const Polyline& p) {
    Curves c;
    c.curves.push_back({p.points, p.closed, {}, {}, {}});
    return c;
}
Curves ToCurves(const std::vector<Region>& rs) {
    Curves c;
    for (const auto& r : rs) c.append(ToCurves(r));
    return c;
}
Curves ToCurves(const RegionSet& s) {
    return ToCurves(s.regions());
}
Curves ToCurves(const std::vector<Point>& pts) {
    Curves c;
    for (const auto& p : pts) c.points.push_back({p, {}});
    return c;
}

}  // namespace tex::disc
