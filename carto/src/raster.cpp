#include "carto/raster.hpp"
#include "libtex/parallel.hpp"

#include <GeographicLib/UTMUPS.hpp>
#include <gdal_priv.h>
#include <gdalwarper.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>

#include "carto/error.hpp"
#include "gdal_scope.hpp"
#include "libtex/fields.hpp"

namespace carto {
namespace {

const float kNaN = std::numeric_limits<float>::quiet_NaN();

// The terrain steps hold several float grids of the DEM's size at once: a raster beyond this
// would exhaust a workstation's memory, so it is refused up front (a larger area is run
// tiled, window by window).
constexpr double kMaxRasterCells = 1e8;

void check_size(double width, double height, const std::string& subject) {
    if (width * height <= kMaxRasterCells) return;
    char buf[160];
    std::snprintf(buf, sizeof buf, "%.0f x %.0f cells, more than the %.0e read at once (crop it, coarsen it or run tiled)",
                  width, height, kMaxRasterCells);
    throw Error(Code::InputMissing, subject + ": the raster is " + buf);
}

RasterInfo info_of(GDALDataset& ds, const std::string& what, const std::string& path) {
    RasterInfo r;
    r.width = ds.GetRasterXSize();
    r.height = ds.GetRasterYSize();
    if (ds.GetRasterCount() < 1 || r.width <= 0 || r.height <= 0)
        throw Error(Code::InputMissing, what + " '" + path + "': no raster band");
    if (ds.GetGeoTransform(r.gt.data()) != CE_None)
        throw Error(Code::NoCrs, what + " '" + path + "': no georeferencing (geotransform)");
    r.crs_wkt = wkt2_of(ds.GetSpatialRef());
    return r;
}

// The cells [col0, col0 + w) x [row0, row0 + h) of band 1 (the whole raster by default).
Raster from_dataset(GDALDataset& ds, const std::string& what, const std::string& path, int col0 = 0, int row0 = 0,
                    int w = -1, int h = -1) {
    const RasterInfo info = info_of(ds, what, path);
    Raster r;
    r.crs_wkt = info.crs_wkt;
    r.gt = info.gt;
    r.width = w < 0 ? info.width : w;
    r.height = h < 0 ? info.height : h;
    if (col0 != 0 || row0 != 0 || r.width != info.width || r.height != info.height) {
        r.col0 = col0;
        r.row0 = row0;
        r.grid_gt = info.gt;
        r.gt[0] = info.gt[0] + col0 * info.gt[1] + row0 * info.gt[2];
        r.gt[3] = info.gt[3] + col0 * info.gt[4] + row0 * info.gt[5];
    }
    check_size(r.width, r.height, what + " '" + path + "'");
    GDALRasterBand* band = ds.GetRasterBand(1);
    int has_nodata = 0;
    const double nodata = band->GetNoDataValue(&has_nodata);
    r.data.resize(std::size_t(r.width) * r.height);
    if (band->RasterIO(GF_Read, col0, row0, r.width, r.height, r.data.data(), r.width, r.height, GDT_Float32,
                       0, 0) != CE_None)
        throw Error(Code::InputMissing, what + " '" + path + "': cannot read the pixels (" +
                                            CPLGetLastErrorMsg() + ")");
    const float nd = float(nodata);
    for (float& v : r.data)
        if (!std::isfinite(v) || (has_nodata && (v == nd || (std::isnan(nd) && std::isnan(v))))) v = kNaN;
    return r;
}

}  // namespace

BBox Raster::bounds() const {
    BBox b;
    b.add(to_world(0, 0));
    b.add(to_world(width, 0));
    b.add(to_world(0, height));
    b.add(to_world(width, height));
    return b;
}

// One bilinear sampler for carto and libtex: tex::sample_grid on the raster's cells.
double Raster::nearest(const Point& w) const { return tex::nearest_grid_pixel(data.data(), width, height, to_pixel(w)); }

std::pair<double, double> Raster::min_max() const {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (float v : data)
        if (!std::isnan(v)) {
            lo = std::min(lo, double(v));
            hi = std::max(hi, double(v));
        }
    if (lo > hi) return {std::nan(""), std::nan("")};
    return {lo, hi};
}

namespace {

// Opens a raster for reading; throws naming `what` when it is missing or unreadable.
DatasetPtr open_raster(const std::string& path, const std::string& what) {
    register_gdal();
    if (!std::filesystem::exists(path)) throw Error(Code::InputMissing, what + " '" + path + "': no such file");
    QuietGdal quiet;
    DatasetPtr ds(GDALDataset::FromHandle(GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY,
                                                     nullptr, nullptr, nullptr)));
    if (!ds) throw Error(Code::InputMissing, what + " '" + path + "': not a raster GDAL can read");
    return ds;
}

// The grid of an open raster, which must have a CRS and no rotation.
RasterInfo checked_info(GDALDataset& ds, const std::string& what, const std::string& path) {
    RasterInfo r = info_of(ds, what, path);
    if (r.crs_wkt.empty()) throw Error(Code::NoCrs, what + " '" + path + "': the raster has no CRS");
    if (r.gt[2] != 0 || r.gt[4] != 0)
        throw Error(Code::BadLayer, what + " '" + path + "': rotated rasters are not supported");
    return r;
}

// The cells [col0, col1) x [row0, row1) of a grid that a box touches, grown by `halo` and
// clipped to the grid (empty when col1 <= col0 or row1 <= row0).
struct CellWindow {
    int col0 = 0, row0 = 0, col1 = 0, row1 = 0;
    bool empty() const { return col1 <= col0 || row1 <= row0; }
};
CellWindow cells_touched(const RasterInfo& info, const BBox& box, int halo) {
    const Point a = tex::grid_pixel(info.gt, {box.xmin, box.ymin}), b = tex::grid_pixel(info.gt, {box.xmax, box.ymax});
    const double c0 = std::floor(std::min(a.x, b.x)) - halo, c1 = std::ceil(std::max(a.x, b.x)) + halo;
    const double r0 = std::floor(std::min(a.y, b.y)) - halo, r1 = std::ceil(std::max(a.y, b.y)) + halo;
    CellWindow w;
    w.col0 = int(std::clamp(c0, 0.0, double(info.width)));
    w.col1 = int(std::clamp(c1, 0.0, double(info.width)));
    w.row0 = int(std::clamp(r0, 0.0, double(info.height)));
    w.row1 = int(std::clamp(r1, 0.0, double(info.height)));
    return w;
}

// A raster with no cells on a grid (a window that misses it).
Raster empty_on(const RasterInfo& info) {
    Raster empty;
    empty.gt = info.gt;
    empty.crs_wkt = info.crs_wkt;
    empty.grid_gt = info.gt;
    return empty;
}

}  // namespace

