// RegionSet: a growing set of regions with an index over their boxes (a hash grid and an
// R-tree), and the Overlap / MinimalDistance tests against it. The index only proposes
// candidates; each decision is made on the geometry (element_view.hpp).
#include <algorithm>
#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>
#include <cmath>
#include <cstdint>
#include <memory>

#include "element_view.hpp"
#include "libtex/error.hpp"

namespace tex::disc {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;

// A named namespace, not an anonymous one: RegionSet::Impl, a class of the header, holds these
// types, and in a unity build GCC warns of such a member whose type is in an anonymous
// namespace of an included file (-Wsubobject-linkage).
namespace region_set_index {
using BPoint = bg::model::point<double, 2, bg::cs::cartesian>;
using BBox2 = bg::model::box<BPoint>;
using Entry = std::pair<BBox2, std::size_t>;

BBox2 to_box(const BBox& b) {
    return {BPoint(b.xmin, b.ymin), BPoint(b.xmax, b.ymax)};
}

// The index is rebuilt (a new grid) whenever the set has doubled since the last build, from
// this many members on; smaller sets stay in the R-tree alone.
constexpr std::size_t kFirstGrid = 64;
// Grid cell side, in medians of the members' larger box sides: a member fits in one cell's
// reach (its box starts in the cell), a query box of a member's size spans 2 to 3 cells.
constexpr double kCellPerMedian = 2.0;
// At most this many grid cells per member (the cells grow when the members are few and far
// apart).
constexpr double kCellsPerMember = 4.0;

// A member in a grid cell: its box beside its index, so that a query tests the boxes of a
// cell without visiting the members' geometry.
struct Slot {
    BBox box;
    std::uint32_t index;
};
}  // namespace region_set_index
using region_set_index::BBox2;
using region_set_index::BPoint;
using region_set_index::Entry;
using region_set_index::kCellPerMedian;
using region_set_index::kCellsPerMember;
using region_set_index::kFirstGrid;
using region_set_index::Slot;
using region_set_index::to_box;

// Two indexes over the members' boxes. Members no larger than a grid cell (almost all the
// members of a dart throwing, which are alike in size) sit in a uniform grid over the
// members' extent at the last build, in the cell holding their box's lower-left corner; the
// others (long hatches across the domain, members added outside that extent, every member of
// a set too small for a grid) in an R-tree. A query visits the grid cells whose members can
// reach its box, and the tree. Past saturation a dart throwing's tests are then cheaper than
// with the tree alone (bench_discrete); the tree keeps long members from filling many cells.
struct RegionSet::Impl {
    std::vector<Region> regions;
    // The segments of each member, made once (views[i].solid points into `regions`).
    std::vector<detail::ElementView> views;
    bgi::rtree<Entry, bgi::rstar<16>> tree;
    double cell = 0;  // 0: no grid
    double x0 = 0, y0 = 0;
    std::int64_t nx = 0, ny = 0;
    std::vector<std::vector<Slot>> grid;  // nx * ny cells, row by row
    std::size_t built_at = 0;

