// Tiled planar maps (thesis Chapter 4): periodic arrangements stored once per period.
//
// A TiledMap stands for the infinite arrangement made of every translate, by i * period1 +
// j * period2 (i, j integers), of a small set of elements. An element is what one cell
// produced: an edge of a tiled partition, or the curves one mapper call returned. Each
// element belongs to the central tile (its reference point, the cell's location, lies in
// the fundamental parallelogram) but its curves may reach into the neighbouring tiles.
//
// How a script asks for it: a partition given `Tiled(border)` instead of a border mode
// returns a TiledMap; MapToVertices / MapToEdges / MapToFaces, Union and GhostMap applied to
// a TiledMap return a TiledMap, so a regular script changes in that one argument. A TiledMap
// converts implicitly to an Arrangement (evaluated on a region with the border mode given
// to Tiled), or explicitly with Convert(region, border).
//
// Mappers run on the cells of a small planar map of a block of tiles around the central
// one (the Neighbourhood-Influence-Zone rule of thesis 4.2.2: the block is wide enough for
// every cell of the central tile to see all its neighbours, so a vertex on the tile's side
// reports its real degree). Their output may overflow into neighbouring tiles: it is kept
// whole and duplicated with the rest. A regular mapper must not draw random numbers (that
// would break the period): Random inside one throws tex::Error. Randomness goes in a ghost
// mapper (4.2.4), the last stage, called on each copy of each element at conversion only.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "libtex/arrangement.hpp"
#include "libtex/mapping.hpp"
#include "libtex/partitions.hpp"
#include "libtex/random.hpp"

namespace tex {

// The argument that asks a partition for its tiled form; `border` is the mode used when the
// tiled map is converted implicitly to an Arrangement.
struct Tiled {
    Border border = Border::KEEP_OUTSIDE;
    Tiled() = default;
    explicit Tiled(Border b) : border(b) {}
};

// One copy of an element met at conversion, as a ghost mapper sees it. A line stored one
// period at a time (a stripe, Element::continues) is seen whole instead: one curve over the
// region's box grown by one period, with j = 0 and a key of the line (element and i), so
// that a line gets the same random numbers in every window.
struct TiledElement {
    Curves curves;           // the element's curves, translated to this copy
    Point anchor;            // reference point of the cell the element came from, translated
    long long i = 0, j = 0;  // the copy's shift in periods
    std::uint64_t key = 0;   // key of this copy (element and shift) for Random
};
// Deterministic value in [min, max) for a copy: a function of its key, n and the seed.
double Random(const TiledElement& e, double min, double max, double n);

using GhostMapper = std::function<Curves(const TiledElement&)>;

class TiledMap {
public:
    struct CellRef {
        int cell = -1;           // index in cells(), -1: no cell on that side
        long long di = 0, dj = 0;  // shift of that cell's copy relative to the element's
    };
    struct Element {
        Curves curves;
        BBox box;
        Point anchor;
        std::uint64_t key = 0;
        // For the edges of a tiled partition: the cells on the left and right of the
        // element's single curve (used by the KEEP_* modes, which keep whole cells).
        CellRef left, right;
        // A piece of a longer line cut at the period: the element's single open curve ends
        // where its copy shifted by +period2 starts. A conversion joins the consecutive
        // copies it keeps into one curve, so a line is drawn whole, as by the engine.
        bool continues = false;
    };
    struct CellRing {
        std::vector<Point> ring;  // counter-clockwise
        BBox box;
        Labels labels;
    };

    TiledMap(Point period1, Point period2, std::vector<Element> elements, Border border,
             std::vector<CellRing> cells = {}, bool bounded_faces = true);
    // A tiled StripesPartition: its faces are infinite bands, so KEEP_INSIDE / KEEP_OUTSIDE
    // (which keep whole faces) are realised as the engine's StripesPartition does it.
    TiledMap(Point period1, Point period2, std::vector<Element> elements, Border border, Stripes stripes);

    const Point& period1() const { return d_->p1; }
    const Point& period2() const { return d_->p2; }
    const std::vector<Element>& elements() const { return d_->elements; }
    const std::vector<CellRing>& cells() const { return d_->cells; }
    Border border() const { return d_->border; }
    bool has_ghost() const { return static_cast<bool>(d_->ghost); }
    bool bounded_faces() const { return d_->bounded_faces; }
    // The stripes this map is the tiled partition of (none for any other map).
    const std::optional<Stripes>& stripes() const { return d_->stripes; }

    // The arrangement over region r with border mode b (thesis 4.2.5). Each copy of each
    // element is classified by its box: wholly inside (kept as is), outside (dropped) or
    // across the region's boundary. CROP cuts the curves of the last kind at the boundary
    // (CROP_ADD_BOUNDARY adds the outline, its inner side labelled with the face it bounds);
    // KEEP_OUTSIDE keeps a copy whole when one of its curves meets the region, KEEP_INSIDE
    // when all of them lie inside (for a tiled partition: the edges of the cells that meet /
    // lie inside the region, as the engine's partitions). Pieces of a line (Element::
    // continues) are joined first, so a line comes out whole. A tiled StripesPartition in a
    // KEEP mode gives exactly the engine's stripes (whole bands, so whole lines across the
    // region's box and beyond: not local). Otherwise the result over a window depends on
    // nothing outside the window; copies are made on the worker threads and concatenated
    // in a fixed order (same bytes at any thread count).
    Curves Convert(const Region& r, Border b) const;
    Curves operator()(const Region& r) const { return Convert(r, border()); }
    operator Arrangement() const;  // NOLINT: a TiledMap is used wherever an Arrangement is

