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

// The rock style reads more than a face's border: cliff tops from the slope field on a global
// lattice, and the faces across the border (which keep strokes from being drawn back there).
TEST(Tiles, TheRockStyleTiledIsTheWholeRunBitForBit) {
    TempDir dir;
    Options o = sample_options();
    o.style = "rock";
    const Drawing whole = hatch(prepare(o), o);
    const Features expected = features(whole);
    std::size_t cliff_strokes = 0;
    for (const auto& f : whole.faces)
        for (const auto& h : f.hatches) cliff_strokes += h.family == Family::Ridge;
    ASSERT_GT(cliff_strokes, 500u);
    std::vector<std::string> parts;
    const auto tiles = tile_grid(raster_info(o.dem, "--dem"), 450);
    for (std::size_t i = 0; i < tiles.size(); ++i) {
        parts.push_back(dir / ("rock" + std::to_string(i) + ".gpkg"));
        run_tile(o, tiles[i], parts.back());
    }
    const std::string merged = dir / "rock.gpkg";
    EXPECT_EQ(merge_gpkg(parts, merged), expected.size());
    EXPECT_TRUE(features(read_gpkg(merged, o.scale)) == expected);
}

TEST(Tiles, ATileReadsOnlyTheDemNearItsFaces) {
    TempDir dir;
    Options o = sample_options();
    o.relief_radius = 100;  // a small relief window: the halo is the style's reach (rock's
                            // structure lines, traced 4.6 mm around each face), 33 cells
    const RasterInfo info = raster_info(o.dem, "--dem");
    const auto tiles = tile_grid(info, 800);
    const RasterInfo grid = working_grid(info).grid;
    const double cell = std::min(std::abs(grid.gt[1]), std::abs(grid.gt[5]));
    const Plan plan = make_plan(o, PlanFor::Drawing);
    const double margin = tile_context_margin(plan, cell);
    const int halo = tile_halo_cells(plan, cell);
    EXPECT_EQ(halo, 33);
    ASSERT_FALSE(plan.crest_band);  // no crest ornaments: the context is the faces' margin alone
    const Partition whole = load_partition(o.partition, grid.crs_wkt);
    const double snap = o.partition.snap;
    // The cells under the whole partition with the same halo: what a tile that read every
    // face would read.
    auto cells_of = [&](const tex::BBox& b) {
        const double w = std::ceil(b.width() / cell) + 1 + 2 * halo, h = std::ceil(b.height() / cell) + 1 + 2 * halo;
        return (long long)(std::min(w, double(grid.width)) * std::min(h, double(grid.height)));
    };
    const long long under_all = cells_of(whole.bounds());
    // Each tile reads the DEM under the box of its own faces grown by the context margin (the
    // faces meeting it, read whole) and the halo, no more: the box of the faces whose box
    // meets the owned faces' box grown by the margin, plus one cell for the rounding out to
    // whole cells and the halo on each side. The faces are taken from the whole partition, whose borders are snapped among
    // more neighbours than a tile's: a snap of slack on each box. A tile that owns no face
    // reads no DEM at all.
    auto check = [&](std::size_t i) {
        tex::BBox own;
        for (const RockFace& f : whole.faces)
            if (owns(tiles[i], face_anchor(f))) own.add(f.region.bbox());
        const long long cells = run_tile(o, tiles[i], dir / ("t" + std::to_string(i) + ".gpkg")).dem_cells;
        if (own.empty()) {
            EXPECT_EQ(cells, 0) << "tile " << i;
            return cells;
        }
        const tex::BBox reach = own.expanded(margin + 2 * snap);
        tex::BBox context;
        for (const RockFace& f : whole.faces)
            if (f.region.bbox().intersects(reach)) context.add(f.region.bbox());
        EXPECT_GT(cells, 0) << "tile " << i;
        EXPECT_LE(cells, cells_of(context.expanded(snap))) << "tile " << i;
        return cells;
    };
    // The centre tile, whose faces' neighbourhood is nearly all of the sample's faces (it
    // reads 191,844 cells of the 192,721 under the partition, within its bound); a corner tile
    // with faces, whose neighbourhood is a corner of the partition (80,512 cells); a corner
    // tile without a face.
    EXPECT_LT(check(4), (long long)info.width * info.height);
    EXPECT_LT(check(2), under_all / 2);
    EXPECT_EQ(check(0), 0);
}

