// RegionSet: a growing set of regions with an R-tree over their boxes, and the Overlap /
// MinimalDistance tests against it. The tree only proposes candidates; each decision is
// made on the geometry (element_view.hpp).
#include <algorithm>
#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>
#include <cmath>

#include "element_view.hpp"
#include "libtex/error.hpp"

namespace tex::disc {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;

namespace {
using BPoint = bg::model::point<double, 2, bg::cs::cartesian>;
using BBox2 = bg::model::box<BPoint>;
using Entry = std::pair<BBox2, std::size_t>;

BBox2 to_box(const BBox& b) {
    return {BPoint(b.xmin, b.ymin), BPoint(b.xmax, b.ymax)};
}
}  // namespace

struct RegionSet::Impl {
    std::vector<Region> regions;
    // The segments of each member, made once (views[i].solid points into `regions`).
    std::vector<detail::ElementView> views;
    bgi::rtree<Entry, bgi::rstar<16>> tree;
};

RegionSet::RegionSet() : impl_(std::make_shared<Impl>()) {}

RegionSet::RegionSet(const std::vector<Region>& regions) : RegionSet() {
    for (const auto& r : regions) add(r);
}

void RegionSet::add(Region r) {
    if (r.empty()) throw Error("RegionSet", "an empty region cannot join a set");
    impl_->tree.insert({to_box(r.bbox()), impl_->regions.size()});
    const Region* before = impl_->regions.data();
    impl_->regions.push_back(std::move(r));
    if (impl_->regions.data() != before)  // moved: point the views at the new places
        for (std::size_t i = 0; i < impl_->views.size(); ++i)
            impl_->views[i].solid = &impl_->regions[i];
    impl_->views.push_back(detail::view_of(impl_->regions.back()));
}

const detail::ElementView& RegionSet::view(std::size_t i) const {
    return impl_->views[i];
}

void RegionSet::clear() {
    impl_->regions.clear();
    impl_->views.clear();
    impl_->tree.clear();
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
    if (box.empty()) return out;
    for (auto it = impl_->tree.qbegin(bgi::intersects(to_box(box))); it != impl_->tree.qend(); ++it)
        out.push_back(it->second);
    std::sort(out.begin(), out.end());
    return out;
}

namespace {

bool overlaps_any(const RegionSet& s, const detail::ElementView& e) {
    for (std::size_t i : s.near(e.box))
        if (detail::overlap(e, s.view(i))) return true;
    return false;
}

bool nearer_than(const RegionSet& s, const detail::ElementView& e, double d) {
    if (!(d >= 0) || !std::isfinite(d))
        throw Error("MinimalDistance",
                    "the distance must be finite and >= 0 (got " + std::to_string(d) + ")");
    for (std::size_t i : s.near(e.box.expanded(d)))
        if (detail::distance(e, s.view(i), d) < d || (d == 0 && detail::overlap(e, s.view(i))))
            return true;
    return false;
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
