#include "libtex/cells.hpp"

#include <algorithm>

#include "libtex/error.hpp"
#include "libtex/random.hpp"

namespace tex {
namespace {

template <class C>
void require(const C& c, const char* op) {
    if (!c.valid()) throw Error(op, "invalid cell (not attached to a planar map)");
}

double keyed_random(std::uint64_t key, double min, double max, double n) {
    std::uint64_t h = hash_combine(mix64(GetSeed() ^ 0x4345114cULL), key);
    h = hash_double(h, n);
    return min + (max - min) * unit_from_hash(mix64(h));
}

}  // namespace

const VertexRec& record(const Vertex& v) { require(v, "Vertex"); return v.map().vertices()[v.id()]; }
const EdgeRec& record(const Edge& e) { require(e, "Edge"); return e.map().edges()[e.id()]; }
const FaceRec& record(const Face& f) { require(f, "Face"); return f.map().faces()[f.id()]; }

std::vector<Face> IncidentFaces(const Vertex& v) {
    std::vector<Face> out;
    for (int f : record(v).faces) out.emplace_back(v.map_ptr(), f);
    return out;
}

std::vector<Edge> IncidentEdges(const Vertex& v) {
    std::vector<Edge> out;
    for (int e : record(v).edges) out.emplace_back(v.map_ptr(), e);
    return out;
}

std::vector<Edge> IncidentEdges(const Face& f) {
    std::vector<Edge> out;
    for (int e : record(f).edges) out.emplace_back(f.map_ptr(), e);
    return out;
}

std::vector<Vertex> IncidentVertices(const Face& f) {
    std::vector<Vertex> out;
    for (int v : record(f).vertices) out.emplace_back(f.map_ptr(), v);
    return out;
}

Vertex SourceVertex(const Edge& e) { return Vertex(e.map_ptr(), record(e).source); }
Vertex TargetVertex(const Edge& e) { return Vertex(e.map_ptr(), record(e).target); }
Face LeftFace(const Edge& e) { return Face(e.map_ptr(), record(e).left); }
Face RightFace(const Edge& e) { return Face(e.map_ptr(), record(e).right); }

BBox CellBBox(const Vertex& c) {
    BBox b;
    b.add(record(c).point);
    return b;
}

BBox CellBBox(const Edge& c) {
    BBox b;
    for (const Point& p : record(c).points) b.add(p);
    return b;
}

BBox CellBBox(const Face& c) {
    const FaceRec& r = record(c);
    BBox b;
    if (r.unbounded) return b;
    for (const Point& p : c.map().cycle_points(c.id(), 0)) b.add(p);
    return b;
}

Curves MatchFace(const Curves& c, const Face& f) {
    const BBox cb = c.bbox(), fb = CellBBox(f);
    if (cb.empty() || fb.empty()) return c;
    const double sx = cb.width() > 0 ? fb.width() / cb.width() : 0.0;
    const double sy = cb.height() > 0 ? fb.height() / cb.height() : 0.0;
    double s = (sx > 0 && sy > 0) ? std::min(sx, sy) : std::max(sx, sy);
    if (s == 0) s = 1;
    Curves out = c;
    out.transform(Affine::translation(fb.center() - cb.center())
                      .then_after(Affine::scaling(s, s, cb.center())));
    return out;
}

Point Location(const Vertex& v) { return record(v).point; }

namespace {

// By arc length along a polyline; a closed one runs on back to its first point.
Point location_along(const std::vector<Point>& p, bool closed, double s) {
    const std::size_t n = p.size() + (closed ? 1 : 0);
    auto at = [&](std::size_t i) -> const Point& { return p[i % p.size()]; };
    double total = 0;
    for (std::size_t i = 1; i < n; ++i) total += distance(at(i - 1), at(i));
    if (!(s > 0) || total == 0) return p.front();
    if (s >= 1) return at(n - 1);
    double want = s * total;
    for (std::size_t i = 1; i < n; ++i) {
        const double l = distance(at(i - 1), at(i));
        if (want <= l && l > 0) return at(i - 1) + (at(i) - at(i - 1)) * (want / l);
        want -= l;
    }
    return at(n - 1);
}

}  // namespace

Point LocationAt(const Edge& e, double s) { return location_along(record(e).points, false, s); }

Point Centroid(const Face& f) {
    const FaceRec& r = record(f);
    if (r.unbounded) throw Error("Centroid", "the unbounded face has no centroid");
    double a = 0, cx = 0, cy = 0;
    for (std::size_t k = 0; k < r.cycles.size(); ++k) {
        const auto ring = f.map().cycle_points(f.id(), k);
        for (std::size_t i = 0; i < ring.size(); ++i) {
            const Point& p = ring[i];
            const Point& q = ring[(i + 1) % ring.size()];
            const double w = cross(p, q);
            a += w;
            cx += (p.x + q.x) * w;
            cy += (p.y + q.y) * w;
        }
    }
    if (a == 0) return CellBBox(f).center();
    return {cx / (3 * a), cy / (3 * a)};
}

Curves Contour(const Face& f) {
    const FaceRec& r = record(f);
    Curves out;
    for (const auto& cycle : r.cycles) {
        // A cycle of one loop edge is a closed curve; otherwise one curve per edge, so that
        // the contour's edges stay the face's edges when the contour is induced again.
        if (cycle.size() == 1) {
            const auto& e = f.map().edges()[cycle[0].edge];
            if (e.source == e.target) {
                Curve c;
                c.points.assign(e.points.begin(), e.points.end() - 1);
                if (!cycle[0].left) std::reverse(c.points.begin(), c.points.end());
                c.closed = true;
                c.left = r.labels;
                out.curves.push_back(std::move(c));
                continue;
            }
        }
        for (const Side& s : cycle) {
            const auto& e = f.map().edges()[s.edge];
            Curve c;
            c.points = e.points;
            if (!s.left) std::reverse(c.points.begin(), c.points.end());
            c.left = r.labels;
            out.curves.push_back(std::move(c));
        }
    }
    return out;
}

Curves ToCurve(const Edge& e) {
    Curves out;
    out.curves.push_back(e.map().edge_curve(e.id()));
    return out;
}

Region ToRegion(const Face& f) {
    const FaceRec& r = record(f);
    if (r.unbounded) throw Error("ToRegion", "the unbounded face is not a region");
    std::vector<std::vector<Point>> holes;
    for (std::size_t k = 1; k < r.cycles.size(); ++k) holes.push_back(f.map().cycle_points(f.id(), k));
    Region region(f.map().cycle_points(f.id(), 0), std::move(holes), "ToRegion");
    // The face's edges with their labels, and on their right the labels of the face
    // across, so that what is evaluated on the face can see both.
    Curves edges = Contour(f);
    std::size_t i = 0;
    for (const auto& cycle : r.cycles)
        for (const Side& s : cycle) {
            const EdgeRec& e = f.map().edges()[s.edge];
            Curve& c = edges.curves[i++];
            c.labels = e.labels;
            c.right = f.map().faces()[s.left ? e.right : e.left].labels;
        }
    return region.with_edges(std::move(edges));
}

bool HasLabel(const Vertex& c, const std::string& l) { return record(c).labels.has(l); }
bool HasLabel(const Edge& c, const std::string& l) { return record(c).labels.has(l); }
bool HasLabel(const Face& c, const std::string& l) { return record(c).labels.has(l); }

template <class C>
static bool any_label(const std::vector<C>& cells, const std::string& l) {
    LabelId id;
    if (!find_label(l, id)) return false;
    return std::any_of(cells.begin(), cells.end(), [&](const C& c) { return record(c).labels.has(id); });
}
bool HasLabel(const std::vector<Vertex>& c, const std::string& l) { return any_label(c, l); }
bool HasLabel(const std::vector<Edge>& c, const std::string& l) { return any_label(c, l); }
bool HasLabel(const std::vector<Face>& c, const std::string& l) { return any_label(c, l); }

bool IsBoundary(const Vertex& c) {
    const int u = c.map().unbounded_face();
    const auto& fs = record(c).faces;
    return std::find(fs.begin(), fs.end(), u) != fs.end();
}

bool IsBoundary(const Edge& c) {
    const EdgeRec& r = record(c);
    const int u = c.map().unbounded_face();
    return r.left == u || r.right == u;
}

bool IsBoundary(const Face& c) {
    const FaceRec& r = record(c);
    if (r.unbounded) return true;
    const int u = c.map().unbounded_face();
    for (int e : r.edges) {
        const EdgeRec& er = c.map().edges()[e];
        if (er.left == u || er.right == u) return true;
    }
    return false;
}

double Random(const Vertex& c, double min, double max, double n) { return keyed_random(record(c).key, min, max, n); }
double Random(const Edge& c, double min, double max, double n) { return keyed_random(record(c).key, min, max, n); }
double Random(const Face& c, double min, double max, double n) { return keyed_random(record(c).key, min, max, n); }

LocalEdge AsLocalEdge(const Edge& e) {
    const EdgeRec& r = record(e);
    LocalEdge out;
    out.curve = e.map().edge_curve(e.id());
    out.key = r.key;
    out.source_key = e.map().vertices()[r.source].key;
    out.target_key = e.map().vertices()[r.target].key;
    return out;
}

Point LocationAt(const LocalEdge& e, double s) { return location_along(e.curve.points, e.curve.closed, s); }
double RandomAtSource(const LocalEdge& e, double min, double max, double n) {
    return keyed_random(e.source_key, min, max, n);
}
double RandomAtTarget(const LocalEdge& e, double min, double max, double n) {
    return keyed_random(e.target_key, min, max, n);
}
BBox CellBBox(const LocalEdge& e) {
    BBox b;
    for (const Point& p : e.curve.points) b.add(p);
    return b;
}

}  // namespace tex