Raster read_raster(const std::string& path, const std::string& what) {
    DatasetPtr ds = open_raster(path, what);
    QuietGdal quiet;
    Raster r = from_dataset(*ds, what, path);
    if (r.crs_wkt.empty()) throw Error(Code::NoCrs, what + " '" + path + "': the raster has no CRS");
    if (!r.north_up())
        throw Error(Code::BadLayer, what + " '" + path + "': rotated rasters are not supported");
    return r;
}

BBox RasterInfo::bounds() const {
    Raster r;
    r.width = width;
    r.height = height;
    r.gt = gt;
    return r.bounds();
}

RasterInfo raster_info(const std::string& path, const std::string& what) {
    DatasetPtr ds = open_raster(path, what);
    QuietGdal quiet;
    return checked_info(*ds, what, path);
}

bool same_grid(const RasterInfo& a, const RasterInfo& b) {
    return a.width == b.width && a.height == b.height && a.gt == b.gt && same_crs(a.crs_wkt, b.crs_wkt);
}

Raster read_raster_window(const std::string& path, const std::string& what, const BBox& box, int halo) {
    DatasetPtr ds = open_raster(path, what);
    QuietGdal quiet;
    const RasterInfo info = checked_info(*ds, what, path);
    const CellWindow w = cells_touched(info, box, halo);
    if (w.empty()) return empty_on(info);
    return from_dataset(*ds, what, path, w.col0, w.row0, w.col1 - w.col0, w.row1 - w.row0);
}

