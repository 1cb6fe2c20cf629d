// Rasters: bilinear sampling, NoData, reading errors, reprojection.
#include <gtest/gtest.h>

#include <GeographicLib/UTMUPS.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>

#include "carto/error.hpp"
#include "carto/control_fields.hpp"
#include "carto/raster.hpp"
#include "carto/terrain.hpp"
#include "libtex/parallel.hpp"

#include "scratch.hpp"

using namespace carto;

namespace {

Raster plane(int w, int h, double cell, double a, double b, double c) {
    Raster r;
    r.width = w;
    r.height = h;
    r.gt = {1000, cell, 0, 2000, 0, -cell};
    r.crs_wkt = epsg_wkt(2154);
    r.data.resize(std::size_t(w) * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const Point p = r.to_world(x + 0.5, y + 0.5);
            r.at(x, y) = float(a * (p.x - 1000) + b * (p.y - 2000) + c);
        }
    return r;
}

std::string tmp(const std::string& name) {
    return rh_test::scratch(name);
}

}  // namespace

TEST(Raster, BilinearReproducesAPlane) {
    const Raster r = plane(20, 10, 5, 0.5, -0.25, 100);
    for (double x : {1003.0, 1017.3, 1050.0, 1093.1})
        for (double y : {1953.0, 1971.7, 1990.0}) {
            const double expected = 0.5 * (x - 1000) - 0.25 * (y - 2000) + 100;
            EXPECT_NEAR(r.sample({x, y}), expected, 1e-4) << x << "," << y;
        }
    EXPECT_TRUE(std::isnan(r.sample({999, 1990})));
    EXPECT_TRUE(std::isnan(r.sample({1050, 2001})));
}

TEST(Raster, NoDataIsLeftOutOfTheInterpolation) {
    Raster r = plane(4, 4, 10, 0, 0, 7);
    r.at(1, 1) = NAN;
    const double v = r.sample(r.to_world(1.6, 1.6));
    EXPECT_NEAR(v, 7, 1e-9);  // the three valid neighbours, renormalised
    r.at(2, 1) = r.at(1, 2) = r.at(2, 2) = NAN;
    EXPECT_TRUE(std::isnan(r.sample(r.to_world(2.0, 2.0))));
    const auto [lo, hi] = r.min_max();
    EXPECT_EQ(lo, 7);
    EXPECT_EQ(hi, 7);
}

namespace {

// Raster::sample as it was before it moved to libtex (north-up), to pin its results.
double former_sample(const Raster& r, const Point& w) {
    const Point p{(w.x - r.gt[0]) / r.gt[1], (w.y - r.gt[3]) / r.gt[5]};
    const double fx = p.x - 0.5, fy = p.y - 0.5;
    if (!(p.x >= 0 && p.y >= 0 && p.x <= r.width && p.y <= r.height)) return std::nan("");
    const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
    const double tx = fx - x0, ty = fy - y0;
    double sum = 0, wsum = 0;
    for (int dy = 0; dy <= 1; ++dy)
        for (int dx = 0; dx <= 1; ++dx) {
            const float v = r.at(std::clamp(x0 + dx, 0, r.width - 1), std::clamp(y0 + dy, 0, r.height - 1));
            if (std::isnan(v)) continue;
            const double wgt = (dx ? tx : 1 - tx) * (dy ? ty : 1 - ty);
            sum += wgt * v;
            wsum += wgt;
        }
    if (wsum <= 1e-12) {
        const int c = int(std::floor(p.x)), row = int(std::floor(p.y));
        if (c < 0 || row < 0 || c >= r.width || row >= r.height) return std::nan("");
        return r.at(c, row);
    }
    return sum / wsum;
}

bool same_bits(double a, double b) {
    if (std::isnan(a) && std::isnan(b)) return true;
    return std::memcmp(&a, &b, sizeof a) == 0;
}

}  // namespace

