// TiledMap: the structure, its conversion to curves over a region, and point queries
// (thesis 4.1 and 4.2.5).
#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <sstream>

#include "geometry/segment_index.hpp"
#include "libtex/error.hpp"
#include "libtex/parallel.hpp"
#include "libtex/tiled.hpp"

namespace tex {
namespace {

// Copies further apart than this many tiles are never enumerated by a conversion.
constexpr double kMaxCopies = 2.0e9;

bool is_axis_rectangle(const Region& r) {
    if (!r.holes().empty() || r.outer().size() != 4) return false;
    const BBox& b = r.bbox();
    for (const auto& p : r.outer())
        if ((p.x != b.xmin && p.x != b.xmax) || (p.y != b.ymin && p.y != b.ymax)) return false;
    return true;
}

std::vector<Point> box_ring(const BBox& b) {
    return {{b.xmin, b.ymin}, {b.xmax, b.ymin}, {b.xmax, b.ymax}, {b.xmin, b.ymax}};
}

// Where a box (or a cell ring) lies against the region; exact on rectangles, else through
// classify_polygon.
Overlap classify_box(const BBox& b, const Region& r, bool rect) {
    const BBox& rb = r.bbox();
    if (!b.intersects(rb)) return Overlap::Disjoint;
    if (rect) {
        if (b.xmin >= rb.xmin && b.xmax <= rb.xmax && b.ymin >= rb.ymin && b.ymax <= rb.ymax)
            return Overlap::Inside;
        return Overlap::Partial;
    }
    return classify_polygon(box_ring(b), b, r);
}

bool proper_cross(const Point& a, const Point& b, const Point& c, const Point& d) {
    using detail::orientation;
    return orientation(a, b, c) * orientation(a, b, d) < 0 && orientation(c, d, a) * orientation(c, d, b) < 0;
}

template <class F>
void for_each_ring_segment(const Region& r, F&& f) {
    auto ring = [&](const std::vector<Point>& pts) {
        for (std::size_t i = 0, j = pts.size() - 1; i < pts.size(); j = i++) f(pts[j], pts[i]);
    };
    ring(r.outer());
    for (const auto& h : r.holes()) ring(h);
}

std::vector<std::pair<Point, Point>> curve_segments_of(const Curve& c) {
    std::vector<std::pair<Point, Point>> s;
    for (std::size_t k = 1; k < c.points.size(); ++k) s.emplace_back(c.points[k - 1], c.points[k]);
    if (c.closed && c.points.size() > 2) s.emplace_back(c.points.back(), c.points.front());
    return s;
}

// KEEP_OUTSIDE for a curve: it meets the (closed) region.
bool curve_meets(const Curve& c, const Region& r) {
    for (const auto& p : c.points)
        if (r.contains(p)) return true;
    bool touch = false;
    const auto segs = curve_segments_of(c);
    for_each_ring_segment(r, [&](const Point& a, const Point& b) {
        for (const auto& [p, q] : segs)
            if (!touch && detail::segments_touch(a, b, p, q)) touch = true;
    });
    return touch;
}

// KEEP_INSIDE for a curve: every point inside and no crossing of the boundary.
bool curve_inside(const Curve& c, const Region& r) {
    for (const auto& p : c.points)
        if (!r.contains(p)) return false;
    bool cross = false;
    const auto segs = curve_segments_of(c);
    for_each_ring_segment(r, [&](const Point& a, const Point& b) {
        for (const auto& [p, q] : segs)
            if (!cross && proper_cross(a, b, p, q)) cross = true;
    });
    return !cross;
}

BBox curve_box(const Curve& c) {
    BBox b;
    for (const auto& p : c.points) b.add(p);
    return b;
}

double point_segment_distance(const Point& p, const Point& a, const Point& b) {
    const Point d = b - a;
    const double l2 = dot(d, d);
    double t = l2 > 0 ? dot(p - a, d) / l2 : 0.0;
    t = std::clamp(t, 0.0, 1.0);
    return distance(p, a + d * t);
}

// The shifts (i, j), in periods, of the copies of a box `piece` that can meet the box `area`
// grown by `margin`: the translations t with piece + t meeting it form a box, whose corners in
// lattice coordinates bound i and j.
struct ShiftRange {
    long long i0, i1, j0, j1;
    double count() const { return double(i1 - i0 + 1) * double(j1 - j0 + 1); }
};
ShiftRange shifts_meeting(const TiledMap& m, const BBox& piece, const BBox& area, double margin) {
    BBox t;
    t.add(Point{area.xmin - piece.xmax - margin, area.ymin - piece.ymax - margin});
    t.add(Point{area.xmax - piece.xmin + margin, area.ymax - piece.ymin + margin});
    double ilo = 1e300, ihi = -1e300, jlo = 1e300, jhi = -1e300;
    for (const auto& c : box_ring(t)) {
        const Point l = m.lattice(c);
        ilo = std::min(ilo, l.x);
        ihi = std::max(ihi, l.x);
        jlo = std::min(jlo, l.y);
        jhi = std::max(jhi, l.y);
    }
    return {(long long)std::floor(ilo), (long long)std::ceil(ihi), (long long)std::floor(jlo), (long long)std::ceil(jhi)};
}

std::string period_text(const Point& p) {
    std::ostringstream s;
    s << "(" << p.x << ", " << p.y << ")";
    return s.str();
}

}  // namespace

// The segments of every copy of the elements near the central tile, in a uniform grid, for
// DistanceToCurves. A copy is stored as (segment of the central copy, shift in periods
// relative to the tile of the query), so that a query computes exactly what the linear scan
// computes (the point moved by the copy's shift against the central segment): the same
// bits, found without visiting the other copies.
struct DistanceIndex {
    struct Copy {
        std::uint32_t seg;
        long long di, dj;
    };
    std::vector<std::pair<Point, Point>> base;  // the segments of the elements, as stored
    std::vector<Copy> copies;                   // the grid's segment k is copies[k]
    std::optional<detail::SegmentGrid> grid;
    bool scan = false;  // too many copies to index (a very thin tile): the linear scan answers
};

// The faces of the framed block for FaceLabelsAt, in two point locators: the faces that do
// not touch the frame (regions with their holes), tried first, then the faces along the
// frame by their outer ring alone. A point in a hole of a frame face lies in a face that
// does not touch the frame, found first; so the frame faces (the space around a whole block
// of bricks, with hundreds of holes) are never tested hole by hole.
struct FramedFaces {
    MapPtr map;
    std::optional<RegionLocator> inner, frame;
    std::vector<int> inner_ids, frame_ids;
    int face_at(const Point& p) const {
        if (const int k = inner->find(p); k >= 0) return inner_ids[std::size_t(k)];
        if (const int k = frame->find(p); k >= 0) return frame_ids[std::size_t(k)];
        return map->unbounded_face();
    }
};

struct TiledMap::Data::Locator {
    std::once_flag faces_once, distance_once;
    FramedFaces faces;
    DistanceIndex distance;
};

double Random(const TiledElement& e, double min, double max, double n) {
    const std::uint64_t h = hash_double(hash_combine(mix64(GetSeed() ^ 0x54494c45ULL), e.key), n);
    return min + (max - min) * unit_from_hash(h);
}

TiledMap::TiledMap(Point p1, Point p2, std::vector<Element> elements, Border border, std::vector<CellRing> cells,
                   bool bounded_faces) {
    const double det = cross(p1, p2);
    if (!std::isfinite(det) || std::abs(det) <= 1e-12 * std::max(1.0, dot(p1, p1) + dot(p2, p2)))
        throw Error("TiledMap", "the periods " + period_text(p1) + " and " + period_text(p2) +
                                    " are colinear (or not finite)");
    auto d = std::make_shared<Data>();
    d->p1 = p1;
    d->p2 = p2;
    d->inv[0] = p2.y / det;
    d->inv[1] = -p2.x / det;
    d->inv[2] = -p1.y / det;
    d->inv[3] = p1.x / det;
    for (auto& e : elements) {
        e.box = BBox{};
        for (const auto& c : e.curves.curves) e.box.add(curve_box(c));
        for (const auto& p : e.curves.points) e.box.add(p.point);
    }
    d->elements = std::move(elements);
    // How many tiles away from the central one the elements reach (computed once: the point
    // queries and the block read it).
    d->reach = 0;
    for (const auto& e : d->elements) {
        if (e.box.empty()) continue;
        for (const auto& c : box_ring(e.box)) {
            const Point l{d->inv[0] * c.x + d->inv[1] * c.y, d->inv[2] * c.x + d->inv[3] * c.y};
            d->reach = std::max({d->reach, -std::floor(l.x), -std::floor(l.y), std::ceil(l.x) - 1, std::ceil(l.y) - 1});
        }
    }
    d->cells = std::move(cells);
    d->border = border;
    d->bounded_faces = bounded_faces;
    d->locator = std::make_shared<Data::Locator>();
    d_ = std::move(d);
}

TiledMap::TiledMap(Point p1, Point p2, std::vector<Element> elements, Border border, Stripes stripes)
    : TiledMap(p1, p2, std::move(elements), border, {}, false) {
    auto d = std::make_shared<Data>(*d_);
    d->stripes = std::move(stripes);
    d_ = std::move(d);
}

Point TiledMap::lattice(const Point& p) const {
    return {d_->inv[0] * p.x + d_->inv[1] * p.y, d_->inv[2] * p.x + d_->inv[3] * p.y};
}

TiledMap TiledMap::with_ghost(GhostMapper g) const {
    auto d = std::make_shared<Data>(*d_);
    d->ghost = std::move(g);
    return TiledMap(std::shared_ptr<const Data>(std::move(d)));
}

TiledMap::operator Arrangement() const {
    TiledMap self = *this;
    return Arrangement([self](const Region& r) { return self.Convert(r, self.border()); });
}

int TiledMap::block_reach() const {
    if (d_->reach > 64) throw Error("TiledMap", "an element reaches more than 64 periods away from its tile");
    return int(d_->reach);
}

namespace {

// ---- The steps of TiledMap::Convert

// The copies (i, j0..j1) of element e: the copies of one column of the lattice whose box can
// meet the region's box.
struct CopyColumn {
    std::size_t e;
    long long i, j0, j1;
};

// What the first pass finds in a column: how many curves it keeps, the curves that cross the
// border (cut after the pass, all at once) and the points kept.
struct ColumnResult {
    std::size_t count = 0;
    std::vector<Curve> kept, partial;  // kept: only with a ghost
    std::vector<LabeledPoint> points;
};

// The columns of copies of every element whose box can meet the region's box `rb`: the
// translations t with (box + t) meeting rb form the box [rb.xmin - box.xmax, rb.xmax -
// box.xmin] x ...; its corners in lattice coordinates bound i and j. A ghost mapper may move
// an element by up to its own size, so its copies are looked for that much further.
std::vector<CopyColumn> copy_columns(const TiledMap& m, const BBox& rb, bool ghost) {
    std::vector<CopyColumn> items;
    double copies = 0;
    for (std::size_t e = 0; e < m.elements().size(); ++e) {
        const BBox& eb = m.elements()[e].box;
        if (eb.empty()) continue;
        const double margin = ghost ? std::max(eb.width(), eb.height()) : 0.0;
        const ShiftRange sr = shifts_meeting(m, eb, rb, margin);
        copies += sr.count();
        if (copies > kMaxCopies) throw Error("TiledMap", "the region holds too many periods to convert");
        for (long long i = sr.i0; i <= sr.i1; ++i) items.push_back({e, i, sr.j0, sr.j1});
    }
    return items;
}

// Where the curves kept from a column go, counted in n: the first pass (dest == nullptr)
// only counts them, or keeps them in the column's result with a ghost mapper (which is not
// run twice); the second pass writes them to the column's slice of the output, `dest`.
struct ColumnSink {
    ColumnSink(Curve* dest, ColumnResult& res, bool ghost) : dest(dest), res(res), ghost(ghost) {}
    Curve* dest;
    ColumnResult& res;
    bool ghost;
    std::size_t n = 0;
    bool first() const { return dest == nullptr; }
    void keep(Curve&& c) {
        if (dest) dest[n] = std::move(c);
        else if (ghost) res.kept.push_back(std::move(c));
        ++n;
    }
};

// The copies of a column over region r with border mode b, in either pass of Convert: each
// copy kept whole, dropped, or (CROP) its curves across the border set aside to be cut.
class ColumnConverter {
public:
    ColumnConverter(const TiledMap& m, const GhostMapper& ghost, const Region& r, Border b)
        : m_(m),
          ghost_(ghost),
          r_(r),
          rb_(r.bbox()),
          b_(b),
          has_ghost_(static_cast<bool>(ghost)),
          rect_(is_axis_rectangle(r)),
          keep_cells_(!has_ghost_ && !m.cells().empty() && (b == Border::KEEP_INSIDE || b == Border::KEEP_OUTSIDE)),
          crop_(b == Border::CROP || b == Border::CROP_ADD_BOUNDARY) {}

