// Ink coverage of a window of the plane cut into square pixels: what every raster image the
// project draws is made of (the tiled maps' Rasterize, rockhatch's PNG previews). Lines are
// covered by their exact distance to each pixel's centre with a soft edge one pixel wide;
// filled rings by the even-odd rule at pixel centres. Coverage is a value in 0..1 per pixel,
// the largest of what covers it; turning it into colours is the caller's.
#pragma once

#include <cstddef>
#include <vector>

#include "libtex/geometry.hpp"

namespace tex {

// The pixels of a window, rows from the top: pixel (col, row) spans
// [xmin + col * pixel, xmin + (col + 1) * pixel] x [ymax - (row + 1) * pixel, ymax - row * pixel].
struct PixelGrid {
    BBox window;
    double pixel = 1;
    int width = 0, height = 0;

    // `pixel` ground units per pixel; enough pixels to hold the window. Throws tex::Error
    // (naming `what`) on a non-positive pixel size, an empty window or more than 1e9 pixels.
    static PixelGrid Of(const BBox& window, double pixel, const char* what = "PixelGrid");
    Point Centre(int col, int row) const {
        return {window.xmin + (col + 0.5) * pixel, window.ymax - (row + 0.5) * pixel};
    }
    std::size_t Size() const { return std::size_t(width) * std::size_t(height); }
};

// Lines of one width: add the polylines, then Render into a coverage raster. Segments are
// bucketed by bands of rows, which are rendered on the worker threads (parallel.hpp); a pixel
// takes the largest coverage of any segment, so the result does not depend on the order of
// the lines or on the thread count.
class StrokeCoverage {
public:
    // `width` in ground units (positive; tex::Error otherwise). Lines much narrower than a
    // pixel come out faint: a preview may want to draw them at least a pixel wide.
    StrokeCoverage(const PixelGrid& grid, double width);
    void Add(const std::vector<Point>& points, bool closed);
    void AddSegment(const Point& a, const Point& b);
    // cover[row * width + col] = max(cover, coverage); `cover` has grid.Size() values.
    void Render(std::vector<float>& cover) const;

private:
    struct Seg {
        Point a, b;
    };
    PixelGrid g_;
    double half_;   // half the line width
    double reach_;  // how far a segment's ink reaches: half the width and the soft edge
    std::vector<std::vector<Seg>> bands_;
};

// One filled shape: pixels whose centre lies inside the rings by the even-odd rule (holes
// are rings too) get coverage 1.
void CoverFill(const PixelGrid& grid, const std::vector<std::vector<Point>>& rings, std::vector<float>& cover);

}  // namespace tex
