// The partition extracted tile by tile (carto/tiles.hpp, extract_tile and
// merge_partition_tiles): a window of the DEM places its faces' points on the whole run's
// bits, and tiles with a long enough halo merge into the whole extraction, byte for byte.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "carto/error.hpp"
#include "carto/extract.hpp"
#include "carto/raster.hpp"
#include "carto/tiles.hpp"

#include "scratch.hpp"

using namespace carto;
namespace fs = std::filesystem;

namespace {

const std::string kDem = std::string(RH_SAMPLE_DIR) + "/dem.tif";

struct TempDir {
    fs::path path;
    TempDir() {
        path = rh_test::scratch_dir() / "extract_tiles";
        fs::remove_all(path);
        fs::create_directories(path);
    }
    ~TempDir() { fs::remove_all(path); }
    std::string operator/(const std::string& name) const { return (path / name).string(); }
};

std::string bytes_of(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

// The sample DEM on a grid whose origin and cell size are not round numbers, so that a point
// placed from a window's own origin, or a fraction added before the window's offset, rounds
// differently from the whole run (on the sample's round 5 m grid most of them happen not to).
std::string odd_grid_dem(const std::string& path) {
    Raster r = read_raster(kDem, "--dem");
    r.gt[0] += 0.123456789;
    r.gt[3] -= 0.987654321;
    r.gt[1] *= 1.0000001;
    r.gt[5] *= 1.0000001;
    write_geotiff(r, path);
    return path;
}

TEST(WindowExtraction, PlacesFacesOnTheWholeRunsBits) {
    TempDir tmp;
    const std::string dem = odd_grid_dem(tmp / "odd.tif");
    ExtractOptions o;
    o.dem = dem;
    const Partition whole = extract_partition(o).partition;
    // A window without the DEM's first 100 columns and rows: its cells are indexed from
    // (100, 100) of the whole raster, and its points must still be the whole run's, bit for
    // bit (a fraction of a cell added to a window coordinate rounds differently wherever the
    // shift carries a coordinate past a power of two, e.g. window column 200 + 0.37 against
    // whole-raster column 300 + 0.37).
    const RasterInfo info = raster_info(dem, "--dem");
    const double cell = info.gt[1];
    tex::BBox box = info.bounds();
    box.xmin += 100.5 * cell;
    box.ymax -= 100.5 * cell;
    o.raster = read_raster_window(dem, "--dem", box, 0);
    ASSERT_EQ(o.raster->col0, 100);
    ASSERT_EQ(o.raster->row0, 100);
    const Partition part = extract_partition(o).partition;
    // Every window face that is the whole run's face up to a micrometre (the flow, which is
    // not local, changes a few faces near the cut; those are not what this test is about) must
    // be it exactly.
    auto distance = [](const std::vector<Point>& a, const std::vector<Point>& b) {
        if (a.size() != b.size()) return HUGE_VAL;
        double d = 0;
        for (std::size_t k = 0; k < a.size(); ++k) d = std::max({d, std::abs(a[k].x - b[k].x), std::abs(a[k].y - b[k].y)});
        return d;
    };
    int close = 0, exact = 0;
    for (const RockFace& f : part.faces)
        for (const RockFace& w : whole.faces) {
            const double d = distance(w.region.outer(), f.region.outer());
            if (d > 1e-6) continue;
            ++close;
            bool same = d == 0 && w.region.holes().size() == f.region.holes().size();
            for (std::size_t h = 0; same && h < w.region.holes().size(); ++h)
                same = distance(w.region.holes()[h], f.region.holes()[h]) == 0;
            exact += same;
            EXPECT_TRUE(same) << "a face at " << f.region.bbox().xmin << ", " << f.region.bbox().ymin
                              << " is the whole run's within " << d << " m, not bit for bit";
        }
    EXPECT_GE(close, 8);
    EXPECT_EQ(exact, close);
}

TEST(ExtractTile, FourTilesMergeIntoTheWholeExtractionByteForByte) {
    TempDir tmp;
    ExtractOptions o;
    o.dem = kDem;
    // The whole extraction, written through the same merge (one part), so that both files
    // are written from faces in the same order.
    write_partition_gpkg(extract_partition(o).partition, tmp / "whole_raw.gpkg", false);
    ASSERT_EQ(merge_partition_tiles({tmp / "whole_raw.gpkg"}, tmp / "whole.gpkg", false).faces, 50u);

    const RasterInfo info = raster_info(kDem, "--dem");
    const std::vector<tex::BBox> grid = tile_grid(info, 1300);  // 2 x 2 tiles of the 2.4 km sample
    ASSERT_EQ(grid.size(), 4u);
    std::vector<std::string> parts;
    std::size_t owned = 0;
    for (std::size_t i = 0; i < grid.size(); ++i) {
        parts.push_back(tmp / ("part_" + std::to_string(i) + ".gpkg"));
        const ExtractTileReport r = extract_tile(o, grid[i], 1000, parts.back());
        EXPECT_GE(r.rounds, 1);
        owned += r.faces;
    }
    EXPECT_EQ(owned, 50u);  // every face once
    const PartitionMerge m = merge_partition_tiles(parts, tmp / "tiled.gpkg", false);
    EXPECT_EQ(m.faces, 50u);
    EXPECT_EQ(m.overlaps, 0u);  // the tiles agree: no face covers another tile's
    EXPECT_GT(m.area, 0.0);
    EXPECT_TRUE(bytes_of(tmp / "tiled.gpkg") == bytes_of(tmp / "whole.gpkg"))
        << "the merged tiles are not the whole extraction";
}

// A tile reads the DEM near itself only: on 600 m tiles with a 300 m halo (the 2.4 km sample
// in 4 x 4 tiles), a tile extracted in one window reads at most the cells of its box grown by
// the halo (plus a cell of rounding each side), far less than the whole DEM.
TEST(ExtractTile, ATileReadsTheDemWithinItsHaloOnly) {
    TempDir tmp;
    ExtractOptions o;
    o.dem = kDem;
    const RasterInfo info = raster_info(kDem, "--dem");
    const double cell = std::min(std::abs(info.gt[1]), std::abs(info.gt[5])), halo = 300;
    const std::vector<tex::BBox> grid = tile_grid(info, 600);
    ASSERT_EQ(grid.size(), 16u);
    const long long whole = (long long)info.width * info.height;
    int single = 0;
    for (std::size_t i = 0; i < grid.size(); ++i) {
        const ExtractTileReport r = extract_tile(o, grid[i], halo, tmp / ("t" + std::to_string(i) + ".gpkg"));
        if (r.rounds != 1) continue;  // a face reached the halo: the window grew to hold it
        ++single;
        const tex::BBox b = grid[i].intersection(info.bounds());
        const long long bound = (long long)(std::ceil((b.width() + 2 * halo) / cell) + 2) *
                                (long long)(std::ceil((b.height() + 2 * halo) / cell) + 2);
        EXPECT_LE(r.dem_cells, bound) << "tile " << i;
        EXPECT_LT(r.dem_cells, whole / 2) << "tile " << i;
    }
    EXPECT_GE(single, 3);  // (the sample's faces are large: most tiles own one that reaches the halo)
}

// With too short a halo the tiles place some faces differently: the merge counts the faces
// of different tiles that overlap (docs/tiles-partition.md: 1300 m tiles, 300 m halo, 0.003%
// of the sample's rock covered twice), which the tiled command reports as a warning.
TEST(ExtractTile, TheMergeCountsWhereTilesDisagree) {
    TempDir tmp;
    ExtractOptions o;
    o.dem = kDem;
    const std::vector<tex::BBox> grid = tile_grid(raster_info(kDem, "--dem"), 1300);
    std::vector<std::string> parts;
    for (std::size_t i = 0; i < grid.size(); ++i) {
        parts.push_back(tmp / ("short_" + std::to_string(i) + ".gpkg"));
        extract_tile(o, grid[i], 300, parts.back());
    }
    const PartitionMerge m = merge_partition_tiles(parts, tmp / "short.gpkg", false);
    EXPECT_GT(m.overlaps, 0u);
    EXPECT_GT(m.overlap_area, 0.0);
    EXPECT_LT(m.overlap_area, 0.01 * m.area);
}

TEST(ExtractTile, RefusesABadHaloAndAMask) {
    TempDir tmp;
    ExtractOptions o;
    o.dem = kDem;
    const tex::BBox tile = raster_info(kDem, "--dem").bounds();
    try {
        extract_tile(o, tile, -1, tmp / "t.gpkg");
        FAIL() << "a negative halo was accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), Code::Usage);
        EXPECT_NE(std::string(e.what()).find("--extract-halo"), std::string::npos);
    }
    o.mask = std::string(RH_SAMPLE_DIR) + "/partition.gpkg";
    EXPECT_THROW(extract_tile(o, tile, 100, tmp / "t.gpkg"), Error);
    EXPECT_FALSE(fs::exists(tmp / "t.gpkg"));
}
