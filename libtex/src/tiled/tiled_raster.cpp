// Rasterising a window of a tiled map: the curves the window receives, drawn segment by
// segment into bands of rows (thesis 4.2.5's local conversion, then a plain scan).
#include <algorithm>
#include <cmath>
#include <sstream>

#include "libtex/coverage.hpp"
#include "libtex/error.hpp"
#include "libtex/tiled.hpp"

namespace tex {

Raster Rasterize(const TiledMap& t, const BBox& window, double pixel, double line_width) {
    const PixelGrid grid = PixelGrid::Of(window, pixel, "Rasterize");
    if (!(line_width > 0) || !std::isfinite(line_width)) {
        std::ostringstream m;
        m << "line width " << line_width << " is not a positive number";
        throw Error("Rasterize", m.str());
    }
    const BBox grown = window.expanded(line_width);
    const Curves curves = t.Convert(Region::rectangle(grown.xmin, grown.ymin, grown.xmax, grown.ymax), KEEP_OUTSIDE);
    StrokeCoverage strokes(grid, line_width);
    for (const auto& c : curves.curves) strokes.Add(c.points, c.closed);
    std::vector<float> cover(grid.Size(), 0.0f);
    strokes.Render(cover);
    Raster out;
    out.width = grid.width;
    out.height = grid.height;
    out.pixels.resize(cover.size());
    for (std::size_t i = 0; i < cover.size(); ++i) out.pixels[i] = std::uint8_t(std::lround(255 * (1 - cover[i])));
    return out;
}

}  // namespace tex
