// PlanarMap: the planar map induced by a set of curves (thesis 3.2).
//
// Induction runs CGAL's Arrangement_2 over an exact-constructions kernel, with every
// segment carrying the ids of the curves it comes from (consolidated curve data, so
// overlapping curves merge their data). CGAL's vertices and x-monotone segments are then
// grouped into the thesis's cells and frozen into plain tables of vertices, edges and
// faces with their labels, incidences and double coordinates:
//
//  - an edge is a maximal piece of the input curves between two vertices: a chain of CGAL
//    segments that only breaks at a curve end, at a point where more or fewer than two
//    segments meet (an intersection, a branching), where the set of curves the piece comes
//    from changes (curves start or stop overlapping), or at a labelled point;
//  - a vertex is such a break point. The points where a flattened curve bends are not
//    vertices; a closed curve that meets nothing is one edge looping on one vertex (its
//    lexicographically smallest point).
//
// The tables are immutable, so mappers may query them from several threads at once and
// never touch CGAL objects.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "libtex/curves.hpp"
#include "libtex/geometry.hpp"
#include "libtex/labels.hpp"

namespace tex {

class PlanarMap;
using MapPtr = std::shared_ptr<const PlanarMap>;

// One curve an edge was cut from: its index in the induced Curves and whether the curve
// runs the same way as the edge.
struct EdgeSource {
    std::uint32_t curve;
    bool forward;
};

// One side of an edge on a face boundary: the edge and whether the face is on its left.
struct Side {
    int edge;
    bool left;
};

struct VertexRec {
    Point point;
    Labels labels;
    // Incident edges, counter-clockwise around the vertex; a loop appears twice (once per
    // end), so the size is the vertex's degree.
    std::vector<int> edges;
    std::vector<int> faces;  // incident faces, counter-clockwise, without repetition
    std::uint64_t key = 0;   // geometric key for Random(cell, ...)
};

struct EdgeRec {
    int source = -1, target = -1;  // edges are oriented like their first source curve
    // The edge's polyline from its source to its target (at least two points; for a loop
    // the first and last points are both the vertex).
    std::vector<Point> points;
    int left = -1, right = -1;     // faces on each side
    Labels labels, left_labels, right_labels;
    std::vector<EdgeSource> sources;
    std::uint64_t key = 0;
};

struct FaceRec {
    bool unbounded = false;
    Labels labels;
    // Boundary cycles: for a bounded face the first one is the outer boundary
    // (counter-clockwise), the others are holes (clockwise); the unbounded face has only
    // hole cycles. The face is on the left of each traversed side.
    std::vector<std::vector<Side>> cycles;
    std::vector<int> vertices;  // distinct vertices of the boundary, in traversal order
    std::vector<int> edges;     // distinct edges of the boundary, in traversal order
    std::uint64_t key = 0;
};

class PlanarMap {
public:
    // Induces the planar map of the curves (segments of every polyline, split at every
    // intersection, overlaps merged). Zero-length segments are ignored.
    static MapPtr induce(const Curves& curves);

    const std::vector<VertexRec>& vertices() const { return vertices_; }
    const std::vector<EdgeRec>& edges() const { return edges_; }
    const std::vector<FaceRec>& faces() const { return faces_; }
    int unbounded_face() const { return unbounded_; }

    // Point of side s traversed with the face on the left: first point of that side.
    const Point& side_start(const Side& s) const {
        const EdgeRec& e = edges_[s.edge];
        return vertices_[s.left ? e.source : e.target].point;
    }
    // A face boundary cycle as a ring of points (every point of its edges' polylines).
    std::vector<Point> cycle_points(int face, std::size_t cycle) const;
    // Edge e as a curve (its polyline, closed for a loop) carrying its labels and side
    // labels.
    Curve edge_curve(int e) const;
    // Every edge as a curve (the planar map drawn as open polylines).
    Curves edge_curves() const;

private:
    friend struct PlanarMapBuilder;
    std::vector<VertexRec> vertices_;
    std::vector<EdgeRec> edges_;
    std::vector<FaceRec> faces_;
    int unbounded_ = -1;
};

class RegionLocator;  // region.hpp

// Point location in a frozen planar map: the face containing a point, its bounded faces
// (those with area) located by a RegionLocator (region.hpp: a uniform grid of face boxes over
// `area`). A point outside every bounded face is in the unbounded face. A point exactly on an
// edge may be given either side. The cost of a query depends on the faces near the point,
// not on the size of the map.
class FaceLocator {
public:
    // Faces whose box misses `area` are not indexed (default: the whole map's box); a query
    // outside `area` is answered as if in the unbounded face.
    explicit FaceLocator(MapPtr map, std::optional<BBox> area = std::nullopt);
    int face_at(const Point& p) const;
    const PlanarMap& map() const { return *map_; }
    const MapPtr& shared_map() const { return map_; }

private:
    MapPtr map_;
    std::shared_ptr<const RegionLocator> locator_;  // over the bounded faces with area
    std::vector<int> ids_;                          // face id of each of its regions
};

}  // namespace tex