void write_geotiff(const Raster& r, const std::string& path, double nodata) {
    register_gdal();
    QuietGdal quiet;
    GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("GTiff");
    const char* opts[] = {"COMPRESS=DEFLATE", "PREDICTOR=3", "TILED=YES", nullptr};
    const std::string tmp = path + ".tmp.tif";
    {
        DatasetPtr ds(drv->Create(tmp.c_str(), r.width, r.height, 1, GDT_Float32, const_cast<char**>(opts)));
        if (!ds) throw Error(Code::OutputExists, "'" + path + "': cannot create (" + CPLGetLastErrorMsg() + ")");
        ds->SetGeoTransform(const_cast<double*>(r.gt.data()));
        if (!r.crs_wkt.empty()) {
            OGRSpatialReference srs;
            srs.importFromWkt(r.crs_wkt.c_str());
            ds->SetSpatialRef(&srs);
        }
        std::vector<float> buf(r.data);
        for (float& v : buf)
            if (std::isnan(v)) v = float(nodata);
        GDALRasterBand* b = ds->GetRasterBand(1);
        b->SetNoDataValue(nodata);
        if (b->RasterIO(GF_Write, 0, 0, r.width, r.height, buf.data(), r.width, r.height, GDT_Float32, 0, 0) !=
            CE_None)
            throw Error(Code::OutputExists, "'" + path + "': write failed");
    }
    std::filesystem::rename(tmp, path);
}

bool is_geographic(const std::string& wkt) {
    OGRSpatialReference srs;
    if (srs.importFromWkt(wkt.c_str()) != OGRERR_NONE) return false;
    return srs.IsGeographic();
}

std::string epsg_wkt(int code) {
    OGRSpatialReference srs;
    if (srs.importFromEPSG(code) != OGRERR_NONE)
        throw Error(Code::NoCrs, "EPSG:" + std::to_string(code) + " is not a CRS PROJ knows");
    return wkt2_of(&srs);
}

std::string crs_name(const std::string& wkt) {
    OGRSpatialReference srs;
    if (srs.importFromWkt(wkt.c_str()) != OGRERR_NONE) return "unknown CRS";
    srs.AutoIdentifyEPSG();
    const char* auth = srs.GetAuthorityName(nullptr);
    const char* code = srs.GetAuthorityCode(nullptr);
    if (auth && code) return std::string(auth) + ":" + code;
    const char* name = srs.GetName();
    return name ? name : "unnamed CRS";
}

bool same_crs(const std::string& a, const std::string& b) {
    OGRSpatialReference sa, sb;
    if (sa.importFromWkt(a.c_str()) != OGRERR_NONE || sb.importFromWkt(b.c_str()) != OGRERR_NONE) return false;
    const char* opts[] = {"IGNORE_DATA_AXIS_TO_SRS_AXIS_MAPPING=YES", "CRITERION=EQUIVALENT_EXCEPT_AXIS_ORDER_GEOGCRS", nullptr};
    return sa.IsSame(&sb, opts);
}

int utm_epsg(double lon, double lat) {
    const int zone = GeographicLib::UTMUPS::StandardZone(lat, lon);
    if (zone == GeographicLib::UTMUPS::UPS)
        throw Error(Code::NoCrs, "the DEM lies in a polar region (UPS), give a projected DEM");
    return (lat >= 0 ? 32600 : 32700) + zone;
}

namespace {

// A georeferenced Float32 MEM dataset of a grid (without cells when `bands` is 0).
DatasetPtr mem_grid(int width, int height, int bands, const std::array<double, 6>& gt, const std::string& wkt) {
    GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
    DatasetPtr ds(mem->Create("", width, height, bands, GDT_Float32, nullptr));
    ds->SetGeoTransform(const_cast<double*>(gt.data()));
    OGRSpatialReference srs;
    srs.importFromWkt(wkt.c_str());
    ds->SetSpatialRef(&srs);
    return ds;
}

// A MEM copy of an in-memory raster (NaN as NoData), for GDAL's warper.
DatasetPtr mem_copy(const Raster& src) {
    DatasetPtr in = mem_grid(src.width, src.height, 1, src.gt, src.crs_wkt);
    GDALRasterBand* b = in->GetRasterBand(1);
    b->SetNoDataValue(std::nan(""));
    std::vector<float> buf(src.data);
    if (b->RasterIO(GF_Write, 0, 0, src.width, src.height, buf.data(), src.width, src.height, GDT_Float32, 0, 0) != CE_None)
        throw Error(Code::Failure, "cannot copy the raster for reprojection");
    return in;
}

}  // namespace

