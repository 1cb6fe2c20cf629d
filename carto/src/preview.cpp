#include "preview.hpp"

#include <algorithm>
#include <cmath>

#include "carto/error.hpp"
#include "libtex/error.hpp"
#include "temp_file.hpp"

namespace carto {

Preview::Preview(const tex::BBox& ground, int pixels, int bands, const std::string& what) : bands_(bands) {
    tex::BBox b = ground.empty() ? tex::BBox{0, 0, 1, 1} : ground;
    const double upp = std::max(b.width(), b.height()) / std::max(1, pixels);  // ground units per pixel
    if (!(upp > 0)) b = {b.xmin, b.ymin, b.xmin + 1, b.ymin + 1};
    const double step = upp > 0 ? upp : 1.0 / std::max(1, pixels);
    // A line (all on one row or column) still gets one pixel across.
    if (!(b.width() > 0)) b.xmax = b.xmin + step;
    if (!(b.height() > 0)) b.ymax = b.ymin + step;
    try {
        grid_ = tex::PixelGrid::Of(b, step, "preview");
    } catch (const tex::Error& e) {
        throw Error(Code::Usage, what + ": " + e.what());
    }
    v_.assign(grid_.Size() * std::size_t(bands_), 1.0f);
}

void Preview::darken(const std::vector<float>& cover, const std::array<float, 3>& ink) {
    for (std::size_t i = 0; i < cover.size(); ++i) {
        if (cover[i] <= 0) continue;
        for (int k = 0; k < bands_; ++k) {
            float& px = v_[i * std::size_t(bands_) + std::size_t(k)];
            px = std::min(px, 1.0f - (1.0f - ink[std::size_t(k)]) * cover[i]);
        }
    }
}

void Preview::over(const std::vector<float>& cover, const std::array<float, 3>& ink) {
    for (std::size_t i = 0; i < cover.size(); ++i) {
        if (cover[i] <= 0) continue;
        for (int k = 0; k < bands_; ++k) {
            float& px = v_[i * std::size_t(bands_) + std::size_t(k)];
            px = px * (1.0f - cover[i]) + ink[std::size_t(k)] * cover[i];
        }
    }
}

void Preview::write_png(const std::string& path, const std::string& what) const {
    std::vector<unsigned char> bytes(v_.size());
    for (std::size_t i = 0; i < v_.size(); ++i)
        bytes[i] = (unsigned char)std::lround(std::clamp(v_[i], 0.0f, 1.0f) * 255);
    write_png_pixels(bytes, grid_.width, grid_.height, bands_, path, what);
}

}  // namespace carto
