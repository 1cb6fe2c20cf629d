// Curves: what every arrangement returns and every mapper produces.
//
// A curve is a polyline (open or closed) that carries its own labels: edge labels, and the
// labels of the faces on its left and on its right. Face labels of a planar map are rebuilt
// from these side labels each time the map is induced (thesis 3.2, "face labels
// reconstruction"). Labelled points ("start", "end", or vertex labels of a partition) ride
// along with the curves and follow every transformation.
#pragma once

#include <string>
#include <vector>

#include "libtex/geometry.hpp"
#include "libtex/labels.hpp"

namespace tex {

struct Curve {
    std::vector<Point> points;
    bool closed = false;
    Labels labels;  // labels of the edges this curve induces
    Labels left;    // labels of the face on the left of the curve's direction
    Labels right;   // labels of the face on the right
};

struct LabeledPoint {
    Point point;
    Labels labels;
};

class Curves {
public:
    Curves() = default;

    std::vector<Curve> curves;
    std::vector<LabeledPoint> points;
    // Where the curves came from (an SVG file name), for error messages.
    std::string origin;

    bool empty() const { return curves.empty() && points.empty(); }
    std::size_t size() const { return curves.size(); }
    BBox bbox() const;
    // Appends other's curves and points (the origin of *this is kept when set).
    void append(const Curves& other);
    void append(Curves&& other);
    // Applies an affine map to every point (direction of closed curves is fixed up when
    // the map mirrors, so that left stays left).
    void transform(const Affine& m);
};

// ---- Table 3.6 utilities and the adjacency built-ins of table 3.4 on curves ----

// An empty set of curves.
Curves Nothing();
// Appends c2 to c1 and returns the new set.
Curves Append(const Curves& c1, const Curves& c2);
double BBoxWidth(const Curves& c);
double BBoxHeight(const Curves& c);
Point BBoxCenter(const Curves& c);
// Points along the polyline `pts` (closed: back to its first point) every 1 / density of
// arc length, from its first point (seed 004's regular pinning along a curve; a closed
// curve does not get its first point twice). density > 0 and pts not empty (unchecked).
std::vector<Point> PointsAlong(const std::vector<Point>& pts, bool closed, double density);
// Scales c by s (or sx, sy) about the centre of its bounding box.
Curves Scale(const Curves& c, double s);
Curves Scale(const Curves& c, double sx, double sy);
// Rotates c by the angle a (radians, counter-clockwise) about the centre of its bounding box.
Curves Rotate(const Curves& c, double a);
// Translates c by v.
Curves Translate(const Curves& c, const Point& v);
// Translates c by t - s; a point of c equal to s lands exactly on t.
Curves MatchPoint(const Curves& c, const Point& s, const Point& t);
// Applies the similarity (rotation, uniform scale, translation) that sends s1 to t1 and
// s2 to t2; points of c equal to s1 or s2 land exactly on t1 or t2 (so that an element
// matched between two vertices ends on them, not a rounding error away).
Curves MatchPoints(const Curves& c, const Point& s1, const Point& s2, const Point& t1,
                   const Point& t2);
// The location of the first point of c labelled l; throws when there is none.
Point PointLabeled(const Curves& c, const std::string& l);
// The curves of c labelled l; throws when there is none.
Curves CurveLabeled(const Curves& c, const std::string& l);
// c with the edge label l added to every curve (to tell kinds of strokes apart downstream).
Curves Labelled(const Curves& c, const std::string& l);
// A single polyline as curves.
Curves Polyline(std::vector<Point> pts, bool closed = false);

namespace detail {
// MatchPoints(c, ...) and Scale(c, s) applied to c itself (the same arithmetic, so the same
// points), for mappers that would otherwise copy every curve once per step; on one curve,
// what they give on curves holding that curve alone.
void match_points_in_place(Curves& c, const Point& s1, const Point& s2, const Point& t1, const Point& t2);
void scale_in_place(Curves& c, double s);
void match_points_in_place(Curve& c, const Point& s1, const Point& s2, const Point& t1, const Point& t2);
void scale_in_place(Curve& c, double s);
}  // namespace detail

}  // namespace tex