    bool ghost() const { return has_ghost_; }

    // Converts the copies of a column; dest == nullptr: first pass (fills `res`); else the
    // column's slice of the output.
    void run(const CopyColumn& it, ColumnResult& res, Curve* dest) const {
        const TiledMap::Element& el = m_.elements()[it.e];
        ColumnSink sink(dest, res, has_ghost_);
        if (el.continues && !keep_cells_) {
            run_line(it, el, sink);
        } else {
            for (long long j = it.j0; j <= it.j1; ++j) run_copy(it, el, j, sink);
        }
        if (sink.first()) res.count = sink.n;
    }

private:
    // Whether the copy of cell c next to the element's copy (i, j) is kept: KEEP_INSIDE when it
    // lies inside the region, KEEP_OUTSIDE when it meets it.
    bool cell_kept(const TiledMap::CellRef& c, long long i, long long j) const {
        if (c.cell < 0) return false;
        const TiledMap::CellRing& cell = m_.cells()[std::size_t(c.cell)];
        const Point s = m_.shift(i + c.di, j + c.dj);
        BBox cb = cell.box;
        cb.xmin += s.x; cb.xmax += s.x; cb.ymin += s.y; cb.ymax += s.y;
        // The cell's own ring, not its box (a tilted cell's box is larger than the cell).
        std::vector<Point> ring = cell.ring;
        for (auto& p : ring) p += s;
        const Overlap o = classify_polygon(ring, cb, r_);
        return b_ == Border::KEEP_INSIDE ? o == Overlap::Inside : o != Overlap::Disjoint;
    }

