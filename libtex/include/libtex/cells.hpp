// Cells of a planar map and the mapper built-ins of the thesis's table 3.4.
//
// A cell is a handle (the map it belongs to and its index). Two handles are equal when
// they denote the same cell of the same map, which is what scripts such as
// `face == RightFace(e)` rely on.
#pragma once

#include <string>
#include <vector>

#include "libtex/curves.hpp"
#include "libtex/planar_map.hpp"
#include "libtex/region.hpp"

namespace tex {

template <class Tag>
class Cell {
public:
    Cell() = default;
    Cell(MapPtr map, int id) : map_(std::move(map)), id_(id) {}
    const PlanarMap& map() const { return *map_; }
    const MapPtr& map_ptr() const { return map_; }
    int id() const { return id_; }
    bool valid() const { return map_ != nullptr && id_ >= 0; }
    bool operator==(const Cell& o) const { return map_ == o.map_ && id_ == o.id_; }
    bool operator!=(const Cell& o) const { return !(*this == o); }

private:
    MapPtr map_;
    int id_ = -1;
};

struct VertexTag {};
struct EdgeTag {};
struct FaceTag {};
using Vertex = Cell<VertexTag>;
using Edge = Cell<EdgeTag>;
using Face = Cell<FaceTag>;

// Record accessors.
const VertexRec& record(const Vertex& v);
const EdgeRec& record(const Edge& e);
const FaceRec& record(const Face& f);

// ---- Incidence ----
std::vector<Face> IncidentFaces(const Vertex& v);
std::vector<Edge> IncidentEdges(const Vertex& v);
std::vector<Edge> IncidentEdges(const Face& f);
std::vector<Vertex> IncidentVertices(const Face& f);
Vertex SourceVertex(const Edge& e);
Vertex TargetVertex(const Edge& e);
Face LeftFace(const Edge& e);
Face RightFace(const Edge& e);

// ---- Adjacency ----
// Scales c uniformly and translates it so that its bounding box fits the face's bounding
// box, centred on it.
Curves MatchFace(const Curves& c, const Face& f);

// ---- Geometry ----
Point Location(const Vertex& v);
// Point at parameter s in [0, 1] along the edge, by arc length from its source to its target.
Point LocationAt(const Edge& e, double s);
// Area centroid of the face (holes subtracted).
Point Centroid(const Face& f);
// Boundary of the face, one curve per edge in the order of its boundary cycles (outer
// cycle counter-clockwise, holes clockwise: the face is on the left), each carrying the
// face's labels on its left side; a cycle made of one loop edge is one closed curve. Induced
// again, the contour has the face's edges.
Curves Contour(const Face& f);
// The whole edge as a curve (its polyline; closed for a loop), with its labels and side
// labels.
Curves ToCurve(const Edge& e);
// The face as a region, so that an arrangement can be evaluated on it.
Region ToRegion(const Face& f);

// ---- Labels ----
bool HasLabel(const Vertex& c, const std::string& l);
bool HasLabel(const Edge& c, const std::string& l);
bool HasLabel(const Face& c, const std::string& l);
// True when any cell of the set carries the label.
bool HasLabel(const std::vector<Vertex>& c, const std::string& l);
bool HasLabel(const std::vector<Edge>& c, const std::string& l);
bool HasLabel(const std::vector<Face>& c, const std::string& l);
// Adjacent to the unbounded face (for a face: sharing an edge with it; the unbounded
// face itself is a boundary cell).
bool IsBoundary(const Vertex& c);
bool IsBoundary(const Edge& c);
bool IsBoundary(const Face& c);

// ---- Random ----
// Deterministic value in [min, max): a pure function of the cell's geometry, n and the
// global seed.
double Random(const Vertex& c, double min, double max, double n);
double Random(const Edge& c, double min, double max, double n);
double Random(const Face& c, double min, double max, double n);

// ---- Bounding boxes of cells (table 3.6 accepts cells too) ----
BBox CellBBox(const Vertex& c);
BBox CellBBox(const Edge& c);
BBox CellBBox(const Face& c);
template <class T>
double BBoxWidth(const Cell<T>& c) { return CellBBox(c).width(); }
template <class T>
double BBoxHeight(const Cell<T>& c) { return CellBBox(c).height(); }
template <class T>
Point BBoxCenter(const Cell<T>& c) { return CellBBox(c).center(); }

// ---- Edges read on their own ----
// An edge as a mapper that reads nothing but the edge itself sees it: its whole curve
// (ToCurve: the polyline from its source to its target, closed for a loop, with its labels
// and side labels), its key and its end vertices' keys. A partition that knows its edges
// without inducing the map hands these to such a mapper (LocalEdgeMapper, mapping.hpp).
struct LocalEdge {
    Curve curve;
    std::uint64_t key = 0, source_key = 0, target_key = 0;
    const Point& source() const { return curve.points.front(); }
    const Point& target() const { return curve.closed ? curve.points.front() : curve.points.back(); }
};
// The edge e of its map, read on its own.
LocalEdge AsLocalEdge(const Edge& e);
// LocationAt and CellBBox as for the edge of the map it was read from; its vertices' Random
// through their keys.
Point LocationAt(const LocalEdge& e, double s);
double RandomAtSource(const LocalEdge& e, double min, double max, double n);
double RandomAtTarget(const LocalEdge& e, double min, double max, double n);
BBox CellBBox(const LocalEdge& e);

}  // namespace tex
