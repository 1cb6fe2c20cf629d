// Shared by the partition fuzz targets: a quiet GDAL, a per-process temporary GeoPackage
// path and the working CRS (Lambert-93, as the sample's).
#pragma once

#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace fuzz {

inline void quiet_gdal() {
    static const bool done = [] {
        GDALAllRegister();
        CPLSetErrorHandler(CPLQuietErrorHandler);
        CPLSetConfigOption("OGR_SQLITE_SYNCHRONOUS", "OFF");
        return true;
    }();
    (void)done;
}

inline const std::string& temp_gpkg() {
    static const std::string path = [] {
        const auto dir = std::filesystem::temp_directory_path() / "rh_fuzz";
        std::filesystem::create_directories(dir);
        return (dir / ("partition_" + std::to_string(getpid()) + ".gpkg")).string();
    }();
    return path;
}

inline std::string wkt_of(int epsg) {
    OGRSpatialReference srs;
    srs.importFromEPSG(epsg);
    char* wkt = nullptr;
    srs.exportToWkt(&wkt);
    std::string s(wkt ? wkt : "");
    CPLFree(wkt);
    return s;
}

inline const std::string& working_wkt() {
    static const std::string w = wkt_of(2154);
    return w;
}

}  // namespace fuzz
