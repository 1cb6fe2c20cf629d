// FaceLocator: which face of a frozen planar map contains a point (planar_map.hpp).
#include <algorithm>
#include <cmath>

#include "libtex/planar_map.hpp"
#include "libtex/region.hpp"

namespace tex {

FaceLocator::FaceLocator(MapPtr map, std::optional<BBox> area) : map_(std::move(map)) {
    const PlanarMap& m = *map_;
    if (area) {
        area_ = *area;
    } else {
        for (const auto& v : m.vertices()) area_.add(v.point);
        for (const auto& e : m.edges())
            for (const auto& p : e.points) area_.add(p);
    }
    for (std::size_t f = 0; f < m.faces().size(); ++f) {
        if (m.faces()[f].unbounded || m.faces()[f].cycles.empty()) continue;
        Candidate c;
        c.face = int(f);
        for (std::size_t k = 0; k < m.faces()[f].cycles.size(); ++k) c.rings.push_back(m.cycle_points(int(f), k));
        for (const auto& p : c.rings.front()) c.box.add(p);
        if (!c.box.intersects(area_)) continue;
        faces_.push_back(std::move(c));
    }
    if (area_.empty()) return;
    // About one face per cell.
    const double cells = std::clamp(double(faces_.size()), 1.0, 65536.0);
    const double w = std::max(area_.width(), 1e-300), h = std::max(area_.height(), 1e-300);
    nx_ = std::clamp(int(std::ceil(std::sqrt(cells * w / h))), 1, 256);
    ny_ = std::clamp(int(std::ceil(cells / nx_)), 1, 256);
    cells_.assign(std::size_t(nx_) * std::size_t(ny_), {});
    auto col = [&](double x) { return std::clamp(int(std::floor((x - area_.xmin) / w * nx_)), 0, nx_ - 1); };
    auto row = [&](double y) { return std::clamp(int(std::floor((y - area_.ymin) / h * ny_)), 0, ny_ - 1); };
    for (std::size_t k = 0; k < faces_.size(); ++k) {
        const BBox& b = faces_[k].box;
        for (int i = col(b.xmin); i <= col(b.xmax); ++i)
            for (int j = row(b.ymin); j <= row(b.ymax); ++j) cells_[std::size_t(j) * nx_ + i].push_back(int(k));
    }
}

int FaceLocator::face_at(const Point& p) const {
    if (!area_.empty() && area_.contains(p)) {
        const int i = std::clamp(int(std::floor((p.x - area_.xmin) / std::max(area_.width(), 1e-300) * nx_)), 0, nx_ - 1);
        const int j = std::clamp(int(std::floor((p.y - area_.ymin) / std::max(area_.height(), 1e-300) * ny_)), 0, ny_ - 1);
        for (int k : cells_[std::size_t(j) * nx_ + i]) {
            const Candidate& c = faces_[std::size_t(k)];
            if (!c.box.contains(p) || !point_in_ring(p, c.rings.front())) continue;
            bool in_hole = false;
            for (std::size_t h = 1; h < c.rings.size() && !in_hole; ++h) in_hole = point_in_ring(p, c.rings[h]);
            if (!in_hole) return c.face;
        }
    }
    return map_->unbounded_face();
}

}  // namespace tex
