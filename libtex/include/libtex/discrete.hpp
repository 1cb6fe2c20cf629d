// The discrete-texture operator set (seed 004, section 2): elements, operators as values,
// and the dart-throwing, relaxation and stream-line programs built from them.
//
// Elements are plain-double geometry: a point (tex::Point, 0D), a Polyline (1D, open or
// closed, not self-intersecting) and a tex::Region (2D, a polygon with holes). A set of
// regions that grows while a program runs is a RegionSet: it keeps a spatial index so that
// Overlap and MinimalDistance against it look only at nearby members, while the decision
// itself is made on the geometry with exact predicates (segment contacts through CGAL's
// filtered Epick predicates), never on the index's boxes.
//
// Operators are values: each construction or scalar operator has a full form
// (Translation(region, point)) and a partially applied form that returns a callable
// (Translation(region) is a shaping point -> region). Not, And and Compose combine any
// callables; a constant turns into a generator with Const. The names are the seed's; they
// live in tex::disc because libtex already has curve-level Scale / Rotate / Translate.
//
// Randomness follows random.hpp: every random operator (RandomPinning, RandomR) takes a
// stream of its own when it is created (NextStream), and its n-th value is a pure function
// of (stream, n), so a program gives the same bytes on every run and with any number of
// threads. The programs themselves are sequential (a dart depends on the darts before it);
// VoronoiCells merges the cells of its regions in parallel, each by index.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "libtex/curves.hpp"
#include "libtex/fields.hpp"
#include "libtex/geometry.hpp"
#include "libtex/region.hpp"

namespace tex::disc {

// ---- Elements ----

namespace detail {
struct ElementView;
}

// A 1D element: a polyline (closed: the last point joins the first).
struct Polyline {
    std::vector<Point> points;
    bool closed = false;
};

// A set of regions with a spatial index over their bounding boxes (a hash grid for
// the members of common size, an R-tree for the larger ones). Copies share
// the same set (a handle, as in the seed's programs where the predicates built on a set see
// it grow).
class RegionSet {
public:
    RegionSet();
    explicit RegionSet(const std::vector<Region>& regions);

