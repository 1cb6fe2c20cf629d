// Partitioning operators (thesis 3.3).
//
// Every partition first builds a small cell complex around the region (vertices, edges with
// the cells on their two sides, cells with labels) in doubles, each vertex computed once and
// shared by all its edges so that the exact planar map sees a clean topology. The border
// mode then turns the complex into curves: KEEP_* keep whole cells, CROP* cut the cells'
// edges with the region through an exact planar map (merge.cpp).
#include "libtex/partitions.hpp"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <numeric>
#include <optional>
#include <sstream>
#include <unordered_map>
#include <utility>

#include "libtex/error.hpp"
#include "libtex/merge.hpp"
#include "libtex/random.hpp"
#include "geometry/segment_index.hpp"

namespace tex {
namespace {

// ---------------------------------------------------------------------------------------
// Cell complex

struct Complex {
    struct CEdge {
        int a, b;         // vertex ids
        int left, right;  // cell ids, -1 when there is no cell on that side
        Labels labels;
    };
    struct CCell {
        std::size_t first = 0, size = 0;  // its ring: ring_points[first, first + size)
        BBox box;
        Labels labels;
    };
    std::vector<Point> verts;
    std::vector<CEdge> edges;
    std::vector<CCell> cells;
    std::vector<Point> ring_points;  // the cells' rings, counter-clockwise, one after another
    std::vector<LabeledPoint> vertex_labels;
    // Proved clean (see "Clean complexes" below): its edges meet only at shared vertices,
    // and different vertices have different points, in doubles as well as in exact values.
    bool clean = false;

    int add_cell(const std::vector<Point>& ring, Labels labels) {
        CCell c;
        c.first = ring_points.size();
        c.size = ring.size();
        ring_points.insert(ring_points.end(), ring.begin(), ring.end());
        if (signed_area(ring) < 0) std::reverse(ring_points.begin() + std::ptrdiff_t(c.first), ring_points.end());
        for (const auto& p : ring) c.box.add(p);
        c.labels = std::move(labels);
        cells.push_back(std::move(c));
        return int(cells.size()) - 1;
    }
    // Cell i's ring, into a buffer of the caller's (one for all the cells it reads).
    void ring_of(std::size_t i, std::vector<Point>& ring) const {
        const auto begin = ring_points.begin() + std::ptrdiff_t(cells[i].first);
        ring.assign(begin, begin + std::ptrdiff_t(cells[i].size));
    }

