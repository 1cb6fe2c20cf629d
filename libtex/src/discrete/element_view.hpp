// Internal: any element (point, polyline, region) seen as a soup of segments plus one probe
// point per connected boundary, which is all that the contact and distance tests need.
#pragma once

#include <utility>
#include <vector>

#include "libtex/discrete.hpp"

namespace tex::disc::detail {

struct ElementView {
    // Segments of the element's boundary (a point is the degenerate segment (p, p)).
    std::vector<std::pair<Point, Point>> segs;
    // A point of the element: if no segment of another element touches this one, the other
    // contains the whole element exactly when it contains this point.
    Point probe;
    // The region when the element has an inside (contains() is asked of it).
    const Region* solid = nullptr;
    BBox box;
};

ElementView view_of(const Point& p);
ElementView view_of(const Polyline& c);
ElementView view_of(const Region& r);

// Whether the two elements share a point (exact segment contacts; containment by a probe).
bool overlap(const ElementView& a, const ElementView& b);
// Smallest distance between the two (0 when they overlap). Stops early and returns a value
// below `stop` as soon as one is found (stop = 0: the exact minimum).
double distance(const ElementView& a, const ElementView& b, double stop = 0);

}  // namespace tex::disc::detail
