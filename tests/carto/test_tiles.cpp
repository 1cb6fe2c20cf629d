// Tiled runs without Dask: a raster window samples the bits of the whole raster, every face
// has exactly one owner tile whatever the tiling, and the merged tiles are the whole run's
// hatches, feature for feature and bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <tuple>

#include "carto/error.hpp"
#include "carto/output.hpp"
#include "carto/pipeline.hpp"
#include "carto/raster.hpp"
#include "carto/tiles.hpp"
#include "libtex/random.hpp"

#include "scratch.hpp"

using namespace carto;
namespace fs = std::filesystem;

namespace {

const std::string kDem = std::string(RH_SAMPLE_DIR) + "/dem.tif";

Options sample_options() {
    Options o;
    o.dem = kDem;
    o.partition.path = std::string(RH_SAMPLE_DIR) + "/partition.gpkg";
    o.threads = 2;
    o.scale = 10000;
    return o;
}

struct TempDir {
    fs::path path;
    TempDir() {
        path = rh_test::scratch_dir() / "tiles";
        fs::remove_all(path);
        fs::create_directories(path);
    }
    ~TempDir() { fs::remove_all(path); }
    std::string operator/(const std::string& name) const { return (path / name).string(); }
};

// (face id, family, rank within its face and family) -> the points, as written.
using Features = std::map<std::tuple<std::int64_t, int, std::size_t>, std::vector<Point>>;
Features features(const Drawing& d) {
    Features out;
    for (const auto& f : d.faces) {
        std::map<int, std::size_t> rank;
        for (const auto& h : f.hatches) out[{f.face_id, int(h.family), rank[int(h.family)]++}] = h.points;
    }
    return out;
}

}  // namespace

TEST(RasterWindow, SamplesTheSameBitsAsTheWholeRaster) {
    const Raster whole = read_raster(kDem, "--dem");
    const tex::BBox b = whole.bounds();
    const tex::BBox box{b.xmin + 700.3, b.ymin + 410.7, b.xmin + 1333.1, b.ymin + 1250.9};
    const Raster win = read_raster_window(kDem, "--dem", box, 3);
    ASSERT_TRUE(win.grid_gt.has_value());
    EXPECT_GT(win.col0, 0);
    EXPECT_GT(win.row0, 0);
    EXPECT_LT(win.width, whole.width);
    // The window's cells are the whole raster's cells.
    for (int r = 0; r < win.height; ++r)
        for (int c = 0; c < win.width; ++c) {
            const float a = win.at(c, r), w = whole.at(c + win.col0, r + win.row0);
            ASSERT_TRUE(a == w || (std::isnan(a) && std::isnan(w)));
        }
    // Bilinear and nearest values anywhere in the box: the same bits.
    tex::KeyedRng rng(7);
    for (int i = 0; i < 20000; ++i) {
        const Point q{box.xmin + rng.uniform() * box.width(), box.ymin + rng.uniform() * box.height()};
        const double s1 = whole.sample(q), s2 = win.sample(q);
        ASSERT_TRUE(s1 == s2 || (std::isnan(s1) && std::isnan(s2))) << q.x << " " << q.y;
        ASSERT_EQ(std::isnan(whole.nearest(q)), std::isnan(win.nearest(q)));
        if (!std::isnan(whole.nearest(q))) ASSERT_EQ(whole.nearest(q), win.nearest(q));
    }
    // A box off the raster reads nothing.
    const Raster none = read_raster_window(kDem, "--dem", tex::BBox{b.xmax + 100, b.ymin, b.xmax + 200, b.ymax}, 2);
    EXPECT_EQ(none.width, 0);
}

TEST(Tiles, GridCoversTheDemAndThePlaneBeyond) {
    const RasterInfo info = raster_info(kDem, "--dem");
    const auto tiles = tile_grid(info, 1000);  // 2400 m: 3 x 3 tiles
    ASSERT_EQ(tiles.size(), 9u);
    // Any point, in the DEM or far outside it, lies in exactly one tile.
    tex::KeyedRng rng(3);
    const tex::BBox b = info.bounds();
    for (int i = 0; i < 5000; ++i) {
        const Point q{b.xmin - 5000 + rng.uniform() * (b.width() + 10000), b.ymin - 5000 + rng.uniform() * (b.height() + 10000)};
        int n = 0;
        for (const auto& t : tiles) n += owns(t, q);
        ASSERT_EQ(n, 1);
    }
    EXPECT_THROW(tile_grid(info, 0), Error);
    EXPECT_THROW(tile_grid(info, 1e-3), Error);  // billions of tiles
}

