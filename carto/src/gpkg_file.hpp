// Every GeoPackage the project writes (the hatches: output.cpp; an extracted partition:
// extract/write.cpp) goes through one writer: a new file at a temporary name renamed onto the
// output at the end (nothing half-written is ever left under the output's name), the same
// bytes for the same data (a fixed timestamp), no SQLite journal or sync while writing (the
// file is not the output until it is renamed), GDAL's messages kept quiet, and one R-tree per
// layer bulk-loaded once the data is written. The GDAL settings this needs are set on the
// writing thread only, for the writer's lifetime (gdal_scope.hpp): use it on one thread.
#pragma once

#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "gdal_scope.hpp"
#include "gpkg_rtree.hpp"
#include "temp_file.hpp"

namespace carto {

class GpkgWriter {
public:
    // `path`: the output the user named with -o (messages name it); `crs_wkt`: the CRS of every
    // layer; `spatial_index`: an R-tree per layer.
    GpkgWriter(const std::string& path, const std::string& crs_wkt, bool spatial_index);
    ~GpkgWriter();
    GpkgWriter(const GpkgWriter&) = delete;
    GpkgWriter& operator=(const GpkgWriter&) = delete;

    // A new layer (fid, geom, then the fields in order); returns its number. Features of a
    // layer are put one after the other, between begin() and end() of its transaction.
    int add_layer(const std::string& name, OGRwkbGeometryType type,
                  const std::vector<std::pair<const char*, OGRFieldType>>& fields);
    OGRFeatureDefn* definition(int layer) const;
    void begin();
    void end();
    // Writes the feature (a new fid); the R-tree gets `box`, or the geometry's envelope.
    void put(int layer, OGRFeature& f, const BoxD& box);
    void put(int layer, OGRFeature& f);
    // Runs an SQL statement on the file (an index, say), in the current transaction if any.
    void sql(const std::string& statement);
    // A metadata item of the file (GeoPackage metadata, as GDAL's GetMetadataItem reads it).
    void set_metadata(const char* key, const std::string& value);
    // Closes the file, loads the R-trees and renames it onto the output. Without commit, the
    // temporary file is removed.
    void commit();

private:
    struct Layer {
        OGRLayer* ogr;
        std::string name;
        std::vector<BoxD> boxes;
        bool geometry;  // false: an attribute table (no R-tree)
    };
    std::string path_;
    bool spatial_index_;
    TempFile tmp_;
    ReproducibleGpkg reproducible_;
    ConfigScope sync_{"OGR_SQLITE_SYNCHRONOUS", "OFF"}, journal_{"OGR_SQLITE_JOURNAL", "OFF"};
    QuietGdal quiet_;
    OGRSpatialReference srs_;
    std::unique_ptr<GDALDataset> ds_;
    std::vector<Layer> layers_;
};

}  // namespace carto