    // The cell containing p (first match), or -1.
    int locate(const Point& p) const {
        std::vector<Point> ring;
        for (std::size_t i = 0; i < cells.size(); ++i) {
            if (!cells[i].box.contains(p)) continue;
            ring_of(i, ring);
            if (point_in_ring(p, ring)) return int(i);
        }
        return -1;
    }
};

Curve complex_edge_curve(const Complex& cx, const Complex::CEdge& e, const std::vector<char>* kept) {
    Curve c;
    c.points = {cx.verts[e.a], cx.verts[e.b]};
    c.labels = e.labels;
    auto side = [&](int cell) {
        if (cell < 0) return Labels{};
        if (kept && !(*kept)[cell]) return Labels{};
        return cx.cells[cell].labels;
    };
    c.left = side(e.left);
    c.right = side(e.right);
    return c;
}

// Turns a complex into the curves of a partition of region r with border mode b. For the
// KEEP modes, `ends` (when given) receives the complex's vertex ids of each curve's two ends,
// and with `only` the edges without that label are left out (the cells kept are the same).
Curves realize(const Complex& cx, const Region& r, Border b, detail::KnownVertices* ends = nullptr,
               std::optional<LabelId> only = std::nullopt) {
    Curves out;
    if (b == Border::KEEP_INSIDE || b == Border::KEEP_OUTSIDE) {
        std::vector<char> kept(cx.cells.size(), 0);
        // Many cells against a region of many vertices (a traced face): index the region
        // once; the answers are the same.
        std::optional<PreparedRegion> prepared;
        if (cx.cells.size() > 4 && PreparedRegion::worth_preparing(r)) prepared.emplace(r);
        std::vector<Point> ring;
        for (std::size_t i = 0; i < cx.cells.size(); ++i) {
            const auto& c = cx.cells[i];
            cx.ring_of(i, ring);
            if (prepared)
                kept[i] = b == Border::KEEP_INSIDE ? prepared->classify_polygon(ring, c.box) == Overlap::Inside
                                                   : prepared->polygon_meets_region(ring, c.box);
            else
                kept[i] = b == Border::KEEP_INSIDE ? classify_polygon(ring, c.box, r) == Overlap::Inside
                                                   : polygon_meets_region(ring, c.box, r);
        }
        out.curves.reserve(cx.edges.size());
        for (const auto& e : cx.edges) {
            const bool l = e.left >= 0 && kept[e.left];
            const bool rr = e.right >= 0 && kept[e.right];
            if ((l || rr) && !(only && !e.labels.has(*only))) {
                out.curves.push_back(complex_edge_curve(cx, e, &kept));
                if (ends) ends->ends.push_back({e.a, e.b});
            }
        }
        if (ends) ends->count = cx.verts.size();
        for (const auto& lp : cx.vertex_labels)
            out.points.push_back(lp);  // labels only attach to vertices that exist
        return out;
    }
    // CROP modes: edges of the cells that may meet the region, cut by the region.
    Curves subject;
    const BBox& rb = r.bbox();
    for (const auto& e : cx.edges) {
        BBox eb;
        eb.add(cx.verts[e.a]);
        eb.add(cx.verts[e.b]);
        if (eb.intersects(rb)) subject.curves.push_back(complex_edge_curve(cx, e, nullptr));
    }
    subject.points = cx.vertex_labels;
    static const LabelId outline = intern_label("\x01libtex-outline");
    out = detail::crop_to_region(subject, r, b, outline);
    if (b == Border::CROP_ADD_BOUNDARY) {
        // Pieces of the region's outline keep the labels of the region's edges (none for a
        // plain region) and get on their inner side the labels of the cell they bound, so
        // that a face bounded only by the outline keeps its labels.
        detail::label_outline_pieces(out, outline, [&](const Point& probe, const Point& mid) -> std::optional<Labels> {
            int cell = cx.locate(probe);
            if (cell < 0) cell = cx.locate(mid);
            if (cell < 0) return std::nullopt;
            return cx.cells[cell].labels;
        });
    }
    return out;
}

// The planar map of realize(cx, r, b). A KEEP mode keeps whole cells, so when the complex is
// clean its kept edges are a clean drawing whose vertices the complex already names: the map
// is traced without the exact check of every pair of segments and without sorting their end
// points (detail::induce_clean_complex). Otherwise (CROP modes, or a complex that rounding
// may have made unclean) the map is induced from the curves.
MapPtr realize_map(const Complex& cx, const Region& r, Border b) {
    if (cx.clean && (b == Border::KEEP_INSIDE || b == Border::KEEP_OUTSIDE)) {
        detail::KnownVertices ends;
        const Curves curves = realize(cx, r, b, &ends);
        return detail::induce_clean_complex(curves, ends);
    }
    return PlanarMap::induce(realize(cx, r, b));
}

// The edges of realize_map(cx, r, b), read without building the map, when the map's
// edges are the complex's kept edges one for one: a clean complex in a KEEP mode (each kept
// edge is a curve of its own whose ends are vertices). Then each edge runs like its curve,
// and the map orders its edges by their pairs of end points (its vertices are numbered in
// the order of their points), and keys an edge and a vertex by hashing their points. With
// `only`, the edges with that label, in the same order.
// Curves that are the map's edges one for one, as those edges: in the map's order, keyed.
std::vector<LocalEdge> edges_in_map_order(Curves curves) {
    const std::size_t n = curves.curves.size();
    struct Ends {
        Point lo, hi;
        std::uint32_t curve;
    };
    std::vector<Ends> order(n);
    for (std::size_t i = 0; i < n; ++i) {
        const auto [lo, hi] = std::minmax(curves.curves[i].points.front(), curves.curves[i].points.back());
        order[i] = {lo, hi, std::uint32_t(i)};
    }
    std::sort(order.begin(), order.end(), [](const Ends& x, const Ends& y) {
        return x.lo < y.lo || (x.lo == y.lo && x.hi < y.hi);
    });
    std::vector<LocalEdge> edges(n);
    for (std::size_t k = 0; k < n; ++k) {
        LocalEdge& e = edges[k];
        e.curve = std::move(curves.curves[order[k].curve]);
        e.source_key = detail::vertex_key(e.curve.points.front());
        e.target_key = detail::vertex_key(e.curve.points.back());
        e.key = detail::edge_key(e.curve.points);
    }
    return edges;
}

std::optional<std::vector<LocalEdge>> realize_edges(const Complex& cx, const Region& r, Border b,
                                                    std::optional<LabelId> only) {
    if (!cx.clean || !(b == Border::KEEP_INSIDE || b == Border::KEEP_OUTSIDE)) return std::nullopt;
    return edges_in_map_order(realize(cx, r, b, nullptr, only));
}

// The edges of a stripes partition in CROP mode, read without building the map. Its lines
// are parallel: the pieces the crop leaves of them are segments that meet no other piece
// except where two share an end (a line through a vertex of the region), and the map's
// vertices are the pieces' ends, so each piece is an edge of the map on its own. With
// `only`, the pieces with that label, in the same order.
std::vector<LocalEdge> stripes_crop_edges(const Complex& cx, const Region& r, std::optional<LabelId> only) {
    Curves pieces = realize(cx, r, Border::CROP);
    if (only) {
        std::size_t kept = 0;
        for (std::size_t i = 0; i < pieces.curves.size(); ++i) {
            if (!pieces.curves[i].labels.has(*only)) continue;
            if (kept != i) pieces.curves[kept] = std::move(pieces.curves[i]);
            ++kept;
        }
        pieces.curves.resize(kept);
    }
    return edges_in_map_order(std::move(pieces));
}

// ---------------------------------------------------------------------------------------
// Clean complexes
//
// A stripes or grid complex is a set of lines with offsets a_i (doubles, so exact values):
// the exact complex of those lines is clean, and any two of its segments that share no
// vertex are at least the smallest gap between two neighbouring lines apart (the segments
// of one line are one gap of the other family long; sin <= 1). Its vertices are computed in
// doubles, each within `err` of its exact position. Moving every vertex by less than half
// the smallest gap keeps segments without a common vertex apart, keeps the far end of a
// segment off its neighbours (so no overlap), and keeps different vertices at different
// points: the drawing in doubles is clean, with the complex's own vertices. The bound on
// `err` is the usual one for a 2 x 2 solve, |offsets| u / det^2 with a few units to spare,
// and the test asks for the gap to exceed it 64 times over.
bool rounding_keeps_clean(double min_gap, double magnitude, double det) {
    constexpr double u = std::numeric_limits<double>::epsilon();
    const double err = 8 * u * magnitude / (det * det);
    return std::isfinite(min_gap) && std::isfinite(err) && min_gap > 64 * err;
}

// ---------------------------------------------------------------------------------------
// Stripes

long long floor_div(long long a, long long b) {
    long long q = a / b;
    if ((a % b != 0) && ((a < 0) != (b < 0))) --q;
    return q;
}
long long pos_mod(long long a, long long m) { return ((a % m) + m) % m; }

struct StripeFamily {
    Point d, n;  // direction of the lines and normal (d rotated by +90 degrees)
    std::vector<double> prefix;  // prefix[k] = w0 + ... + w_{k-1}, prefix.size() = m + 1
    double period = 0;
    const Stripes* p = nullptr;
    // The label cycles, interned once (a partition asks for a label per line and band).
    std::vector<LabelId> edge_ids, face_ids;

