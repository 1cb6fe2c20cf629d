#include "carto/partition.hpp"

#include <cpl_vsi.h>
#include <gdal_priv.h>
#include <ogr_geometry.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <unordered_map>

#include "carto/error.hpp"
#include "libtex/parallel.hpp"
#include "gdal_scope.hpp"

namespace carto {
namespace {

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

bool parse_kind(const std::string& raw, LineKind& out) {
    const std::string v = lower(raw);
    if (v == "ridge" || v == "crete" || v == "crête" || v == "arete" || v == "arête") out = LineKind::Ridge;
    else if (v == "valley" || v == "thalweg" || v == "talweg" || v == "couloir") out = LineKind::Valley;
    else if (v == "cliff" || v == "falaise" || v == "wand") out = LineKind::Cliff;
    else if (v == "other" || v == "" || v == "boundary" || v == "limit") out = LineKind::Other;
    else return false;
    return true;
}

OGRwkbGeometryType flat(OGRLayer* l) { return wkbFlatten(l->GetGeomType()); }
bool is_polygon_layer(OGRLayer* l) { return flat(l) == wkbPolygon || flat(l) == wkbMultiPolygon; }
bool is_line_layer(OGRLayer* l) { return flat(l) == wkbLineString || flat(l) == wkbMultiLineString; }

struct Reprojector {
    std::unique_ptr<OGRCoordinateTransformation> ct;  // none: the layer is in the working CRS
    void apply(OGRGeometry* g) const {
        if (ct) g->transform(ct.get());
    }
};

// Restricts a layer to the features meeting `box` (working CRS): through the layer's own
// spatial filter (its index) when it is in the working CRS, else by `keep` on each feature
// once reprojected.
void filter_layer(OGRLayer* layer, const Reprojector& proj, const std::optional<tex::BBox>& box);
bool keep(const OGRGeometry* reprojected, const std::optional<tex::BBox>& box) {
    if (!box) return true;
    OGREnvelope e;
    reprojected->getEnvelope(&e);
    return !(e.MaxX < box->xmin || e.MinX > box->xmax || e.MaxY < box->ymin || e.MinY > box->ymax);
}

std::string wkt2(const OGRSpatialReference& srs) {
    const char* const options[] = {"FORMAT=WKT2_2019", nullptr};
    char* wkt = nullptr;
    std::string out;
    if (srs.exportToWkt(&wkt, options) == OGRERR_NONE && wkt) out = wkt;
    CPLFree(wkt);
    return out;
}

// The reprojection of a layer into the working CRS. PROJ takes 2 to 6 ms to make a
// transformation, and a partition's layers, repeated runs (QGIS, tiles) and the fuzzer ask for
// the same few again and again: each one made is kept for the process, by the layer CRS's WKT
// and the working CRS's, and every caller gets its own copy (a transformation is not safe to
// share between threads).
Reprojector reprojector(OGRLayer* layer, const std::string& working_wkt, const std::string& what) {
    const OGRSpatialReference* srs = layer->GetSpatialRef();
    // GeoPackage layers without a CRS report an "Undefined" placeholder.
    const char* name = srs ? srs->GetName() : nullptr;
    if (!srs || srs->IsEmpty() || (name && std::string(name).find("Undefined") != std::string::npos))
        throw Error(Code::NoCrs, what + ": layer '" + layer->GetName() + "' has no CRS");
    // Never destroyed: PROJ may be torn down before static destructors run at exit.
    static std::mutex mutex;
    static auto& kept = *new std::map<std::string, std::unique_ptr<OGRCoordinateTransformation>>;  // null: same CRS
    std::string key = wkt2(*srs);
    if (!key.empty()) key.append("\n").append(working_wkt);
    Reprojector r;
    if (!key.empty()) {
        const std::lock_guard<std::mutex> lock(mutex);
        if (const auto it = kept.find(key); it != kept.end()) {
            r.ct.reset(it->second ? it->second->Clone() : nullptr);
            return r;
        }
    }
    OGRSpatialReference dst;
    dst.importFromWkt(working_wkt.c_str());
    dst.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    OGRSpatialReference src(*srs);
    src.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    if (!src.IsSame(&dst)) {
        r.ct.reset(OGRCreateCoordinateTransformation(&src, &dst));
        if (!r.ct) throw Error(Code::NoCrs, what + ": cannot reproject layer '" + std::string(layer->GetName()) + "'");
    }
    if (!key.empty()) {
        const std::lock_guard<std::mutex> lock(mutex);
        if (kept.size() >= 64) kept.clear();  // a bound: what was cleared is made again
        kept.emplace(key, r.ct ? std::unique_ptr<OGRCoordinateTransformation>(r.ct->Clone()) : nullptr);
    }
    return r;
}

void filter_layer(OGRLayer* layer, const Reprojector& proj, const std::optional<tex::BBox>& box) {
    if (box && !proj.ct) layer->SetSpatialFilterRect(box->xmin, box->ymin, box->xmax, box->ymax);
    else layer->SetSpatialFilter(nullptr);
}

// Whether every coordinate of g is a finite number: NaN or infinite ones come from broken
// files, or from a reprojection outside the working CRS's domain.
bool finite_coordinates(const OGRGeometry* g) {
    const auto t = wkbFlatten(g->getGeometryType());
    if (t == wkbPoint) return std::isfinite(g->toPoint()->getX()) && std::isfinite(g->toPoint()->getY());
    if (t == wkbLineString || t == wkbLinearRing) {
        const OGRSimpleCurve* c = g->toSimpleCurve();
        for (int i = 0; i < c->getNumPoints(); ++i)
            if (!std::isfinite(c->getX(i)) || !std::isfinite(c->getY(i))) return false;
        return true;
    }
    if (t == wkbPolygon) {
        for (const auto* ring : *g->toPolygon())
            if (!finite_coordinates(ring)) return false;
        return true;
    }
    if (OGR_GT_IsSubClassOf(t, wkbGeometryCollection)) {
        for (const auto* part : *g->toGeometryCollection())
            if (!finite_coordinates(part)) return false;
        return true;
    }
    return true;  // other types are not read
}

void require_finite(const OGRGeometry* g, const std::string& what, const std::string& feature) {
    if (!finite_coordinates(g))
        throw Error(Code::BadGeometry, what + ": " + feature + " has coordinates that are not finite numbers");
}

std::vector<Point> ring_points(const OGRLinearRing* ring) {
    std::vector<Point> pts;
    pts.reserve(ring->getNumPoints());
    for (int i = 0; i < ring->getNumPoints(); ++i) pts.push_back({ring->getX(i), ring->getY(i)});
    return pts;
}

void add_lines(const OGRGeometry* g, LineKind kind, std::vector<LabelledLine>& out) {
    const auto t = wkbFlatten(g->getGeometryType());
    if (t == wkbLineString) {
        const auto* ls = g->toLineString();
        LabelledLine l;
        l.kind = kind;
        for (int i = 0; i < ls->getNumPoints(); ++i) l.points.push_back({ls->getX(i), ls->getY(i)});
        if (l.points.size() >= 2) out.push_back(std::move(l));
    } else if (t == wkbMultiLineString || t == wkbGeometryCollection) {
        for (const auto* part : *g->toGeometryCollection()) add_lines(part, kind, out);
    }
}

// Segment index on a uniform grid of cell size `cell`: a segment is listed in every cell it
// passes through, so a query finds every segment within `cell` of the point.
// The cells of a SegmentGrid that hold entries: an open-addressing table from a cell's key to
// its first and last entry (a std::unordered_map's node per cell was most of the grid's cost).
class CellTable {
public:
    using Range = std::pair<int, int>;
    void reserve(std::size_t n) {
        std::size_t cap = 16;
        while (cap < 2 * n) cap *= 2;
        if (cap > slots_.size()) rehash(cap);
    }
    const Range* find(std::uint64_t k) const {
        if (slots_.empty()) return nullptr;
        for (std::size_t i = slot(k);; i = (i + 1) & mask_) {
            const Slot& s = slots_[i];
            if (s.range.first < 0) return nullptr;
            if (s.key == k) return &s.range;
        }
    }
    // The range of cell k, made (first = last = e) if the cell was empty; whether it was made.
    std::pair<Range*, bool> try_emplace(std::uint64_t k, int e) {
        if (2 * (count_ + 1) > slots_.size()) rehash(std::max<std::size_t>(16, 2 * slots_.size()));
        for (std::size_t i = slot(k);; i = (i + 1) & mask_) {
            Slot& s = slots_[i];
            if (s.range.first < 0) {
                s = {k, {e, e}};
                ++count_;
                return {&s.range, true};
            }
            if (s.key == k) return {&s.range, false};
        }
    }

private:
    struct Slot {
        std::uint64_t key;
        Range range;  // first < 0: empty slot
    };
    std::size_t slot(std::uint64_t k) const { return std::size_t((k * 0xD6E8FEB86659FD93ULL) >> 32) & mask_; }
    void rehash(std::size_t cap) {
        std::vector<Slot> old(cap, Slot{0, {-1, -1}});
        old.swap(slots_);
        mask_ = cap - 1;
        count_ = 0;
        for (const Slot& s : old)
            if (s.range.first >= 0) *try_emplace(s.key, 0).first = s.range;
    }
    std::vector<Slot> slots_;
    std::size_t mask_ = 0, count_ = 0;
};

struct SegmentGrid {
    double cell;
    CellTable cells;  // first and last entry of each cell
    std::vector<std::pair<int, int>> entries;                       // id, next entry of the cell
    std::vector<int> long_ones;  // crossing too many cells: checked by every query
    static std::uint64_t key(long long i, long long j) {
        return (std::uint64_t(i) * 0x9E3779B97F4A7C15ULL) ^ std::uint64_t(j);
    }
    // The cell of a coordinate, clamped in double before it becomes an integer: coordinates
    // far beyond any CRS (1e300, fuzz_partition_struct) made the conversion overflow.
    long long index(double v) const {
        const double c = std::floor(v / cell);
        if (!(c == c)) return 0;  // NaN: never from finite coordinates (see insert)
        return c < -1e15 ? -1000000000000000LL : c > 1e15 ? 1000000000000000LL : (long long)c;
    }
    void insert(const Point& a, const Point& b, int id) {
        const long long i0 = index(std::min(a.x, b.x)), i1 = index(std::max(a.x, b.x));
        const long long j0 = index(std::min(a.y, b.y)), j1 = index(std::max(a.y, b.y));
        if ((i1 - i0 + 1) + (j1 - j0 + 1) > 8192) {
            long_ones.push_back(id);
            return;
        }
        // Column by column, the rows the segment spans within the column.
        const Point lo = a.x <= b.x ? a : b, hi = a.x <= b.x ? b : a;
        const double dx = hi.x - lo.x;
        for (long long i = i0; i <= i1; ++i) {
            double ya = lo.y, yb = hi.y;
            if (dx > 0) {
                const double xa = std::max(lo.x, double(i) * cell), xb = std::min(hi.x, double(i + 1) * cell);
                ya = lo.y + (hi.y - lo.y) * ((xa - lo.x) / dx);
                yb = lo.y + (hi.y - lo.y) * ((xb - lo.x) / dx);
                // dx overflows to +inf between -1e308 and 1e308: then every row of the
                // column (NaN rows made the conversion to an integer undefined).
                if (!std::isfinite(ya) || !std::isfinite(yb)) ya = lo.y, yb = hi.y;
            }
            // A little slack against rounding at the column edges.
            const double slack = 1e-9 * cell;
            const long long ja = std::max(j0, index(std::min(ya, yb) - slack));
            const long long jb = std::min(j1, index(std::max(ya, yb) + slack));
            for (long long j = ja; j <= jb; ++j) add(key(i, j), id);
        }
    }
    void add(std::uint64_t k, int id) {
        entries.push_back({id, -1});
        const int e = int(entries.size()) - 1;
        auto [range, fresh] = cells.try_emplace(k, e);
        if (!fresh) {
            entries[std::size_t(range->second)].second = e;
            range->second = e;
        }
    }
    template <class F>
    void query(const Point& p, F&& f) const {
        const long long i = index(p.x), j = index(p.y);
        for (long long di = -1; di <= 1; ++di)
            for (long long dj = -1; dj <= 1; ++dj) {
                if (const CellTable::Range* range = cells.find(key(i + di, j + dj)))
                    for (int e = range->first; e >= 0; e = entries[std::size_t(e)].second) f(entries[std::size_t(e)].first);
            }
        for (int id : long_ones) f(id);
    }
};

double seg_distance(const Point& p, const Point& a, const Point& b) {
    const Point d = b - a;
    const double l2 = tex::dot(d, d);
    double t = l2 > 0 ? tex::dot(p - a, d) / l2 : 0;
    t = std::clamp(t, 0.0, 1.0);
    return tex::distance(p, a + d * t);
}

// ---- Snapping borders (issue 11)

// A sorted run of face indices.
struct Faces {
    const int *b, *e;
};

bool share_a_face(Faces x, Faces y) {
    while (x.b != x.e && y.b != y.e) {
        if (*x.b == *y.b) return true;
        if (*x.b < *y.b) ++x.b;
        else ++y.b;
    }
    return false;
}

// The rings of all faces over shared nodes: the distinct vertices, numbered in lexicographic
// order of their coordinates, so that every choice made on them depends on the geometry only
// and never on the order of the faces.
struct RingNodes {
    std::vector<Point> pt;                    // node coordinates, sorted
    std::vector<std::vector<int>> ring;       // node ids of each ring
    std::vector<int> face_begin, face_of;     // faces through each node (sorted, CSR)