TEST(Raster, SamplingIsLibtexGridSamplingBitForBit) {
    Raster r = plane(17, 11, 3.7, 0.31, -0.17, 50);
    for (int i = 0; i < 187; i += 7) r.data[std::size_t(i)] = NAN;  // scattered NoData
    for (int x = 0; x < 4; ++x)
        for (int y = 0; y < 3; ++y) r.at(x, y) = NAN;  // a NoData block
    tex::GridSamples g{r.width, r.height, r.gt, std::make_shared<const std::vector<float>>(r.data)};
    const tex::Field grid = tex::GridField(g);
    const Field field = raster_field(r);
    std::mt19937 rng(5);
    const BBox b = r.bounds().expanded(2);
    std::uniform_real_distribution<double> ux(b.xmin, b.xmax), uy(b.ymin, b.ymax);
    int nan = 0;
    for (int i = 0; i < 20000; ++i) {
        const Point q{ux(rng), uy(rng)};
        const double want = former_sample(r, q);
        nan += std::isnan(want);
        ASSERT_TRUE(same_bits(r.sample(q), want)) << q.x << " " << q.y;
        ASSERT_TRUE(same_bits(grid(q), want)) << q.x << " " << q.y;
        ASSERT_TRUE(same_bits(field(q), want)) << q.x << " " << q.y;
    }
    EXPECT_GT(nan, 100);  // outside and inside the NoData block
    EXPECT_LT(nan, 10000);
    EXPECT_STREQ(field.kind(), "raster");
    // Offset and range as before: (value - offset) / range.
    const Point q = r.to_world(5.2, 6.9);
    EXPECT_TRUE(same_bits(raster_field(r, 3, 7)(q), (former_sample(r, q) - 3) / 7));
}

TEST(Raster, WriteReadRoundTripKeepsNoDataAndCrs) {
    Raster r = plane(8, 6, 2, 1, 1, 0);
    r.at(3, 2) = NAN;
    const std::string path = tmp("roundtrip.tif");
    write_geotiff(r, path);
    const Raster back = read_raster(path, "--dem");
    EXPECT_EQ(back.width, 8);
    EXPECT_EQ(back.height, 6);
    EXPECT_TRUE(std::isnan(back.at(3, 2)));
    EXPECT_FLOAT_EQ(back.at(4, 2), r.at(4, 2));
    EXPECT_EQ(crs_name(back.crs_wkt), "EPSG:2154");
    std::filesystem::remove(path);
}

TEST(Raster, ReadErrorsNameTheInput) {
    try {
        read_raster("/nonexistent/dem.tif", "--dem");
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), Code::InputMissing);
        EXPECT_NE(std::string(e.what()).find("--dem '/nonexistent/dem.tif'"), std::string::npos);
    }
    Raster r = plane(4, 4, 1, 0, 0, 1);
    r.crs_wkt.clear();
    const std::string path = tmp("nocrs.tif");
    write_geotiff(r, path);
    try {
        read_raster(path, "--slope");
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), Code::NoCrs);
        EXPECT_NE(std::string(e.what()).find("no CRS"), std::string::npos);
    }
    std::filesystem::remove(path);
}

TEST(Raster, GeographicRastersWarpToUtm) {
    Raster g;
    g.width = 30;
    g.height = 20;
    g.gt = {6.90, 1.0 / 3600, 0, 45.95, 0, -1.0 / 3600};
    g.crs_wkt = epsg_wkt(4326);
    // A plane: 10 per column eastwards, 1 per row southwards (bilinear warps keep it).
    g.data.resize(600);
    for (int r = 0; r < 20; ++r)
        for (int c = 0; c < 30; ++c) g.at(c, r) = float(1000 + 10 * c + r);
    EXPECT_TRUE(is_geographic(g.crs_wkt));
    EXPECT_EQ(utm_epsg(6.9, 45.9), 32632);
    EXPECT_EQ(utm_epsg(-3.0, -10.0), 32730);
    std::string note;
    const Raster u = to_working_crs(g, &note);
    EXPECT_EQ(crs_name(u.crs_wkt), "EPSG:32632");
    EXPECT_NE(note.find("EPSG:32632"), std::string::npos) << note;
    // Square cells of one arc-second north-south (30.92 m), on multiples of 2^-10 m.
    EXPECT_NEAR(u.cell_x(), 111320.0 / 3600, 1e-3);
    EXPECT_DOUBLE_EQ(u.cell_x(), u.cell_y());
    EXPECT_EQ(u.cell_x() * 1024, std::round(u.cell_x() * 1024));
    EXPECT_EQ(u.gt[0] * 1024, std::round(u.gt[0] * 1024));
    // So a cell centre is the same number from a window's origin as from the grid's (with the
    // unsnapped 30.92 m cell, thousands of these pairs differ in the last bit).
    int differ = 0;
    for (int c0 = 0; c0 < 200; ++c0)
        for (int c = 0; c < 200; ++c) {
            const double window_origin = u.gt[0] + c0 * u.gt[1];
            differ += window_origin + (c + 0.5) * u.gt[1] != u.gt[0] + (c0 + c + 0.5) * u.gt[1];
        }
    EXPECT_EQ(differ, 0);
    // 30 arc-seconds east-west at 45.9 N is about 645 m: 20 to 22 cells of 30.9 m.
    EXPECT_NEAR(u.width, 21, 1);
    // A known place lands where GeographicLib puts it, with its value: a shifted or mirrored
    // warp would be off by 10 per 30 m column.
    for (const auto& [lon, lat] : {std::pair{6.90 + 15.0 / 3600, 45.95 - 10.0 / 3600},
                                   std::pair{6.90 + 9.0 / 3600, 45.95 - 13.0 / 3600}}) {
        int zone = 0;
        bool north = true;
        double x = 0, y = 0;
        GeographicLib::UTMUPS::Forward(lat, lon, zone, north, x, y, 32);
        const double col = (lon - 6.90) * 3600 - 0.5, row = (45.95 - lat) * 3600 - 0.5;
        EXPECT_NEAR(u.sample({x, y}), 1000 + 10 * col + row, 0.5) << lon << " " << lat;
    }
}