    // A curve moved by s.
    static Curve translated(const Curve& c, const Point& s) {
        Curve copy = c;
        for (auto& p : copy.points) p += s;
        return copy;
    }

    // The curves kept from one copy (or one joined line) that was not wholly inside.
    void keep_partial(Curves& copy, ColumnSink& sink) const {
        if (crop_) {
            // Curves inside stay whole; the others are cut below, all at once.
            for (auto& c : copy.curves) {
                const Overlap o = classify_box(curve_box(c), r_, rect_);
                if (o == Overlap::Inside) sink.keep(std::move(c));
                else if (o == Overlap::Partial && sink.first()) sink.res.partial.push_back(std::move(c));
            }
        } else {
            // KEEP_* keep or drop a copy whole, as the engine keeps or drops whole cells:
            // KEEP_OUTSIDE when one of its curves meets the region, KEEP_INSIDE when all
            // lie inside.
            bool any = false, all = true;
            for (const auto& c : copy.curves) {
                const Overlap o = classify_box(curve_box(c), r_, rect_);
                const bool meets = o == Overlap::Inside || (o == Overlap::Partial && curve_meets(c, r_));
                const bool inside = o == Overlap::Inside || (o == Overlap::Partial && curve_inside(c, r_));
                any = any || meets;
                all = all && inside;
            }
            if (b_ == Border::KEEP_OUTSIDE ? any : all)
                for (auto& c : copy.curves) sink.keep(std::move(c));
        }
        if (sink.first())
            for (auto& p : copy.points)
                if (r_.contains(p.point)) sink.res.points.push_back(std::move(p));
    }