    RingNodes(const std::vector<std::vector<Point>>& rings, const std::vector<int>& ring_face) {
        for (const auto& r : rings) pt.insert(pt.end(), r.begin(), r.end());
        std::sort(pt.begin(), pt.end());
        pt.erase(std::unique(pt.begin(), pt.end()), pt.end());
        std::vector<std::pair<int, int>> nf;
        ring.resize(rings.size());
        for (std::size_t k = 0; k < rings.size(); ++k)
            for (const Point& q : rings[k]) {
                const int n = int(std::lower_bound(pt.begin(), pt.end(), q) - pt.begin());
                ring[k].push_back(n);
                nf.push_back({n, ring_face[k]});
            }
        std::sort(nf.begin(), nf.end());
        nf.erase(std::unique(nf.begin(), nf.end()), nf.end());
        face_begin.assign(pt.size() + 1, 0);
        for (const auto& e : nf) ++face_begin[std::size_t(e.first) + 1];
        for (std::size_t n = 0; n < pt.size(); ++n) face_begin[n + 1] += face_begin[n];
        for (const auto& e : nf) face_of.push_back(e.second);
    }
    Faces faces(int n) const {
        return {face_of.data() + face_begin[std::size_t(n)], face_of.data() + face_begin[std::size_t(n) + 1]};
    }
};

// Vertex to vertex: the nodes in lexicographic order; a node not yet taken anchors a cluster
// and takes the free nodes within `snap` of it, nearest first, as long as no two nodes of the
// cluster belong to the same face (a ring is never snapped onto itself). Taken nodes move
// onto the anchor. Returns whether a node moved.
bool snap_vertices(std::vector<std::vector<Point>>& rings, const RingNodes& g, double snap) {
    const int n = int(g.pt.size());
    SegmentGrid grid{snap, {}, {}, {}};
    grid.cells.reserve(g.pt.size());
    for (int k = 0; k < n; ++k) grid.insert(g.pt[std::size_t(k)], g.pt[std::size_t(k)], k);
    std::vector<int> target(std::size_t(n), -1);
    bool moved = false;
    std::vector<std::pair<double, int>> cand;
    for (int a = 0; a < n; ++a) {
        if (target[std::size_t(a)] >= 0) continue;
        target[std::size_t(a)] = a;
        const Point pa = g.pt[std::size_t(a)];
        cand.clear();
        grid.query(pa, [&](int b) {
            if (target[std::size_t(b)] >= 0) return;
            const double d = tex::distance(pa, g.pt[std::size_t(b)]);
            if (d <= snap) cand.push_back({d, b});
        });
        if (cand.empty()) continue;
        std::sort(cand.begin(), cand.end());
        cand.erase(std::unique(cand.begin(), cand.end()), cand.end());
        const Faces fa = g.faces(a);
        std::vector<int> fs(fa.b, fa.e);
        for (const auto& [d, b] : cand) {
            const Faces fb = g.faces(b);
            if (share_a_face({fs.data(), fs.data() + fs.size()}, fb)) continue;
            target[std::size_t(b)] = a;
            fs.insert(fs.end(), fb.b, fb.e);
            std::sort(fs.begin(), fs.end());
            moved = true;
        }
    }
    if (moved)
        for (std::size_t k = 0; k < rings.size(); ++k)
            for (std::size_t i = 0; i < rings[k].size(); ++i) rings[k][i] = g.pt[std::size_t(target[std::size_t(g.ring[k][i])])];
    return moved;
}

// Vertex to segment: a node within `snap` of the inside of a border segment of faces it does
// not belong to moves onto its projection there, and the projection is inserted into that
// segment in every ring running along it. Each node takes its nearest segment (ties: the
// lexicographically smallest end nodes); all moves are decided on the same geometry, then
// applied together. Returns whether anything changed.
bool snap_to_segments(std::vector<std::vector<Point>>& rings, const RingNodes& g, const std::vector<int>& ring_face,
                      double snap) {
    // Undirected edges (u < v), the faces along them, and the edge of every ring step.
    struct Step {
        int u, v, face;
        std::size_t ring, pos;
    };
    std::vector<Step> steps;
    for (std::size_t k = 0; k < g.ring.size(); ++k) {
        const auto& r = g.ring[k];
        for (std::size_t i = 0; i < r.size(); ++i) {
            const int a = r[i], b = r[(i + 1) % r.size()];
            if (a != b) steps.push_back({std::min(a, b), std::max(a, b), ring_face[k], k, i});
        }
    }
    std::sort(steps.begin(), steps.end(), [](const Step& x, const Step& y) {
        return std::tie(x.u, x.v, x.face) < std::tie(y.u, y.v, y.face);
    });
    struct Edge {
        int u, v;
        std::size_t faces;  // first of its faces in edge_faces
    };
    std::vector<int> edge_faces;
    std::vector<Edge> edges;
    std::vector<std::vector<int>> step_edge(g.ring.size());
    for (std::size_t k = 0; k < g.ring.size(); ++k) step_edge[k].assign(g.ring[k].size(), -1);
    double total = 0;
    for (const Step& s : steps) {
        if (edges.empty() || edges.back().u != s.u || edges.back().v != s.v) {
            edges.push_back({s.u, s.v, edge_faces.size()});
            total += tex::distance(g.pt[std::size_t(s.u)], g.pt[std::size_t(s.v)]);
        }
        if (edge_faces.size() == edges.back().faces || edge_faces.back() != s.face) edge_faces.push_back(s.face);
        step_edge[s.ring][s.pos] = int(edges.size()) - 1;
    }
    if (edges.empty()) return false;
    auto faces_of_edge = [&](std::size_t e) {
        const std::size_t end = e + 1 < edges.size() ? edges[e + 1].faces : edge_faces.size();
        return Faces{edge_faces.data() + edges[e].faces, edge_faces.data() + end};
    };
    // Cells about as long as the mean edge keep the index near-linear whatever the snap.
    SegmentGrid grid{std::max(snap, total / double(edges.size())), {}, {}, {}};
    grid.cells.reserve(2 * edges.size());
    for (std::size_t e = 0; e < edges.size(); ++e)
        grid.insert(g.pt[std::size_t(edges[e].u)], g.pt[std::size_t(edges[e].v)], int(e));

    struct Insert {
        int edge;
        double t;
        Point q;
    };
    // Each node decides on its own: blocks of nodes in parallel, their inserts in node order.
    constexpr int kBlock = 4096;
    const int nodes = int(g.pt.size());
    std::vector<std::vector<Insert>> block_inserts(std::size_t((nodes + kBlock - 1) / kBlock));
    std::vector<Point> moved_to(g.pt);
    tex::parallel_for(block_inserts.size(), [&](std::size_t block) {
        std::vector<Insert>& inserts = block_inserts[block];
        for (int n = int(block) * kBlock; n < std::min(nodes, int(block + 1) * kBlock); ++n) {
            const Point p = g.pt[std::size_t(n)];
            const Faces fn = g.faces(n);
            int best = -1;
            double best_d = snap, best_t = 0;
            Point best_q;
            grid.query(p, [&](int e) {
                const Edge& ed = edges[std::size_t(e)];
                const Point a = g.pt[std::size_t(ed.u)], b = g.pt[std::size_t(ed.v)];
                const Point d = b - a;
                const double t = tex::dot(p - a, d) / tex::dot(d, d);
                if (!(t > 0 && t < 1)) return;
                const Point q = a + d * t;
                const double dist = tex::distance(p, q);
                if (dist > best_d || q == a || q == b) return;
                if (dist == best_d && best >= 0 && std::tie(ed.u, ed.v) >= std::tie(edges[std::size_t(best)].u, edges[std::size_t(best)].v))
                    return;
                if (share_a_face(fn, faces_of_edge(std::size_t(e)))) return;
                best = e;
                best_d = dist;
                best_t = t;
                best_q = q;
            });
            if (best < 0) continue;
            moved_to[std::size_t(n)] = best_q;
            inserts.push_back({best, best_t, best_q});
        }
    });
    std::vector<Insert> inserts;
    for (const auto& b : block_inserts) inserts.insert(inserts.end(), b.begin(), b.end());
    if (inserts.empty()) return false;
    std::sort(inserts.begin(), inserts.end(), [](const Insert& x, const Insert& y) {
        return std::tie(x.edge, x.t) < std::tie(y.edge, y.t);
    });
    std::vector<std::size_t> first(edges.size() + 1, 0);
    for (const Insert& in : inserts) ++first[std::size_t(in.edge) + 1];
    for (std::size_t e = 0; e < edges.size(); ++e) first[e + 1] += first[e];
    for (std::size_t k = 0; k < rings.size(); ++k) {
        const auto& r = g.ring[k];
        std::vector<Point> out;
        out.reserve(r.size());
        for (std::size_t i = 0; i < r.size(); ++i) {
            out.push_back(moved_to[std::size_t(r[i])]);
            const int e = step_edge[k][i];
            if (e < 0) continue;
            const std::size_t b = first[std::size_t(e)], f = first[std::size_t(e) + 1];
            // Along the edge from u to v: increasing t.
            if (r[i] == edges[std::size_t(e)].u)
                for (std::size_t j = b; j < f; ++j) out.push_back(inserts[j].q);
            else
                for (std::size_t j = f; j > b; --j) out.push_back(inserts[j - 1].q);
        }
        rings[k] = std::move(out);
    }
    return true;
}

// A ring without repeated points in a row and without spikes (a, b, a).
std::vector<Point> tidy_ring(const std::vector<Point>& ring) {
    std::vector<Point> out;
    out.reserve(ring.size());
    for (const Point& q : ring) {
        if (!out.empty() && out.back() == q) continue;
        if (out.size() >= 2 && out[out.size() - 2] == q) {
            out.pop_back();
            continue;
        }
        out.push_back(q);
    }
    // The same at the closing point.
    for (bool again = true; again && out.size() >= 2;) {
        again = false;
        if (out.front() == out.back()) {
            out.pop_back();
            again = true;
        } else if (out.size() >= 3 && out[out.size() - 2] == out.front()) {
            out.pop_back();
            again = true;
        } else if (out.size() >= 3 && out[1] == out.back()) {
            out.erase(out.begin());
            again = true;
        }
    }
    return out;
}

double ring_length(const std::vector<Point>& r) {
    double l = 0;
    for (std::size_t i = 0; i < r.size(); ++i) l += tex::distance(r[i], r[(i + 1) % r.size()]);
    return l;
}

// A ring that snapping left without area: fewer than three points, or a mean width below a
// millionth of the tolerance.
bool degenerate(const std::vector<Point>& r, double snap) {
    return r.size() < 3 || std::abs(tex::signed_area(r)) <= 1e-6 * snap * ring_length(r);
}

}  // namespace

const char* kind_name(LineKind k) {
    switch (k) {
        case LineKind::Ridge: return "ridge";
        case LineKind::Valley: return "valley";
        case LineKind::Cliff: return "cliff";
        default: return "other";
    }
}

tex::BBox Partition::bounds() const {
    tex::BBox b;
    for (const auto& f : faces) b.add(f.region.bbox());
    return b;
}

Point face_anchor(const RockFace& f) { return f.anchor ? *f.anchor : interior_point(f.region); }

bool owns(const tex::BBox& tile, const Point& p) {
    return p.x >= tile.xmin && p.x < tile.xmax && p.y >= tile.ymin && p.y < tile.ymax;
}

void snap_borders(Partition& p, double snap) {
    if (!(snap > 0) || p.faces.empty()) return;
    std::vector<std::vector<Point>> rings;
    std::vector<int> ring_face;
    for (std::size_t f = 0; f < p.faces.size(); ++f) {
        rings.push_back(p.faces[f].region.outer());
        ring_face.push_back(int(f));
        for (const auto& h : p.faces[f].region.holes()) {
            rings.push_back(h);
            ring_face.push_back(int(f));
        }
    }
    const std::vector<std::vector<Point>> before = rings;
    // Vertices onto vertices, then vertices onto segments, until nothing moves: a vertex moved
    // onto a segment may come near other vertices or segments.
    for (int round = 0; round < 8; ++round) {
        std::optional<RingNodes> g(std::in_place, rings, ring_face);
        const bool v = snap_vertices(rings, *g, snap);
        if (v) g.emplace(rings, ring_face);
        const bool s = snap_to_segments(rings, *g, ring_face, snap);
        if (!v && !s) break;
    }
    // Rebuild the faces whose rings changed; drop those that lost their area.
    std::vector<RockFace> kept;
    std::vector<std::string> dropped;
    int lost_holes = 0;
    for (std::size_t f = 0, k = 0; f < p.faces.size(); ++f) {
        RockFace& face = p.faces[f];
        const std::size_t k0 = k;
        k += 1 + face.region.holes().size();
        bool same = true;
        for (std::size_t j = k0; j < k; ++j) same = same && rings[j] == before[j];
        if (!same) {
            const std::vector<Point> outer = tidy_ring(rings[k0]);
            if (degenerate(outer, snap)) {
                dropped.push_back(std::to_string(face.id));
                continue;
            }
            std::vector<std::vector<Point>> holes;
            for (std::size_t j = k0 + 1; j < k; ++j) {
                std::vector<Point> h = tidy_ring(rings[j]);
                if (degenerate(h, snap)) ++lost_holes;
                else holes.push_back(std::move(h));
            }
            try {
                face.region = tex::Region(outer, holes, "face");
            } catch (const std::exception&) {
                dropped.push_back(std::to_string(face.id));
                continue;
            }
            face.boundary.clear();  // label_boundaries gives it again
        }
        kept.push_back(std::move(face));
    }
    p.faces = std::move(kept);
    if (!dropped.empty()) {
        std::string ids;
        for (const auto& d : dropped) ids += (ids.empty() ? "" : ", ") + d;
        p.notes.push_back("dropped " + std::to_string(dropped.size()) + " face(s) left without area by snapping borders (id " +
                          ids + ")");
    }
    if (lost_holes) p.notes.push_back("dropped " + std::to_string(lost_holes) + " hole(s) left without area by snapping borders");
}

void label_boundaries(Partition& p, double snap) {
    // Index the labelled line segments.
    struct Seg {
        Point a, b;
        LineKind kind;
    };
    std::vector<Seg> segs;
    for (const auto& l : p.lines)
        for (std::size_t i = 0; i + 1 < l.points.size(); ++i) segs.push_back({l.points[i], l.points[i + 1], l.kind});
    const double cell = std::max(snap * 8, 1e-6);
    SegmentGrid lines_grid{cell, {}, {}, {}};
    for (std::size_t i = 0; i < segs.size(); ++i) lines_grid.insert(segs[i].a, segs[i].b, int(i));

    // Boundary segments of all faces, keyed by their ends for adjacency.
    struct Ref {
        Point a, b;
        int face, seg;
    };
    std::vector<Ref> refs;
    for (std::size_t f = 0; f < p.faces.size(); ++f) {
        RockFace& rf = p.faces[f];
        rf.boundary.clear();
        auto add_ring = [&](const std::vector<Point>& ring) {
            for (std::size_t i = 0; i < ring.size(); ++i) {
                BoundarySegment s;
                s.a = ring[i];
                s.b = ring[(i + 1) % ring.size()];
                const Point m = (s.a + s.b) / 2;
                const Point d = s.b - s.a;
                const double len = tex::norm(d);
                if (len == 0) continue;
                // A boundary segment lies on a labelled line when its midpoint is within the
                // tolerance and the directions agree (within about 10 degrees).
                double best = snap;
                lines_grid.query(m, [&](int id) {
                    const Seg& sg = segs[id];
                    const Point e = sg.b - sg.a;
                    const double le = tex::norm(e);
                    if (le == 0) return;
                    if (std::abs(tex::cross(d, e)) > 0.18 * len * le) return;
                    const double dist = seg_distance(m, sg.a, sg.b);
                    if (dist <= best) {
                        best = dist;
                        s.kind = sg.kind;
                    }
                });
                refs.push_back({s.a, s.b, int(f), int(rf.boundary.size())});
                rf.boundary.push_back(s);
            }
        };
        add_ring(rf.region.outer());
        for (const auto& h : rf.region.holes()) add_ring(h);
    }
    // Neighbours: another face's boundary segment with the same ends, run the other way (the
    // borders were snapped onto each other; several candidates: the first face).
    auto before = [](const Ref& x, const Ref& y) {
        if (x.a != y.a) return x.a < y.a;
        if (x.b != y.b) return x.b < y.b;
        return x.face < y.face;
    };
    std::vector<Ref> sorted = refs;
    std::sort(sorted.begin(), sorted.end(), before);
    for (const Ref& r : refs) {
        const Ref key{r.b, r.a, -1, 0};
        for (auto it = std::lower_bound(sorted.begin(), sorted.end(), key, before);
             it != sorted.end() && it->a == r.b && it->b == r.a; ++it)
            if (it->face != r.face) {
                p.faces[std::size_t(r.face)].boundary[std::size_t(r.seg)].neighbor = it->face;
                break;
            }
    }
}

namespace {

// ---- Reading the partition: the steps of load_partition

// The dataset being read, with what every step reads along: its name for the messages, the
// options and the working CRS.
struct PartitionSource {
    GDALDataset& ds;
    const std::string& what;  // "--partition '<path>'", the start of every message
    const PartitionOptions& opt;
    const std::string& working_wkt;