namespace {

// A geographic DEM on file (1 arc-second, a rough surface and a hole of NoData), written as
// Int16 with a NoData value as DEMs come.
std::string geographic_dem_file(const std::string& name) {
    Raster g;
    g.width = 120;
    g.height = 90;
    g.gt = {6.85, 1.0 / 3600, 0, 45.93, 0, -1.0 / 3600};
    g.crs_wkt = epsg_wkt(4326);
    g.data.resize(std::size_t(g.width) * g.height);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> noise(-40, 40);
    for (int r = 0; r < g.height; ++r)
        for (int c = 0; c < g.width; ++c)
            g.at(c, r) = (c - 60) * (c - 60) + (r - 45) * (r - 45) < 40 ? NAN : std::round(1500 + 7 * c - 3 * r + noise(rng));
    const std::string path = tmp(name);
    write_geotiff(g, path, -32768);
    return path;
}

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

TEST(Raster, AWindowOfAReprojectedDemHoldsTheWholeGridsBits) {
    const std::string path = geographic_dem_file("geo_windows.tif");
    const WorkingGrid g = working_grid(raster_info(path, "--dem"));
    ASSERT_TRUE(g.reprojected());
    EXPECT_EQ(g.epsg, 32632);
    const Raster whole = read_working(path, "--dem", g);
    ASSERT_EQ(whole.width, g.grid.width);
    ASSERT_EQ(whole.height, g.grid.height);
    int nodata = 0;
    for (float v : whole.data) nodata += std::isnan(v);
    EXPECT_GT(nodata, 0);  // the hole and the corners outside the source
    // The in-memory path (bindings, a DEM handed over in memory) gives the same cells.
    const Raster mem = to_working_crs(read_raster(path, "--dem"));
    ASSERT_EQ(mem.data.size(), whole.data.size());
    for (std::size_t i = 0; i < mem.data.size(); ++i) ASSERT_TRUE(same_bits(mem.data[i], whole.data[i])) << i;
    // Windows of any size and place, with halos, alone, and with one or two threads: the
    // whole grid's bits at the same cells. (With GDAL's kernel ratio estimated per chunk,
    // XSCALE/YSCALE unset, the first window is off by 2.7 m.)
    std::mt19937 rng(3);
    const BBox b = g.grid.bounds();
    std::uniform_real_distribution<double> ux(b.xmin, b.xmax), uy(b.ymin, b.ymax);
    int compared = 0;
    for (int k = 0; k < 12; ++k) {
        const double x0 = ux(rng), y0 = uy(rng), x1 = ux(rng), y1 = uy(rng);
        const BBox box{std::min(x0, x1), std::min(y0, y1), std::max(x0, x1), std::max(y0, y1)};
        tex::ThreadsScope threads(1 + k % 2);
        const Raster w = read_working_window(path, "--dem", g, box, k % 4);
        ASSERT_GT(w.width, 0);
        for (int r = 0; r < w.height; ++r)
            for (int c = 0; c < w.width; ++c) {
                ASSERT_TRUE(same_bits(w.at(c, r), whole.at(c + w.col0, r + w.row0)))
                    << "window " << k << " cell " << c << "," << r << ": " << w.at(c, r) << " against "
                    << whole.at(c + w.col0, r + w.row0);
                ++compared;
            }
        // The window samples as the whole raster does, at any point inside it.
        const Point p = w.to_world(w.width / 2.0 + 0.3, w.height / 2.0 - 0.2);
        EXPECT_TRUE(std::isnan(w.sample(p)) ? std::isnan(whole.sample(p)) : w.sample(p) == whole.sample(p));
    }
    EXPECT_GT(compared, 1000);
    // A raster on another grid is not read through the DEM's reprojection.
    const std::string other = tmp("geo_other.tif");
    Raster o = read_raster(path, "--slope");
    o.gt[0] += 1.0 / 3600;
    write_geotiff(o, other);
    try {
        read_working_window(other, "--slope", g, b, 0);
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("not on the grid of the DEM"), std::string::npos) << e.what();
    }
    std::filesystem::remove(path);
    std::filesystem::remove(other);
}