    // A line cut at the period: each run of consecutive copies whose boxes meet the
    // region's box becomes one curve, from the first copy's start to the last one's
    // end, then kept, cut or dropped as one copy. A ghost mapper sees that whole line
    // (over the region's box grown by one piece, the margin it may move it by), keyed
    // by the line (element and i), not by where the region cuts it.
    void run_line(const CopyColumn& it, const TiledMap::Element& el, ColumnSink& sink) const {
        const Curve& piece = el.curves.curves.front();
        const double margin = has_ghost_ ? std::max(el.box.width(), el.box.height()) : 0.0;
        auto meets_box = [&](long long jj) {
            BBox cb = el.box.expanded(margin);
            const Point s = m_.shift(it.i, jj);
            cb.xmin += s.x; cb.xmax += s.x; cb.ymin += s.y; cb.ymax += s.y;
            return cb.intersects(rb_);
        };
        long long j = it.j0;
        while (j <= it.j1) {
            if (!meets_box(j)) {
                ++j;
                continue;
            }
            long long last = j;
            while (last + 1 <= it.j1 && meets_box(last + 1)) ++last;
            Curves line;
            line.curves.push_back(joined_line(piece, it.i, j, last));
            keep_line(el, it.i, line, sink);
            j = last + 1;
        }
    }