    void place(std::size_t i) {
        const BBox& b = views[i].box;
        if (cell > 0 && b.width() <= cell && b.height() <= cell) {
            const double cx = std::floor((b.xmin - x0) / cell), cy = std::floor((b.ymin - y0) / cell);
            if (cx >= 0 && cy >= 0 && cx < double(nx) && cy < double(ny)) {
                grid[std::size_t(cy) * std::size_t(nx) + std::size_t(cx)].push_back({b, std::uint32_t(i)});
                return;
            }
        }
        tree.insert({to_box(b), i});
    }
    // A new grid from the members' sizes and extent, and every member placed again.
    void rebuild() {
        std::vector<double> sides;
        sides.reserve(views.size());
        BBox extent;
        for (const auto& v : views) {
            sides.push_back(std::max(v.box.width(), v.box.height()));
            extent.add(Point{v.box.xmin, v.box.ymin});
        }
        std::nth_element(sides.begin(), sides.begin() + sides.size() / 2, sides.end());
        const double median = sides[sides.size() / 2];
        tree.clear();
        grid.clear();
        cell = 0;
        std::vector<Entry> big;
        if (median > 0 && std::isfinite(median) && std::isfinite(extent.width()) &&
            std::isfinite(extent.height()) && regions.size() < (std::size_t(1) << 31)) {
            cell = kCellPerMedian * median;
            const double budget = kCellsPerMember * double(views.size());
            const double want = (extent.width() / cell + 1) * (extent.height() / cell + 1);
            if (want > budget) cell *= std::sqrt(want / budget);
            x0 = extent.xmin, y0 = extent.ymin;
            nx = std::int64_t(extent.width() / cell) + 1, ny = std::int64_t(extent.height() / cell) + 1;
            grid.resize(std::size_t(nx) * std::size_t(ny));
        }
        for (std::size_t i = 0; i < views.size(); ++i) {
            const BBox& b = views[i].box;
            const bool fits = cell > 0 && b.width() <= cell && b.height() <= cell;
            if (fits)
                place(i);
            else
                big.push_back({to_box(b), i});
        }
        // Bulk-loaded (packed): faster to build than one insertion per member, and a tree
        // with less overlap between its nodes.
        tree = decltype(tree)(big.begin(), big.end());
        built_at = regions.size();
    }
    void grew(std::size_t first) {
        if (regions.size() >= kFirstGrid && regions.size() >= 2 * built_at)
            rebuild();
        else
            for (std::size_t i = first; i < regions.size(); ++i) place(i);
    }
};

RegionSet::RegionSet() : impl_(std::make_shared<Impl>()) {}

RegionSet::RegionSet(const std::vector<Region>& regions) : RegionSet() {
    add(std::vector<Region>(regions));
}

void RegionSet::add(std::vector<Region> rs) {
    for (const auto& r : rs)
        if (r.empty()) throw Error("RegionSet", "an empty region cannot join a set");
    Impl& m = *impl_;
    const std::size_t first = m.regions.size();
    // Geometric growth: a set filled by many bulk adds (a band of strokes at a time) would
    // otherwise move all its members at every add.
    if (m.regions.capacity() < first + rs.size())
        m.regions.reserve(std::max(first + rs.size(), 2 * m.regions.capacity()));
    for (auto& r : rs) m.regions.push_back(std::move(r));
    // The views of the members already there point into the vector, which may have moved.
    for (std::size_t i = 0; i < first; ++i) m.views[i].solid = &m.regions[i];
    for (std::size_t i = first; i < m.regions.size(); ++i) m.views.push_back(detail::view_of(m.regions[i]));
    m.grew(first);
}

void RegionSet::add(Region r) {
    if (r.empty()) throw Error("RegionSet", "an empty region cannot join a set");
    Impl& m = *impl_;
    const Region* before = m.regions.data();
    m.regions.push_back(std::move(r));
    if (m.regions.data() != before)  // moved: point the views at the new places
        for (std::size_t i = 0; i < m.views.size(); ++i) m.views[i].solid = &m.regions[i];
    m.views.push_back(detail::view_of(m.regions.back()));
    m.grew(m.regions.size() - 1);
}

const detail::ElementView& RegionSet::view(std::size_t i) const {
    return impl_->views[i];
}

void RegionSet::clear() {
    impl_->regions.clear();
    impl_->views.clear();
    impl_->tree.clear();
    impl_->grid.clear();
    impl_->cell = 0;
    impl_->built_at = 0;
}

std::size_t RegionSet::size() const {
    return impl_->regions.size();
}

const Region& RegionSet::operator[](std::size_t i) const {
    if (i >= size())
        throw Error("RegionSet",
                    "index " + std::to_string(i) + " out of " + std::to_string(size()));
    return impl_->regions[i];
}

const std::vector<Region>& RegionSet::regions() const {
    return impl_->regions;
}

std::vector<std::size_t> RegionSet::near(const BBox& box) const {
    std::vector<std::size_t> out;
    any_near(box, [&](std::size_t i) {
        out.push_back(i);
        return false;
    });
    std::sort(out.begin(), out.end());
    return out;
}

bool RegionSet::any_near(const BBox& box, const std::function<bool(std::size_t)>& hit) const {
    if (box.empty()) return false;
    const Impl& m = *impl_;
    bool found = false;
    if (!m.tree.empty()) {
        // query() with a predicate rather than qbegin(): the query iterator is type-erased
        // (a heap allocation and virtual calls per query). The predicate records the first
        // hit and asks no more once it has one.
        const auto test = [&](const Entry& e) {
            if (!found && hit(e.second)) found = true;
            return false;
        };
        struct Discard {
            Discard& operator*() { return *this; }
            Discard& operator++() { return *this; }
            Discard operator++(int) { return *this; }
            Discard& operator=(const Entry&) { return *this; }
        };
        m.tree.query(bgi::intersects(to_box(box)) && bgi::satisfies(test), Discard{});
        if (found) return true;
    }
    if (m.grid.empty()) return false;
    // A member of the grid starts in its cell and is at most a cell wide: the cells from one
    // before the box's lower-left corner to its upper-right corner hold all that can meet it.
    const double cx0 = std::max(0.0, std::floor((box.xmin - m.cell - m.x0) / m.cell));
    const double cy0 = std::max(0.0, std::floor((box.ymin - m.cell - m.y0) / m.cell));
    const double cx1 = std::min(double(m.nx - 1), std::floor((box.xmax - m.x0) / m.cell));
    const double cy1 = std::min(double(m.ny - 1), std::floor((box.ymax - m.y0) / m.cell));
    if (!(cx0 <= cx1 && cy0 <= cy1)) return false;
    for (std::size_t iy = std::size_t(cy0); iy <= std::size_t(cy1); ++iy)
        for (std::size_t ix = std::size_t(cx0); ix <= std::size_t(cx1); ++ix)
            for (const Slot& e : m.grid[iy * std::size_t(m.nx) + ix])
                if (e.box.intersects(box) && hit(e.index)) return true;
    return false;
}

namespace {

bool overlaps_any(const RegionSet& s, const detail::ElementView& e) {
    return s.any_near(e.box, [&](std::size_t i) { return detail::overlap(e, s.view(i)); });
}

bool nearer_than(const RegionSet& s, const detail::ElementView& e, double d) {
    if (!(d >= 0) || !std::isfinite(d))
        throw Error("MinimalDistance",
                    "the distance must be finite and >= 0 (got " + std::to_string(d) + ")");
    return s.any_near(e.box.expanded(d), [&](std::size_t i) {
        return detail::distance(e, s.view(i), d) < d || (d == 0 && detail::overlap(e, s.view(i)));
    });
}

}  // namespace

bool Overlap(const RegionSet& s, const Point& e) {
    return overlaps_any(s, detail::view_of(e));
}
bool Overlap(const RegionSet& s, const Polyline& e) {
    return overlaps_any(s, detail::view_of(e));
}
bool Overlap(const RegionSet& s, const Region& e) {
    return overlaps_any(s, detail::view_of(e));
}
bool MinimalDistance(const RegionSet& s, const Point& e, double d) {
    return nearer_than(s, detail::view_of(e), d);
}
bool MinimalDistance(const RegionSet& s, const Polyline& e, double d) {
    return nearer_than(s, detail::view_of(e), d);
}
bool MinimalDistance(const RegionSet& s, const Region& e, double d) {
    return nearer_than(s, detail::view_of(e), d);
}

OverlapTest Overlap(const RegionSet& s) {
    return {s};
}
DistanceTest MinimalDistance(const RegionSet& s, double d) {
    if (!(d >= 0) || !std::isfinite(d))
        throw Error("MinimalDistance",
                    "the distance must be finite and >= 0 (got " + std::to_string(d) + ")");
    return {s, d};
}

}  // namespace tex::disc
