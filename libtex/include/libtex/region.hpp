// Region: the domain an arrangement is evaluated on, a polygon with holes.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "libtex/geometry.hpp"

namespace tex {

class Curves;

class Region {
public:
    Region() = default;
    // Outer ring and holes; orientations are normalised (outer counter-clockwise, holes
    // clockwise, so the inside is always on the left). Throws tex::Error naming `op` when
    // the outer ring has fewer than three distinct points or no area.
    Region(std::vector<Point> outer, std::vector<std::vector<Point>> holes = {},
           const std::string& op = "Region");

    static Region rectangle(double xmin, double ymin, double xmax, double ymax);

    const std::vector<Point>& outer() const { return outer_; }
    const std::vector<std::vector<Point>>& holes() const { return holes_; }
    bool empty() const { return outer_.empty(); }
    const BBox& bbox() const { return bbox_; }
    double area() const;
    // The area of this region (its outer ring less its holes) inside `convex`, whose outer
    // ring is taken as convex (a cell of a jittered grid): each ring clipped by it
    // (Sutherland-Hodgman). What a tone budget divides a cell's ink by where the cell reaches
    // out of a face.
    double area_within(const Region& convex) const;
    // Even-odd test over all rings; points on a ring count as inside.
    bool contains(const Point& p) const;
    // The boundary as curves, inside on the left: the labelled edges when the region has
    // them (see with_edges), else the rings as closed curves.
    Curves boundary() const;
    // The same region whose boundary is given as labelled curves (the edges of a face with
    // their labels, inside on the left), so that a partition cropped to it with
    // CROP_ADD_BOUNDARY keeps the labels of the face's edges on its outline (thesis: a
    // sub-partition's border edges carry the labels of the edges they lie on). The curves
    // must run along the rings; they are not checked.
    Region with_edges(Curves edges) const;
    bool has_edges() const { return edges_ != nullptr; }

private:
    std::vector<Point> outer_;
    std::vector<std::vector<Point>> holes_;
    BBox bbox_;
    std::shared_ptr<const Curves> edges_;
};

// Relation of a convex polygon to a region, decided on doubles (used by the KEEP_INSIDE /
// KEEP_OUTSIDE border modes, which keep or drop whole cells).
enum class Overlap { Disjoint, Partial, Inside };
Overlap classify_polygon(const std::vector<Point>& poly, const BBox& poly_box, const Region& r);
// classify_polygon(...) != Overlap::Disjoint, without the work that only tells Inside from
// Partial.
bool polygon_meets_region(const std::vector<Point>& poly, const BBox& poly_box, const Region& r);

// True when the point lies inside the (closed) polygon ring.
bool point_in_ring(const Point& p, const std::vector<Point>& ring);
// A point inside the region: the centroid of its outer ring when inside the region, else a
// point just inside the middle of the outer ring's longest side.
Point InteriorPoint(const Region& r);

// A region prepared for many tests: the segments and vertices of each ring are sorted into
// horizontal slabs, so that a point test visits the segments that span the point's height
// and a polygon test the segments and vertices near the polygon's box, instead of every
// segment of every ring. The answers are the region's own (Region::contains,
// classify_polygon, polygon_meets_region), computed by the same arithmetic on the same
// segments: only the segments the plain tests skip at once are left out. It refers to the
// region, which must outlive it. Worth building when a region of many vertices is asked
// about many points or cells (a KEEP partition over a traced face).
class PreparedRegion {
public:
    explicit PreparedRegion(const Region& r);
    // Whether preparing r pays off for more than a few tests: its rings hold more than a few
    // dozen points (a traced face; a rectangle or a small polygon is quicker scanned).
    static bool worth_preparing(const Region& r);
    const Region& region() const { return *r_; }
    bool contains(const Point& p) const;
    Overlap classify_polygon(const std::vector<Point>& poly, const BBox& poly_box) const;
    bool polygon_meets_region(const std::vector<Point>& poly, const BBox& poly_box) const;

    // One ring's segments (by the index of their first point) and vertices, per slab.
    struct Slabs {
        double y0 = 0, height = 1;
        int n = 1;
        std::vector<std::uint32_t> seg_start, segs, vertex_start, vertices;
        int slab(double y) const;
    };

private:
    Overlap classify_as(const std::vector<Point>& poly, const BBox& poly_box, bool only_disjoint) const;
    const Region* r_;
    Slabs outer_;
    std::vector<Slabs> holes_;
};

// Which of a set of regions holds a point: the regions whose box holds it are tested through a
// uniform grid of boxes (about one region per cell) over `area`, in the order given, and the
// first that contains the point (Region::contains: its border counts) answers. The cost of a
// query depends on the regions near the point, not on how many there are. Used by the
// face-wise fields (fields.hpp) and by the point location in planar maps (FaceLocator).
class RegionLocator {
public:
    // Regions whose box misses `area` are not indexed (default: the union of their boxes);
    // a point outside `area` is in none.
    explicit RegionLocator(std::vector<Region> regions, std::optional<BBox> area = std::nullopt);
    // The index of the first region holding p, or -1.
    int find(const Point& p) const;
    const BBox& area() const { return area_; }
    const std::vector<Region>& regions() const { return *regions_; }

private:
    // Shared by copies (they are never changed): the prepared forms of the regions of many
    // vertices refer to these regions.
    std::shared_ptr<const std::vector<Region>> regions_;
    std::shared_ptr<const std::vector<std::optional<PreparedRegion>>> prepared_;
    BBox area_;
    int nx_ = 1, ny_ = 1;
    std::vector<std::vector<int>> cells_;  // region indices per grid cell, ascending
};

}  // namespace tex
