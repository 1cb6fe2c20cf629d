// Internal: a uniform grid over segments, exact intersection tests on double coordinates,
// and point location against a mask boundary. Used by the masks (merge.cpp) to decide
// which curves need the exact planar map and which can be classified by one point.
//
// Every decision here is exact for the double coordinates it is given (CGAL's filtered
// predicates of the Epick kernel); the grid only narrows the candidates, conservatively.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <vector>

#include "libtex/curves.hpp"
#include "libtex/geometry.hpp"
#include "libtex/partitions.hpp"
#include "libtex/planar_map.hpp"

namespace tex::detail {

struct Seg {
    Point a, b;
    // For point location: whether the left / right side of a -> b is inside the mask.
    bool in_left = false, in_right = false;
    // Whether the inside changes across the segment (exactly one side inside).
    bool changes() const { return in_left != in_right; }
    std::uint32_t owner = 0;  // index of the curve (or edge) the segment comes from
};

// Exact orientation of c against the line a -> b: 1 left turn, -1 right turn, 0 collinear.
int orientation(const Point& a, const Point& b, const Point& c);

// Exact test: do the closed segments ab and cd share a point?
bool segments_touch(const Point& a, const Point& b, const Point& c, const Point& d);

class SegmentGrid {
public:
    explicit SegmentGrid(std::vector<Seg> segs);

    const std::vector<Seg>& segments() const { return segs_; }
    bool empty() const { return segs_.empty(); }

    // Calls f(i) once for each segment i registered in a cell that box overlaps.
    template <class F>
    void for_each_in(const BBox& box, F&& f) const {
        if (segs_.empty() || !box.intersects(box_)) return;
        const int c0 = col(box.xmin), c1 = col(box.xmax), r0 = row(box.ymin), r1 = row(box.ymax);
        ++stamp_;
        for (int r = r0; r <= r1; ++r)
            for (int c = c0; c <= c1; ++c)
                for (std::uint32_t k = start_[cell(c, r)]; k < start_[cell(c, r) + 1]; ++k) {
                    const std::uint32_t i = items_[k];
                    if (seen_[i] == stamp_) continue;
                    seen_[i] = stamp_;
                    f(i);
                }
    }

    // The least `dist(i)` over the grid's segments i, where dist(i) is the caller's distance
    // from p to segment i (up to rounding). Cells are visited in square rings around p's cell
    // until every cell left is further from p than the best distance found (one ring of
    // slack for rounding), so the answer is the minimum over all segments. A segment may be
    // seen more than once. Reads no mutable state: queries may run on several threads.
    // Infinity when the grid is empty.
    template <class F>
    double nearest(const Point& p, F&& dist) const {
        double best = std::numeric_limits<double>::infinity();
        if (segs_.empty()) return best;
        const int c = col(p.x), r = row(p.y);
        const double step = std::min(cw_, ch_);
        const int last = std::max({c, nx_ - 1 - c, r, ny_ - 1 - r});
        auto visit = [&](int cc, int rr) {
            if (cc < 0 || cc >= nx_ || rr < 0 || rr >= ny_) return;
            for (std::uint32_t k = start_[cell(cc, rr)]; k < start_[cell(cc, rr) + 1]; ++k)
                best = std::min(best, double(dist(items_[k])));
        };
        for (int d = 0; d <= last; ++d) {
            for (int cc = c - d; cc <= c + d; ++cc) {
                visit(cc, r - d);
                if (d > 0) visit(cc, r + d);
            }
            for (int rr = r - d + 1; rr <= r + d - 1; ++rr) {
                visit(c - d, rr);
                visit(c + d, rr);
            }
            // Cells outside rings 0..d lie at least d * step from p (p is in its cell, or
            // beyond the grid on that side); one step less for the rounding of col / row.
            if (best <= (d - 1) * step) break;
        }
        return best;
    }

    // Whether the polyline segment pq shares a point with any segment of the grid
    // (when only_changing, with any segment across which the inside changes). With
    // `owners`, every touched segment's owner is marked there (and the search goes on).
    bool touches(const Point& p, const Point& q, bool only_changing, std::vector<char>* owners = nullptr) const;

    // Whether the box (closed) meets any segment of the grid (when only_changing, any segment
    // across which the inside changes), up to a rounding margin. False: nothing inside the
    // box can touch the grid's segments, so a whole curve is classified by its box alone.
    bool box_meets(const BBox& box, bool only_changing) const;