Raster warp(const Raster& src, const std::string& dst_wkt) {
    register_gdal();
    QuietGdal quiet;
    DatasetPtr in = mem_copy(src);
    GDALWarpOptions* wo = GDALCreateWarpOptions();
    wo->eResampleAlg = GRA_Bilinear;
    wo->papszWarpOptions = CSLSetNameValue(wo->papszWarpOptions, "INIT_DEST", "NO_DATA");
    // The run's thread count (tex::ThreadsScope): GDAL warps rows in parallel, each output
    // pixel computed alone, so the result does not depend on it.
    wo->papszWarpOptions =
        CSLSetNameValue(wo->papszWarpOptions, "NUM_THREADS", std::to_string(tex::GetThreads()).c_str());
    DatasetPtr vrt(GDALDataset::FromHandle(GDALAutoCreateWarpedVRTEx(
        GDALDataset::ToHandle(in.get()), src.crs_wkt.c_str(), dst_wkt.c_str(), GRA_Bilinear, 0.0, wo, nullptr)));
    GDALDestroyWarpOptions(wo);
    if (!vrt) throw Error(Code::NoCrs, std::string("cannot reproject the raster: ") + CPLGetLastErrorMsg());
    Raster out = from_dataset(*vrt, "warp", "");
    out.crs_wkt = dst_wkt;
    return out;
}

}  // namespace carto