    // The copies j..last of a line's piece in column i as one curve: the first copy's start,
    // the inner points of every copy, the last copy's end.
    Curve joined_line(const Curve& piece, long long i, long long j, long long last) const {
        Curve c = piece;
        const Point s0 = m_.shift(i, j), s1 = m_.shift(i, last);
        c.points.assign(1, piece.points.front() + s0);
        for (long long jj = j; jj <= last; ++jj)  // the inner points of every piece
            for (std::size_t k = 1; k + 1 < piece.points.size(); ++k)
                c.points.push_back(piece.points[k] + m_.shift(i, jj));
        c.points.push_back(piece.points.back() + s1);
        return c;
    }

    // A joined line of column i: through the ghost mapper, else kept whole when inside,
    // else as a copy across the border.
    void keep_line(const TiledMap::Element& el, long long i, Curves& line, ColumnSink& sink) const {
        if (has_ghost_) {
            TiledElement te;
            te.curves = std::move(line);
            te.anchor = el.anchor + m_.shift(i, 0);
            te.i = i;
            te.j = 0;
            te.key = hash_combine(hash_combine(el.key, std::uint64_t(i)), 0x4c494e45ULL);
            RandomScope scope(te.key);
            Curves mapped = ghost_(te);
            keep_partial(mapped, sink);
        } else if (classify_box(curve_box(line.curves.front()), r_, rect_) == Overlap::Inside) {
            sink.keep(std::move(line.curves.front()));
        } else {
            keep_partial(line, sink);
        }
    }

    // The copy (i, j) of an element, moved by s: a partition edge by its cells, else through
    // the ghost mapper, else by its box.
    void run_copy(const CopyColumn& it, const TiledMap::Element& el, long long j, ColumnSink& sink) const {
        const Point s = m_.shift(it.i, j);
        if (keep_cells_) keep_cell_edge(el, it.i, j, s, sink);
        else if (has_ghost_) keep_ghost_copy(el, it.i, j, s, sink);
        else keep_copy(el, s, sink);
    }

    // A partition edge stays when a cell on one of its sides is kept; the side of a dropped
    // cell loses its labels (as the planar-map engine does).
    void keep_cell_edge(const TiledMap::Element& el, long long i, long long j, const Point& s,
                        ColumnSink& sink) const {
        const bool l = cell_kept(el.left, i, j), rr = cell_kept(el.right, i, j);
        if (!l && !rr) return;
        for (const auto& c : el.curves.curves) {
            if (sink.first()) {
                ++sink.n;
                continue;
            }
            Curve copy = translated(c, s);
            if (!l) copy.left = Labels{};
            if (!rr) copy.right = Labels{};
            sink.keep(std::move(copy));
        }
        if (sink.first())
            for (const auto& p : el.curves.points)
                if (r_.contains(p.point + s)) sink.res.points.push_back({p.point + s, p.labels});
    }

    // The ghost mapper's image of the copy (i, j) of an element (moved by s), when the copy
    // moved by up to its size can meet the region's box; then kept as a copy across the border.
    void keep_ghost_copy(const TiledMap::Element& el, long long i, long long j, const Point& s,
                         ColumnSink& sink) const {
        BBox moved = el.box.expanded(std::max(el.box.width(), el.box.height()));
        moved.xmin += s.x; moved.xmax += s.x; moved.ymin += s.y; moved.ymax += s.y;
        if (!moved.intersects(rb_)) return;
        Curves copy = mapped_copy(el, i, j, s);
        keep_partial(copy, sink);
    }

    // Runs the ghost mapper on the copy (i, j) of an element (moved by s), keyed by the copy.
    Curves mapped_copy(const TiledMap::Element& el, long long i, long long j, const Point& s) const {
        TiledElement te;
        te.curves = el.curves;
        te.curves.transform(Affine::translation(s));
        te.anchor = el.anchor + s;
        te.i = i;
        te.j = j;
        te.key = hash_combine(hash_combine(el.key, std::uint64_t(i)), std::uint64_t(j));
        RandomScope scope(te.key);
        return ghost_(te);
    }

    // A copy of an element (moved by s) by its box: dropped when outside the region, kept
    // whole when inside, else curve by curve.
    void keep_copy(const TiledMap::Element& el, const Point& s, ColumnSink& sink) const {
        BBox cb = el.box;
        cb.xmin += s.x; cb.xmax += s.x; cb.ymin += s.y; cb.ymax += s.y;
        const Overlap o = classify_box(cb, r_, rect_);
        if (o == Overlap::Disjoint) return;
        if (o == Overlap::Inside) {
            // The common case: the whole copy is kept as it is.
            if (sink.first()) {
                sink.n += el.curves.curves.size();
                for (const auto& p : el.curves.points) sink.res.points.push_back({p.point + s, p.labels});
            } else {
                for (const auto& c : el.curves.curves) sink.keep(translated(c, s));
            }
            return;
        }
        Curves copy = el.curves;
        for (auto& c : copy.curves)
            for (auto& p : c.points) p += s;
        for (auto& p : copy.points) p.point += s;
        keep_partial(copy, sink);
    }