    // The layer named `name`, checked by `pred` when given; nullptr when no name is given.
    OGRLayer* find_layer(const std::string& name, bool (*pred)(OGRLayer*), const char* role) const {
        if (!name.empty()) {
            OGRLayer* l = ds.GetLayerByName(name.c_str());
            if (!l) throw Error(Code::BadLayer, what + ": no layer named '" + name + "'");
            if (pred && !pred(l))
                throw Error(Code::BadLayer, what + ": layer '" + name + "' is not a " + role + " layer");
            return l;
        }
        return nullptr;
    }
};

// Opens the dataset, read-only, once the file is known to be there (a path GDAL can stat: a
// file, or one of its virtual file systems such as /vsizip/ or /vsimem/).
DatasetPtr open_partition(const std::string& path, const std::string& what) {
    VSIStatBufL st;
    if (VSIStatL(path.c_str(), &st) != 0) throw Error(Code::InputMissing, what + ": no such file");
    DatasetPtr ds(GDALDataset::FromHandle(
        GDALOpenEx(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
    if (!ds) throw Error(Code::InputMissing, what + ": not a vector dataset OGR can read");
    return ds;
}

// The faces' layer: the one named, else the first polygon layer.
OGRLayer* face_layer(const PartitionSource& src) {
    OGRLayer* faces = src.find_layer(src.opt.faces_layer, is_polygon_layer, "polygon");
    if (!faces)
        for (int i = 0; i < src.ds.GetLayerCount() && !faces; ++i)
            if (is_polygon_layer(src.ds.GetLayer(i))) faces = src.ds.GetLayer(i);
    if (!faces) throw Error(Code::BadLayer, src.what + ": no polygon layer (the rock faces)");
    return faces;
}

// The fields of the faces' layer that a face reads (-1: none).
struct FaceFields {
    int id_idx;
    std::string orient_name, dens_name;
    int orient_idx, dens_idx;
};

// Finds the id, orientation and density fields of the faces' layer.
FaceFields face_fields(const PartitionSource& src, OGRLayer* faces) {
    const PartitionOptions& opt = src.opt;
    const std::string& what = src.what;
    OGRFeatureDefn* fdef = faces->GetLayerDefn();
    FaceFields f;
    f.id_idx = opt.id_field.empty() ? -1 : fdef->GetFieldIndex(opt.id_field.c_str());
    if (!opt.id_field.empty() && f.id_idx < 0)
        throw Error(Code::BadLayer, what + ": layer '" + faces->GetName() + "' has no field '" + opt.id_field + "'");
    f.orient_name = opt.orientation_field.empty() ? "orientation" : opt.orientation_field;
    f.dens_name = opt.density_field.empty() ? "density" : opt.density_field;
    f.orient_idx = fdef->GetFieldIndex(f.orient_name.c_str());
    f.dens_idx = fdef->GetFieldIndex(f.dens_name.c_str());
    // A field the user named must be there (the density may come from --density-layer instead).
    auto missing = [&](const std::string& field, const char* option) {
        return Error(Code::BadLayer, what + ": layer '" + faces->GetName() + "' has no field '" + field + "' (" +
                                         option + ")");
    };
    if (!opt.orientation_field.empty() && f.orient_idx < 0) throw missing(f.orient_name, "--orientation-field");
    if (!opt.density_field.empty() && opt.density_layer.empty() && f.dens_idx < 0)
        throw missing(f.dens_name, "--density-field");
    return f;
}

constexpr double kRepairableMetres = 1e10;

// GEOS's repair of an invalid face (MakeValid), kept for the process by the face's exact
// coordinates (its WKB): a tile reads the faces meeting it twice (tiles.cpp), a face meeting
// several tiles is read for each, each run from QGIS reads the partition again, and the
// repair of a ten-vertex self-intersecting face can take GEOS a few hundred overlays. The same
// coordinates always get the same repair; every caller gets its own copy. nullptr: GEOS could
// not repair it.
std::unique_ptr<OGRGeometry> repaired_copy(const OGRGeometry& g) {
    static std::mutex mutex;
    // Never destroyed, as the transformations above.
    static auto& kept = *new std::unordered_map<std::string, std::unique_ptr<OGRGeometry>>;
    static std::size_t kept_bytes = 0;
    std::string key(std::size_t(g.WkbSize()), '\0');
    g.exportToWkb(wkbNDR, reinterpret_cast<unsigned char*>(key.data()), wkbVariantIso);
    {
        const std::lock_guard<std::mutex> lock(mutex);
        if (const auto it = kept.find(key); it != kept.end()) {
            if (!it->second) return nullptr;
            std::unique_ptr<OGRGeometry> copy(it->second->clone());
            copy->assignSpatialReference(g.getSpatialReference());  // as MakeValid does
            return copy;
        }
    }
    std::unique_ptr<OGRGeometry> fixed(g.MakeValid());
    const std::lock_guard<std::mutex> lock(mutex);
    // A bound, 16 MB of faces (their repairs about as much): what was cleared is repaired again.
    if (kept_bytes + key.size() > (std::size_t(16) << 20)) {
        kept.clear();
        kept_bytes = 0;
    }
    std::unique_ptr<OGRGeometry> copy(fixed ? fixed->clone() : nullptr);
    if (copy) copy->assignSpatialReference(nullptr);  // the layer's CRS is not kept alive by it
    const std::size_t size = key.size();
    if (kept.try_emplace(std::move(key), std::move(copy)).second) kept_bytes += size;
    return fixed;
}

// A face feature's geometry in the working CRS, repaired when invalid (counted in `repaired`)
// unless --no-repair; nullptr for a feature without geometry or off the filter box.
std::unique_ptr<OGRGeometry> face_geometry(const PartitionSource& src, const OGRFeature& feat, const Reprojector& proj,
                                           int& repaired) {
    const std::string& what = src.what;
    const OGRGeometry* g0 = feat.GetGeometryRef();
    if (!g0 || g0->IsEmpty()) return nullptr;
    std::unique_ptr<OGRGeometry> g(g0->clone());
    proj.apply(g.get());
    require_finite(g.get(), what, "face " + std::to_string(feat.GetFID()));
    if (!keep(g.get(), src.opt.filter)) return nullptr;
    if (!g->IsValid()) {
        if (!src.opt.repair)
            throw Error(Code::BadGeometry, what + ": face " + std::to_string(feat.GetFID()) +
                                               " is not a valid polygon (self-intersecting?); repair it or drop "
                                               "--no-repair");
        // GEOS's repair works in the coordinates' own magnitude: near the largest doubles its
        // sums overflow and a ten-vertex face took minutes (fuzz_partition_struct). No map's
        // coordinates come near 1e10 m (250 times round the Earth).
        OGREnvelope e;
        g->getEnvelope(&e);
        if (std::max({std::abs(e.MinX), std::abs(e.MaxX), std::abs(e.MinY), std::abs(e.MaxY)}) > kRepairableMetres)
            throw Error(Code::BadGeometry, what + ": face " + std::to_string(feat.GetFID()) +
                                               " is invalid and lies beyond any map (coordinates over 1e10 m): it "
                                               "cannot be repaired");
        std::unique_ptr<OGRGeometry> fixed = repaired_copy(*g);
        if (!fixed || fixed->IsEmpty())
            throw Error(Code::BadGeometry,
                        what + ": face " + std::to_string(feat.GetFID()) + " is invalid and cannot be repaired");
        g = std::move(fixed);
        ++repaired;
    }
    return g;
}

// The polygons of a geometry, in order (a repaired face may be a collection).
void collect_polygons(const OGRGeometry* x, std::vector<const OGRPolygon*>& polys) {
    const auto t = wkbFlatten(x->getGeometryType());
    if (t == wkbPolygon) polys.push_back(x->toPolygon());
    else if (t == wkbMultiPolygon || t == wkbGeometryCollection)
        for (const auto* part : *x->toGeometryCollection()) collect_polygons(part, polys);
}

// A face's orientation and density from the fields of its feature, when set.
void read_face_attributes(const PartitionSource& src, const OGRFeature& feat, const FaceFields& fields, RockFace& rf) {
    const std::string& what = src.what;
    if (fields.orient_idx >= 0 && feat.IsFieldSetAndNotNull(fields.orient_idx)) {
        const double az = feat.GetFieldAsDouble(fields.orient_idx);
        if (!std::isfinite(az))
            throw Error(Code::BadLayer, what + ": face " + std::to_string(rf.id) + ": bad " + fields.orient_name);
        rf.orientation = (90.0 - az) * M_PI / 180.0;
    }
    if (fields.dens_idx >= 0 && feat.IsFieldSetAndNotNull(fields.dens_idx)) {
        const double d = feat.GetFieldAsDouble(fields.dens_idx);
        if (!(d >= 0 && d <= 1))
            throw Error(Code::BadLayer, what + ": face " + std::to_string(rf.id) + ": " + fields.dens_name + " " +
                                            std::to_string(d) + " is not in [0, 1]");
        rf.density = d;
    }
}

// The faces of one feature, one per polygon of its geometry `g` (a zero-area sliver left by
// a repair makes none).
void add_faces(const PartitionSource& src, const OGRFeature& feat, const OGRGeometry* g, const FaceFields& fields,
               std::vector<RockFace>& faces) {
    std::vector<const OGRPolygon*> polys;
    collect_polygons(g, polys);
    for (const OGRPolygon* poly : polys) {
        if (!poly->getExteriorRing() || poly->getExteriorRing()->getNumPoints() < 4) continue;
        RockFace rf;
        rf.id = fields.id_idx >= 0 ? feat.GetFieldAsInteger64(fields.id_idx) : feat.GetFID();
        std::vector<std::vector<Point>> holes;
        for (int k = 0; k < poly->getNumInteriorRings(); ++k)
            holes.push_back(ring_points(poly->getInteriorRing(k)));
        try {
            rf.region = tex::Region(ring_points(poly->getExteriorRing()), holes, "face");
        } catch (const std::exception&) {
            continue;  // a zero-area sliver left by a repair
        }
        rf.anchor = interior_point(rf.region);
        read_face_attributes(src, feat, fields, rf);
        faces.push_back(std::move(rf));
    }
}

// Reads the faces meeting the filter box (all without one) and notes the repairs.
void read_faces(const PartitionSource& src, OGRLayer* faces, const Reprojector& proj, const FaceFields& fields,
                Partition& p) {
    int repaired = 0;
    filter_layer(faces, proj, src.opt.filter);
    faces->ResetReading();
    for (auto& feat : *faces) {
        const std::unique_ptr<OGRGeometry> g = face_geometry(src, *feat, proj, repaired);
        if (g) add_faces(src, *feat, g.get(), fields, p.faces);
    }
    if (p.faces.empty() && !src.opt.filter)
        throw Error(Code::BadLayer, src.what + ": layer '" + std::string(faces->GetName()) + "' holds no polygon");
    if (repaired) p.notes.push_back("repaired " + std::to_string(repaired) + " invalid face polygon(s)");
}

// Borders digitised twice become one (neighbours are matched on identical segments).
void snap_face_borders(const PartitionSource& src, Partition& p) {
    snap_borders(p, src.opt.snap);
    if (p.faces.empty() && !src.opt.filter)
        throw Error(Code::BadLayer, src.what + ": no face keeps an area once its borders are snapped");
}

// The line layers: one layer with a label attribute, or one layer per kind, or OSM lines.
struct LineLayers {
    OGRLayer* labelled = nullptr;
    std::vector<std::pair<OGRLayer*, LineKind>> per_kind;
    OGRLayer* osm = nullptr;
};

// The OSM `natural` value of a feature: its field, else the key in `other_tags` ("" if none).
std::string osm_natural(OGRFeature& feat) {
    const int field = feat.GetFieldIndex("natural");
    if (field >= 0) return feat.IsFieldSetAndNotNull(field) ? feat.GetFieldAsString(field) : "";
    const int other = feat.GetFieldIndex("other_tags");
    if (other < 0 || !feat.IsFieldSetAndNotNull(other)) return "";
    const std::string tags = feat.GetFieldAsString(other), key = "\"natural\"=>\"";
    const std::size_t at = tags.find(key);
    if (at == std::string::npos) return "";
    const std::size_t from = at + key.size(), to = tags.find('"', from);
    return to == std::string::npos ? "" : tags.substr(from, to - from);
}

// The kind an OSM natural value names (false: not a structure line).
bool osm_kind(const std::string& natural, LineKind& out) {
    if (natural == "ridge" || natural == "arete") out = LineKind::Ridge;
    else if (natural == "cliff") out = LineKind::Cliff;
    else if (natural == "valley") out = LineKind::Valley;
    else return false;
    return true;
}

// Finds the line layers: the one named, else the layers named after a kind and the first
// other line layer with the label field.
LineLayers line_layers(const PartitionSource& src) {
    LineLayers layers;
    OGRLayer*& lines = layers.labelled;
    lines = src.find_layer(src.opt.lines_layer, is_line_layer, "line");
    if (!lines) {
        for (int i = 0; i < src.ds.GetLayerCount(); ++i) {
            OGRLayer* l = src.ds.GetLayer(i);
            if (!is_line_layer(l)) continue;
            const std::string n = lower(l->GetName());
            const OGRFeatureDefn* defn = l->GetLayerDefn();
            if (n.rfind("ridge", 0) == 0 || n.rfind("crete", 0) == 0) layers.per_kind.push_back({l, LineKind::Ridge});
            else if (n.rfind("valley", 0) == 0 || n.rfind("thalweg", 0) == 0 || n.rfind("talweg", 0) == 0)
                layers.per_kind.push_back({l, LineKind::Valley});
            else if (n.rfind("cliff", 0) == 0 || n.rfind("falaise", 0) == 0)
                layers.per_kind.push_back({l, LineKind::Cliff});
            else if (!lines && defn->GetFieldIndex(src.opt.label_field.c_str()) >= 0)
                lines = l;
            else if (!layers.osm && (defn->GetFieldIndex("natural") >= 0 || defn->GetFieldIndex("other_tags") >= 0))
                layers.osm = l;
        }
    }
    return layers;
}

// The ridges, arêtes, cliffs and valleys of an OSM line layer (natural=*); other lines skipped.
void read_osm_lines(const PartitionSource& src, OGRLayer* lines, const std::optional<tex::BBox>& around,
                    std::vector<LabelledLine>& out) {
    const Reprojector proj = reprojector(lines, src.working_wkt, src.what);
    filter_layer(lines, proj, around);
    lines->ResetReading();
    for (auto& feat : *lines) {
        OGRGeometry* g = feat->GetGeometryRef();
        LineKind kind;
        if (!g || !osm_kind(osm_natural(*feat), kind)) continue;
        std::unique_ptr<OGRGeometry> c(g->clone());
        proj.apply(c.get());
        require_finite(c.get(), src.what, "line " + std::to_string(feat->GetFID()));
        if (keep(c.get(), around)) add_lines(c.get(), kind, out);
    }
}

// The ridge and valley lines of a layer labelled by an attribute (other lines are skipped).
void read_labelled_lines(const PartitionSource& src, OGRLayer* lines, const std::optional<tex::BBox>& around,
                         std::vector<LabelledLine>& out) {
    const std::string& what = src.what;
    const Reprojector proj = reprojector(lines, src.working_wkt, what);
    const int idx = lines->GetLayerDefn()->GetFieldIndex(src.opt.label_field.c_str());
    if (idx < 0)
        throw Error(Code::BadLayer, what + ": line layer '" + std::string(lines->GetName()) + "' has no label field '" +
                                        src.opt.label_field + "' (ridge / valley / cliff / other)");
    filter_layer(lines, proj, around);
    lines->ResetReading();
    for (auto& feat : *lines) {
        OGRGeometry* g = feat->GetGeometryRef();
        if (!g) continue;
        LineKind kind;
        const std::string v = feat->IsFieldSetAndNotNull(idx) ? feat->GetFieldAsString(idx) : "";
        if (!parse_kind(v, kind))
            throw Error(Code::BadLayer, what + ": line " + std::to_string(feat->GetFID()) + ": label '" + v +
                                            "' is not ridge, valley, cliff or other");
        if (kind == LineKind::Other) continue;
        std::unique_ptr<OGRGeometry> c(g->clone());
        proj.apply(c.get());
        require_finite(c.get(), what, "line " + std::to_string(feat->GetFID()));
        if (keep(c.get(), around)) add_lines(c.get(), kind, out);
    }
}

// The lines of the layers named after their kind, layer by layer.
void read_per_kind_lines(const PartitionSource& src, const std::vector<std::pair<OGRLayer*, LineKind>>& per_kind,
                         const std::optional<tex::BBox>& around, std::vector<LabelledLine>& out) {
    const std::string& what = src.what;
    for (auto [l, kind] : per_kind) {
        const Reprojector proj = reprojector(l, src.working_wkt, what);
        filter_layer(l, proj, around);
        l->ResetReading();
        for (auto& feat : *l) {
            if (!feat->GetGeometryRef()) continue;
            std::unique_ptr<OGRGeometry> c(feat->GetGeometryRef()->clone());
            proj.apply(c.get());
            require_finite(c.get(), what,
                           "line " + std::to_string(feat->GetFID()) + " of layer '" + l->GetName() + "'");
            if (keep(c.get(), around)) add_lines(c.get(), kind, out);
        }
    }
}

// The line layers (line_layers); without any the borders cannot be labelled: an error.
LineLayers required_line_layers(const PartitionSource& src) {
    LineLayers layers = line_layers(src);
    if (!layers.labelled && layers.per_kind.empty() && !layers.osm)
        throw Error(Code::BadLayer, src.what + ": no line layer with a '" + src.opt.label_field +
                                        "' field and no 'ridges' / 'valleys' layers: the faces' borders cannot be "
                                        "labelled");
    return layers;
}

// Reads the ridge and valley lines of `layers` near the faces (`around`).
void read_lines(const PartitionSource& src, const LineLayers& layers, const std::optional<tex::BBox>& around,
                Partition& p) {
    if (layers.labelled) {
        read_labelled_lines(src, layers.labelled, around, p.lines);
    } else if (!layers.per_kind.empty()) {
        read_per_kind_lines(src, layers.per_kind, around, p.lines);
    } else {
        read_osm_lines(src, layers.osm, around, p.lines);
    }
}

// The orientation layer: the one named, else the first line layer named "orient...".
OGRLayer* orientation_layer(const PartitionSource& src) {
    OGRLayer* olayer = src.find_layer(src.opt.orientation_layer, is_line_layer, "line");
    if (!olayer && src.opt.orientation_layer.empty()) {
        for (int i = 0; i < src.ds.GetLayerCount() && !olayer; ++i) {
            const std::string n = lower(src.ds.GetLayer(i)->GetName());
            if (is_line_layer(src.ds.GetLayer(i)) && n.rfind("orient", 0) == 0) olayer = src.ds.GetLayer(i);
        }
    }
    return olayer;
}

// Gives the line's direction, from its first point to its last, to the first face without
// an orientation that holds its midpoint. Returns whether a face took it.
bool orient_face(const LabelledLine& l, std::vector<RockFace>& faces) {
    const Point a = l.points.front(), b = l.points.back();
    const Point mid = (a + b) / 2;
    for (auto& f : faces)
        if (!f.orientation && f.region.contains(mid)) {
            f.orientation = std::atan2(b.y - a.y, b.x - a.x);
            return true;
        }
    return false;
}

// Orientations from the lines of the orientation layer, when there is one (noted).
void read_orientations(const PartitionSource& src, const std::optional<tex::BBox>& around, Partition& p) {
    OGRLayer* olayer = orientation_layer(src);
    if (!olayer) return;
    const Reprojector proj = reprojector(olayer, src.working_wkt, src.what);
    int matched = 0;
    filter_layer(olayer, proj, around);
    olayer->ResetReading();
    for (auto& feat : *olayer) {
        if (!feat->GetGeometryRef()) continue;
        std::unique_ptr<OGRGeometry> c(feat->GetGeometryRef()->clone());
        proj.apply(c.get());
        require_finite(c.get(), src.what, "orientation line " + std::to_string(feat->GetFID()));
        std::vector<LabelledLine> ls;
        add_lines(c.get(), LineKind::Other, ls);
        for (const auto& l : ls)
            if (orient_face(l, p.faces)) ++matched;
    }
    p.notes.push_back("orientation of " + std::to_string(matched) + " face(s) from layer '" + olayer->GetName() +
                      "'");
}

// Densities from the --density-layer: each feature's density goes to the faces holding its
// centroid.
void read_densities(const PartitionSource& src, const std::string& dens_name, const std::optional<tex::BBox>& around,
                    Partition& p) {
    const std::string& what = src.what;
    const std::string& layer = src.opt.density_layer;
    OGRLayer* dlayer = src.find_layer(layer, nullptr, "");
    if (!dlayer) return;
    const Reprojector proj = reprojector(dlayer, src.working_wkt, what);
    const int idx = dlayer->GetLayerDefn()->GetFieldIndex(dens_name.c_str());
    if (idx < 0) throw Error(Code::BadLayer, what + ": layer '" + layer + "' has no field '" + dens_name + "'");
    filter_layer(dlayer, proj, around);
    dlayer->ResetReading();
    for (auto& feat : *dlayer) {
        if (!feat->GetGeometryRef() || !feat->IsFieldSetAndNotNull(idx)) continue;
        const double d = feat->GetFieldAsDouble(idx);
        if (!(d >= 0 && d <= 1))
            throw Error(Code::BadLayer,
                        what + ": layer '" + layer + "': density " + std::to_string(d) + " is not in [0, 1]");
        std::unique_ptr<OGRGeometry> c(feat->GetGeometryRef()->clone());
        proj.apply(c.get());
        require_finite(c.get(), what, "feature " + std::to_string(feat->GetFID()) + " of layer '" + layer + "'");
        OGRPoint centre;
        c->Centroid(&centre);
        for (auto& f : p.faces)
            if (f.region.contains({centre.getX(), centre.getY()})) f.density = d;
    }
}

// The polygons of a scree geometry, in order, as regions.
void add_scree(const OGRGeometry* x, const std::string& what, const std::string& which,
               std::vector<tex::Region>& scree) {
    const auto t = wkbFlatten(x->getGeometryType());
    if (t == wkbMultiPolygon || t == wkbGeometryCollection)
        for (const auto* part : *x->toGeometryCollection()) add_scree(part, what, which, scree);
    if (t != wkbPolygon) return;
    const OGRPolygon* poly = x->toPolygon();
    std::vector<std::vector<Point>> holes;
    for (int i = 0; i < poly->getNumInteriorRings(); ++i) holes.push_back(ring_points(poly->getInteriorRing(i)));
    scree.emplace_back(ring_points(poly->getExteriorRing()), std::move(holes), what + ": " + which);
}

// The scree areas of the --scree-layer, when given (noted), repaired when invalid.
void read_scree(const PartitionSource& src, Partition& p) {
    const std::string& what = src.what;
    const std::string& layer = src.opt.scree_layer;
    OGRLayer* slayer = src.find_layer(layer, is_polygon_layer, "polygon");
    if (!slayer) return;
    const Reprojector proj = reprojector(slayer, src.working_wkt, what);
    slayer->ResetReading();
    for (auto& feat : *slayer) {
        const OGRGeometry* g0 = feat->GetGeometryRef();
        if (!g0 || g0->IsEmpty()) continue;
        const std::string which = "scree area " + std::to_string(feat->GetFID()) + " of layer '" + layer + "'";
        std::unique_ptr<OGRGeometry> g(g0->clone());
        proj.apply(g.get());
        require_finite(g.get(), what, which);
        if (!g->IsValid()) g.reset(g->MakeValid());
        if (!g || g->IsEmpty())
            throw Error(Code::BadGeometry, what + ": " + which + " is invalid and cannot be repaired");
        add_scree(g.get(), what, which, p.scree);
    }
    p.notes.push_back(std::to_string(p.scree.size()) + " scree area(s) from layer '" + layer + "'");
}

}  // namespace

Partition load_partition(const PartitionOptions& opt, const std::string& working_wkt) {
    register_gdal();
    const QuietGdal quiet;
    const DatasetPtr ds = open_partition(opt.path, "--partition '" + opt.path + "'");
    return load_partition(*ds, opt, working_wkt);
}

Partition load_partition(GDALDataset& ds, const PartitionOptions& opt, const std::string& working_wkt) {
    register_gdal();
    const QuietGdal quiet;
    const std::string what = "--partition '" + opt.path + "'";
    const PartitionSource src{ds, what, opt, working_wkt};

    Partition p;
    p.crs_wkt = working_wkt;
    OGRLayer* faces = face_layer(src);
    const Reprojector face_proj = reprojector(faces, working_wkt, what);
    const FaceFields fields = face_fields(src, faces);
    // The line layers are found before any face is read: a partition without them fails at
    // once, not after the repair of every invalid face (a third of fuzz_partition_struct's time).
    const LineLayers lines = required_line_layers(src);
    read_faces(src, faces, face_proj, fields, p);
    if (!opt.as_digitised) snap_face_borders(src, p);

    // The lines, orientations and densities of every face read, including the parts of the
    // faces beyond the filter box (a face meeting the box is read whole, its attributes too).
    std::optional<tex::BBox> around = opt.filter;
    if (around) around->add(p.bounds());
    read_lines(src, lines, around, p);
    read_orientations(src, around, p);
    read_densities(src, fields.dens_name, around, p);
    read_scree(src, p);
    if (!opt.as_digitised) label_boundaries(p, opt.snap);
    return p;
}

}  // namespace carto
