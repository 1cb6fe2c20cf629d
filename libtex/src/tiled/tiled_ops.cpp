// Operators on tiled maps: the tiled partitions, the mappers by the Neighbourhood-Influence-
// Zone rule (thesis 4.2.2), ghost mapping (4.2.4) and the union on commensurable periods.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <numeric>
#include <optional>
#include <sstream>
#include <type_traits>

#include "libtex/error.hpp"
#include "libtex/merge.hpp"
#include "libtex/parallel.hpp"
#include "libtex/tiled.hpp"

namespace tex {
namespace {

// Fraction of a period by which the fundamental tile is moved off the lattice, so that the
// reference points of regular partitions (which sit on simple fractions of the period) never
// fall on a tile's side and each cell class has exactly one representative.
constexpr double kTileOffset = 0.2718281828459045;

long long pos_mod(long long a, long long m) { return ((a % m) + m) % m; }

long long lcm_ll(long long a, long long b) { return a / std::gcd(a, b) * b; }

// One family of parallel lines of a tiled partition, over one full period of its widths
// and label cycles.
struct Family {
    Point d, n;
    std::vector<double> offsets;  // offsets of the lines 0..count, offsets[count] = period
    long long count = 0;
    const Stripes* s = nullptr;

    Family(const Stripes& st, const char* op) : s(&st) {
        if (!std::isfinite(st.angle)) throw Error(op, "the angle is not a finite number");
        if (st.widths.empty()) throw Error(op, "no width given");
        const auto bad = std::find_if(st.widths.begin(), st.widths.end(),
                                      [](double w) { return !(w > 0 && std::isfinite(w)); });
        if (bad != st.widths.end()) {
            std::ostringstream m;
            m << "width " << *bad << " is not a positive number";
            throw Error(op, m.str());
        }
        d = {std::cos(st.angle), std::sin(st.angle)};
        // Axis-aligned directions exactly so (cos(pi/2) is not 0), as the planar-map engine.
        if (std::abs(d.x) < 1e-12) d = {0.0, d.y > 0 ? 1.0 : -1.0};
        if (std::abs(d.y) < 1e-12) d = {d.x > 0 ? 1.0 : -1.0, 0.0};
        n = {-d.y, d.x};
        count = (long long)st.widths.size();
        if (!st.edge_labels.empty()) count = lcm_ll(count, (long long)st.edge_labels.size());
        if (!st.face_labels.empty()) count = lcm_ll(count, (long long)st.face_labels.size());
        if (count > 100000) throw Error(op, "the width and label cycles repeat only after more than 100000 lines");
        // Offsets as the engine computes them: whole width periods plus a prefix sum.
        std::vector<double> prefix{0};
        for (double w : st.widths) prefix.push_back(prefix.back() + w);
        const long long m = (long long)st.widths.size();
        for (long long i = 0; i <= count; ++i) offsets.push_back(double(i / m) * prefix.back() + prefix[std::size_t(i % m)]);
    }
    double period() const { return offsets.back(); }
    Labels edge_label(long long i) const {
        Labels l;
        if (!s->edge_labels.empty()) l.add(s->edge_labels[std::size_t(pos_mod(i, (long long)s->edge_labels.size()))]);
        return l;
    }
    Labels face_label(long long i) const {
        Labels l;
        if (!s->face_labels.empty()) l.add(s->face_labels[std::size_t(pos_mod(i, (long long)s->face_labels.size()))]);
        return l;
    }
};

std::uint64_t anchor_key(const Point& p) { return hash_point(0x54504d4b4559ULL, p); }

Curve segment(const Point& a, const Point& b, Labels labels, Labels left, Labels right) {
    Curve c;
    c.points = {a, b};
    c.labels = std::move(labels);
    c.left = std::move(left);
    c.right = std::move(right);
    return c;
}

void check_regular(const TiledMap& a, const char* op) {
    if (a.has_ghost())
        throw Error(op, "the tiled map has a ghost mapper, which must be the last stage; map it before GhostMap");
    if (!a.bounded_faces())
        throw Error(op, "the tiled map has unbounded faces (stripes); map a tiled GridPartition instead");
}

// Which tile (in lattice units, moved by kTileOffset) a reference point falls in.
bool in_central_tile(const TiledMap& a, const Point& p) {
    const Point l = a.lattice(p);
    return std::floor(l.x + kTileOffset) == 0 && std::floor(l.y + kTileOffset) == 0;
}

std::vector<TiledMap::Element> repeat(const TiledMap& a, int m1, int m2);

// The copies of one vertex made by two different translations (a + s, b + t with a + s = b +
// t on paper) may differ in their last bits when the periods are not exact in binary (a
// lattice turned 45 degrees); the exact planar map of a block would then hold two vertices and
// a sliver edge between them. The welder moves every point within `tolerance` of a point met
// before onto that point (cells of 4 * tolerance, the 3 x 3 cells around a point searched).
class Welder {
public:
    explicit Welder(double tolerance) : tol_(tolerance), cell_(4 * tolerance) {}
    Point operator()(const Point& p) {
        const long long cx = (long long)std::floor(p.x / cell_), cy = (long long)std::floor(p.y / cell_);
        for (long long dx = -1; dx <= 1; ++dx)
            for (long long dy = -1; dy <= 1; ++dy) {
                const auto it = seen_.find({cx + dx, cy + dy});
                if (it == seen_.end()) continue;
                for (const Point& q : it->second)
                    if (std::abs(q.x - p.x) <= tol_ && std::abs(q.y - p.y) <= tol_) return q;
            }
        seen_[{cx, cy}].push_back(p);
        return p;
    }
    void weld(Curves& c) {
        for (auto& cv : c.curves)
            for (auto& p : cv.points) p = (*this)(p);
        for (auto& p : c.points) p.point = (*this)(p.point);
    }

private:
    double tol_, cell_;
    std::map<std::pair<long long, long long>, std::vector<Point>> seen_;
};

// A welding tolerance for a block of curves: far above the rounding of a translation, far
// below any feature a texture draws.
double weld_tolerance(const Curves& c) {
    const BBox b = c.bbox();
    return 1e-9 * std::max({1.0, std::abs(b.xmin), std::abs(b.xmax), std::abs(b.ymin), std::abs(b.ymax)});
}

std::string point_text(const Point& p) {
    std::ostringstream s;
    s << "(" << p.x << ", " << p.y << ")";
    return s.str();
}

// The smallest k in 1..64 with k * ratio a whole number, or 0.
int denominator(double ratio) {
    for (int k = 1; k <= 64; ++k) {
        const double v = k * ratio;
        if (std::abs(v - std::round(v)) <= 1e-9 * std::max(1.0, std::abs(v))) return k;
    }
    return 0;
}

// A partition built inside a mapper lays lines anchored to the plane. The mapper's output for
// a copy of a cell is its output for the central cell moved by the copy's shift only when
// every such family of lines is invariant by the shift: the projection of each period on the
// family's normal a whole number of the family's periods. When both projections are
// rational (denominators k1, k2), the lattice of k1 * period1 and k2 * period2 is; otherwise
// no lattice is and the arrangement is not periodic.
std::pair<int, int> lattice_multiples(const TiledMap& a, const std::vector<detail::StripesProbe::Family>& families,
                                      const char* op) {
    long long k1 = 1, k2 = 1;
    for (const auto& f : families) {
        const int d1 = denominator(dot(f.normal, a.period1()) / f.period);
        const int d2 = denominator(dot(f.normal, a.period2()) / f.period);
        if (d1 == 0 || d2 == 0 || std::lcm(k1, (long long)d1) > 64 || std::lcm(k2, (long long)d2) > 64) {
            std::ostringstream m;
            m << "a partition built inside the mapper has lines repeating every " << f.period << " across the normal "
              << point_text(f.normal) << ", which do not repeat with the tiled map's periods "
              << point_text(a.period1()) << " and " << point_text(a.period2())
              << " (their projections on that normal are " << dot(f.normal, a.period1()) << " and "
              << dot(f.normal, a.period2())
              << ", not rational multiples of it within 64 periods): the mapped arrangement is not periodic; "
                 "evaluate it with the planar-map engine, or choose periods that are commensurable";
            throw Error(op, m.str());
        }
        k1 = std::lcm(k1, (long long)d1);
        k2 = std::lcm(k2, (long long)d2);
    }
    return {int(k1), int(k2)};
}

// Whether curves b, moved by `back`, are curves a: the same curves in any order, each with
// the same labels and points within tol (a closed curve from any of its points).
bool same_moved(const Curves& a, const Curves& b, const Point& back, double tol) {
    if (a.curves.size() != b.curves.size() || a.points.size() != b.points.size()) return false;
    auto same_curve = [&](const Curve& x, const Curve& y) {
        if (x.closed != y.closed || x.points.size() != y.points.size() || !(x.labels == y.labels) ||
            !(x.left == y.left) || !(x.right == y.right))
            return false;
        const std::size_t n = x.points.size();
        if (n == 0) return true;
        auto from = [&](std::size_t r) {
            for (std::size_t k = 0; k < n; ++k)
                if (distance(x.points[k], y.points[(k + r) % n] + back) > tol) return false;
            return true;
        };
        if (!x.closed) return from(0);
        for (std::size_t r = 0; r < n; ++r)
            if (distance(x.points[0], y.points[r] + back) <= tol && from(r)) return true;
        return false;
    };
    std::vector<char> used(b.curves.size(), 0);
    for (std::size_t k = 0; k < a.curves.size(); ++k) {
        bool found = false;
        // The same position first (the usual case), then any.
        for (std::size_t t = 0; t < b.curves.size() && !found; ++t) {
            const std::size_t m = (k + t) % b.curves.size();
            if (!used[m] && same_curve(a.curves[k], b.curves[m])) {
                used[m] = 1;
                found = true;
            }
        }
        if (!found) return false;
    }
    for (std::size_t k = 0; k < a.points.size(); ++k)
        if (!(a.points[k].labels == b.points[k].labels) || distance(a.points[k].point, b.points[k].point + back) > tol)
            return false;
    return true;
}

// A tiled map copies the mapper's output for each cell of the central tile by the periods,
// which is right only when the mapper's output for a copy of a cell is its output for the
// cell, moved. A mapper that reads absolute positions (a closed-form field, a test such as
// x > 0) breaks that without any Random. Checked on the copies of every cell one period
// away along -period1 and -period2 (cells of the block, with their whole neighbourhoods):
// the mapper runs on each and its output, moved back, must be the central cell's.
template <class CellT, class Mapper, class RefOf>
void check_translation_invariant(const TiledMap& a, const TiledMap::Block& b, const Mapper& m,
                                 const std::vector<int>& ids, const std::vector<TiledMap::Element>& out, RefOf ref_of,
                                 MapperThreads threads, const char* op) {
    const PlanarMap& map = *b.map;
    std::size_t count = 0;
    if constexpr (std::is_same_v<CellT, Vertex>) count = map.vertices().size();
    else if constexpr (std::is_same_v<CellT, Edge>) count = map.edges().size();
    else count = map.faces().size();
    BBox box;
    for (const auto& v : map.vertices()) box.add(v.point);
    const double scale = std::max({1.0, std::abs(box.xmin), std::abs(box.xmax), std::abs(box.ymin), std::abs(box.ymax)});
    const double tol = 1e-7 * scale;
    // The central cells by their reference point, sorted by x, to find a copy's original.
    std::vector<std::pair<Point, std::size_t>> central;
    for (std::size_t k = 0; k < ids.size(); ++k) central.push_back({ref_of(b.map, ids[k]), k});
    std::sort(central.begin(), central.end(), [](const auto& x, const auto& y) { return x.first.x < y.first.x; });
    auto original = [&](const Point& p) -> std::optional<std::size_t> {
        auto it = std::lower_bound(central.begin(), central.end(), p.x - tol,
                                   [](const auto& c, double x) { return c.first.x < x; });
        for (; it != central.end() && it->first.x <= p.x + tol; ++it)
            if (std::abs(it->first.y - p.y) <= tol) return it->second;
        return std::nullopt;
    };
    struct Probe {
        int copy;
        std::size_t original;
        Point back;
    };
    std::vector<Probe> probes;
    for (const Point& back : {a.period1(), a.period2()}) {
        for (std::size_t c = 0; c < count; ++c) {
            if constexpr (std::is_same_v<CellT, Face>) {
                if (map.faces()[c].unbounded) continue;
            }
            const Point moved = ref_of(b.map, int(c)) + back;
            if (!in_central_tile(a, moved)) continue;
            if (const auto k = original(moved)) probes.push_back({int(c), *k, back});
        }
    }
    std::vector<char> bad(probes.size(), 0);
    auto visit = [&](std::size_t k) {
        CellT cell(b.map, probes[k].copy);
        detail::NoRandomScope regular(op);
        detail::StripesProbe probe;
        bad[k] = !same_moved(out[probes[k].original].curves, m(cell), probes[k].back, tol);
    };
    if (threads == MapperThreads::Serial) {
        for (std::size_t k = 0; k < probes.size(); ++k) visit(k);
    } else {
        parallel_for(probes.size(), visit);
    }
    const auto first = std::find(bad.begin(), bad.end(), 1);
    if (first == bad.end()) return;
    const Probe& pr = probes[std::size_t(first - bad.begin())];
    std::ostringstream msg;
    msg << "the mapper's output for the cell at " << point_text(out[pr.original].anchor) << " is not its output for "
        << "the copy of that cell one period " << point_text(Point{0.0 - pr.back.x, 0.0 - pr.back.y})
        << " away, moved back: the mapper reads absolute positions (a closed-form field, a test on x or y), "
           "so its output does not repeat with the tiled map's periods "
        << point_text(a.period1()) << " and " << point_text(a.period2())
        << " and a tiled map cannot stand for it; make the mapper depend only on the cell (its geometry relative "
           "to itself, its labels and neighbours), or evaluate the script with the planar-map engine";
    throw Error(op, msg.str());
}

// The mapper run on the cells of the central tile of a's block (NIZ rule), each call in a
// probe of the partitions it builds. When those partitions repeat only on a multiple of a's
// lattice, the mapping is done again on that coarser lattice, so that the result is exact.
template <class CellT, class Mapper, class RefOf>
TiledMap map_block(const TiledMap& a, const Mapper& m, const std::vector<int> TiledMap::Block::*ids_of, RefOf ref_of,
                   MapperThreads t, const char* op, bool coarsened = false) {
    const TiledMap::Block b = a.block();
    const std::vector<int>& ids = b.*ids_of;
    std::vector<TiledMap::Element> out(ids.size());
    std::vector<std::vector<detail::StripesProbe::Family>> families(ids.size());
    auto visit = [&](std::size_t k) {
        CellT cell(b.map, ids[k]);
        detail::NoRandomScope regular(op);
        detail::StripesProbe probe;
        out[k].curves = m(cell);
        out[k].anchor = ref_of(b.map, ids[k]);
        out[k].key = anchor_key(out[k].anchor);
        families[k] = probe.families();
    };
    if (t == MapperThreads::Serial) {
        for (std::size_t k = 0; k < ids.size(); ++k) visit(k);
    } else {
        parallel_for(ids.size(), visit);
    }
    std::vector<detail::StripesProbe::Family> all;
    for (auto& f : families) all.insert(all.end(), f.begin(), f.end());
    const auto [k1, k2] = lattice_multiples(a, all, op);
    if (k1 > 1 || k2 > 1) {
        if (coarsened) throw Error(op, "the partitions built inside the mapper do not repeat on the coarser lattice");
        const TiledMap coarse(a.period1() * double(k1), a.period2() * double(k2), repeat(a, k1, k2), a.border(), {},
                              a.bounded_faces());
        return map_block<CellT>(coarse, m, ids_of, ref_of, t, op, true);
    }
    check_translation_invariant<CellT>(a, b, m, ids, out, ref_of, t, op);
    std::vector<TiledMap::Element> kept;
    for (auto& e : out) {
        e.curves.origin.clear();
        if (!e.curves.empty()) kept.push_back(std::move(e));
    }
    return TiledMap(a.period1(), a.period2(), std::move(kept), a.border());
}

}  // namespace

TiledMap GridPartition(const Stripes& s1, const Stripes& s2, Tiled t) {
    const Family f1(s1, "GridPartition"), f2(s2, "GridPartition");
    const double det = cross(f1.n, f2.n);
    if (std::abs(det) < 1e-9) throw Error("GridPartition", "the two stripe families are parallel");
    // p with n1.p = a and n2.p = b.
    auto solve = [&](double a, double b) { return Point{(a * f2.n.y - b * f1.n.y) / det, (f1.n.x * b - f2.n.x * a) / det}; };
    const Point p1 = solve(f1.period(), 0), p2 = solve(0, f2.period());
    const long long n1 = f1.count, n2 = f2.count;
    if (n1 * n2 > 4'000'000) throw Error("GridPartition", "more than 4,000,000 cells in one period");
    auto vert = [&](long long i, long long j) { return solve(f1.offsets[std::size_t(i)], f2.offsets[std::size_t(j)]); };
    auto cell_index = [&](long long i, long long j) { return int(pos_mod(i, n1) * n2 + pos_mod(j, n2)); };
    auto cell_ref = [&](long long i, long long j) {
        TiledMap::CellRef c;
        c.cell = cell_index(i, j);
        c.di = (i - pos_mod(i, n1)) / n1;
        c.dj = (j - pos_mod(j, n2)) / n2;
        return c;
    };
    std::vector<TiledMap::CellRing> cells(std::size_t(n1 * n2));
    for (long long i = 0; i < n1; ++i)
        for (long long j = 0; j < n2; ++j) {
            TiledMap::CellRing& c = cells[std::size_t(cell_index(i, j))];
            c.ring = {vert(i, j), vert(i + 1, j), vert(i + 1, j + 1), vert(i, j + 1)};
            if (signed_area(c.ring) < 0) std::reverse(c.ring.begin(), c.ring.end());
            for (const auto& p : c.ring) c.box.add(p);
            c.labels = f1.face_label(i);
            c.labels.merge(f2.face_label(j));
        }
    auto face_labels = [&](long long i, long long j) { return cells[std::size_t(cell_index(i, j))].labels; };
    std::vector<TiledMap::Element> elements;
    // Edges on the lines of family 1, oriented like the engine's (+d1): the cell above the
    // line (+n1) on the left; then those of family 2.
    const bool j_along_d1 = dot(f1.d, f2.n) > 0, i_along_d2 = dot(f2.d, f1.n) > 0;
    for (long long i = 0; i < n1; ++i)
        for (long long j = 0; j < n2; ++j) {
            Point a = vert(i, j), b = vert(i, j + 1);
            if (!j_along_d1) std::swap(a, b);
            TiledMap::Element e;
            e.curves.curves.push_back(segment(a, b, f1.edge_label(i), face_labels(i, j), face_labels(i - 1, j)));
            e.left = cell_ref(i, j);
            e.right = cell_ref(i - 1, j);
            e.anchor = (a + b) / 2;
            e.key = anchor_key(e.anchor);
            elements.push_back(std::move(e));
        }
    for (long long j = 0; j < n2; ++j)
        for (long long i = 0; i < n1; ++i) {
            Point a = vert(i, j), b = vert(i + 1, j);
            if (!i_along_d2) std::swap(a, b);
            TiledMap::Element e;
            e.curves.curves.push_back(segment(a, b, f2.edge_label(j), face_labels(i, j), face_labels(i, j - 1)));
            e.left = cell_ref(i, j);
            e.right = cell_ref(i, j - 1);
            e.anchor = (a + b) / 2;
            e.key = anchor_key(e.anchor);
            elements.push_back(std::move(e));
        }
    return TiledMap(p1, p2, std::move(elements), t.border, std::move(cells));
}

TiledMap StripesPartition(const Stripes& s, Tiled t) {
    const Family f(s, "StripesPartition");
    // Across: one full period of lines; along: pieces one period long.
    const Point across = f.n * f.period(), along = f.d * f.period();
    std::vector<TiledMap::Element> elements;
    for (long long i = 0; i < f.count; ++i) {
        const Point a = f.n * f.offsets[std::size_t(i)];
        TiledMap::Element e;
        e.curves.curves.push_back(segment(a, a + along, f.edge_label(i), f.face_label(i), f.face_label(i - 1)));
        e.anchor = a + along / 2;
        e.key = anchor_key(e.anchor);
        e.continues = true;
        elements.push_back(std::move(e));
    }
    return TiledMap(across, along, std::move(elements), t.border, s);
}

Curves TiledMap::block_curves() const {
    const int k = 2 * block_reach() + 2;
    Curves all;
    for (long long i = -k; i <= k; ++i)
        for (long long j = -k; j <= k; ++j) {
            const Point s = shift(i, j);
            for (const auto& e : d_->elements) {
                for (const auto& c : e.curves.curves) {
                    Curve copy = c;
                    for (auto& p : copy.points) p += s;
                    all.curves.push_back(std::move(copy));
                }
                for (const auto& p : e.curves.points) all.points.push_back({p.point + s, p.labels});
            }
        }
    Welder(weld_tolerance(all)).weld(all);
    return all;
}

TiledMap::Block TiledMap::block() const {
    const Curves all = block_curves();
    Block b;
    const BBox box = all.bbox();
    b.map = PlanarMap::induce(all);
    const PlanarMap& m = *b.map;
    for (std::size_t v = 0; v < m.vertices().size(); ++v)
        if (in_central_tile(*this, m.vertices()[v].point)) b.vertices.push_back(int(v));
    for (std::size_t e = 0; e < m.edges().size(); ++e)
        if (in_central_tile(*this, LocationAt(Edge(b.map, int(e)), 0.5))) b.edges.push_back(int(e));
    for (std::size_t f = 0; f < m.faces().size(); ++f) {
        if (m.faces()[f].unbounded) continue;
        if (!in_central_tile(*this, Centroid(Face(b.map, int(f))))) continue;
        // A face of the central tile reaching the block's own box is not closed within the
        // block (an infinite band, or a face wider than the block): no complete neighbourhood.
        const BBox fb = CellBBox(Face(b.map, int(f)));
        if (fb.xmin <= box.xmin || fb.ymin <= box.ymin || fb.xmax >= box.xmax || fb.ymax >= box.ymax)
            throw Error("TiledMap", "a face of the central tile reaches the edge of its block of tiles (an "
                                    "unbounded or very large face)");
        b.faces.push_back(int(f));
    }
    return b;
}

TiledMap MapToVertices(VertexMapper m, const TiledMap& a, MapperThreads t) {
    check_regular(a, "MapToVertices");
    return map_block<Vertex>(
        a, m, &TiledMap::Block::vertices, [](const MapPtr& map, int v) { return map->vertices()[v].point; }, t,
        "MapToVertices");
}

TiledMap MapToEdges(EdgeMapper m, const TiledMap& a, MapperThreads t) {
    check_regular(a, "MapToEdges");
    return map_block<Edge>(
        a, m, &TiledMap::Block::edges, [](const MapPtr& map, int e) { return LocationAt(Edge(map, e), 0.5); }, t,
        "MapToEdges");
}

TiledMap MapToFaces(FaceMapper m, const TiledMap& a, MapperThreads t) {
    check_regular(a, "MapToFaces");
    return map_block<Face>(
        a, m, &TiledMap::Block::faces, [](const MapPtr& map, int f) { return Centroid(Face(map, f)); }, t,
        "MapToFaces");
}

TiledMap GhostMap(GhostMapper g, const TiledMap& a) {
    if (!g) throw Error("GhostMap", "no mapper given");
    if (a.has_ghost()) throw Error("GhostMap", "the tiled map already has a ghost mapper");
    return a.with_ghost(std::move(g));
}

namespace {

// The integer n (1..64) with n * q equal to a whole multiple of p (p and q parallel), or 0.
int commensurate(const Point& p, const Point& q, int& multiple_of_p) {
    if (std::abs(cross(p, q)) > 1e-9 * norm(p) * norm(q)) return 0;
    const double ratio = dot(q, p) / dot(p, p);  // q = ratio * p
    for (int n = 1; n <= 64; ++n) {
        const double k = n * ratio;
        if (std::abs(k - std::round(k)) < 1e-9 * std::max(1.0, std::abs(k)) && std::round(k) != 0) {
            multiple_of_p = int(std::llround(std::abs(k)));
            return n;
        }
    }
    return 0;
}

std::string periods_text(const TiledMap& a) {
    std::ostringstream s;
    s << "(" << a.period1().x << ", " << a.period1().y << ") and (" << a.period2().x << ", " << a.period2().y << ")";
    return s.str();
}

// The elements of a repeated m1 x m2 times, as the elements of a coarser lattice. A piece of
// a line (continues along period2) becomes one piece m2 times as long, which continues along
// the coarser period2.
std::vector<TiledMap::Element> repeat(const TiledMap& a, int m1, int m2) {
    std::vector<TiledMap::Element> out;
    for (int i = 0; i < m1; ++i)
        for (const auto& e : a.elements()) {
            if (!e.continues) continue;
            TiledMap::Element c;
            const Curve& piece = e.curves.curves.front();
            Curve line = piece;
            line.points.assign(1, piece.points.front() + a.shift(i, 0));
            for (int j = 0; j < m2; ++j)  // the inner points of every piece
                for (std::size_t k = 1; k + 1 < piece.points.size(); ++k) line.points.push_back(piece.points[k] + a.shift(i, j));
            line.points.push_back(piece.points.back() + a.shift(i, m2 - 1));
            c.curves.curves.push_back(std::move(line));
            c.anchor = e.anchor + a.shift(i, 0);
            c.key = anchor_key(c.anchor);
            c.continues = true;
            out.push_back(std::move(c));
        }
    for (int i = 0; i < m1; ++i)
        for (int j = 0; j < m2; ++j) {
            const Point s = a.shift(i, j);
            for (const auto& e : a.elements()) {
                if (e.continues) continue;
                TiledMap::Element c;
                c.curves = e.curves;
                c.curves.transform(Affine::translation(s));
                c.anchor = e.anchor + s;
                c.key = anchor_key(c.anchor);
                out.push_back(std::move(c));
            }
        }
    return out;
}

}  // namespace

namespace {

// Both maps on their common lattice: each period of the result is the least common multiple
// of the two maps' periods of that rank, which must be parallel with a rational ratio
// (denominator at most 64).
struct Common {
    Point p1, p2;
    std::vector<TiledMap::Element> first, second;
};

Common common_lattice(const TiledMap& a1, const TiledMap& a2, const char* op) {
    if (a1.has_ghost() || a2.has_ghost())
        throw Error(op, "a tiled map with a ghost mapper cannot be combined; combine before GhostMap");
    int k1 = 0, k2 = 0;
    const int n1 = commensurate(a1.period1(), a2.period1(), k1);
    const int n2 = commensurate(a1.period2(), a2.period2(), k2);
    if (n1 == 0 || n2 == 0)
        throw Error(op, "the periods " + periods_text(a1) + " and " + periods_text(a2) +
                            " have no common multiple (the lattices must share their directions, "
                            "with rational length ratios)");
    // n * q = k * p: the common period is k * p1 for map 1, n * q1 for map 2.
    return {a1.period1() * double(k1), a1.period2() * double(k2), repeat(a1, k1, k2), repeat(a2, n1, n2)};
}

// The pieces of lines that a mask kept, joined again where the line was cut only by the
// period. A tiled line is stored one period at a time (Element::continues), so the mask sees
// pieces and keeps cuts where the engine, masking whole lines, has none. Two kept curves are
// joined at a joint of the stored pieces (the start of a `continues` element, up to the
// lattice) when exactly one of them ends there and one starts there, both open with equal
// labels, and nothing else passes there (no other kept curve, no curve of the mask): a
// vertex of degree 2 in the engine's map too. A piece that the mask kept whole (it starts
// where its own copy ends) is a whole line again (continues). The joint point itself is left
// out when the line is straight there, as the engine draws a stripe's line as one segment.
struct JoinedCurve {
    Curve curve;
    bool continues = false;
};

std::vector<JoinedCurve> join_line_pieces(const TiledMap& lattice, const std::vector<Point>& joints,
                                          std::vector<Curve> kept, const Curves& mask_block) {
    std::vector<JoinedCurve> out;
    const std::size_t n = kept.size();
    double scale = 1;
    for (const auto& c : kept)
        for (const auto& p : c.points) scale = std::max({scale, std::abs(p.x), std::abs(p.y)});
    const double tol = 1e-9 * scale;
    // The shift (in periods) taking b onto a, when a - b is a lattice vector.
    auto lattice_shift = [&](const Point& a, const Point& b) -> std::optional<std::pair<long long, long long>> {
        const Point l = lattice.lattice(a - b);
        const long long i = std::llround(l.x), j = std::llround(l.y);
        if (distance(a, b + lattice.shift(i, j)) > tol) return std::nullopt;
        return std::pair{i, j};
    };
    auto near_segment = [&](const Point& p, const Point& a, const Point& b) {
        const Point d = b - a;
        const double l2 = dot(d, d);
        const double t = l2 > 0 ? std::clamp(dot(p - a, d) / l2, 0.0, 1.0) : 0.0;
        return distance(p, a + d * t) <= tol;
    };
    const int reach = lattice.block_reach() + 1;
    // next[k]: the curve that continues curve k, and the shift that puts it after k's end.
    struct Next {
        std::size_t curve = SIZE_MAX;
        long long i = 0, j = 0;
    };
    std::vector<Next> next(n);
    std::vector<char> has_prev(n, 0);
    for (const Point& joint : joints) {
        std::vector<std::size_t> ends, starts;
        bool blocked = false;
        for (std::size_t k = 0; k < n && !blocked; ++k) {
            const Curve& c = kept[k];
            if (c.points.size() < 2) continue;
            const bool e = lattice_shift(c.points.back(), joint).has_value();
            const bool s = lattice_shift(c.points.front(), joint).has_value();
            if (c.closed && (e || s)) blocked = true;
            if (e) ends.push_back(k);
            if (s) starts.push_back(k);
            // A curve through a copy of the joint elsewhere than at its ends.
            for (std::size_t m = 1; m + 1 < c.points.size() && !blocked; ++m)
                blocked = lattice_shift(c.points[m], joint).has_value();
            const std::size_t segs = c.closed ? c.points.size() : c.points.size() - 1;
            for (std::size_t m = 0; m < segs && !blocked; ++m) {
                const Point& a = c.points[m];
                const Point& b = c.points[(m + 1) % c.points.size()];
                for (long long i = -reach; i <= reach && !blocked; ++i)
                    for (long long j = -reach; j <= reach && !blocked; ++j) {
                        const Point q = joint + lattice.shift(i, j);
                        if (near_segment(q, a, b) && distance(q, a) > tol && distance(q, b) > tol) blocked = true;
                    }
            }
        }
        if (blocked || ends.size() != 1 || starts.size() != 1) continue;
        const Curve &a = kept[ends[0]], &b = kept[starts[0]];
        if (!(a.labels == b.labels && a.left == b.left && a.right == b.right)) continue;
        // No curve of the mask through the joint (the mask's block surrounds the central tile).
        const Point at = a.points.back();
        bool on_mask = false;
        for (const auto& c : mask_block.curves) {
            const std::size_t segs = c.closed ? c.points.size() : c.points.size() - 1;
            for (std::size_t m = 0; m < segs && !on_mask; ++m)
                on_mask = near_segment(at, c.points[m], c.points[(m + 1) % c.points.size()]);
            if (on_mask) break;
        }
        if (on_mask) continue;
        const auto sh = lattice_shift(a.points.back(), b.points.front());
        if (!sh) continue;
        next[ends[0]] = {starts[0], sh->first, sh->second};
        has_prev[starts[0]] = 1;
    }
    auto straight = [&](const Point& p, const Point& q, const Point& r) {
        return std::abs(cross(q - p, r - q)) <= tol * (norm(q - p) + norm(r - q));
    };
    std::vector<char> used(n, 0);
    // A piece kept whole: its own successor, one period along.
    for (std::size_t k = 0; k < n; ++k) {
        if (next[k].curve != k) continue;
        used[k] = 1;
        const bool one_period_along = next[k].i == 0 && next[k].j == 1;
        out.push_back({std::move(kept[k]), one_period_along});
    }
    // Chains from a curve with no predecessor; the rest (cycles of several pieces, which a
    // tiled line does not make) stay as they are.
    for (std::size_t k = 0; k < n; ++k) {
        if (used[k] || has_prev[k]) continue;
        Curve line = kept[k];
        used[k] = 1;
        long long si = 0, sj = 0;
        for (std::size_t c = k; next[c].curve != SIZE_MAX && !used[next[c].curve];) {
            const Next& nx = next[c];
            si += nx.i;
            sj += nx.j;
            const Point s = lattice.shift(si, sj);
            const Curve& b = kept[nx.curve];
            // The joint (the line's last point, b's first): dropped where the line goes
            // straight through it.
            if (line.points.size() >= 2 && straight(line.points[line.points.size() - 2], line.points.back(), b.points[1] + s))
                line.points.pop_back();
            for (std::size_t m = 1; m < b.points.size(); ++m) line.points.push_back(b.points[m] + s);
            used[nx.curve] = 1;
            c = nx.curve;
        }
        out.push_back({std::move(line), false});
    }
    for (std::size_t k = 0; k < n; ++k)
        if (!used[k]) out.push_back({std::move(kept[k]), false});
    return out;
}

// Inside / Outside: a1's elements cut by (or kept against) the bounded faces of a2. The mask
// is the planar map of a2 over a block of tiles wide enough to hold every element of a1 with
// the faces around it, induced once.
TiledMap mask(const TiledMap& a1, const TiledMap& a2, Border b, MaskSide side, const char* op) {
    Common c = common_lattice(a1, a2, op);
    const TiledMap subject(c.p1, c.p2, std::move(c.first), a1.border(), {}, a1.bounded_faces());
    const TiledMap masks(c.p1, c.p2, std::move(c.second), a1.border(), {}, a2.bounded_faces());
    const Border cut = b == Border::CROP_ADD_BOUNDARY ? Border::CROP : b;
    const int k = subject.block_reach() + 2 * masks.block_reach() + 2;
    Curves block;
    for (long long i = -k; i <= k; ++i)
        for (long long j = -k; j <= k; ++j)
            for (const auto& e : masks.elements()) {
                Curves copy = e.curves;
                copy.transform(Affine::translation(masks.shift(i, j)));
                block.append(std::move(copy));
            }
    Welder(weld_tolerance(block)).weld(block);
    const MapPtr mask_map = PlanarMap::induce(block);
    // One mask over all of a1's elements at once (KEEP_* then see a1's own edges, as in the
    // engine); every curve it keeps becomes an element of its own.
    Curves all;
    for (const auto& e : subject.elements()) all.append(e.curves);
    Curves kept = apply_mask(all, *mask_map, side, cut);
    std::vector<Point> joints;
    for (const auto& e : subject.elements())
        if (e.continues && !e.curves.curves.empty() && !e.curves.curves.front().points.empty())
            joints.push_back(e.curves.curves.front().points.front());
    std::vector<TiledMap::Element> elements;
    for (auto& joined : join_line_pieces(subject, joints, std::move(kept.curves), block)) {
        TiledMap::Element e;
        e.anchor = joined.curve.points.empty() ? Point{} : joined.curve.points.front();
        e.key = anchor_key(e.anchor);
        e.continues = joined.continues;
        e.curves.curves.push_back(std::move(joined.curve));
        elements.push_back(std::move(e));
    }
    for (const auto& point : kept.points) {
        TiledMap::Element e;
        e.curves.points.push_back(point);
        e.anchor = point.point;
        e.key = anchor_key(e.anchor);
        elements.push_back(std::move(e));
    }
    TiledMap out(c.p1, c.p2, std::move(elements), a1.border(), {}, a1.bounded_faces());
    // CROP_ADD_BOUNDARY: the mask's own curves added once (not once per element).
    return b == Border::CROP_ADD_BOUNDARY ? Union(out, masks) : out;
}

}  // namespace

TiledMap Union(const TiledMap& a1, const TiledMap& a2) {
    Common c = common_lattice(a1, a2, "Union");
    for (auto& e : c.second) c.first.push_back(std::move(e));
    const bool bounded = a1.bounded_faces() && a2.bounded_faces();
    return TiledMap(c.p1, c.p2, std::move(c.first), a1.border(), {}, bounded);
}

TiledMap Inside(const TiledMap& a1, const TiledMap& a2, Border b) { return mask(a1, a2, b, MaskSide::Inside, "Inside"); }

TiledMap Outside(const TiledMap& a1, const TiledMap& a2, Border b) {
    return mask(a1, a2, b, MaskSide::Outside, "Outside");
}

}  // namespace tex
