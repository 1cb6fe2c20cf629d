// Geometric building blocks of the rock-hatching styles, in plain doubles: they place and
// clip strokes inside one face and never need a planar map (ARCHITECTURE.md, "right tool
// per step"). Every random offset is keyed by a position in the plane and the seed, so a
// face is hatched the same way whichever faces are hatched with it (local control).
#pragma once

#include <cstdint>
#include <vector>

#include "libtex/region.hpp"

namespace carto {

using tex::Point;
using Polyline = std::vector<Point>;

// Pieces of a polyline inside a region (polygon with holes).
std::vector<Polyline> clip_to_region(const Polyline& line, const tex::Region& region);

// The same for many lines against one region: the region's edges are indexed on a grid
// once, so each segment only meets the edges near it.
class RegionClipper {
public:
    explicit RegionClipper(const tex::Region& region);
    std::vector<Polyline> clip(const Polyline& line) const;
    const tex::Region& region() const { return region_; }

private:
    struct Edge {
        Point a, b;
    };
    const tex::Region& region_;
    std::vector<Edge> edges_;
    tex::BBox box_;
    int nx_ = 1, ny_ = 1;
    double cw_ = 1, ch_ = 1;
    std::vector<std::vector<int>> cells_;
};
// Clips a polyline to a convex polygon (counter-clockwise).
std::vector<Polyline> clip_to_convex(const Polyline& line, const std::vector<Point>& convex);
// Intersection of a polygon (any simple ring) with a convex polygon (Sutherland-Hodgman).
std::vector<Point> clip_polygon_convex(const std::vector<Point>& subject, const std::vector<Point>& convex);

// Deterministic jitter in [-1, 1]^2 of a plane position (keyed by the rounded position,
// a stream number and the seed).
Point jitter_at(const Point& p, std::uint64_t seed, std::uint64_t stream);

// Hatch lines at `angle` covering a box: lines every `spacing` along the normal, each broken
// every `length` along the direction; break points are jittered by up to jitter_across x
// spacing / 2 across and jitter_along x length / 2 along. Offsets are anchored to the
// origin of the plane. Returns one polyline per line.
std::vector<Polyline> jittered_lines(const tex::BBox& box, double angle, double spacing, double length,
                                     double jitter_across, double jitter_along, std::uint64_t seed,
                                     std::uint64_t stream);

// Scales each segment of a polyline about its middle (gap < 1 breaks a line into strokes).
std::vector<Polyline> split_strokes(const Polyline& line, double gap);

// Area centroid of a ring.
Point ring_centroid(const std::vector<Point>& ring);
// Ring scaled about its centroid.
std::vector<Point> scale_ring(const std::vector<Point>& ring, double s);

}  // namespace carto
