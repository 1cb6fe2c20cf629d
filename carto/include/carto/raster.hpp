// Rasters read through GDAL, as float grids with NaN for NoData, a geotransform and a CRS.
#pragma once

#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "libtex/fields.hpp"
#include "libtex/geometry.hpp"

namespace carto {

using tex::BBox;
using tex::Point;

struct Raster {
    int width = 0, height = 0;
    std::array<double, 6> gt{0, 1, 0, 0, 0, -1};  // GDAL geotransform
    std::string crs_wkt;                          // empty: no CRS
    std::vector<float> data;                      // row-major, NaN = NoData
    // A window of a larger raster (read_raster_window): its first cell is cell (col0, row0)
    // of the raster whose geotransform is grid_gt. Points are located in that raster's pixel
    // grid and shifted by the (integer) offset, an exact step, so a window samples the same
    // bits as the whole raster does (a tiled run hatches exactly as a whole one).
    int col0 = 0, row0 = 0;
    std::optional<std::array<double, 6>> grid_gt;

    float at(int col, int row) const { return data[std::size_t(row) * width + col]; }
    float& at(int col, int row) { return data[std::size_t(row) * width + col]; }
    bool north_up() const { return gt[2] == 0 && gt[4] == 0; }
    double cell_x() const { return std::abs(gt[1]); }
    double cell_y() const { return std::abs(gt[5]); }
    // World coordinates of a pixel position (col, row in pixel units, 0.5 = centre).
    Point to_world(double col, double row) const {
        return {gt[0] + col * gt[1] + row * gt[2], gt[3] + col * gt[4] + row * gt[5]};
    }
    // World coordinates of a pixel position placed in the whole raster's grid (grid_gt) when
    // this is a window of one: the same number in a window as in the whole (to_world adds the
    // window's offset to its own origin, which may round differently).
    Point grid_world(double col, double row) const {
        if (!grid_gt) return to_world(col, row);
        const auto& g = *grid_gt;
        const double c = col + col0, r = row + row0;
        return {g[0] + c * g[1] + r * g[2], g[3] + c * g[4] + r * g[5]};
    }
    // A rotated geotransform is inverted.
    Point to_pixel(const Point& w) const {
        if (!grid_gt) return tex::grid_pixel(gt, w);
        const Point p = tex::grid_pixel(*grid_gt, w);
        return {p.x - col0, p.y - row0};
    }
    BBox bounds() const;
    // Bilinear interpolation at a world point over the four surrounding cell centres;
    // NoData neighbours are left out and the weights renormalised. NaN outside or when all
    // four are NoData.
    // Every field reading of the DEM and its rasters: inline.
    double sample(const Point& w) const { return tex::sample_grid_pixel(data.data(), width, height, to_pixel(w)); }
    // Value of the cell containing w (NaN outside).
    double nearest(const Point& w) const;
    // Minimum and maximum of the valid cells (NaN, NaN when none).
    std::pair<double, double> min_max() const;
};

// Reads band 1 of a raster. `what` names the input in error messages ("--dem").
Raster read_raster(const std::string& path, const std::string& what);

// A raster's grid and CRS, without its cells.
struct RasterInfo {
    int width = 0, height = 0;
    std::array<double, 6> gt{0, 1, 0, 0, 0, -1};
    std::string crs_wkt;
    BBox bounds() const;
};
RasterInfo raster_info(const std::string& path, const std::string& what);
// True when both have the same size, geotransform and CRS.
bool same_grid(const RasterInfo& a, const RasterInfo& b);
// Band 1 of the cells of a raster that a box (in its CRS) touches, grown by `halo` cells on
// every side and clipped to the raster: only those cells are read (a VRT mosaic reads only
// the files under the window). An empty window (the box misses the raster) has width 0.
Raster read_raster_window(const std::string& path, const std::string& what, const BBox& box, int halo);
// Writes a Float32 GeoTIFF (deflate), NaN written as NoData (-9999 unless given).
void write_geotiff(const Raster& r, const std::string& path, double nodata = -9999.0);
// True when the CRS is geographic (degrees).
bool is_geographic(const std::string& wkt);
// WKT of an EPSG code.
std::string epsg_wkt(int code);
// Short "AUTHORITY:CODE" name (e.g. EPSG:2154) when the CRS has one, else its name.
std::string crs_name(const std::string& wkt);
// True when both describe the same CRS.
bool same_crs(const std::string& a, const std::string& b);
// The UTM zone (WGS 84) containing a longitude/latitude, as an EPSG code (GeographicLib).
int utm_epsg(double lon, double lat);
// Reprojects a raster (bilinear, NoData kept) to a CRS, on the grid GDAL suggests.
Raster warp(const Raster& src, const std::string& dst_wkt);

// The grid a DEM is worked on: slopes need ground distances. A projected DEM is worked on its
// own grid. A geographic one is reprojected to the UTM zone of its centre (GeographicLib),
// with square cells of its north-south ground size, over the extent GDAL suggests, origin
// and cell on multiples of 2^-10 m; each cell is the bilinear interpolation of the DEM at
// the cell centre's exact position (PROJ per cell), NoData kept. A cell depends on the DEM
// and its position only, so a window of the grid, read alone, holds the bits the whole grid
// holds there (a tiled run equals a whole run on a geographic DEM too).
struct WorkingGrid {
    RasterInfo source;  // the DEM's own grid
    RasterInfo grid;    // the grid the terrain steps see (== source when not reprojected)
    int epsg = 0;       // the UTM zone's EPSG code when reprojected, else 0
    bool reprojected() const { return epsg != 0; }
    // "DEM in a geographic CRS: reprojected to EPSG:..." when reprojected, else "".
    std::string note() const;
};
WorkingGrid working_grid(const RasterInfo& dem);
// A raster on the DEM's own grid (the DEM, or a slope or roughness raster given with it), in
// the working grid: the cells a box (working CRS) touches grown by `halo` cells and clipped
// (read_raster_window when the grid is not reprojected; only the source cells under the
// window are read), or all of them.
Raster read_working_window(const std::string& path, const std::string& what, const WorkingGrid& g, const BBox& box,
                           int halo);
Raster read_working(const std::string& path, const std::string& what, const WorkingGrid& g);
// A DEM file read whole in its working grid; `note` (when given) gets WorkingGrid::note().
Raster read_working_dem(const std::string& path, const std::string& what, std::string* note = nullptr);
// An in-memory DEM in the working grid (the same cells as read_working of a file holding
// it); `note` (when given) says when it was reprojected.
Raster to_working_crs(Raster dem, std::string* note = nullptr);
// Resamples `src` onto the grid of `like` (same CRS assumed or reprojected): each cell the
// bilinear sample of `src` at its centre (placed in the whole grid when `like` is a window,
// so a window of `like` gets the whole result's cells from a window of `src` that holds the
// samples' neighbours).
Raster resample_like(const Raster& src, const Raster& like);

}  // namespace carto