    explicit StripeFamily(const Stripes& s) : p(&s) {
        for (const auto& l : s.edge_labels) edge_ids.push_back(intern_label(l));
        for (const auto& l : s.face_labels) face_ids.push_back(intern_label(l));
        d = {std::cos(s.angle), std::sin(s.angle)};
        // cos(pi/2) is 6e-17, not 0: snap axis-aligned directions so that lines meant to be
        // vertical or horizontal are exactly so (no sliver faces along a region's sides).
        if (std::abs(d.x) < 1e-12) d = {0.0, d.y > 0 ? 1.0 : -1.0};
        if (std::abs(d.y) < 1e-12) d = {d.x > 0 ? 1.0 : -1.0, 0.0};
        n = {-d.y, d.x};
        prefix.push_back(0);
        for (double w : s.widths) prefix.push_back(prefix.back() + w);
        period = prefix.back();
    }
    std::size_t m() const { return prefix.size() - 1; }
    // Distance across which the widths and both label cycles repeat.
    double full_period() const {
        long long n = (long long)m();
        if (!p->edge_labels.empty()) n = std::lcm(n, (long long)p->edge_labels.size());
        if (!p->face_labels.empty()) n = std::lcm(n, (long long)p->face_labels.size());
        return period * double(n / (long long)m());
    }
    double offset(long long i) const {
        const long long k = floor_div(i, (long long)m());
        return double(k) * period + prefix[pos_mod(i, (long long)m())];
    }
    // Largest i with offset(i) <= t.
    long long index_at(double t) const {
        const double k = std::floor(t / period);
        const double rem = t - k * period;
        long long j = (long long)(std::upper_bound(prefix.begin(), prefix.end() - 1, rem) - prefix.begin()) - 1;
        if (j < 0) j = 0;
        return (long long)k * (long long)m() + j;
    }
    Labels edge_label(long long i) const {
        Labels l;
        if (!edge_ids.empty()) l.add(edge_ids[std::size_t(pos_mod(i, (long long)edge_ids.size()))]);
        return l;
    }
    Labels face_label(long long i) const {
        Labels l;
        if (!face_ids.empty()) l.add(face_ids[std::size_t(pos_mod(i, (long long)face_ids.size()))]);
        return l;
    }
};

// Stripes and their family, made once for a partition (its labels interned once, not at
// every region it is evaluated on).
struct PreparedStripes {
    Stripes s;
    StripeFamily f{s};
    explicit PreparedStripes(const Stripes& stripes) : s(stripes) {}
    PreparedStripes(const PreparedStripes&) = delete;  // f points into s
    PreparedStripes& operator=(const PreparedStripes&) = delete;
};

void check_stripes(const Stripes& s, const char* op) {
    if (!std::isfinite(s.angle)) throw Error(op, "the angle is not a finite number");
    if (s.widths.empty()) throw Error(op, "no width given");
    for (double w : s.widths)
        if (!(w > 0) || !std::isfinite(w)) {
            std::ostringstream m;
            m << "width " << w << " is not a positive number";
            throw Error(op, m.str());
        }
}

// Projection range of the region's bounding box (expanded) on a unit vector.
std::pair<double, double> project(const BBox& b, const Point& u) {
    const Point corners[4] = {{b.xmin, b.ymin}, {b.xmax, b.ymin}, {b.xmax, b.ymax}, {b.xmin, b.ymax}};
    double lo = dot(corners[0], u), hi = lo;
    for (const auto& c : corners) {
        lo = std::min(lo, dot(c, u));
        hi = std::max(hi, dot(c, u));
    }
    return {lo, hi};
}

thread_local detail::StripesProbe* t_probe = nullptr;

Complex stripes_complex(const StripeFamily& f, const Region& r) {
    detail::StripesProbe::record(f.n, f.full_period());
    const BBox box = r.bbox().expanded(1.0 + 0.01 * std::max(r.bbox().width(), r.bbox().height()));
    auto [tlo, thi] = project(box, f.n);
    auto [slo, shi] = project(box, f.d);
    const long long i0 = f.index_at(tlo), i1 = f.index_at(thi) + 1;
    if (i1 - i0 > 4'000'000) throw Error("StripesPartition", "too many stripes for the region");
    Complex cx;
    // Bands i0 - 1 .. i1 clipped to the [slo, shi] range along the lines.
    auto pt = [&](double t, double sv) { return f.n * t + f.d * sv; };
    std::vector<Point> ring;
    for (long long i = i0 - 1; i <= i1; ++i) {
        const double a = f.offset(i), b = f.offset(i + 1);
        ring.assign({pt(a, slo), pt(a, shi), pt(b, shi), pt(b, slo)});
        cx.add_cell(ring, f.face_label(i));
    }
    for (long long i = i0; i <= i1; ++i) {
        const double t = f.offset(i);
        cx.verts.push_back(pt(t, slo));
        cx.verts.push_back(pt(t, shi));
        const int cell_left = int(i - (i0 - 1));  // band i lies on the +n (left) side of line i
        cx.edges.push_back({int(cx.verts.size()) - 2, int(cx.verts.size()) - 1, cell_left,
                            cell_left - 1, f.edge_label(i)});
    }
    double gap = std::numeric_limits<double>::infinity();
    for (long long i = i0; i < i1; ++i) gap = std::min(gap, f.offset(i + 1) - f.offset(i));
    const double mag = std::max(std::abs(f.offset(i0)), std::abs(f.offset(i1))) +
                       std::max(std::abs(slo), std::abs(shi));
    cx.clean = rounding_keeps_clean(gap, mag, 1.0);
    return cx;
}

Complex grid_complex(const StripeFamily& f1, const StripeFamily& f2, const Region& r) {
    const double det = cross(f1.n, f2.n);
    if (std::abs(det) < 1e-9) throw Error("GridPartition", "the two stripe families are parallel");
    detail::StripesProbe::record(f1.n, f1.full_period());
    detail::StripesProbe::record(f2.n, f2.full_period());
    const BBox box = r.bbox().expanded(1e-6 * (1 + r.bbox().width() + r.bbox().height()));
    auto [t1lo, t1hi] = project(box, f1.n);
    auto [t2lo, t2hi] = project(box, f2.n);
    const long long i0 = f1.index_at(t1lo), i1 = f1.index_at(t1hi) + 1;
    const long long j0 = f2.index_at(t2lo), j1 = f2.index_at(t2hi) + 1;
    if ((i1 - i0 + 1) * (j1 - j0 + 1) > 20'000'000)
        throw Error("GridPartition", "too many cells for the region");
    const long long ni = i1 - i0 + 1, nj = j1 - j0 + 1;
    Complex cx;
    // Vertex (i, j): p.n1 = offset1(i), p.n2 = offset2(j).
    cx.verts.resize(std::size_t(ni * nj));
    auto vid = [&](long long i, long long j) { return int((i - i0) * nj + (j - j0)); };
    for (long long i = i0; i <= i1; ++i) {
        const double a = f1.offset(i);
        for (long long j = j0; j <= j1; ++j) {
            const double b = f2.offset(j);
            // Solve [n1; n2] p = [a; b].
            cx.verts[vid(i, j)] = Point{(a * f2.n.y - b * f1.n.y) / det, (f1.n.x * b - f2.n.x * a) / det};
        }
    }
    // Cells (i, j) for i in [i0, i1), j in [j0, j1), skipping those far from the region.
    std::vector<int> cell_id(std::size_t((ni - 1) * (nj - 1)), -1);
    cx.cells.reserve(cell_id.size());
    cx.ring_points.reserve(4 * cell_id.size());
    cx.edges.reserve(std::size_t(ni * (nj - 1) + nj * (ni - 1)));
    auto cid = [&](long long i, long long j) -> int {
        if (i < i0 || i >= i1 || j < j0 || j >= j1) return -1;
        return cell_id[std::size_t((i - i0) * (nj - 1) + (j - j0))];
    };
    std::vector<Point> ring;
    for (long long i = i0; i < i1; ++i)
        for (long long j = j0; j < j1; ++j) {
            ring.assign({cx.verts[vid(i, j)], cx.verts[vid(i + 1, j)], cx.verts[vid(i + 1, j + 1)], cx.verts[vid(i, j + 1)]});
            BBox cb;
            for (const auto& p : ring) cb.add(p);
            if (!cb.intersects(box)) continue;
            Labels l = f1.face_label(i);
            l.merge(f2.face_label(j));
            cell_id[std::size_t((i - i0) * (nj - 1) + (j - j0))] = cx.add_cell(ring, std::move(l));
        }
    // Edges along the lines of family 1 (between family-2 lines j and j+1), oriented +d1:
    // the band above (+n1) is cell (i, j), the one below is cell (i-1, j).
    const bool j_along_d1 = dot(f1.d, f2.n) > 0;
    for (long long i = i0; i <= i1; ++i)
        for (long long j = j0; j < j1; ++j) {
            const int left = cid(i, j), right = cid(i - 1, j);
            if (left < 0 && right < 0) continue;
            int a = vid(i, j), b = vid(i, j + 1);
            if (!j_along_d1) std::swap(a, b);
            cx.edges.push_back({a, b, left, right, f1.edge_label(i)});
        }
    const bool i_along_d2 = dot(f2.d, f1.n) > 0;
    for (long long j = j0; j <= j1; ++j)
        for (long long i = i0; i < i1; ++i) {
            const int left = cid(i, j), right = cid(i, j - 1);
            if (left < 0 && right < 0) continue;
            int a = vid(i, j), b = vid(i + 1, j);
            if (!i_along_d2) std::swap(a, b);
            cx.edges.push_back({a, b, left, right, f2.edge_label(j)});
        }
    double gap = std::numeric_limits<double>::infinity();
    for (long long i = i0; i < i1; ++i) gap = std::min(gap, f1.offset(i + 1) - f1.offset(i));
    for (long long j = j0; j < j1; ++j) gap = std::min(gap, f2.offset(j + 1) - f2.offset(j));
    const double mag = std::max(std::abs(f1.offset(i0)), std::abs(f1.offset(i1))) +
                       std::max(std::abs(f2.offset(j0)), std::abs(f2.offset(j1)));
    cx.clean = rounding_keeps_clean(gap, mag, std::abs(det));
    return cx;
}

// ---------------------------------------------------------------------------------------
// Irregular partitions

void check_density(double d, const char* op) {
    if (!(d > 0) || !std::isfinite(d)) {
        std::ostringstream m;
        m << "density " << d << " is not a positive number";
        throw Error(op, m.str());
    }
}

void check_weights(const std::vector<WeightedLabel>& w, const char* op) {
    double sum = 0;
    for (const auto& l : w) {
        if (!(l.weight >= 0 && l.weight <= 1)) {
            std::ostringstream m;
            m << "weight " << l.weight << " of label '" << l.label << "' is not a probability in [0, 1]";
            throw Error(op, m.str());
        }
        sum += l.weight;
    }
    if (sum > 1 + 1e-9) {
        std::ostringstream m;
        m << "the weights sum to " << sum << ", more than 1";
        throw Error(op, m.str());
    }
}

Labels pick_label(const std::vector<WeightedLabel>& w, std::uint64_t stream, std::uint64_t key) {
    Labels l;
    if (w.empty()) return l;
    const double u = unit_from_hash(hash_combine(hash_combine(mix64(GetSeed() ^ 0x4c41424cULL), stream), key));
    double acc = 0;
    for (const auto& x : w) {
        acc += x.weight;
        if (u < acc) {
            l.add(x.label);
            break;
        }
    }
    return l;
}

struct TileKey {
    long long i, j;
    bool operator==(const TileKey& o) const { return i == o.i && j == o.j; }
};
struct TileHash {
    std::size_t operator()(const TileKey& k) const {
        return hash_combine(std::uint64_t(k.i), std::uint64_t(k.j));
    }
};

std::uint64_t tile_seed(std::uint64_t salt, std::uint64_t stream, double density, long long i, long long j) {
    std::uint64_t h = hash_combine(hash_combine(mix64(GetSeed() ^ salt), stream), std::uint64_t(i));
    h = hash_combine(h, std::uint64_t(j));
    return hash_double(h, density);
}

// Measured with PoissonDiskSites on large boxes (tests/libtex/test_partitions.cpp checks
// the resulting density): sites per unit area = kDiskPacking / r^2.
constexpr double kDiskPacking = 0.623;
constexpr int kDartsPerTile = 48;

// Poisson-disk sampling anchored to the plane. The plane is cut into square tiles of side
// 2r coloured in four phases (parity of i and j). A tile's darts are thrown after those of
// its lower-phase neighbours and tested against them; tiles of one phase are two radii
// apart and never conflict. The sites of a tile therefore depend only on the tiles within
// three steps of it, whatever region asked for them.
class DiskSampler {
public:
    DiskSampler(double density, std::uint64_t stream)
        : density_(density), stream_(stream), r_(PoissonDiskRadius(density)), s_(2 * r_) {}