TEST(Terrain, SlopeAspectRoughnessOfAPlane) {
    // z rises eastwards by 0.5 m per metre: 50% slope, downhill towards the west.
    const Terrain t = compute_terrain(plane(12, 12, 5, 0.5, 0, 2000));
    for (int y = 0; y < 12; ++y)
        for (int x = 0; x < 12; ++x) {
            EXPECT_NEAR(t.slope.at(x, y), 50.0, 1e-3);
            EXPECT_NEAR(std::abs(t.aspect.at(x, y)), M_PI, 1e-6);
            EXPECT_NEAR(t.roughness.at(x, y), 0.0, 1e-6);
        }
    // Hillshade: a west-facing slope is lit by the north-west light more than an east-facing one.
    const Terrain east = compute_terrain(plane(12, 12, 5, -0.5, 0, 2000));
    EXPECT_GT(t.hillshade.at(5, 5), east.hillshade.at(5, 5));
}

TEST(Terrain, NoDataStaysNoDataAndNeighboursStayFinite) {
    Raster dem = plane(9, 9, 5, 0.3, 0.2, 1000);
    dem.at(4, 4) = NAN;
    const Terrain t = compute_terrain(dem);
    EXPECT_TRUE(std::isnan(t.slope.at(4, 4)));
    EXPECT_TRUE(std::isnan(t.roughness.at(4, 4)));
    EXPECT_TRUE(std::isfinite(t.slope.at(3, 4)));
    EXPECT_TRUE(std::isfinite(t.hillshade.at(5, 5)));
}

TEST(Terrain, RoughnessGrowsWithDisorder) {
    // The same slope with the same pattern of bumps at growing amplitudes (0, 1, 2 and 4 m):
    // the mean roughness over the interior cells (away from the border, where the kernels
    // see fewer neighbours) is 0 on the bare plane and grows with the amplitude, staying
    // within 0..1 everywhere (measured means: 0, 0.0056, 0.021, 0.074).
    double previous = -1;
    for (double amplitude : {0.0, 1.0, 2.0, 4.0}) {
        Raster dem = plane(16, 16, 5, 0.5, 0, 1000);
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x) dem.at(x, y) += float(((x * 7 + y * 13) % 5) * amplitude);
        const Terrain t = compute_terrain(dem);
        double sum = 0;
        int n = 0;
        for (int y = 2; y < 14; ++y)
            for (int x = 2; x < 14; ++x) {
                const double r = t.roughness.at(x, y);
                ASSERT_GE(r, 0.0) << "amplitude " << amplitude << " at " << x << "," << y;
                ASSERT_LE(r, 1.0) << "amplitude " << amplitude << " at " << x << "," << y;
                sum += r;
                ++n;
            }
        const double mean = sum / n;
        if (amplitude == 0)
            EXPECT_NEAR(mean, 0.0, 1e-6);
        else
            EXPECT_GT(mean, previous + 0.001) << "amplitude " << amplitude;
        previous = mean;
    }
}
