// Point location: RegionLocator (region.hpp) and, on it, FaceLocator (planar_map.hpp).
#include <algorithm>
#include <cmath>

#include "libtex/error.hpp"
#include "libtex/planar_map.hpp"
#include "libtex/region.hpp"

namespace tex {

RegionLocator::RegionLocator(std::vector<Region> regions, std::optional<BBox> area) {
    auto kept = std::make_shared<std::vector<Region>>();
    if (area) {
        area_ = *area;
        for (auto& r : regions)
            if (r.bbox().intersects(area_)) kept->push_back(std::move(r));
    } else {
        *kept = std::move(regions);
        for (const auto& r : *kept) area_.add(r.bbox());
    }
    // Regions of many vertices (traced faces) are asked through their slabs: same answers.
    auto prepared = std::make_shared<std::vector<std::optional<PreparedRegion>>>(kept->size());
    for (std::size_t k = 0; k < kept->size(); ++k) {
        const Region& r = (*kept)[k];
        if (PreparedRegion::worth_preparing(r)) (*prepared)[k].emplace(r);
    }
    regions_ = std::move(kept);
    prepared_ = std::move(prepared);
    const std::vector<Region>& rs = *regions_;
    if (area_.empty()) return;
    // About one region per cell.
    const double cells = std::clamp(double(rs.size()), 1.0, 65536.0);
    const double w = std::max(area_.width(), 1e-300), h = std::max(area_.height(), 1e-300);
    nx_ = std::clamp(int(std::ceil(std::sqrt(cells * w / h))), 1, 256);
    ny_ = std::clamp(int(std::ceil(cells / nx_)), 1, 256);
    cells_.assign(std::size_t(nx_) * std::size_t(ny_), {});
    auto col = [&](double x) { return std::clamp(int(std::floor((x - area_.xmin) / w * nx_)), 0, nx_ - 1); };
    auto row = [&](double y) { return std::clamp(int(std::floor((y - area_.ymin) / h * ny_)), 0, ny_ - 1); };
    for (std::size_t k = 0; k < rs.size(); ++k) {
        const BBox& b = rs[k].bbox();
        if (b.empty()) continue;  // an empty region holds no point
        for (int i = col(b.xmin); i <= col(b.xmax); ++i)
            for (int j = row(b.ymin); j <= row(b.ymax); ++j) cells_[std::size_t(j) * nx_ + i].push_back(int(k));
    }
}

int RegionLocator::find(const Point& p) const {
    if (area_.empty() || !area_.contains(p)) return -1;
    const int i = std::clamp(int(std::floor((p.x - area_.xmin) / std::max(area_.width(), 1e-300) * nx_)), 0, nx_ - 1);
    const int j = std::clamp(int(std::floor((p.y - area_.ymin) / std::max(area_.height(), 1e-300) * ny_)), 0, ny_ - 1);
    for (int k : cells_[std::size_t(j) * nx_ + i]) {
        const auto& pr = (*prepared_)[std::size_t(k)];
        if (pr ? pr->contains(p) : (*regions_)[std::size_t(k)].contains(p)) return k;
    }
    return -1;
}

namespace {

// The bounded faces of a map as regions (faces without area hold no point), with their ids.
std::pair<std::vector<Region>, std::vector<int>> face_regions(const PlanarMap& m) {
    std::vector<Region> regions;
    std::vector<int> ids;
    for (std::size_t f = 0; f < m.faces().size(); ++f) {
        if (m.faces()[f].unbounded || m.faces()[f].cycles.empty()) continue;
        std::vector<std::vector<Point>> holes;
        for (std::size_t k = 1; k < m.faces()[f].cycles.size(); ++k) holes.push_back(m.cycle_points(int(f), k));
        try {
            regions.emplace_back(m.cycle_points(int(f), 0), std::move(holes), "FaceLocator");
            ids.push_back(int(f));
        } catch (const Error&) {
        }
    }
    return {std::move(regions), std::move(ids)};
}

BBox map_box(const PlanarMap& m) {
    BBox b;
    for (const auto& v : m.vertices()) b.add(v.point);
    for (const auto& e : m.edges())
        for (const auto& p : e.points) b.add(p);
    return b;
}

}  // namespace

FaceLocator::FaceLocator(MapPtr map, std::optional<BBox> area) : map_(std::move(map)) {
    auto [regions, ids] = face_regions(*map_);
    std::vector<int> kept;  // the ids of the regions the locator keeps (those meeting the area)
    const BBox a = area ? *area : map_box(*map_);
    for (std::size_t k = 0; k < regions.size(); ++k)
        if (regions[k].bbox().intersects(a)) kept.push_back(ids[k]);
    ids_ = std::move(kept);
    locator_ = std::make_shared<const RegionLocator>(std::move(regions), a);
}

int FaceLocator::face_at(const Point& p) const {
    const int k = locator_->find(p);
    return k >= 0 ? ids_[std::size_t(k)] : map_->unbounded_face();
}

}  // namespace tex