    std::vector<Point> sites(const BBox& box) {
        std::vector<Point> out;
        const long long i0 = (long long)std::floor(box.xmin / s_), i1 = (long long)std::floor(box.xmax / s_);
        const long long j0 = (long long)std::floor(box.ymin / s_), j1 = (long long)std::floor(box.ymax / s_);
        if ((i1 - i0 + 1) * (j1 - j0 + 1) > 50'000'000)
            throw Error("UniformPartition", "too many sites for the region (density too high)");
        for (long long j = j0; j <= j1; ++j)
            for (long long i = i0; i <= i1; ++i)
                for (const auto& p : tile(i, j))
                    if (box.contains(p)) out.push_back(p);
        return out;
    }

private:
    static int phase(long long i, long long j) { return int(pos_mod(i, 2) + 2 * pos_mod(j, 2)); }

    const std::vector<Point>& tile(long long i, long long j) {
        auto it = tiles_.find({i, j});
        if (it != tiles_.end()) return it->second;
        const int ph = phase(i, j);
        std::vector<const std::vector<Point>*> lower;
        for (int dj = -1; dj <= 1; ++dj)
            for (int di = -1; di <= 1; ++di)
                if ((di || dj) && phase(i + di, j + dj) < ph) lower.push_back(&tile(i + di, j + dj));
        KeyedRng rng(tile_seed(0x44495343ULL, stream_, density_, i, j));
        std::vector<Point> pts;
        const double r2 = r_ * r_;
        for (int k = 0; k < kDartsPerTile; ++k) {
            const Point p{(double(i) + rng.uniform()) * s_, (double(j) + rng.uniform()) * s_};
            auto far = [&](const std::vector<Point>& v) {
                for (const auto& q : v)
                    if (dot(p - q, p - q) < r2) return false;
                return true;
            };
            bool ok = far(pts);
            for (std::size_t l = 0; ok && l < lower.size(); ++l) ok = far(*lower[l]);
            if (ok) pts.push_back(p);
        }
        return tiles_.emplace(TileKey{i, j}, std::move(pts)).first->second;
    }

