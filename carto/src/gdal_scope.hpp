// GDAL settings scoped to a call (internal to carto). carto runs inside other programs (the
// QGIS plugin, a user's Python): a configuration option set for the process would change how
// every later GeoPackage of that program is written, so carto sets options on its own thread
// only, for the time of the call, and puts back what was there.
#pragma once

#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <memory>
#include <optional>
#include <string>

namespace carto {

// Registers GDAL's drivers when nobody has yet; a host that registered (or deregistered)
// drivers keeps its choice.
inline void register_gdal() {
    if (GDALGetDriverCount() == 0) GDALAllRegister();
}

// A dataset closed (GDALClose) when its owner goes.
struct DatasetCloser {
    void operator()(GDALDataset* d) const { GDALClose(GDALDataset::ToHandle(d)); }
};
using DatasetPtr = std::unique_ptr<GDALDataset, DatasetCloser>;

// A configuration option for the calling thread (CPLSetThreadLocalConfigOption), the thread's
// previous value back at the end of the scope. The GDAL work that reads it must run on this
// thread; the global value (CPLSetConfigOption) is never touched.
class ConfigScope {
public:
    ConfigScope(const char* key, const char* value) : key_(key) {
        if (const char* old = CPLGetThreadLocalConfigOption(key, nullptr)) saved_ = old;
        CPLSetThreadLocalConfigOption(key, value);
    }
    ~ConfigScope() { CPLSetThreadLocalConfigOption(key_.c_str(), saved_ ? saved_->c_str() : nullptr); }
    ConfigScope(const ConfigScope&) = delete;
    ConfigScope& operator=(const ConfigScope&) = delete;

private:
    std::string key_;
    std::optional<std::string> saved_;
};

// A GeoPackage written by carto: a fixed timestamp in gpkg_contents, so the same run writes
// the same bytes.
struct ReproducibleGpkg {
    ConfigScope date{"OGR_CURRENT_DATE", "2000-01-01T00:00:00.000Z"};
};

// The SQLite pragmas of a GeoPackage a run creates: pages of 64 KiB, SQLite's largest. A
// drawing's millions of rows then fill a sixteenth of the pages, with as many fewer page
// splits and writes, and the file reads back faster. A host's own OGR_SQLITE_PRAGMA comes
// after, so a page_size it sets wins.
inline std::string large_page_pragmas() {
    std::string v = "page_size=65536";
    if (const char* host = CPLGetConfigOption("OGR_SQLITE_PRAGMA", nullptr); host && *host) v += std::string(",") + host;
    return v;
}

// GDAL prints its own errors to stderr; keep them quiet (on this thread, for the scope) and
// turn them into messages.
struct QuietGdal {
    QuietGdal() { CPLPushErrorHandler(CPLQuietErrorHandler); }
    ~QuietGdal() { CPLPopErrorHandler(); }
    QuietGdal(const QuietGdal&) = delete;
    QuietGdal& operator=(const QuietGdal&) = delete;
};

// A CRS as WKT2 (2019), the form carto keeps CRSs in ("" when there is none).
inline std::string wkt2_of(const OGRSpatialReference* srs) {
    if (!srs) return "";
    char* wkt = nullptr;
    const char* opts[] = {"FORMAT=WKT2_2019", nullptr};
    srs->exportToWkt(&wkt, opts);
    std::string out = wkt ? wkt : "";
    CPLFree(wkt);
    return out;
}

}  // namespace carto