TEST(Tiles, RefusesWhatATiledRunCannotDoExactly) {
    TempDir dir;
    Options o = sample_options();
    const auto tiles = tile_grid(raster_info(o.dem, "--dem"), 1000);
    // The code and a piece of the message of the error run_tile throws (Failure and the
    // message "accepted" when it throws none), so each refusal is the one meant.
    auto refusal = [&](const Options& opt, const std::string& out) -> std::pair<Code, std::string> {
        try {
            run_tile(opt, tiles[0], out);
        } catch (const Error& e) {
            return {e.code(), e.what()};
        }
        return {Code::Failure, "accepted"};
    };
    // --partition auto: the partition is extracted tile by tile first, not by a hatching tile.
    o.partition.path = "auto";
    auto [code, what] = refusal(o, dir / "a.gpkg");
    EXPECT_EQ(code, Code::Usage) << what;
    EXPECT_NE(what.find("--partition auto"), std::string::npos) << what;
    EXPECT_FALSE(fs::exists(dir / "a.gpkg"));
    o = sample_options();
    // A tile file that exists is a finished tile: not written over.
    run_tile(o, tiles[0], dir / "b.gpkg");
    const auto size = fs::file_size(dir / "b.gpkg");
    std::tie(code, what) = refusal(o, dir / "b.gpkg");
    EXPECT_EQ(code, Code::OutputExists) << what;
    EXPECT_NE(what.find("b.gpkg"), std::string::npos) << what;
    EXPECT_NE(what.find("exists"), std::string::npos) << what;
    EXPECT_EQ(fs::file_size(dir / "b.gpkg"), size);
}

namespace {

// A long slope falling to the south, 4 km x 1 km at 5 m, with shallow ribs, and small
// square rock faces in a row along its top: a DEM much wider than a terrain style's reach,
// whose faces are small, so that tiles read windows of it.
void write_long_slope(const std::string& dem_path, const std::string& faces_path) {
    constexpr double x0 = 900000, y0 = 6500000, w = 4000, h = 1000, cell = 5;
    Raster r;
    r.width = int(w / cell), r.height = int(h / cell);
    r.gt = {x0, cell, 0, y0 + h, 0, -cell};
    r.crs_wkt = epsg_wkt(2154);
    r.data.resize(std::size_t(r.width) * r.height);
    for (int row = 0; row < r.height; ++row)
        for (int col = 0; col < r.width; ++col) {
            const Point q = r.to_world(col + 0.5, row + 0.5);
            const double u = q.x - x0, v = q.y - y0;
            r.at(col, row) = float(1500 + 0.6 * v + 12 * std::sin(u / 90) + 0.05 * u);
        }
    write_geotiff(r, dem_path);
    Partition p;
    p.crs_wkt = r.crs_wkt;
    for (int k = 0; k < 8; ++k) {
        RockFace f;
        f.id = k + 1;
        const double a = x0 + 150 + 500 * k, b = y0 + 760;
        f.region = tex::Region::rectangle(a, b, a + 130, b + 110);
        const auto& ring = f.region.outer();
        for (std::size_t i = 0; i < ring.size(); ++i) f.boundary.push_back({ring[i], ring[(i + 1) % ring.size()]});
        f.orientation = M_PI / 2;
        f.density = 0.5;
        p.faces.push_back(std::move(f));
    }
    write_partition_gpkg(p, faces_path, true, nullptr, true);
}

// The terrain elements of a drawing, sorted (tiles write them tile by tile).
std::vector<std::vector<Point>> terrain_elements(const Drawing& d) {
    std::vector<std::vector<Point>> out;
    for (const auto& f : d.faces)
        if (f.face_id == kTerrainFaceId)
            for (const auto& h : f.hatches) out.push_back(h.points);
    auto less = [](const std::vector<Point>& a, const std::vector<Point>& b) {
        return std::lexicographical_compare(a.begin(), a.end(), b.begin(), b.end(), [](const Point& p, const Point& q) {
            return std::tie(p.x, p.y) < std::tie(q.x, q.y);
        });
    };
    std::sort(out.begin(), out.end(), less);
    return out;
}

}  // namespace