namespace carto {

namespace {

// Working grids are laid on multiples of 2^-10 ground units: a cell centre computed from a
// window's origin, (x0 + c0 * cell) + (c + 0.5) * cell, is then the same double as from the
// grid's, x0 + (c0 + c + 0.5) * cell (every sum and product is exact), so a window warped
// alone samples the DEM at the very points the whole raster does.
constexpr double kGridStep = 1.0 / 1024;

double snap_down(double v) { return std::floor(v / kGridStep) * kGridStep; }
double snap_up(double v) { return std::ceil(v / kGridStep) * kGridStep; }

// Warps band 1 of `src` (on the grid g.source) onto the cells `w` of the working grid:
// bilinear over the 2 x 2 source cells around each cell centre's exact position (PROJ for
// every cell, no approximation; the kernel is not widened where the source is finer, so
// its weights do not depend on the window either), NoData kept. A cell's value depends on
// the source and its position only: windows give the whole raster's bits.
Raster warp_cells(GDALDataset& src, const WorkingGrid& g, const CellWindow& w, const std::string& what) {
    const double cell = g.grid.gt[1];
    const int width = w.col1 - w.col0, height = w.row1 - w.row0;
    check_size(width, height, what + " reprojected to UTM");
    const std::array<double, 6> gt{g.grid.gt[0] + w.col0 * cell, cell, 0, g.grid.gt[3] - w.row0 * cell, 0, -cell};
    DatasetPtr dst = mem_grid(width, height, 1, gt, g.grid.crs_wkt);
    GDALRasterBand* out = dst->GetRasterBand(1);
    out->SetNoDataValue(std::nan(""));

    char** topts = CSLSetNameValue(nullptr, "SRC_SRS", g.source.crs_wkt.c_str());
    topts = CSLSetNameValue(topts, "DST_SRS", g.grid.crs_wkt.c_str());
    void* transform = GDALCreateGenImgProjTransformer2(GDALDataset::ToHandle(&src), GDALDataset::ToHandle(dst.get()), topts);
    CSLDestroy(topts);
    if (!transform) throw Error(Code::NoCrs, what + ": cannot reproject to UTM (" + CPLGetLastErrorMsg() + ")");

    GDALRasterBand* in = src.GetRasterBand(1);
    int has_nodata = 0;
    double nodata = in->GetNoDataValue(&has_nodata);
    if (!has_nodata && GDALDataTypeIsFloating(in->GetRasterDataType())) {
        has_nodata = 1;
        nodata = std::nan("");
    }
    GDALWarpOptions* wo = GDALCreateWarpOptions();
    wo->hSrcDS = GDALDataset::ToHandle(&src);
    wo->hDstDS = GDALDataset::ToHandle(dst.get());
    wo->nBandCount = 1;
    wo->panSrcBands = static_cast<int*>(CPLMalloc(sizeof(int)));
    wo->panSrcBands[0] = 1;
    wo->panDstBands = static_cast<int*>(CPLMalloc(sizeof(int)));
    wo->panDstBands[0] = 1;
    wo->eResampleAlg = GRA_Bilinear;
    wo->eWorkingDataType = GDT_Float32;
    wo->pfnTransformer = GDALGenImgProjTransform;
    wo->pTransformerArg = transform;
    if (has_nodata) {
        wo->padfSrcNoDataReal = static_cast<double*>(CPLMalloc(sizeof(double)));
        wo->padfSrcNoDataReal[0] = nodata;
        wo->padfSrcNoDataImag = static_cast<double*>(CPLCalloc(1, sizeof(double)));
    }
    wo->padfDstNoDataReal = static_cast<double*>(CPLMalloc(sizeof(double)));
    wo->padfDstNoDataReal[0] = std::nan("");
    wo->padfDstNoDataImag = static_cast<double*>(CPLCalloc(1, sizeof(double)));
    wo->papszWarpOptions = CSLSetNameValue(wo->papszWarpOptions, "INIT_DEST", "NO_DATA");
    // GDAL widens the bilinear kernel by a ratio it estimates per chunk of work: fixed here.
    wo->papszWarpOptions = CSLSetNameValue(wo->papszWarpOptions, "XSCALE", "1");
    wo->papszWarpOptions = CSLSetNameValue(wo->papszWarpOptions, "YSCALE", "1");
    // The run's thread count (tex::ThreadsScope): rows are warped in parallel, each cell alone.
    wo->papszWarpOptions =
        CSLSetNameValue(wo->papszWarpOptions, "NUM_THREADS", std::to_string(tex::GetThreads()).c_str());
    CPLErr err;
    {
        GDALWarpOperation op;
        err = op.Initialize(wo);
        if (err == CE_None) err = op.ChunkAndWarpImage(0, 0, width, height);
    }
    GDALDestroyWarpOptions(wo);
    GDALDestroyGenImgProjTransformer(transform);
    if (err != CE_None) throw Error(Code::InputMissing, what + ": cannot reproject to UTM (" + CPLGetLastErrorMsg() + ")");

    Raster r;
    r.width = width;
    r.height = height;
    r.gt = gt;
    r.crs_wkt = g.grid.crs_wkt;
    if (width != g.grid.width || height != g.grid.height) {
        r.col0 = w.col0;
        r.row0 = w.row0;
        r.grid_gt = g.grid.gt;
    }
    r.data.resize(std::size_t(width) * height);
    if (out->RasterIO(GF_Read, 0, 0, width, height, r.data.data(), width, height, GDT_Float32, 0, 0) != CE_None)
        throw Error(Code::Failure, what + ": cannot read the reprojected cells");
    for (float& v : r.data)
        if (!std::isfinite(v)) v = kNaN;
    return r;
}

}  // namespace

WorkingGrid working_grid(const RasterInfo& dem) {
    WorkingGrid g;
    g.source = dem;
    g.grid = dem;
    if (!is_geographic(dem.crs_wkt)) return g;
    register_gdal();
    QuietGdal quiet;
    const BBox b = dem.bounds();
    g.epsg = utm_epsg(b.center().x, b.center().y);
    g.grid.crs_wkt = epsg_wkt(g.epsg);
    // Square cells of the north-south ground size of a source cell.
    const double cell = std::max(kGridStep, std::round(std::abs(dem.gt[5]) * 111320.0 / kGridStep) * kGridStep);
    // The extent GDAL suggests for the reprojection (the source's outline, transformed exactly).
    // (A dataset of the source grid without cells: GDAL needs one to suggest the extent.)
    DatasetPtr src = mem_grid(dem.width, dem.height, 0, dem.gt, dem.crs_wkt);
    void* transform = GDALCreateGenImgProjTransformer(GDALDataset::ToHandle(src.get()), dem.crs_wkt.c_str(), nullptr,
                                                      g.grid.crs_wkt.c_str(), FALSE, 0.0, 1);
    if (!transform) throw Error(Code::NoCrs, std::string("cannot reproject the DEM to UTM: ") + CPLGetLastErrorMsg());
    std::array<double, 6> suggested{};
    int w = 0, h = 0;
    const CPLErr err = GDALSuggestedWarpOutput(GDALDataset::ToHandle(src.get()), GDALGenImgProjTransform, transform,
                                               suggested.data(), &w, &h);
    GDALDestroyGenImgProjTransformer(transform);
    if (err != CE_None) throw Error(Code::NoCrs, std::string("cannot reproject the DEM to UTM: ") + CPLGetLastErrorMsg());
    Raster extent;
    extent.width = w;
    extent.height = h;
    extent.gt = suggested;
    const BBox e = extent.bounds();
    const double x0 = snap_down(e.xmin), y0 = snap_up(e.ymax);
    check_size(std::ceil((e.xmax - x0) / cell), std::ceil((y0 - e.ymin) / cell), "the DEM reprojected to UTM");
    g.grid.width = std::max(1, int(std::ceil((e.xmax - x0) / cell)));
    g.grid.height = std::max(1, int(std::ceil((y0 - e.ymin) / cell)));
    g.grid.gt = {x0, cell, 0, y0, 0, -cell};
    return g;
}

std::string WorkingGrid::note() const {
    if (!reprojected()) return "";
    return "DEM in a geographic CRS: reprojected to EPSG:" + std::to_string(epsg) + " (UTM, " +
           std::to_string(int(std::round(grid.gt[1]))) + " m cells)";
}

Raster read_working_window(const std::string& path, const std::string& what, const WorkingGrid& g, const BBox& box,
                           int halo) {
    if (!g.reprojected()) return read_raster_window(path, what, box, halo);
    DatasetPtr ds = open_raster(path, what);
    QuietGdal quiet;
    if (!same_grid(checked_info(*ds, what, path), g.source))
        throw Error(Code::Usage, what + " '" + path + "': not on the grid of the DEM");
    const CellWindow w = cells_touched(g.grid, box, halo);
    if (w.empty()) return empty_on(g.grid);
    return warp_cells(*ds, g, w, what + " '" + path + "'");
}

Raster read_working(const std::string& path, const std::string& what, const WorkingGrid& g) {
    if (!g.reprojected()) return read_raster(path, what);
    return read_working_window(path, what, g, g.grid.bounds(), 0);
}

Raster read_working_dem(const std::string& path, const std::string& what, std::string* note) {
    const WorkingGrid g = working_grid(raster_info(path, what));
    if (note) *note = g.note();
    return read_working(path, what, g);
}

Raster to_working_crs(Raster dem, std::string* note) {
    if (!is_geographic(dem.crs_wkt)) return dem;
    RasterInfo info;
    info.width = dem.width;
    info.height = dem.height;
    info.gt = dem.gt;
    info.crs_wkt = dem.crs_wkt;
    const WorkingGrid g = working_grid(info);
    if (note) *note = g.note();
    register_gdal();
    QuietGdal quiet;
    DatasetPtr in = mem_copy(dem);
    return warp_cells(*in, g, CellWindow{0, 0, g.grid.width, g.grid.height}, "the DEM");
}

Raster resample_like(const Raster& src0, const Raster& like) {
    const Raster src = same_crs(src0.crs_wkt, like.crs_wkt) ? src0 : warp(src0, like.crs_wkt);
    Raster out = like;
    for (int r = 0; r < like.height; ++r)
        for (int c = 0; c < like.width; ++c) out.at(c, r) = float(src.sample(like.grid_world(c + 0.5, r + 0.5)));
    return out;
}

}  // namespace carto
