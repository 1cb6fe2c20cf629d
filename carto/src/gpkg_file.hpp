// Every GeoPackage the project writes (the hatches: output.cpp; an extracted partition:
// extract/write.cpp) goes through one writer: a new file at a temporary name renamed onto the
// output at the end (nothing half-written is ever left under the output's name), the same
// bytes for the same data (a fixed timestamp), no SQLite journal or sync while writing (the
// file is not the output until it is renamed), GDAL's messages kept quiet, and one R-tree per
// layer bulk-loaded once the data is written. The GDAL settings this needs are set on the
// writing thread only, for the writer's lifetime (gdal_scope.hpp): use it on one thread.
//
// Millions of features (the hatches) skip GDAL's feature objects: GDAL creates the file, its
// layers, fields, CRS and metadata, and the rows are inserted with SQLite's prepared
// statements (insert()), their geometries encoded beforehand as GeoPackage blobs (GpkgRows,
// on any thread), byte for byte the blobs GDAL writes. The writer switches between GDAL and
// SQLite by closing one before opening the other, and leaves what GDAL keeps per layer (the
// extent in gpkg_contents, the count in gpkg_ogr_contents and its triggers) as GDAL would.
#pragma once

#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "libtex/geometry.hpp"

#include "gdal_scope.hpp"
#include "gpkg_rtree.hpp"
#include "temp_file.hpp"

struct sqlite3;
struct sqlite3_stmt;

namespace carto {

// Rows for GpkgWriter::insert, encoded on any thread: each row a layer, a geometry (a
// GeoPackage blob: "GP", version, flags, srs_id, the XY envelope, then little-endian WKB) or
// none (attribute tables), then the values of the layer's fields in order.
class GpkgRows {
public:
    explicit GpkgRows(std::int32_t srs_id = 0) : srs_id_(srs_id) {}
    // A row of `layer` with a LineString (a Polygon of one ring when `polygon`) of the n
    // points, the first repeated at the end when `close`.
    void line(int layer, const tex::Point* pts, std::size_t n, bool close, bool polygon);
    // A row with a Polygon of the rings (outer first), each closed (its first point repeated).
    void polygon(int layer, const std::vector<std::vector<tex::Point>>& rings);
    // A row without geometry.
    void attributes(int layer);
    // The values of the current row's fields, in order.
    void integer(std::int64_t v);
    void real(double v);
    void text(std::string_view v);
    // Appends the rows of `from` whose layer is `layer`, as rows of layer `as`.
    void append(const GpkgRows& from, int layer, int as);
    std::size_t size() const { return rows_.size(); }
    std::size_t bytes() const { return data_.size() + rows_.size() * sizeof(Row) + cells_.size() * sizeof(Cell); }
    bool empty() const { return rows_.empty(); }
    void clear();

private:
    friend class GpkgWriter;
    // A row and its cells in 56 and 16 bytes: a face's rows wait in memory for their turn
    // (OrderedInserter), and the fewer bytes they take, the more of them may wait.
    struct Row {
        int layer;
        std::uint32_t first_cell, cells;
        std::uint32_t blob_size;  // 0: no geometry
        std::size_t blob;         // its place in data_
        BoxD box;
    };
    struct Cell {
        enum Kind : std::uint8_t { Integer, Real, Text } kind;
        std::uint32_t size;  // a text's length
        union {
            std::int64_t i;
            double d;
            std::size_t at;  // a text's place in data_
        };
    };
    static Cell make_cell(Cell::Kind kind, std::int64_t i, double d, std::size_t at, std::size_t size);
    void begin_geometry(int layer, const BoxD& box);
    void end_geometry();
    std::int32_t srs_id_;
    std::string data_;
    std::vector<Row> rows_;
    std::vector<Cell> cells_;
};

// Appends the little-endian WKB of a LineString of the n points (a Polygon of one ring when
// `polygon`), the first repeated at the end when `close`: the WKB part of GpkgRows::line's blob.
void append_line_wkb(std::string& out, const tex::Point* pts, std::size_t n, bool close, bool polygon);
// The WKB part of a GeoPackage geometry blob (after its header and envelope); the blob as it
// is when it is not one.
std::string_view gpkg_blob_wkb(std::string_view blob);

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
    OGRFeatureDefn* definition(int layer);
    void begin();
    void end();
    // Writes the feature (a new fid); the R-tree gets `box`, or the geometry's envelope.
    void put(int layer, OGRFeature& f, const BoxD& box);
    void put(int layer, OGRFeature& f);
    // Runs an SQL statement on the file (an index, say), in the current transaction if any
    // (SQLite's when rows were inserted last, else GDAL's).
    void sql(const std::string& statement);
    // A metadata item of the file (GeoPackage metadata, as GDAL's GetMetadataItem reads it).
    void set_metadata(const char* key, const std::string& value);
    // Closes the file, loads the R-trees and renames it onto the output. Without commit, the
    // temporary file is removed.
    void commit();

    // The srs_id of the layers' CRS in the file (for GpkgRows); opens the file with SQLite.
    std::int32_t srs_id();
    // Inserts the rows in order (SQLite, one transaction until GDAL is needed again). Any thread
    // may call it, one at a time, while the thread that made the writer makes no other call.
    void insert(const GpkgRows& rows);
    bool has_layer(const std::string& name) const;

private:
    struct Layer {
        OGRLayer* ogr;  // while GDAL has the file open
        std::string name;
        std::vector<std::string> field_names;
        std::vector<BoxF> boxes;  // of the rows not yet in the R-tree
        bool geometry;  // false: an attribute table (no R-tree)
        // GDAL's count and (for the rows inserted with SQLite) extent, written at the end
        // (write_counts). A layer takes its rows from put() or from insert(), not both.
        std::int64_t rows = 0, inserted = 0;
        double minx = INFINITY, maxx = -INFINITY, miny = INFINITY, maxy = -INFINITY;
        // One row, and kBatch rows in one statement (SQLite reads and writes the
        // AUTOINCREMENT sequence once per statement, not per row).
        sqlite3_stmt* insert = nullptr;
        sqlite3_stmt* insert_batch = nullptr;
        std::string count_trigger;  // its SQL, dropped while SQLite inserts
        // The R-tree of a layer SQLite inserts into, written as the rows go in (pack_boxes),
        // and how many rows it has.
        std::shared_ptr<RtreeLoader> rtree;
        std::int64_t packed = 0;
    };
    [[noreturn]] void fail(const std::string& what) const;
    void open_gdal();
    void close_gdal();
    void open_sqlite();
    void close_sqlite();
    void pack_boxes(Layer& l);
    void exec(const std::string& sql);
    void prepare_layer(Layer& l);
    int bind_row(sqlite3_stmt* st, int param, const GpkgRows& rows, const GpkgRows::Row& r, Layer& l);
    void write_counts();
    std::string path_;
    bool spatial_index_;
    TempFile tmp_;
    ReproducibleGpkg reproducible_;
    ConfigScope sync_{"OGR_SQLITE_SYNCHRONOUS", "OFF"}, journal_{"OGR_SQLITE_JOURNAL", "OFF"};
    ConfigScope pages_{"OGR_SQLITE_PRAGMA", large_page_pragmas().c_str()};
    QuietGdal quiet_;
    OGRSpatialReference srs_;
    std::unique_ptr<GDALDataset> ds_;
    sqlite3* db_ = nullptr;
    std::int32_t srs_id_ = -1;
    std::vector<Layer> layers_;
};

}  // namespace carto
