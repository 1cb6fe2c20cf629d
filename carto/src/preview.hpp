// The canvas of the PNG previews (hatches: output.cpp; partitions: extract/write.cpp): grey or
// colour values over a window of the ground, white to start. What lines and filled shapes
// cover comes from libtex (libtex/coverage.hpp); this lays inks over it and writes the file.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "libtex/coverage.hpp"

namespace carto {

class Preview {
public:
    // `pixels` along the longer side of `ground` (a window of no width or height gets one
    // pixel across); `bands` 1 (grey) or 3 (RGB). Throws Error(Usage) naming `what` when the
    // image would be absurdly large.
    Preview(const tex::BBox& ground, int pixels, int bands, const std::string& what);

    const tex::PixelGrid& grid() const { return grid_; }
    int bands() const { return bands_; }
    float* at(int col, int row) { return &v_[(std::size_t(row) * std::size_t(grid_.width) + std::size_t(col)) * bands_]; }
    // A coverage raster for this canvas, all 0.
    std::vector<float> blank() const { return std::vector<float>(grid_.Size(), 0.0f); }

    // Ink as a pen on paper: each band darkens to at most paper + (ink - paper) x coverage,
    // paper being white, whatever lies below; the order of darkening does not matter.
    void darken(const std::vector<float>& cover, const std::array<float, 3>& ink);
    // Ink laid over what lies below in proportion to its coverage (later inks on top).
    void over(const std::vector<float>& cover, const std::array<float, 3>& ink);

    // 8 bits per band, written atomically (temp_file.hpp); `what` names the output in errors.
    void write_png(const std::string& path, const std::string& what) const;

private:
    tex::PixelGrid grid_;
    int bands_;
    std::vector<float> v_;
};

}  // namespace carto
