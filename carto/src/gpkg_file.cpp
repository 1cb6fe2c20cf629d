#include "gpkg_file.hpp"

#include "carto/error.hpp"

namespace carto {

GpkgWriter::GpkgWriter(const std::string& path, const std::string& crs_wkt, bool spatial_index)
    : path_(path), spatial_index_(spatial_index), tmp_((register_gdal(), path), ".gpkg") {
    GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("GPKG");
    if (!drv) throw Error(Code::Failure, "GDAL has no GeoPackage driver");
    ds_.reset(drv->Create(tmp_.path.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
    if (!ds_) throw Error(Code::OutputExists, "-o '" + path + "': cannot create (" + CPLGetLastErrorMsg() + ")");
    srs_.importFromWkt(crs_wkt.c_str());
    srs_.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);  // x = easting / longitude
}

// Closed before the scopes (members declared before it) end: the settings hold while SQLite
// writes. The temporary file goes with tmp_ unless committed.
GpkgWriter::~GpkgWriter() { ds_.reset(); }

int GpkgWriter::add_layer(const std::string& name, OGRwkbGeometryType type,
                          const std::vector<std::pair<const char*, OGRFieldType>>& fields) {
    // GDAL would fill the R-tree row by row (most of the time spent writing a large drawing):
    // it is bulk-loaded once the file is closed (gpkg_rtree.cpp).
    const char* lco[] = {"SPATIAL_INDEX=NO", "FID=fid", "GEOMETRY_NAME=geom", nullptr};
    OGRLayer* l = ds_->CreateLayer(name.c_str(), &srs_, type, const_cast<char**>(lco));
    if (!l) throw Error(Code::OutputExists, "-o '" + path_ + "': cannot create layer " + name);
    for (const auto& [field, ftype] : fields) {
        OGRFieldDefn fd(field, ftype);
        if (l->CreateField(&fd) != OGRERR_NONE)
            throw Error(Code::OutputExists, "-o '" + path_ + "': cannot create field " + field + " of layer " + name);
    }
    layers_.push_back({l, name, {}, type != wkbNone});
    return int(layers_.size()) - 1;
}

OGRFeatureDefn* GpkgWriter::definition(int layer) const { return layers_[std::size_t(layer)].ogr->GetLayerDefn(); }

void GpkgWriter::begin() { ds_->StartTransaction(); }

void GpkgWriter::end() {
    if (ds_->CommitTransaction() != OGRERR_NONE)
        throw Error(Code::OutputExists, "-o '" + path_ + "': write failed (" + CPLGetLastErrorMsg() + ")");
}

void GpkgWriter::put(int layer, OGRFeature& f, const BoxD& box) {
    Layer& l = layers_[std::size_t(layer)];
    f.SetFID(OGRNullFID);
    if (l.ogr->CreateFeature(&f) != OGRERR_NONE)
        throw Error(Code::OutputExists, "-o '" + path_ + "': write failed (" + CPLGetLastErrorMsg() + ")");
    if (spatial_index_) l.boxes.push_back(box);
}

void GpkgWriter::put(int layer, OGRFeature& f) {
    BoxD box{1, 0, 1, 0};  // empty
    if (const OGRGeometry* g = f.GetGeometryRef(); g && !g->IsEmpty()) {
        OGREnvelope e;
        g->getEnvelope(&e);
        box = {e.MinX, e.MaxX, e.MinY, e.MaxY};
    }
    put(layer, f, box);
}

void GpkgWriter::sql(const std::string& statement) {
    CPLErrorReset();
    ds_->ExecuteSQL(statement.c_str(), nullptr, nullptr);
    if (CPLGetLastErrorType() >= CE_Failure)
        throw Error(Code::OutputExists, "-o '" + path_ + "': write failed (" + CPLGetLastErrorMsg() + ")");
}

void GpkgWriter::set_metadata(const char* key, const std::string& value) {
    if (ds_->SetMetadataItem(key, value.c_str()) != CE_None)
        throw Error(Code::OutputExists, "-o '" + path_ + "': cannot write the metadata " + key);
}

void GpkgWriter::commit() {
    ds_.reset();  // flushes the file
    if (spatial_index_)
        for (Layer& l : layers_) {
            if (!l.geometry) continue;
            bulk_load_rtree(tmp_.path, l.name, "geom", "fid", l.boxes);
            std::vector<BoxD>().swap(l.boxes);
        }
    tmp_.commit(path_);
}

}  // namespace carto
