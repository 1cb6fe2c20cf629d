#include "carto/terrain.hpp"

#include <algorithm>
#include <cmath>

namespace carto {

Terrain compute_terrain(const Raster& dem) {
    Terrain t;
    t.elevation = dem;
    t.slope = t.aspect = t.roughness = t.hillshade = dem;
    const int w = dem.width, h = dem.height;
    const double dx = dem.cell_x(), dy = dem.cell_y();
    // Illumination from the north-west (azimuth 315, altitude 45), the map convention.
    const double az = (360.0 - 315.0 + 90.0) * M_PI / 180.0;  // as a math angle
    const double alt = 45.0 * M_PI / 180.0;
    const double lx = std::cos(alt) * std::cos(az), ly = std::cos(alt) * std::sin(az), lz = std::sin(alt);
    // Each cell's unit normal (NaN where the DEM has no value), for the roughness below. One
    // vector of triples: with three vectors GCC 12 warned of a free of a non-heap pointer
    // (-Wfree-nonheap-object, a false positive) when they were destroyed.
    struct Normal {
        float x = NAN, y = NAN, z = NAN;
    };
    std::vector<Normal> normal(dem.data.size());
    // A missing neighbour (raster edge or NoData) is extrapolated linearly through the
    // centre from the opposite neighbour (or, at a corner, from its two sides), so planes keep
    // their exact slope up to the edge; with nothing to extrapolate from it takes the centre's
    // value.
    auto valid = [&](int c, int r) { return c >= 0 && r >= 0 && c < w && r < h && !std::isnan(dem.at(c, r)); };
    auto z = [&](auto&& self, int c0, int r0, int dc, int dr) -> double {
        const double centre = dem.at(c0, r0);
        if (valid(c0 + dc, r0 + dr)) return dem.at(c0 + dc, r0 + dr);
        if (valid(c0 - dc, r0 - dr)) return 2 * centre - dem.at(c0 - dc, r0 - dr);
        // A corner: sum of the two steps when both exist (exact on planes).
        if (dc != 0 && dr != 0) return self(self, c0, r0, dc, 0) + self(self, c0, r0, 0, dr) - centre;
        return centre;
    };
    for (int r = 0; r < h; ++r)
        for (int c = 0; c < w; ++c) {
            const float z0 = dem.at(c, r);
            const std::size_t i = std::size_t(r) * w + c;
            if (std::isnan(z0)) {
                t.slope.data[i] = t.aspect.data[i] = t.hillshade.data[i] = NAN;
                continue;
            }
            auto zz = [&](int dc, int dr) { return z(z, c, r, dc, dr); };
            const double a = zz(-1, -1), b = zz(0, -1), cc = zz(1, -1);
            const double d = zz(-1, 0), f = zz(1, 0);
            const double g = zz(-1, 1), hh = zz(0, 1), ii = zz(1, 1);
            // Horn: east and north gradients (rows go south).
            const double dzdx = ((cc + 2 * f + ii) - (a + 2 * d + g)) / (8 * dx);
            const double dzdy = ((a + 2 * b + cc) - (g + 2 * hh + ii)) / (8 * dy);
            const double grad = std::hypot(dzdx, dzdy);
            t.slope.data[i] = float(100.0 * grad);
            t.aspect.data[i] = grad > 0 ? float(std::atan2(-dzdy, -dzdx)) : NAN;
            const double n = std::sqrt(dzdx * dzdx + dzdy * dzdy + 1);
            Normal& nm = normal[i];
            nm.x = float(-dzdx / n);
            nm.y = float(-dzdy / n);
            nm.z = float(1 / n);
            t.hillshade.data[i] = float(std::max(0.0, (nm.x * lx + nm.y * ly + nm.z * lz)));
        }
    // Vector ruggedness: 1 - |mean unit normal| over the 3x3 window (0 flat or planar, up to 1).
    for (int r = 0; r < h; ++r)
        for (int c = 0; c < w; ++c) {
            const std::size_t i = std::size_t(r) * w + c;
            if (std::isnan(normal[i].z)) {
                t.roughness.data[i] = NAN;
                continue;
            }
            double sx = 0, sy = 0, sz = 0;
            int n = 0;
            for (int rr = std::max(0, r - 1); rr <= std::min(h - 1, r + 1); ++rr)
                for (int cc = std::max(0, c - 1); cc <= std::min(w - 1, c + 1); ++cc) {
                    const std::size_t j = std::size_t(rr) * w + cc;
                    const Normal& nm = normal[j];
                    if (std::isnan(nm.z)) continue;
                    sx += nm.x;
                    sy += nm.y;
                    sz += nm.z;
                    ++n;
                }
            t.roughness.data[i] = float(1.0 - std::sqrt(sx * sx + sy * sy + sz * sz) / n);
        }
    return t;
}

}  // namespace carto