TEST(Tiles, TerrainStylesTiledAreTheWholeRunBitForBit) {
    // Each tile draws the terrain elements of the style's grid tiles whose centre it holds,
    // after those they depend on, from a window of the DEM and the faces within the style's
    // reach: the merged tiles hold the whole run's elements, bit for bit, and its hatches.
    TempDir dir;
    write_long_slope(dir / "slope.tif", dir / "faces.gpkg");
    std::vector<std::pair<std::string, std::map<std::string, double>>> cases{{"scree", {}},
                                                                            {"slope-hachures", {{"interval", 5}}}};
    for (const auto& [style, params] : cases) {
        Options o;
        o.dem = dir / "slope.tif";
        o.partition.path = dir / "faces.gpkg";
        o.style = style;
        o.params = params;
        o.threads = 2;
        o.relief_radius = 100;
        o.seed = 9;
        const Drawing whole = hatch(prepare(o), o);
        const auto expected = terrain_elements(whole);
        ASSERT_GT(expected.size(), 500u) << style;
        const RasterInfo info = raster_info(o.dem, "--dem");
        const auto tiles = tile_grid(info, 800);
        std::vector<std::string> parts;
        long long fewest = (long long)info.width * info.height;
        for (std::size_t i = 0; i < tiles.size(); ++i) {
            parts.push_back(dir / (style + std::to_string(i) + ".gpkg"));
            fewest = std::min(fewest, run_tile(o, tiles[i], parts.back()).dem_cells);
        }
        // The tiles read windows: the test sees the style's reach, not the whole DEM.
        EXPECT_LT(fewest, (long long)info.width * info.height * 7 / 10) << style;
        const std::string merged = dir / (style + "_merged.gpkg");
        merge_gpkg(parts, merged);
        const Drawing tiled = read_gpkg(merged, o.scale);
        const auto got = terrain_elements(tiled);
        EXPECT_EQ(got.size(), expected.size()) << style;
        EXPECT_TRUE(got == expected) << style << ": the tiles drew other terrain elements than the whole run";
        Drawing rock = whole;
        rock.faces.pop_back();  // the terrain entry
        Features rock_tiled = features(tiled);
        for (auto it = rock_tiled.begin(); it != rock_tiled.end();)
            it = std::get<0>(it->first) == kTerrainFaceId ? rock_tiled.erase(it) : std::next(it);
        EXPECT_TRUE(rock_tiled == features(rock)) << style;
    }
}

TEST(Tiles, ATerrainStyleInAWindowHasTheWholeRunsFrame) {
    // In the user's --window the whole run frames a terrain style by what it drew, not by the
    // DEM; so does each tile, and the merged tiles carry the whole run's frame, which the SVG
    // and PNG drawn from them use. (The tiles framed the whole DEM before.)
    TempDir dir;
    write_long_slope(dir / "slope.tif", dir / "faces.gpkg");
    Options o;
    o.dem = dir / "slope.tif";
    o.partition.path = dir / "faces.gpkg";
    o.style = "scree";
    o.threads = 2;
    o.relief_radius = 100;
    o.seed = 9;
    o.window = tex::BBox{901000, 6500300, 902600, 6501000};
    const Drawing whole = hatch(prepare(o), o);
    ASSERT_GT(terrain_elements(whole).size(), 100u);
    const RasterInfo info = raster_info(o.dem, "--dem");
    // Drawn elements only: well inside the DEM's extent.
    ASSERT_GT(whole.bounds.xmin, info.bounds().xmin + 500);
    ASSERT_LT(whole.bounds.xmax, info.bounds().xmax - 500);
    std::vector<std::string> parts;
    for (const auto& tile : tile_grid(info, 800)) {
        parts.push_back(dir / ("t" + std::to_string(parts.size()) + ".gpkg"));
        run_tile(o, tile, parts.back());
    }
    merge_gpkg(parts, dir / "merged.gpkg");
    const Drawing tiled = read_gpkg(dir / "merged.gpkg", o.scale);
    EXPECT_TRUE(terrain_elements(tiled) == terrain_elements(whole));
    EXPECT_EQ(tiled.bounds.xmin, whole.bounds.xmin);
    EXPECT_EQ(tiled.bounds.ymin, whole.bounds.ymin);
    EXPECT_EQ(tiled.bounds.xmax, whole.bounds.xmax);
    EXPECT_EQ(tiled.bounds.ymax, whole.bounds.ymax);
}