// The crest polygons of a drawing as written: (ridge id, rings) in a canonical order.
static std::vector<std::pair<std::int64_t, std::vector<std::vector<Point>>>> crest_polygons_written(const Drawing& d,
                                                                                           const std::string& path) {
    write_gpkg(d, path, false);
    std::vector<std::pair<std::int64_t, std::vector<std::vector<Point>>>> out;
    const Drawing back = read_gpkg(path, d.scale);
    for (const auto& c : *back.crests) out.push_back({c.id, c.rings});
    std::sort(out.begin(), out.end());
    return out;
}

TEST(Tiles, MergedTilesAreTheWholeRunBitForBit) {
    TempDir dir;
    Options o = sample_options();
    // With crest ornaments: each tile draws the ridges anchored in it, reading their neighbours.
    o.crest_ornament = kDefaultCrest;
    o.crest_height_mm = 3;
    const Prepared p = prepare(o);
    const Drawing whole = hatch(p, o);
    const Features expected = features(whole);
    const auto expected_crests = crest_polygons_written(whole, dir / "whole.gpkg");
    ASSERT_GE(expected_crests.size(), 5u);
    ASSERT_GT(expected.size(), 10000u);
    // Some faces are larger than the smaller tiles: they are still drawn once and whole.
    double widest = 0;
    for (const auto& f : p.partition.faces) widest = std::max(widest, std::max(f.region.bbox().width(), f.region.bbox().height()));
    EXPECT_GT(widest, 450.0);
    const RasterInfo info = raster_info(o.dem, "--dem");
    // Tiles smaller than the widest face (one size: the test runs under ASan in CI too).
    for (double size : {450.0}) {
        std::vector<std::string> parts;
        std::size_t owned = 0;
        const auto tiles = tile_grid(info, size);
        for (std::size_t i = 0; i < tiles.size(); ++i) {
            parts.push_back(dir / ("tile" + std::to_string(size) + "_" + std::to_string(i) + ".gpkg"));
            const TileReport r = run_tile(o, tiles[i], parts.back());
            owned += r.faces;
            EXPECT_LE(r.faces, r.context_faces);
        }
        // Every face drawn once: the faces of the tiles add up to the partition's.
        EXPECT_EQ(owned, p.partition.faces.size()) << "tile size " << size;
        const std::string merged = dir / ("merged" + std::to_string(size) + ".gpkg");
        EXPECT_EQ(merge_gpkg(parts, merged), expected.size());
        const Drawing tiled = read_gpkg(merged, o.scale);
        EXPECT_TRUE(features(tiled) == expected) << "tile size " << size;
        ASSERT_TRUE(tiled.crests);
        std::vector<std::pair<std::int64_t, std::vector<std::vector<Point>>>> got;
        for (const auto& c : *tiled.crests) got.push_back({c.id, c.rings});
        std::sort(got.begin(), got.end());
        EXPECT_TRUE(got == expected_crests) << "tile size " << size << ": " << got.size() << " crest polygons, "
                                            << expected_crests.size() << " in the whole run";
    }
}

TEST(Tiles, ATileReadsOnlyTheDemNearItsFaces) {
    TempDir dir;
    Options o = sample_options();
    o.relief_radius = 100;  // a small relief window: the halo is 24 cells
    const RasterInfo info = raster_info(o.dem, "--dem");
    const auto tiles = tile_grid(info, 800);
    long long most = 0;
    // The centre tile and a corner one (each reads its faces' neighbourhood and window).
    for (std::size_t i : {std::size_t(4), std::size_t(0)})
        most = std::max(most, run_tile(o, tiles[i], dir / ("t" + std::to_string(i) + ".gpkg")).dem_cells);
    EXPECT_GT(most, 0);
    EXPECT_LT(most, (long long)info.width * info.height);
}

TEST(Tiles, RefusesWhatATiledRunCannotDoExactly) {
    TempDir dir;
    Options o = sample_options();
    const auto tiles = tile_grid(raster_info(o.dem, "--dem"), 1000);
    o.partition.path = "auto";
    EXPECT_THROW(run_tile(o, tiles[0], dir / "a.gpkg"), Error);
    o = sample_options();
    // A tile file that exists is a finished tile: not written over.
    run_tile(o, tiles[0], dir / "b.gpkg");
    EXPECT_THROW(run_tile(o, tiles[0], dir / "b.gpkg"), Error);
}