    // Point location against the segments across which the inside changes.
    enum class Where { Out, In, On };
    Where locate(const Point& p) const;

    // The lowest segment (among those `use` accepts) met by a ray going up from p, taken
    // just right of p (segments' x ranges are half open); -1 when there is none. `on` is set
    // when p lies on an accepted segment (then the result is that segment).
    int first_above(const Point& p, const std::function<bool(std::uint32_t)>& use, bool& on) const;

private:
    // first_above's search, for any predicate (locate's inline, the public one's through
    // std::function).
    template <class Use>
    int first_above_with(const Point& p, const Use& use, bool& on) const;
    int col(double x) const;
    int row(double y) const;
    std::size_t cell(int c, int r) const { return std::size_t(r) * std::size_t(nx_) + std::size_t(c); }

    std::vector<Seg> segs_;
    BBox box_;
    int nx_ = 1, ny_ = 1;
    double cw_ = 1, ch_ = 1;
    std::vector<std::uint32_t> start_, items_;
    mutable std::vector<std::uint64_t> seen_;
    mutable std::uint64_t stamp_ = 0;
};

// The segments of a set of curves (zero-length and non-finite segments left out), each
// tagged with the index of its curve.
std::vector<Seg> curve_segments(const Curves& c);
// The same into `out` (cleared first; its storage is reused).
void curve_segments(const Curves& c, std::vector<Seg>& out);

// The edges of the planar map the curves induce, as curves (PlanarMap::edge_curves()),
// computed without the exact planar map for the curves that meet no other curve and do
// not touch themselves: such a curve is one edge on its own.
Curves maximal_edges(const Curves& c);

// Adds n to this thread's count of segments searched one by one (tex::detail::segments_searched).
void note_segments_searched(std::size_t n);

}  // namespace tex::detail

namespace tex::detail {
// The planar map of the curves, always through CGAL's exact arrangement (PlanarMap::induce
// traces clean connected drawings directly); for the tests that compare both ways.
MapPtr induce_with_cgal(const Curves& curves, bool caching = true);
// How many planar maps this thread traced directly (for the tests).
std::uint64_t direct_inductions();

// The vertices of a drawing known to be clean, as a partition's cell complex knows them:
// for the k-th segment of curve_segments(curves), the ids (below `count`) of its two ends.
// Equal ids mean the same point and different ids different points.
struct KnownVertices {
    std::vector<std::array<int, 2>> ends;
    std::size_t count = 0;
};
// The planar map of curves whose drawing the caller has proved clean (segments meet only at
// shared end points, without overlapping; see partitions.cpp, "clean complexes"): the same
// map as PlanarMap::induce(curves), without the exact check or the sort of the end points.
// Falls back to PlanarMap::induce when `known` does not match the curves' segments.
MapPtr induce_clean_complex(const Curves& curves, const KnownVertices& known);
// How many planar maps this thread built through induce_clean_complex (for the tests).
std::uint64_t complex_inductions();
// The keys a planar map gives a vertex at p and an edge with the polyline `points` (read in
// its canonical direction, whatever the edge's).
std::uint64_t vertex_key(const Point& p);
// `reversed`: the canonical reading runs from the last point (the reversed polyline is
// lexicographically smaller), when the caller already knows it.
std::uint64_t edge_key(const std::vector<Point>& points, bool reversed);
std::uint64_t edge_key(const std::vector<Point>& points);
// A polyline read in the direction that starts at its smaller end point (for a loop, the
// one whose second point is smaller): how a planar map orders and keys its edges.
std::vector<Point> canonical_points(const std::vector<Point>& pts);
}  // namespace tex::detail

namespace tex::detail {
// apply_mask with a region, the pieces of the region's boundary that CROP_ADD_BOUNDARY adds
// carrying the label `outline` besides their own (the cropping partitions find them so).
// With `movable` (subject itself, given up by the caller), curves kept whole may be moved
// out of it.
Curves crop_to_region(const Curves& subject, const Region& region, Border b, std::optional<LabelId> outline,
                      Curves* movable = nullptr);
// The pieces of `cropped` carrying `outline` (pieces of the region's outline) lose that label
// and their side labels, and get on their left, the inner side, what `inner(probe, mid)` says
// of the face there: `mid` is the middle of the piece's first segment (a piece may turn a
// corner of the outline) and `probe` a point just beside it, inside.
void label_outline_pieces(Curves& cropped, LabelId outline,
                          const std::function<std::optional<Labels>(const Point& probe, const Point& mid)>& inner);
}  // namespace tex::detail