    const TiledMap& m_;
    const GhostMapper& ghost_;
    const Region& r_;
    const BBox& rb_;
    Border b_;
    bool has_ghost_, rect_, keep_cells_, crop_;
};

// The first pass's curves across the border, gathered column by column (its points go to
// `out`).
Curves gather_partial(std::vector<ColumnResult>& results, Curves& out) {
    Curves subject;
    for (auto& res : results) {
        for (auto& c : res.partial) subject.curves.push_back(std::move(c));
        for (auto& p : res.points) out.points.push_back(std::move(p));
    }
    return subject;
}

// The pieces across the border: cut to the region with the pieces of the outline (CROP
// modes), or the outline whole (CROP_ADD_BOUNDARY, nothing crossing it); none otherwise.
Curves border_pieces_of(const TiledMap& m, const Curves& subject, const Region& r, Border b) {
    const bool crop = b == Border::CROP || b == Border::CROP_ADD_BOUNDARY;
    Curves border_pieces;
    if (b == Border::CROP_ADD_BOUNDARY && subject.curves.empty()) {
        // Nothing crosses the outline: it is added whole, inside a single face.
        border_pieces = r.boundary();
        for (auto& c : border_pieces.curves)
            if (c.points.size() >= 2) c.left = m.FaceLabelsAt((c.points[0] + c.points[1]) / 2);
    } else if (crop) {
        static const LabelId outline = intern_label("\x01libtex-tiled-outline");
        border_pieces = detail::crop_to_region(subject, r, b, outline);
        // A piece of the outline: the labels of the face it bounds on its inner side.
        detail::label_outline_pieces(border_pieces, outline,
                                     [&](const Point& probe, const Point&) -> std::optional<Labels> {
                                         return m.FaceLabelsAt(probe);
                                     });
    }
    return border_pieces;
}

// The second pass: the output allocated once (with room for `extra` curves after the kept
// ones), then each column's kept curves written at its offset on the worker threads.
void write_kept_curves(const ColumnConverter& conv, const std::vector<CopyColumn>& items,
                       std::vector<ColumnResult>& results, std::size_t extra, Curves& out) {
    std::vector<std::size_t> offset(items.size() + 1, 0);
    for (std::size_t k = 0; k < items.size(); ++k) offset[k + 1] = offset[k] + results[k].count;
    out.curves.reserve(offset.back() + extra);
    out.curves.resize(offset.back());
    parallel_for(items.size(), [&](std::size_t k) {
        if (conv.ghost()) {
            std::move(results[k].kept.begin(), results[k].kept.end(), out.curves.begin() + std::ptrdiff_t(offset[k]));
            std::vector<Curve>().swap(results[k].kept);
        } else if (results[k].count > 0) {
            conv.run(items[k], results[k], out.curves.data() + offset[k]);
        }
    });
}

}  // namespace

Curves TiledMap::Convert(const Region& r, Border b) const {
    Curves out;
    if (r.empty()) return out;
    const bool ghost = static_cast<bool>(d_->ghost);
    // Stripes' faces are infinite bands: a KEEP mode keeps whole bands, which no copy of a
    // finite element can stand for. They are the engine's, cut where the engine cuts them.
    if (d_->stripes && !ghost && (b == Border::KEEP_INSIDE || b == Border::KEEP_OUTSIDE))
        return StripesPartition(*d_->stripes, b)(r);
    const ColumnConverter conv(*this, d_->ghost, r, b);
    const std::vector<CopyColumn> items = copy_columns(*this, r.bbox(), ghost);

    // Two passes, so that the output is allocated once and filled in place (memory bounded
    // by the output): the first counts each item's kept curves and collects the few that
    // cross the border; the second writes the kept curves at their final offsets. With a
    // ghost mapper (which is not run twice) the first pass keeps its curves instead.
    std::vector<ColumnResult> results(items.size());
    parallel_for(items.size(), [&](std::size_t k) { conv.run(items[k], results[k], nullptr); });
    // The pieces across the border (cut, and the outline, before the output is allocated so
    // that it is allocated once).
    const Curves subject = gather_partial(results, out);
    Curves border_pieces = border_pieces_of(*this, subject, r, b);
    write_kept_curves(conv, items, results, border_pieces.curves.size(), out);
    for (auto& c : border_pieces.curves) out.curves.push_back(std::move(c));
    return out;
}

double TiledMap::DistanceToCurvesByScan(const Point& p) const {
    const Point l = lattice(p);
    const long long ti = (long long)std::floor(l.x), tj = (long long)std::floor(l.y);
    const int reach = block_reach() + 1;
    double best = std::numeric_limits<double>::infinity();
    for (long long i = ti - reach; i <= ti + reach; ++i)
        for (long long j = tj - reach; j <= tj + reach; ++j) {
            const Point s = shift(i, j);
            const Point q = p - s;  // p in the frame of the element's central copy
            for (const auto& e : d_->elements)
                for (const auto& c : e.curves.curves)
                    for (const auto& [a, b] : curve_segments_of(c)) best = std::min(best, point_segment_distance(q, a, b));
        }
    return best;
}

namespace {

// Copies of segments beyond this many are not indexed (the linear scan answers instead).
constexpr double kMaxIndexedCopies = 4.0e6;

}  // namespace

double TiledMap::DistanceToCurves(const Point& p) const {
    DistanceIndex& index = d_->locator->distance;
    std::call_once(d_->locator->distance_once, [&] {
        for (const auto& e : d_->elements)
            for (const auto& c : e.curves.curves)
                for (const auto& s : curve_segments_of(c)) index.base.push_back(s);
        if (index.base.empty()) return;
        // A query point is moved into the central tile. Every point of the tile lies within D
        // of a curve: within (distance from the nearest corner to the central copies) +
        // (the tile's diagonal). So the copies whose box comes within D of the tile's box
        // hold the nearest curve of any point of the tile.
        BBox tile;
        for (const Point& c : {Point{0, 0}, d_->p1, d_->p2, d_->p1 + d_->p2}) tile.add(c);
        double corner = 0;
        for (const Point& c : box_ring(tile)) {
            double best = std::numeric_limits<double>::infinity();
            for (const auto& [a, b] : index.base) best = std::min(best, point_segment_distance(c, a, b));
            corner = std::max(corner, best);
        }
        const double reach = corner + std::hypot(tile.width(), tile.height());
        const BBox area = tile.expanded(reach * (1 + 1e-9) + 1e-9 * (1 + tile.width() + tile.height()));
        std::vector<detail::Seg> segs;
        for (std::size_t k = 0; k < index.base.size(); ++k) {
            const auto& [a, b] = index.base[k];
            BBox sb;
            sb.add(a);
            sb.add(b);
            const ShiftRange sr = shifts_meeting(*this, sb, area, 0.0);
            if (sr.count() + double(segs.size()) > kMaxIndexedCopies) {
                index.scan = true;
                return;
            }
            for (long long i = sr.i0; i <= sr.i1; ++i)
                for (long long j = sr.j0; j <= sr.j1; ++j) {
                    const Point s = shift(i, j);
                    BBox cb = sb;
                    cb.xmin += s.x; cb.xmax += s.x; cb.ymin += s.y; cb.ymax += s.y;
                    if (!cb.intersects(area)) continue;
                    detail::Seg sg;
                    sg.a = a + s;
                    sg.b = b + s;
                    sg.owner = std::uint32_t(index.copies.size());
                    index.copies.push_back({std::uint32_t(k), i, j});
                    segs.push_back(sg);
                }
        }
        index.grid.emplace(std::move(segs));
    });
    if (index.scan) return DistanceToCurvesByScan(p);
    if (!index.grid) return std::numeric_limits<double>::infinity();
    const Point l = lattice(p);
    const long long ti = (long long)std::floor(l.x), tj = (long long)std::floor(l.y);
    const Point q0 = p - shift(ti, tj);
    const auto& segs = index.grid->segments();
    return index.grid->nearest(q0, [&](std::uint32_t k) {
        const DistanceIndex::Copy& c = index.copies[segs[k].owner];
        const auto& [a, b] = index.base[c.seg];
        return point_segment_distance(p - shift(ti + c.di, tj + c.dj), a, b);
    });
}

Labels TiledMap::FaceLabelsAt(const Point& p) const {
    const Point l = lattice(p);
    const long long ti = (long long)std::floor(l.x), tj = (long long)std::floor(l.y);
    // A tiled partition knows its cells: the one containing p.
    if (!d_->cells.empty()) {
        const int reach = block_reach() + 1;
        for (long long i = ti - reach; i <= ti + reach; ++i)
            for (long long j = tj - reach; j <= tj + reach; ++j) {
                const Point q = p - shift(i, j);
                for (const auto& c : d_->cells)
                    if (c.box.contains(q) && point_in_ring(q, c.ring)) return c.labels;
            }
    }
    // Otherwise the face containing p moved into the central tile, in a closed block: the
    // copies of the elements over the block of tiles around the central one, and a frame
    // (a parallelogram of the lattice, r + 1 tiles beyond the central one on each side, where
    // r = block_reach(): every curve of the infinite arrangement that passes inside it has a
    // copy in the block) added as an unlabelled closed curve. A face that is
    // unbounded in the infinite arrangement (a band of stripes, the space around closed
    // shapes) is closed by the frame; its labels are those of its sides inside the frame,
    // merged as the planar map merges them (the frame adds none).
    Data::Locator& loc = *d_->locator;
    std::call_once(loc.faces_once, [&] {
        BBox tile;
        for (const Point& c : {Point{0, 0}, d_->p1, d_->p2, d_->p1 + d_->p2}) tile.add(c);
        // Off the lattice by an irrational fraction of a period, so that no line of a regular
        // texture runs along the frame.
        const double lo = -(block_reach() + 1) + 0.1415926535897932, hi = block_reach() + 2 - 0.1415926535897932;
        std::vector<Point> frame;
        for (const auto& [a, b] : {std::pair{lo, lo}, {hi, lo}, {hi, hi}, {lo, hi}})
            frame.push_back(d_->p1 * a + d_->p2 * b);
        if (signed_area(frame) < 0) std::reverse(frame.begin(), frame.end());
        // The copies are not cut to the frame (cut ends, rounded, would miss it): the
        // planar map cuts them exactly; what lies outside belongs to faces never queried.
        Curves all = block_curves();
        Curve outline;
        outline.points = std::move(frame);
        outline.closed = true;
        all.curves.push_back(std::move(outline));
        FramedFaces& ff = loc.faces;
        ff.map = PlanarMap::induce(all);
        const PlanarMap& m = *ff.map;
        auto on_frame = [&](const Point& v) {
            const Point l = lattice(v);
            const double eps = 1e-9 * (1 + std::abs(lo) + std::abs(hi));
            return std::abs(l.x - lo) <= eps || std::abs(l.x - hi) <= eps || std::abs(l.y - lo) <= eps ||
                   std::abs(l.y - hi) <= eps;
        };
        std::vector<Region> inner, along;
        for (std::size_t f = 0; f < m.faces().size(); ++f) {
            if (m.faces()[f].unbounded || m.faces()[f].cycles.empty()) continue;
            std::vector<Point> ring = m.cycle_points(int(f), 0);
            const bool touches = std::any_of(ring.begin(), ring.end(), on_frame);
            try {  // a face without area holds no point
                if (touches) {
                    along.emplace_back(std::move(ring), std::vector<std::vector<Point>>{}, "FaceLabelsAt");
                    ff.frame_ids.push_back(int(f));
                } else {
                    std::vector<std::vector<Point>> holes;
                    for (std::size_t k = 1; k < m.faces()[f].cycles.size(); ++k) holes.push_back(m.cycle_points(int(f), k));
                    inner.emplace_back(std::move(ring), std::move(holes), "FaceLabelsAt");
                    ff.inner_ids.push_back(int(f));
                }
            } catch (const Error&) {
            }
        }
        // Only the faces meeting the central tile are kept (the ids follow the regions kept).
        const BBox area = tile.expanded(1e-9 * (1 + tile.width() + tile.height()));
        auto keep = [&](std::vector<Region>& regions, std::vector<int>& ids) {
            std::vector<Region> r;
            std::vector<int> i;
            for (std::size_t k = 0; k < regions.size(); ++k)
                if (regions[k].bbox().intersects(area)) {
                    r.push_back(std::move(regions[k]));
                    i.push_back(ids[k]);
                }
            ids = std::move(i);
            return RegionLocator(std::move(r), area);
        };
        ff.inner.emplace(keep(inner, ff.inner_ids));
        ff.frame.emplace(keep(along, ff.frame_ids));
    });
    const Point q = p - shift(ti, tj);
    return loc.faces.map->faces()[std::size_t(loc.faces.face_at(q))].labels;
}

}  // namespace tex