    double density_;
    std::uint64_t stream_;
    double r_, s_;
    std::unordered_map<TileKey, std::vector<Point>, TileHash> tiles_;
};

using DtKernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using DtVb = CGAL::Triangulation_vertex_base_with_info_2<int, DtKernel>;
using DtFb = CGAL::Triangulation_face_base_with_info_2<int, DtKernel>;
using DtTds = CGAL::Triangulation_data_structure_2<DtVb, DtFb>;
using Delaunay = CGAL::Delaunay_triangulation_2<DtKernel, DtTds>;

// Voronoi cells of the sites as a complex. Cells of hull sites are unbounded and left out
// (the sites cover a margin around the region, so no such cell meets it).
Complex voronoi_complex(const std::vector<Point>& sites, const Irregular& p, std::uint64_t stream,
                        std::vector<Point>& hull_sites) {
    Complex cx;
    std::vector<std::pair<DtKernel::Point_2, int>> pts;
    pts.reserve(sites.size());
    for (std::size_t i = 0; i < sites.size(); ++i) pts.emplace_back(DtKernel::Point_2(sites[i].x, sites[i].y), int(i));
    Delaunay dt;
    dt.insert(pts.begin(), pts.end());
    // Everything below is ordered by site indices, never by the triangulation's internal
    // order, so the complex is the same whatever the memory layout.
    std::vector<Delaunay::Vertex_handle> by_site(sites.size());
    for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) by_site[v->info()] = v;

