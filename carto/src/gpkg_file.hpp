// The start of every GeoPackage the project writes (the hatch writer in output.cpp, the
// partition writer in extract/write.cpp): a new dataset on the temporary file that will be
// renamed onto the output, and the working CRS its layers carry. The caller holds a
// ReproducibleGpkg (gdal_scope.hpp) while writing, so the same data gives the same bytes.
#pragma once

#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <memory>
#include <string>

#include "carto/error.hpp"

namespace carto {

// `tmp` is created; `path` (the output the user named with -o) names it in the error.
inline std::unique_ptr<GDALDataset> create_gpkg(const std::string& tmp, const std::string& path) {
    GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("GPKG");
    if (!drv) throw Error(Code::Failure, "GDAL has no GeoPackage driver");
    std::unique_ptr<GDALDataset> ds(drv->Create(tmp.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
    if (!ds)
        throw Error(Code::OutputExists,
                    "-o '" + path + "': cannot create (" + CPLGetLastErrorMsg() + ")");
    return ds;
}

// The CRS of a layer from its WKT, axes in x = easting / longitude order.
inline OGRSpatialReference layer_srs(const std::string& wkt) {
    OGRSpatialReference srs;
    srs.importFromWkt(wkt.c_str());
    srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    return srs;
}

}  // namespace carto
