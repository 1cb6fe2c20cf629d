// Rasterising a window of a tiled map: the curves the window receives, drawn segment by
// segment into bands of rows (thesis 4.2.5's local conversion, then a plain scan).
#include <algorithm>
#include <cmath>
#include <sstream>

#include "libtex/error.hpp"
#include "libtex/parallel.hpp"
#include "libtex/tiled.hpp"

namespace tex {
namespace {

constexpr int kBandRows = 32;

double segment_distance(const Point& p, const Point& a, const Point& b) {
    const Point d = b - a;
    const double l2 = dot(d, d);
    const double t = l2 > 0 ? std::clamp(dot(p - a, d) / l2, 0.0, 1.0) : 0.0;
    return distance(p, a + d * t);
}

}  // namespace

Raster Rasterize(const TiledMap& t, const BBox& window, double pixel, double line_width) {
    auto fail = [](const std::string& what) { throw Error("Rasterize", what); };
    if (!(pixel > 0) || !std::isfinite(pixel)) {
        std::ostringstream m;
        m << "pixel size " << pixel << " is not a positive number";
        fail(m.str());
    }
    if (!(line_width > 0) || !std::isfinite(line_width)) {
        std::ostringstream m;
        m << "line width " << line_width << " is not a positive number";
        fail(m.str());
    }
    if (window.empty() || !(window.width() > 0) || !(window.height() > 0)) fail("the window is empty");
    const double w = std::ceil(window.width() / pixel), h = std::ceil(window.height() / pixel);
    if (w * h > 1.0e9) fail("more than 1e9 pixels");
    Raster out;
    out.width = int(w);
    out.height = int(h);
    out.pixels.assign(std::size_t(out.width) * std::size_t(out.height), 255);

    const BBox grown = window.expanded(line_width);
    const Curves curves = t.Convert(Region::rectangle(grown.xmin, grown.ymin, grown.xmax, grown.ymax), KEEP_OUTSIDE);
    struct Seg {
        Point a, b;
    };
    // Segments bucketed by the bands of rows their box (grown by half the line) covers.
    const int bands = (out.height + kBandRows - 1) / kBandRows;
    std::vector<std::vector<Seg>> by_band(static_cast<std::size_t>(bands));
    const double half = line_width / 2 + pixel;  // reach of a segment's ink, with the soft edge
    auto row_of = [&](double y) { return (window.ymax - y) / pixel; };
    for (const auto& c : curves.curves) {
        const std::size_t n = c.points.size();
        const std::size_t segs = c.closed && n > 2 ? n : (n ? n - 1 : 0);
        for (std::size_t k = 0; k < segs; ++k) {
            const Point a = c.points[k], b = c.points[(k + 1) % n];
            const double r0 = row_of(std::max(a.y, b.y) + half), r1 = row_of(std::min(a.y, b.y) - half);
            const int b0 = std::max(0, int(std::floor(r0)) / kBandRows);
            const int b1 = std::min(bands - 1, int(std::floor(std::min(r1, double(out.height)))) / kBandRows);
            for (int band = b0; band <= b1; ++band) by_band[std::size_t(band)].push_back({a, b});
        }
    }
    parallel_for(std::size_t(bands), [&](std::size_t band) {
        const int row0 = int(band) * kBandRows, row1 = std::min(out.height, row0 + kBandRows);
        for (const Seg& s : by_band[band]) {
            const int c0 = std::max(0, int(std::floor((std::min(s.a.x, s.b.x) - half - window.xmin) / pixel)));
            const int c1 = std::min(out.width - 1, int(std::floor((std::max(s.a.x, s.b.x) + half - window.xmin) / pixel)));
            const int r0 = std::max(row0, int(std::floor(row_of(std::max(s.a.y, s.b.y) + half))));
            const int r1 = std::min(row1 - 1, int(std::floor(row_of(std::min(s.a.y, s.b.y) - half))));
            for (int r = r0; r <= r1; ++r)
                for (int c = c0; c <= c1; ++c) {
                    const Point p{window.xmin + (c + 0.5) * pixel, window.ymax - (r + 0.5) * pixel};
                    // Ink coverage: 1 within the line, falling to 0 over one pixel at its edge.
                    const double cover = std::clamp((line_width / 2 - segment_distance(p, s.a, s.b)) / pixel + 0.5, 0.0, 1.0);
                    const auto v = std::uint8_t(std::lround(255 * (1 - cover)));
                    std::uint8_t& px = out.pixels[std::size_t(r) * std::size_t(out.width) + std::size_t(c)];
                    px = std::min(px, v);
                }
        }
    });
    return out;
}

}  // namespace tex