    // Voronoi vertices: one per finite triangle, numbered by the sorted site triple.
    std::vector<std::pair<std::array<int, 3>, Delaunay::Face_handle>> tris;
    for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) {
        std::array<int, 3> k = {f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()};
        std::sort(k.begin(), k.end());
        tris.push_back({k, f});
    }
    std::sort(tris.begin(), tris.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (const auto& [k, f] : tris) {
        const auto c = CGAL::circumcenter(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point());
        f->info() = int(cx.verts.size());
        cx.verts.push_back(Point{c.x(), c.y()});
    }
    if (!p.vertex_labels.empty()) {
        for (const auto& v : cx.verts) {
            Labels l = pick_label(p.vertex_labels, stream, hash_point(0x56564c42ULL, v));
            if (!l.empty()) cx.vertex_labels.push_back({v, std::move(l)});
        }
    }
    // Cells, in site order; a ring starts at its smallest Voronoi vertex id.
    std::vector<int> cell_of(sites.size(), -1);
    for (std::size_t si = 0; si < sites.size(); ++si) {
        const auto v = by_site[si];
        if (v == Delaunay::Vertex_handle()) continue;  // a duplicate site
        std::vector<int> ids;
        bool bounded = true;
        auto fc = dt.incident_faces(v), done = fc;
        do {
            if (dt.is_infinite(fc)) {
                bounded = false;
                break;
            }
            ids.push_back(fc->info());
        } while (++fc != done);
        if (!bounded) {
            hull_sites.push_back(sites[si]);
            continue;
        }
        std::rotate(ids.begin(), std::min_element(ids.begin(), ids.end()), ids.end());
        std::vector<Point> ring;
        for (int id : ids)
            if (ring.empty() || ring.back() != cx.verts[id]) ring.push_back(cx.verts[id]);
        while (ring.size() > 1 && ring.front() == ring.back()) ring.pop_back();
        if (ring.size() < 3) continue;
        cell_of[si] = cx.add_cell(ring, pick_label(p.face_labels, stream, hash_point(0x53495445ULL, sites[si])));
    }
    // Edges: duals of the Delaunay edges between two finite triangles, by site pair.
    std::vector<std::pair<std::pair<int, int>, Delaunay::Edge>> des;
    for (auto e = dt.finite_edges_begin(); e != dt.finite_edges_end(); ++e) {
        const int a = e->first->vertex(e->first->cw(e->second))->info();
        const int b = e->first->vertex(e->first->ccw(e->second))->info();
        des.push_back({{std::min(a, b), std::max(a, b)}, *e});
    }
    std::sort(des.begin(), des.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    for (const auto& [key, e] : des) {
        const auto f = e.first;
        const int i = e.second;
        const auto g = f->neighbor(i);
        if (dt.is_infinite(f) || dt.is_infinite(g)) continue;
        // Orient the Voronoi edge from the lower to the higher vertex id.
        int a = f->info(), b = g->info();
        if (a > b) std::swap(a, b);
        if (cx.verts[a] == cx.verts[b]) continue;
        const int sa = key.first, sb = key.second;
        const int ca = cell_of[sa], cb = cell_of[sb];
        if (ca < 0 && cb < 0) continue;
        // Which site is on the left of a -> b?
        const bool a_left = cross(cx.verts[b] - cx.verts[a], sites[sa] - cx.verts[a]) > 0;
        const Point& pa = sites[sa];
        const Point& pb = sites[sb];
        const std::uint64_t ekey = pa < pb ? hash_point(hash_point(0x45444745ULL, pa), pb)
                                           : hash_point(hash_point(0x45444745ULL, pb), pa);
        cx.edges.push_back({a, b, a_left ? ca : cb, a_left ? cb : ca, pick_label(p.edge_labels, stream, ekey)});
    }
    return cx;
}

Arrangement irregular_partition(const Irregular& p, Border b, bool disk, const char* op,
                                std::optional<std::uint64_t> seed) {
    check_density(p.density, op);
    // The stream is fixed now, when the operator is created (random.hpp, "Streams").
    const std::uint64_t stream = seed ? SeededStream(*seed) : NextStream();
    return Arrangement([p, b, disk, op, stream](const Region& r) {
        const double spacing = 1.0 / std::sqrt(p.density);
        double margin = 3 * spacing;
        for (int attempt = 0;; ++attempt) {
            const BBox box = r.bbox().expanded(margin);
            const double expected = p.density * (box.width() * box.height());
            if (expected > 2e7) throw Error(op, "too many sites for the region (density too high)");
            const std::vector<Point> sites =
                disk ? PoissonDiskSites(p.density, box, stream) : PoissonSites(p.density, box, stream);
            std::vector<Point> hull;
            Complex cx = voronoi_complex(sites, p, stream, hull);
            // Every cell meeting the region must be bounded, so no hull site (whose cell
            // is unbounded) may lie near the region; widen the margin otherwise.
            const BBox near = r.bbox().expanded(1.5 * spacing);
            bool ok = !cx.cells.empty();
            for (const auto& h : hull) ok = ok && !near.contains(h);
            if (ok || attempt >= 4) return realize(cx, r, b);
            margin *= 2;
        }
    });
}

}  // namespace

const char* border_name(Border b) {
    switch (b) {
        case Border::CROP: return "CROP";
        case Border::CROP_ADD_BOUNDARY: return "CROP_ADD_BOUNDARY";
        case Border::KEEP_INSIDE: return "KEEP_INSIDE";
        case Border::KEEP_OUTSIDE: return "KEEP_OUTSIDE";
    }
    return "?";
}

Stripes StripesProperties(double angle, std::vector<double> widths) {
    Stripes s;
    s.angle = angle;
    s.widths = std::move(widths);
    check_stripes(s, "StripesProperties");
    return s;
}

Stripes& SetEdgeLabels(Stripes& p, std::vector<std::string> labels) {
    p.edge_labels = std::move(labels);
    return p;
}

Stripes& SetFaceLabels(Stripes& p, std::vector<std::string> labels) {
    p.face_labels = std::move(labels);
    return p;
}

Irregular IrregularProperties(double density) {
    check_density(density, "IrregularProperties");
    Irregular p;
    p.density = density;
    return p;
}

Irregular& SetWeightedVertexLabels(Irregular& p, std::vector<WeightedLabel> labels) {
    check_weights(labels, "SetWeightedVertexLabels");
    p.vertex_labels = std::move(labels);
    return p;
}
Irregular& SetWeightedEdgeLabels(Irregular& p, std::vector<WeightedLabel> labels) {
    check_weights(labels, "SetWeightedEdgeLabels");
    p.edge_labels = std::move(labels);
    return p;
}
Irregular& SetWeightedFaceLabels(Irregular& p, std::vector<WeightedLabel> labels) {
    check_weights(labels, "SetWeightedFaceLabels");
    p.face_labels = std::move(labels);
    return p;
}

detail::StripesProbe::StripesProbe() : saved_(t_probe) { t_probe = this; }
detail::StripesProbe::~StripesProbe() { t_probe = saved_; }
void detail::StripesProbe::record(const Point& normal, double period) {
    if (t_probe) t_probe->families_.push_back({normal, period});
}

// The partitions' three ways (curves, map, edges) share one copy of their stripes: programs
// build a partition per cell.
Arrangement StripesPartition(const Stripes& p, Border b) {
    check_stripes(p, "StripesPartition");
    auto s = std::make_shared<const PreparedStripes>(p);
    return Arrangement([s, b](const Region& r) { return realize(stripes_complex(s->f, r), r, b); },
                       [s, b](const Region& r) { return realize_map(stripes_complex(s->f, r), r, b); },
                       [s, b](const Region& r, std::optional<LabelId> only) -> std::optional<std::vector<LocalEdge>> {
                           if (b == Border::CROP) return stripes_crop_edges(stripes_complex(s->f, r), r, only);
                           return realize_edges(stripes_complex(s->f, r), r, b, only);
                       });
}

Arrangement GridPartition(const Stripes& s1, const Stripes& s2, Border b) {
    check_stripes(s1, "GridPartition");
    check_stripes(s2, "GridPartition");
    auto s = std::make_shared<const std::pair<PreparedStripes, PreparedStripes>>(std::piecewise_construct,
                                                                                  std::forward_as_tuple(s1),
                                                                                  std::forward_as_tuple(s2));
    return Arrangement([s, b](const Region& r) { return realize(grid_complex(s->first.f, s->second.f, r), r, b); },
                       [s, b](const Region& r) { return realize_map(grid_complex(s->first.f, s->second.f, r), r, b); },
                       [s, b](const Region& r, std::optional<LabelId> only) {
                           return realize_edges(grid_complex(s->first.f, s->second.f, r), r, b, only);
                       });
}

Arrangement UniformPartition(const Irregular& p, Border b, std::optional<std::uint64_t> seed) {
    return irregular_partition(p, b, true, "UniformPartition", seed);
}

Arrangement RandomPartition(const Irregular& p, Border b, std::optional<std::uint64_t> seed) {
    return irregular_partition(p, b, false, "RandomPartition", seed);
}

double PoissonDiskRadius(double density) {
    check_density(density, "PoissonDiskRadius");
    return std::sqrt(kDiskPacking / density);
}

std::vector<Point> PoissonDiskSites(double density, const BBox& box, std::uint64_t stream) {
    check_density(density, "UniformPartition");
    return DiskSampler(density, stream).sites(box);
}

std::vector<Point> PoissonSites(double density, const BBox& box, std::uint64_t stream) {
    check_density(density, "RandomPartition");
    const double t = std::sqrt(8.0 / density);  // about eight sites per tile
    const long long i0 = (long long)std::floor(box.xmin / t), i1 = (long long)std::floor(box.xmax / t);
    const long long j0 = (long long)std::floor(box.ymin / t), j1 = (long long)std::floor(box.ymax / t);
    std::vector<Point> out;
    for (long long j = j0; j <= j1; ++j)
        for (long long i = i0; i <= i1; ++i) {
            KeyedRng rng(tile_seed(0x504f4953ULL, stream, density, i, j));
            const std::uint32_t n = rng.poisson(density * t * t);
            for (std::uint32_t k = 0; k < n; ++k) {
                const Point p{(double(i) + rng.uniform()) * t, (double(j) + rng.uniform()) * t};
                if (box.contains(p)) out.push_back(p);
            }
        }
    return out;
}

}  // namespace tex