    void add(Region r);  // throws tex::Error on an empty region
    // Many members at once, in order (into an empty set the index is bulk-loaded); throws
    // tex::Error on an empty region, before adding any.
    void add(std::vector<Region> rs);
    void clear();
    std::size_t size() const;
    bool empty() const { return size() == 0; }
    const Region& operator[](std::size_t i) const;
    const std::vector<Region>& regions() const;
    // Indices of the members whose bounding box meets `box` (ascending).
    std::vector<std::size_t> near(const BBox& box) const;
    // Whether hit(i) holds for a member i whose bounding box meets `box`; stops at the first
    // such member (members are visited in no particular order).
    bool any_near(const BBox& box, const std::function<bool(std::size_t)>& hit) const;
    // The segments of member i (internal: what Overlap and MinimalDistance test).
    const detail::ElementView& view(std::size_t i) const;

private:
    struct Impl;
    std::shared_ptr<Impl> impl_;
};

// ---- Operators as values ----

using Condition = std::function<bool()>;               // ∅ -> B (a loop condition)
using Pinning = std::function<Point()>;                // ∅ -> 0D
using Shaping = std::function<Region(const Point&)>;   // 0D -> 2D
using Check = std::function<bool(const Region&)>;      // 2D -> B
using PointCheck = std::function<bool(const Point&)>;  // 0D -> B
using FlowField = std::function<Point(const Point&)>;  // 0D -> 0D (a displacement)
using RealGen = std::function<double()>;               // ∅ -> R
using ThicknessFn = std::function<double(double)>;     // R -> R
using Reshaping = std::function<std::vector<Region>(const std::vector<Region>&)>;  // s(2D) -> s(2D)
using Repinning = std::function<Point(const Region&)>;                             // 2D -> 0D
using RegionGen = std::function<Region()>;                                         // ∅ -> 2D

// Not ∘ f.
template <class F>
auto Not(F f) {
    return [f](const auto&... a) -> bool { return !f(a...); };
}
// And(f, g): both hold (g is not evaluated when f fails).
template <class F, class G>
auto And(F f, G g) {
    return [f, g](const auto&... a) -> bool { return f(a...) && g(a...); };
}
// f ∘ g. With a generator g (no argument) the result is a generator: the seed's type
// override "an (∅ -> T) operator stands for a T".
template <class F, class G>
auto Compose(F f, G g) {
    return [f, g](const auto&... a) { return f(g(a...)); };
}
// A constant as a generator (∅ -> T).
template <class T>
std::function<T()> Const(T value) {
    return [value] { return value; };
}
// A set of points as a pinning (the seed's s(0D) in place of ∅ -> 0D): its points in order;
// asking for more than it has is a tex::Error.
Pinning Sequence(std::vector<Point> points);

// ---- Construction operators ----

// Uniform random points in the region (rejection in its bounding box), from a stream of
// their own. With `density` (a field, e.g. an Image's grey levels, read as an acceptance
// probability clamped to [0, 1]) the points follow that density. Throws tex::Error on an
// empty region, or when a point cannot be found after many tries (the density is ~0).
Pinning RandomPinning(const Region& region);
Pinning RandomPinning(const Region& region, Field density);
// The same in the union of pieces that do not overlap (a point of a shared part would be
// drawn twice as often): a piece is chosen with probability proportional to its area, a
// point in it by rejection in its box. The cost per point does not grow with the empty
// space between scattered pieces, as it does with one region around them all. Throws
// tex::Error on no piece or an empty one.
Pinning RandomPinning(const std::vector<Region>& pieces, Field density);
// The centres of an nx x ny grid over the region's bounding box, those inside the region.
std::vector<Point> RegularPinning(const Region& region, int nx, int ny);
// Points along the curve every 1/density units of length, starting at its first point.
std::vector<Point> RegularPinning1D(const Polyline& curve, double density);
std::vector<Point> RegularPinning1D(const std::vector<Polyline>& curves, double density);
// Area centroid (holes taken out); the vertex mean for a curve.
Point Centroid(const Region& r);
Point Centroid(const Polyline& c);
// A direction field along the boundaries of the regions: at p, the tangents of the nearest
// boundary points of the (up to three) nearest regions, averaged as axes (angle doubled,
// weights 1/d^2), returned as a displacement of length `step`. A tangent has no sign: the
// stream lines keep the sign of their previous step. Throws on an empty set or step <= 0.
FlowField TangentFlowField(const RegionSet& regions, double step);
// The outer ring of a region as a closed curve; of each region of a set.
Polyline Contour(const Region& r);
std::vector<Polyline> Contour(const RegionSet& s);
// A curve through the points: a Catmull-Rom spline with `subdivisions` pieces per span
// (1: the polyline itself).
Polyline Interpolation(const std::vector<Point>& points, int subdivisions = 4);
// The Voronoi cells of a set of regions, cut to `domain`: cells[i] holds the points of the
// domain nearer to regions[i] than to any other region. Computed on the boundaries sampled
// every `spacing` (0: a tenth of the smallest region's mean width) with CGAL's Delaunay
// triangulation; the Voronoi cells of the samples of one region are merged (see
// docs/discrete.md). Throws on fewer than two regions or an empty domain.
std::vector<Region> VoronoiCells(const std::vector<Region>& regions, const BBox& domain,
                                 double spacing = 0);
// Partial form: the reshaping s(2D) -> s(2D) of the relaxation.
Reshaping VoronoiCells(const BBox& domain, double spacing = 0);
// A region around the curve: at arc-length fraction t in [0, 1] its width is thickness(t).
// Throws on a curve of fewer than two distinct points or a negative or non-finite width.
Region ApplyThickness(const Polyline& curve, const ThicknessFn& thickness);

// ---- Transformations ----
// A region or curve is moved so that its centroid lands on p, turned and scaled about its
// centroid; a point is a position (Translation gives p) or a vector (turned and scaled
// about the origin, which is what Rotation ∘ TangentFlowField needs).
Region Translation(const Region& r, const Point& p);
Polyline Translation(const Polyline& c, const Point& p);
Point Translation(const Point& q, const Point& p);
Region Rotation(const Region& r, double angle);
Polyline Rotation(const Polyline& c, double angle);
Point Rotation(const Point& v, double angle);
Region Scale(const Region& r, double s);
Polyline Scale(const Polyline& c, double s);
Point Scale(const Point& v, double s);
std::vector<Region> Scale(const std::vector<Region>& rs, double s);

// The full forms with a generator for the element, the location, the angle or the factor
// (the seed's override: an ∅ -> T operator stands for a T): a generator of regions that
// draws its generators anew at every call, the element first. Rotation(shape, RandomR(0, pi))
// is Compose(Rotation(RandomR(0, pi)), Const(shape)); Translation(shape, pinning) places the
// shape at the pinning's successive points.
RegionGen Translation(const Region& r, Pinning p);
RegionGen Translation(RegionGen r, const Point& p);
RegionGen Translation(RegionGen r, Pinning p);
RegionGen Rotation(const Region& r, RealGen angle);
RegionGen Rotation(RegionGen r, double angle);
RegionGen Rotation(RegionGen r, RealGen angle);
RegionGen Scale(const Region& r, RealGen factor);
RegionGen Scale(RegionGen r, double factor);
RegionGen Scale(RegionGen r, RealGen factor);

// Partial forms. Translation(element) is a shaping; the element may be a generator (a new
// region for every pin).
Shaping Translation(Region r);
Shaping Translation(std::function<Region()> gen);
// Rotation(angle) / Scale(factor) as element -> element operators; the angle or factor may
// be a generator, drawn once per call.
struct Rotator {
    RealGen angle;
    Region operator()(const Region& r) const { return Rotation(r, angle()); }
    Polyline operator()(const Polyline& c) const { return Rotation(c, angle()); }
    Point operator()(const Point& v) const { return Rotation(v, angle()); }
};
struct Scaler {
    RealGen factor;
    Region operator()(const Region& r) const { return Scale(r, factor()); }
    Polyline operator()(const Polyline& c) const { return Scale(c, factor()); }
    Point operator()(const Point& v) const { return Scale(v, factor()); }
};
Rotator Rotation(double angle);
Rotator Rotation(RealGen angle);
Scaler Scale(double factor);
Scaler Scale(RealGen factor);

// ---- Scalar operators ----

// True n times, then false (each copy shares the count).
Condition CountUpTo(long long n);
// Uniform reals in [a, b) from a stream of their own.
RealGen RandomR(double a, double b);
// Smallest distance between two elements (0 when they touch or one contains the other).
double Distance(const Point& a, const Point& b);
double Distance(const Point& a, const Polyline& b);
double Distance(const Point& a, const Region& b);
double Distance(const Polyline& a, const Polyline& b);
double Distance(const Polyline& a, const Region& b);
double Distance(const Region& a, const Region& b);
// Whether the element shares a point with a region of the set (closed sets: touching counts).
bool Overlap(const RegionSet& s, const Point& e);
bool Overlap(const RegionSet& s, const Polyline& e);
bool Overlap(const RegionSet& s, const Region& e);
// Whether the element comes nearer than d to a region of the set (the "too close" test:
// Not ∘ MinimalDistance accepts an element at least d away from every member).
bool MinimalDistance(const RegionSet& s, const Point& e, double d);
bool MinimalDistance(const RegionSet& s, const Polyline& e, double d);
bool MinimalDistance(const RegionSet& s, const Region& e, double d);
// Partial forms (element -> B), for checks and their compositions.
struct OverlapTest {
    RegionSet set;
    template <class E>
    bool operator()(const E& e) const {
        return Overlap(set, e);
    }
};
struct DistanceTest {
    RegionSet set;
    double d;
    template <class E>
    bool operator()(const E& e) const {
        return MinimalDistance(set, e, d);
    }
};
OverlapTest Overlap(const RegionSet& s);
DistanceTest MinimalDistance(const RegionSet& s, double d);

// ---- Input / output ----

// The frame of a width x height image with its lower-left corner at the origin.
Region Image(double width, double height);
// A grey image read from a binary (P5) or text (P2) PGM file: one unit per pixel, y up, the
// first row at the top; values scaled to [0, 1] (0 black). Throws tex::Error naming the
// file on a missing or malformed file.
GridSamples ReadPGM(const std::string& filename);
// The same from the bytes of a PGM file (origin names the source in messages).
GridSamples ParsePGM(const std::string& bytes, const std::string& origin = "<pgm bytes>");
// The frame of a grid.
Region Image(const GridSamples& grid);
// A thin rectangle (length x width) centred on the origin, along x.
Region BuiltinHatch(double length = 24, double width = 3);
// A rectangle (width x height) centred on the origin.
Region BuiltinRectangle(double width = 240, double height = 160);
// A circle of radius r as a polygon of `segments` sides, centred on the origin.
Region BuiltinCircle(double radius = 20, int segments = 40);
// A user region from curves (an SVG file's ImportSVG): the region its closed curves bound
// (FrameRegion: the largest ring outside, the rings inside it holes).
Region UserRegion(const Curves& curves);

// Elements as curves, for the SVG writer and for any mapper of the engine.
Curves ToCurves(const Region& r);
Curves ToCurves(const Polyline& c);
Curves ToCurves(const std::vector<Region>& rs);
Curves ToCurves(const RegionSet& s);
Curves ToCurves(const std::vector<Point>& pts);

// ---- Programs (seed section 3.1 and 3.3) ----

// Dart throwing: out is emptied, then while loop() holds a point is pinned, shaped, and
// the shape is kept when check(shape) holds. An empty shape (a stream line too short to
// thicken) is never kept. Returns the number of darts thrown.
long long greedy_distribution(RegionSet& out, const Condition& loop, const Pinning& pinning,
                              const Shaping& shaping, const Check& check);

// Lloyd-like relaxation: out starts as a copy of in; while loop() holds, the set is
// reshaped (e.g. VoronoiCells), each new shape repinned (e.g. Centroid), and member i of
// out is moved (Translation) to the pin of shape i. Throws when reshaping does not return
// one shape per member.
void relaxation(const RegionSet& in, RegionSet& out, const Condition& loop,
                const Reshaping& reshaping, const Repinning& repinning);

// A stream line: from start, steps of flow (its sign kept from step to step) are taken
// while the next point passes `check`, the length stays within `length` and the step does
// not touch the line's own earlier steps (the curve never crosses itself); the points are
// interpolated and thickened with `thickness`. When the first step fails the check the
// line goes the other way. Returns an empty region when the line is shorter than
// `min_length` (two steps at least).
Region stream_line(const Point& start, const FlowField& flow, const PointCheck& check,
                   double length, const ThicknessFn& thickness, double min_length = 0);
// The polyline only (before interpolation and thickness).
Polyline trace_stream(const Point& start, const FlowField& flow, const PointCheck& check,
                      double length);
// Partial form: the shaping of a greedy distribution of stream lines.
Shaping stream_line(FlowField flow, PointCheck check, double length, ThicknessFn thickness,
                    double min_length = 0);

}  // namespace tex::disc
