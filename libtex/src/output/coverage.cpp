#include "libtex/coverage.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "libtex/error.hpp"
#include "libtex/parallel.hpp"

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

PixelGrid PixelGrid::Of(const BBox& window, double pixel, const char* what) {
    if (!(pixel > 0) || !std::isfinite(pixel)) {
        std::ostringstream m;
        m << "pixel size " << pixel << " is not a positive number";
        throw Error(what, m.str());
    }
    if (window.empty() || !(window.width() > 0) || !(window.height() > 0) || !std::isfinite(window.width()) ||
        !std::isfinite(window.height()))
        throw Error(what, "the window is empty");
    const double w = std::max(1.0, std::ceil(window.width() / pixel)),
                 h = std::max(1.0, std::ceil(window.height() / pixel));
    if (w * h > 1.0e9) throw Error(what, "more than 1e9 pixels");
    PixelGrid g;
    g.window = window;
    g.pixel = pixel;
    g.width = int(w);
    g.height = int(h);
    return g;
}

StrokeCoverage::StrokeCoverage(const PixelGrid& grid, double width)
    : g_(grid), half_(width / 2), reach_(half_ + grid.pixel),
      bands_(std::size_t((grid.height + kBandRows - 1) / kBandRows)) {
    if (!(width > 0) || !std::isfinite(width)) {
        std::ostringstream m;
        m << "line width " << width << " is not a positive number";
        throw Error("StrokeCoverage", m.str());
    }
}

void StrokeCoverage::AddSegment(const Point& a, const Point& b) {
    const int nb = int(bands_.size());
    const double r0 = (g_.window.ymax - (std::max(a.y, b.y) + reach_)) / g_.pixel;
    const double r1 = (g_.window.ymax - (std::min(a.y, b.y) - reach_)) / g_.pixel;
    if (!(r1 >= 0) || !(r0 < g_.height)) return;  // above or below the window (or NaN)
    const int b0 = std::max(0, int(std::floor(r0)) / kBandRows);
    const int b1 = std::min(nb - 1, int(std::floor(std::min(r1, double(g_.height)))) / kBandRows);
    for (int band = b0; band <= b1; ++band) bands_[std::size_t(band)].push_back({a, b});
}

void StrokeCoverage::Add(const std::vector<Point>& points, bool closed) {
    const std::size_t n = points.size();
    const std::size_t segs = closed && n > 2 ? n : (n ? n - 1 : 0);
    for (std::size_t k = 0; k < segs; ++k) AddSegment(points[k], points[(k + 1) % n]);
}

void StrokeCoverage::Render(std::vector<float>& cover) const {
    if (cover.size() != g_.Size()) throw Error("StrokeCoverage", "the coverage raster does not match the grid");
    const PixelGrid& g = g_;
    parallel_for(bands_.size(), [&](std::size_t band) {
        const int row0 = int(band) * kBandRows, row1 = std::min(g.height, row0 + kBandRows);
        for (const Seg& s : bands_[band]) {
            const int c0 = std::max(0, int(std::floor((std::min(s.a.x, s.b.x) - reach_ - g.window.xmin) / g.pixel)));
            const int c1 = std::min(g.width - 1,
                                    int(std::floor((std::max(s.a.x, s.b.x) + reach_ - g.window.xmin) / g.pixel)));
            const int r0 = std::max(row0, int(std::floor((g.window.ymax - std::max(s.a.y, s.b.y) - reach_) / g.pixel)));
            const int r1 = std::min(row1 - 1, int(std::floor((g.window.ymax - std::min(s.a.y, s.b.y) + reach_) / g.pixel)));
            for (int r = r0; r <= r1; ++r)
                for (int c = c0; c <= c1; ++c) {
                    // 1 within the line, falling to 0 over one pixel at its edge.
                    const double v =
                        std::clamp((half_ - segment_distance(g.Centre(c, r), s.a, s.b)) / g.pixel + 0.5, 0.0, 1.0);
                    float& px = cover[std::size_t(r) * std::size_t(g.width) + std::size_t(c)];
                    px = std::max(px, float(v));
                }
        }
    });
}

void CoverFill(const PixelGrid& g, const std::vector<std::vector<Point>>& rings, std::vector<float>& cover) {
    if (cover.size() != g.Size()) throw Error("CoverFill", "the coverage raster does not match the grid");
    BBox box;
    for (const auto& ring : rings)
        for (const Point& q : ring) box.add(q);
    if (box.empty()) return;
    const int r0 = std::max(0, int(std::floor((g.window.ymax - box.ymax) / g.pixel)));
    const int r1 = std::min(g.height - 1, int(std::ceil((g.window.ymax - box.ymin) / g.pixel)));
    std::vector<double> xs;
    for (int r = r0; r <= r1; ++r) {
        const double y = g.window.ymax - (r + 0.5) * g.pixel;
        xs.clear();
        for (const auto& ring : rings)
            for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
                const Point &p = ring[i], &q = ring[j];
                if ((p.y > y) != (q.y > y)) xs.push_back(p.x + (y - p.y) * (q.x - p.x) / (q.y - p.y));
            }
        std::sort(xs.begin(), xs.end());
        for (std::size_t k = 0; k + 1 < xs.size(); k += 2) {
            const int c0 = std::max(0, int(std::ceil((xs[k] - g.window.xmin) / g.pixel - 0.5)));
            const int c1 = std::min(g.width - 1, int(std::floor((xs[k + 1] - g.window.xmin) / g.pixel - 0.5)));
            for (int c = c0; c <= c1; ++c) cover[std::size_t(r) * std::size_t(g.width) + std::size_t(c)] = 1.0f;
        }
    }
}

}  // namespace tex
