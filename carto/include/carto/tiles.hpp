// A tiled run (rockhatch tiles): the area is cut into square tiles; each tile hatches the
// faces it owns, reading only the DEM and the partition near them, and writes its own
// GeoPackage; the tiles are merged at the end. The Python module rockhatch.tiles runs the
// tiles on a Dask cluster; this is the work of one tile, and the merge.
//
// Ownership: a face belongs to the tile whose half-open box holds its anchor (face_anchor,
// a point inside the face as read), a rule that does not depend on the tiling, so every
// face is drawn once, whole, by one tile, however large it is.
//
// Exactness: a tile reads the faces within a context margin of the faces it owns (their
// neighbours, whose labels and controls the style reads across the border) and the DEM cells
// under them plus a halo as wide as the relief window (Options::relief_radius) and the
// terrain kernels. Every field a style reads is then computed from the same cells, through
// the same pixel positions (Raster::grid_gt), as in a whole run: a tile's hatches are the
// whole run's hatches of its faces, bit for bit.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "carto/extract.hpp"
#include "carto/pipeline.hpp"
#include "carto/raster.hpp"

namespace carto {

// What one tile read and drew.
struct TileReport {
    std::size_t faces = 0;          // faces owned and hatched
    std::size_t context_faces = 0;  // faces read (owned ones and their neighbourhood)
    std::size_t hatches = 0;
    long long dem_cells = 0;        // DEM cells read (the window with its halo)
    double seconds = 0;
};

// The tiles of side `size` (ground units) covering the DEM, from its north-west corner, row
// by row from the north; their union covers the DEM's extent.
std::vector<tex::BBox> tile_grid(const RasterInfo& dem, double size);

// The margin (ground units) around the owned faces within which neighbouring faces are
// read, and the halo (DEM cells) around them: both from the options and the DEM's cell.
double tile_context_margin(const Plan& plan, double cell);
int tile_halo_cells(const Plan& plan, double cell);

// Refuses (Error Usage) a --slope or --roughness raster a tile cannot read as the whole run
// does: one on another grid than the DEM's and in another CRS than the one the DEM is worked
// in (the whole run warps that file whole first). One on another grid in the working CRS is
// resampled tile by tile at the DEM's cell centres, as the whole run resamples it.
void check_tiled_rasters(const Options& o);

// Hatches the faces owned by `tile` and writes them to the GeoPackage `out` (no spatial
// index; written to a temporary file and renamed, so a tile file that exists is complete).
// o.outputs are the final outputs of the run (checked against the inputs); `out` must not
// exist unless o.overwrite. --slope and --roughness rasters as check_tiled_rasters. Errors as
// carto::run.
TileReport run_tile(const Plan& plan, const tex::BBox& tile, const std::string& out);

// What a tile reads to draw the faces around a box as the whole run draws them: the faces
// of po (po.filter: the box grown by tile_context_margin), the DEM's cells under them and
// under `terrain` (a terrain style's reach) with tile_halo_cells more, their terrain, the
// --slope and --roughness cells alike, the relief and the faces' controls. run_tile and
// update (carto/update.hpp) read this way; *dem_cells: the DEM cells read.
Prepared prepare_around(const Plan& plan, const WorkingGrid& grid, const PartitionOptions& po,
                        const std::optional<tex::BBox>& terrain, long long* dem_cells = nullptr);
// Whether the --slope and --roughness of o (when given) can be read by windows (on the DEM's
// grid or in its working CRS), which check_tiled_rasters demands.
bool rasters_read_by_window(const Options& o, const WorkingGrid& grid);
// The same from the options: their plan, with the tile file checked as one more output.
TileReport run_tile(const Options& o, const tex::BBox& tile, const std::string& out);

// ---- `--partition auto`: the partition extracted tile by tile (docs/tiles-partition.md) ----
//
// A tile reads the DEM cells under its box plus `halo` ground units (GDAL windowed read,
// never the whole DEM), runs extract_partition on that window, and keeps the faces whose
// anchor lies in its box (the hatching tiles' rule) and the border lines of those faces. A
// kept face that comes within `halo` of the window's edge (where that edge is not the DEM's)
// may be cut or changed by what lies beyond, so the tile extracts again over a window that
// holds all such faces plus the halo, until none does: a face larger than a tile comes out
// once and whole, from the tile holding its anchor. The extraction places its points in the
// whole raster's pixel grid (extract/grid.hpp), and numbers faces by the whole raster's
// index of their first cell; the merge numbers them 1.. in that order, as a whole run does.
//
// Not exact in general: contributing areas and depression filling are not local, so a window
// can place a line or a face differently from the whole DEM when the halo is too short; the
// difference against the whole extraction is measured in docs/tiles-partition.md.
struct ExtractTileReport {
    std::size_t faces = 0;     // face polygons owned and written
    std::size_t lines = 0;     // border lines of those faces written
    long long dem_cells = 0;   // DEM cells of the last window read
    int rounds = 0;            // windows extracted (1 unless an owned face reached the halo)
    double seconds = 0;
};

// Extracts the faces owned by `tile` and writes them to the GeoPackage `out` (layers faces,
// lines and mask as write_partition_gpkg; `id` is the face's whole-raster first-cell index,
// written atomically, replacing `out`). The DEM (o.dem, a file) must be in a projected CRS.
ExtractTileReport extract_tile(const ExtractOptions& o, const tex::BBox& tile, double halo, const std::string& out);

// What a merge of partition tiles wrote, and where its tiles disagree.
struct PartitionMerge {
    std::size_t faces = 0;     // face polygons written
    // Pairs of faces from different tiles that overlap (by more than a millionth of the
    // smaller one: faces that only share a border do not count): where neighbouring tiles
    // placed a face differently (a halo too short for the basins there).
    std::size_t overlaps = 0;
    double overlap_area = 0;   // their common area (ground units squared)
    double area = 0;           // the area of all faces
};

// Merges partition tiles into one partition GeoPackage: faces in the order of their first
// cells, numbered from 1; border lines shared by two tiles written once. Counts the faces
// of different tiles that overlap (tiles that disagree).
PartitionMerge merge_partition_tiles(const std::vector<std::string>& parts, const std::string& out, bool overwrite);

}  // namespace carto
