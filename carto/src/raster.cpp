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

struct DatasetCloser {
    void operator()(GDALDataset* d) const { GDALClose(GDALDataset::ToHandle(d)); }
};
using DatasetPtr = std::unique_ptr<GDALDataset, DatasetCloser>;

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

Point Raster::to_pixel(const Point& w) const {
    if (!grid_gt) return tex::grid_pixel(gt, w);
    const Point p = tex::grid_pixel(*grid_gt, w);
    return {p.x - col0, p.y - row0};
}

BBox Raster::bounds() const {
    BBox b;
    b.add(to_world(0, 0));
    b.add(to_world(width, 0));
    b.add(to_world(0, height));
    b.add(to_world(width, height));
    return b;
}

// One bilinear sampler for carto and libtex: tex::sample_grid on the raster's cells.
double Raster::sample(const Point& w) const { return tex::sample_grid_pixel(data.data(), width, height, to_pixel(w)); }

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

Raster read_raster_window(const std::string& path, const std::string& what, const BBox& box, int halo) {
    DatasetPtr ds = open_raster(path, what);
    QuietGdal quiet;
    const RasterInfo info = checked_info(*ds, what, path);
    // The cells the box touches, in the raster's pixel grid.
    const Point a = tex::grid_pixel(info.gt, {box.xmin, box.ymin}), b = tex::grid_pixel(info.gt, {box.xmax, box.ymax});
    const double c0 = std::floor(std::min(a.x, b.x)) - halo, c1 = std::ceil(std::max(a.x, b.x)) + halo;
    const double r0 = std::floor(std::min(a.y, b.y)) - halo, r1 = std::ceil(std::max(a.y, b.y)) + halo;
    const int col0 = int(std::clamp(c0, 0.0, double(info.width))), col1 = int(std::clamp(c1, 0.0, double(info.width)));
    const int row0 = int(std::clamp(r0, 0.0, double(info.height))), row1 = int(std::clamp(r1, 0.0, double(info.height)));
    if (col1 <= col0 || row1 <= row0) {
        Raster empty;
        empty.gt = info.gt;
        empty.crs_wkt = info.crs_wkt;
        empty.grid_gt = info.gt;
        return empty;
    }
    return from_dataset(*ds, what, path, col0, row0, col1 - col0, row1 - row0);
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

Raster warp(const Raster& src, const std::string& dst_wkt, double cell) {
    register_gdal();
    QuietGdal quiet;
    GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
    DatasetPtr in(mem->Create("", src.width, src.height, 1, GDT_Float32, nullptr));
    in->SetGeoTransform(const_cast<double*>(src.gt.data()));
    OGRSpatialReference srs;
    srs.importFromWkt(src.crs_wkt.c_str());
    in->SetSpatialRef(&srs);
    GDALRasterBand* b = in->GetRasterBand(1);
    b->SetNoDataValue(std::nan(""));
    std::vector<float> buf(src.data);
    if (b->RasterIO(GF_Write, 0, 0, src.width, src.height, buf.data(), src.width, src.height, GDT_Float32, 0, 0) != CE_None)
        throw Error(Code::Failure, "cannot copy the raster for reprojection");

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
    if (cell > 0) {
        // Resample to square cells of the requested size over the same extent.
        Raster target;
        const BBox bb = out.bounds();
        check_size(std::ceil(bb.width() / cell), std::ceil(bb.height() / cell), "reprojecting to square cells");
        target.width = std::max(1, int(std::ceil(bb.width() / cell)));
        target.height = std::max(1, int(std::ceil(bb.height() / cell)));
        target.gt = {bb.xmin, cell, 0, bb.ymax, 0, -cell};
        target.crs_wkt = dst_wkt;
        target.data.assign(std::size_t(target.width) * target.height, kNaN);
        for (int r = 0; r < target.height; ++r)
            for (int c = 0; c < target.width; ++c) target.at(c, r) = float(out.sample(target.to_world(c + 0.5, r + 0.5)));
        target.crs_wkt = dst_wkt;
        return target;
    }
    out.crs_wkt = dst_wkt;
    return out;
}

}  // namespace carto

namespace carto {

Raster to_working_crs(Raster dem, std::string* note) {
    if (!is_geographic(dem.crs_wkt)) return dem;
    const BBox b = dem.bounds();
    const int epsg = utm_epsg(b.center().x, b.center().y);
    const double cell = dem.cell_y() * 111320.0;
    if (note)
        *note = "DEM in a geographic CRS: reprojected to EPSG:" + std::to_string(epsg) + " (UTM, " +
                std::to_string(int(std::round(cell))) + " m cells)";
    return warp(dem, epsg_wkt(epsg), cell);
}

Raster resample_like(const Raster& src0, const Raster& like) {
    const Raster src = same_crs(src0.crs_wkt, like.crs_wkt) ? src0 : warp(src0, like.crs_wkt);
    Raster out = like;
    for (int r = 0; r < like.height; ++r)
        for (int c = 0; c < like.width; ++c) out.at(c, r) = float(src.sample(like.to_world(c + 0.5, r + 0.5)));
    return out;
}

}  // namespace carto