    // The planar map of the block of (2k+1) x (2k+1) tiles around the central one, and the
    // cells of it whose reference point lies in the central tile (what mappers visit).
    struct Block {
        MapPtr map;
        std::vector<int> vertices, edges, faces;
    };
    Block block() const;
    // The copies of the elements over that block, with the copies of a vertex welded.
    Curves block_curves() const;
    // Smallest k such that the block of (2k+1)^2 tiles holds every cell a mapper of the
    // central tile can reach (its neighbours' neighbours).
    int block_reach() const;

    // ---- Point queries (cost independent of the window) ----
    // Distance from p to the nearest curve of the infinite arrangement (ghost ignored):
    // p moved into the central tile, then a nearest-segment search in a uniform grid of the
    // copies of the elements' segments that can be nearest to a point of that tile (built
    // once, on the first query). The same value, bit for bit, as DistanceToCurvesByScan.
    double DistanceToCurves(const Point& p) const;
    // The reference: every segment of every copy within block_reach() + 1 tiles of p's tile.
    double DistanceToCurvesByScan(const Point& p) const;
    // Labels of the face of the infinite arrangement containing p: for a tiled partition,
    // of the cell containing p; otherwise, of the face containing p moved into the central
    // tile in the planar map of the block's copies closed by an unlabelled frame (built once,
    // on the first query; located through a grid of the faces' regions). A face that is unbounded in the
    // infinite arrangement (a band of stripes, the space around closed shapes) gets the
    // labels of its sides within the block.
    Labels FaceLabelsAt(const Point& p) const;

    // Lattice coordinates of p (p = a * period1 + b * period2).
    Point lattice(const Point& p) const;
    Point shift(long long i, long long j) const { return d_->p1 * double(i) + d_->p2 * double(j); }

    // Internal: the same map with a ghost mapper.
    TiledMap with_ghost(GhostMapper g) const;

private:
    struct Data {
        Point p1, p2;
        double inv[4];  // inverse of the period matrix
        std::vector<Element> elements;
        std::vector<CellRing> cells;
        Border border;
        bool bounded_faces;
        double reach = 0;  // block_reach() before its check
        std::optional<Stripes> stripes;
        GhostMapper ghost;
        struct Locator;  // the block's planar map and its FaceLocator, made on first use
        std::shared_ptr<Locator> locator;
    };
    explicit TiledMap(std::shared_ptr<const Data> d) : d_(std::move(d)) {}
    std::shared_ptr<const Data> d_;
};

// ---- Rasterising a window ----
// A grey image of the window (8 bits, rows from the top, white paper, black ink): every
// curve the window receives (KEEP_OUTSIDE over the window grown by the line width, ghost
// included) drawn `line_width` wide with an anti-aliased edge, at `pixel` units per pixel.
// No planar map is built; rows are filled in bands on the worker threads (same bytes at any
// thread count). Writing it to a file is libtex_image's (tiled_image.hpp, OpenImageIO).
struct Raster {
    int width = 0, height = 0;
    std::vector<std::uint8_t> pixels;  // width * height, row-major from the top
};
Raster Rasterize(const TiledMap& t, const BBox& window, double pixel, double line_width);

// ---- Tiled partitions ----
// The grid as a tiled map: the period along each family is LCM(n, edge labels, face labels) / n
// times the sum of its n widths, so that widths and label cycles all repeat.
TiledMap GridPartition(const Stripes& s1, const Stripes& s2, Tiled t);
// Stripes as a tiled map (period along the lines: one period across). Its faces are
// infinite bands, so mapping its vertices, edges or faces is an error; use a grid.
TiledMap StripesPartition(const Stripes& p, Tiled t);

// ---- Mapping (regular mappers: no Random) ----
TiledMap MapToVertices(VertexMapper m, const TiledMap& a, MapperThreads t = MapperThreads::Parallel);
TiledMap MapToEdges(EdgeMapper m, const TiledMap& a, MapperThreads t = MapperThreads::Parallel);
TiledMap MapToFaces(FaceMapper m, const TiledMap& a, MapperThreads t = MapperThreads::Parallel);

// ---- Ghost mapping (thesis 4.2.4) ----
// The last stage: g runs on every copy of every element when the map is converted, and
// may use Random (keyed by the copy), so the output is semi-regular; nothing is mapped
// before conversion. A tiled map with a ghost cannot be mapped again.
TiledMap GhostMap(GhostMapper g, const TiledMap& a);

// ---- Combiners ----
// All elements of both maps. Their lattices must be commensurable: each period of one an
// integer combination of the other's up to a common multiple; the result's periods are the
// least common multiples. Otherwise a tex::Error names both pairs of periods.
TiledMap Union(const TiledMap& a1, const TiledMap& a2);
// The curves of a1 inside / outside the bounded faces of a2, on their common lattice: the
// engine's mask (merge.hpp) applied once to the elements of one tile of a1 against a planar
// map of a2 over a block of tiles around it; each curve kept becomes an element.
// CROP_ADD_BOUNDARY adds a2's curves once.
TiledMap Inside(const TiledMap& a1, const TiledMap& a2, Border b);
TiledMap Outside(const TiledMap& a1, const TiledMap& a2, Border b);


}  // namespace tex
