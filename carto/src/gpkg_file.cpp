#include "gpkg_file.hpp"

#include <sqlite3.h>

#include <cstring>

#include "carto/error.hpp"

namespace carto {
namespace {

static_assert(sizeof(tex::Point) == 2 * sizeof(double), "points are copied into WKB as pairs of doubles");
#if !defined(__BYTE_ORDER__) || __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "GpkgRows writes little-endian blobs by copying the host's numbers"
#endif

template <class T>
void put(std::string& s, T v) {
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    s.append(b, sizeof(T));
}

void extend(BoxD& b, const tex::Point* pts, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) {
        b.minx = std::min(b.minx, pts[i].x);
        b.maxx = std::max(b.maxx, pts[i].x);
        b.miny = std::min(b.miny, pts[i].y);
        b.maxy = std::max(b.maxy, pts[i].y);
    }
}

void put_points(std::string& s, const tex::Point* pts, std::size_t n, bool close) {
    put(s, std::uint32_t(n + (close ? 1 : 0)));
    s.append(reinterpret_cast<const char*>(pts), n * sizeof(tex::Point));
    if (close) s.append(reinterpret_cast<const char*>(pts), sizeof(tex::Point));
}

constexpr std::uint32_t kWkbLineString = 2, kWkbPolygon = 3;
// Rows a multi-row INSERT holds (at most 5 parameters each, far below SQLite's limit).
constexpr int kBatch = 64;
// Boxes packed into R-tree leaves at a time while the rows go in (GpkgWriter::pack_boxes).
constexpr std::size_t kRtreeChunk = 32768;

}  // namespace

// The blob as GDAL's GeoPackage driver writes a LineString or a Polygon: magic "GP", version
// 0, flags 0x03 (little-endian, an XY envelope; not empty, standard type), the srs_id, the
// envelope as minx, maxx, miny, maxy (begin_geometry), then the WKB (byte order 1, type,
// counts, points).
void GpkgRows::begin_geometry(int layer, const BoxD& box) {
    rows_.push_back({layer, std::uint32_t(cells_.size()), 0, 0, data_.size(), box});
    data_ += "GP";
    data_ += char(0);
    data_ += char(0x03);
    put(data_, srs_id_);
    put(data_, box.minx);
    put(data_, box.maxx);
    put(data_, box.miny);
    put(data_, box.maxy);
}

void append_line_wkb(std::string& out, const tex::Point* pts, std::size_t n, bool close, bool polygon) {
    out += char(1);
    put(out, polygon ? kWkbPolygon : kWkbLineString);
    if (polygon) put(out, std::uint32_t(1));
    put_points(out, pts, n, close);
}

std::string_view gpkg_blob_wkb(std::string_view blob) {
    if (blob.size() < 8 || blob[0] != 'G' || blob[1] != 'P') return blob;
    // Flags bits 1-3: the envelope (none, XY, XYZ, XYM, XYZM).
    static constexpr std::size_t kEnvelope[8] = {0, 32, 48, 48, 64, 0, 0, 0};
    const std::size_t at = 8 + kEnvelope[(std::uint8_t(blob[3]) >> 1) & 7];
    return at <= blob.size() ? blob.substr(at) : blob;
}

void GpkgRows::line(int layer, const tex::Point* pts, std::size_t n, bool close, bool polygon) {
    BoxD box{INFINITY, -INFINITY, INFINITY, -INFINITY};
    extend(box, pts, n);
    begin_geometry(layer, box);
    append_line_wkb(data_, pts, n, close, polygon);
    end_geometry();
}

void GpkgRows::polygon(int layer, const std::vector<std::vector<tex::Point>>& rings) {
    BoxD box{INFINITY, -INFINITY, INFINITY, -INFINITY};
    for (const auto& r : rings) extend(box, r.data(), r.size());
    begin_geometry(layer, box);
    data_ += char(1);
    put(data_, kWkbPolygon);
    put(data_, std::uint32_t(rings.size()));
    for (const auto& r : rings) put_points(data_, r.data(), r.size(), !r.empty());
    end_geometry();
}

void GpkgRows::end_geometry() {
    const std::size_t size = data_.size() - rows_.back().blob;
    if (size > INT32_MAX) throw Error(Code::Failure, "a geometry of more than 2 GB for a GeoPackage row");
    rows_.back().blob_size = std::uint32_t(size);
}

void GpkgRows::attributes(int layer) {
    rows_.push_back({layer, std::uint32_t(cells_.size()), 0, 0, data_.size(), BoxD{1, 0, 1, 0}});
}

GpkgRows::Cell GpkgRows::make_cell(Cell::Kind kind, std::int64_t i, double d, std::size_t at, std::size_t size) {
    static_assert(sizeof(Row) <= 56 && sizeof(Cell) <= 16, "a waiting row takes few bytes");
    if (size > UINT32_MAX) throw Error(Code::Failure, "a text of more than 4 GB for a GeoPackage row");
    Cell c;
    c.kind = kind;
    c.size = std::uint32_t(size);
    if (kind == Cell::Integer) c.i = i;
    else if (kind == Cell::Real) c.d = d;
    else c.at = at;
    return c;
}

void GpkgRows::integer(std::int64_t v) {
    cells_.push_back(make_cell(Cell::Integer, v, 0, 0, 0));
    ++rows_.back().cells;
}

void GpkgRows::real(double v) {
    cells_.push_back(make_cell(Cell::Real, 0, v, 0, 0));
    ++rows_.back().cells;
}

void GpkgRows::text(std::string_view v) {
    cells_.push_back(make_cell(Cell::Text, 0, 0, data_.size(), v.size()));
    data_.append(v);
    ++rows_.back().cells;
}

void GpkgRows::append(const GpkgRows& from, int layer, int as) {
    for (const Row& r : from.rows_) {
        if (r.layer != layer) continue;
        Row row = r;
        row.layer = as;
        row.blob = data_.size();
        data_.append(from.data_, r.blob, r.blob_size);
        row.first_cell = std::uint32_t(cells_.size());
        for (std::uint32_t c = 0; c < r.cells; ++c) {
            Cell cell = from.cells_[r.first_cell + c];
            if (cell.kind == Cell::Text) {
                const std::size_t at = data_.size();
                data_.append(from.data_, cell.at, cell.size);
                cell.at = at;
            }
            cells_.push_back(cell);
        }
        rows_.push_back(row);
    }
}

void GpkgRows::clear() {
    data_.clear();
    rows_.clear();
    cells_.clear();
}

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
GpkgWriter::~GpkgWriter() {
    if (db_) {
        for (Layer& l : layers_) {
            sqlite3_finalize(l.insert);
            sqlite3_finalize(l.insert_batch);
        }
        sqlite3_close(db_);
    }
    ds_.reset();
}

void GpkgWriter::fail(const std::string& what) const {
    throw Error(Code::OutputExists, "-o '" + path_ + "': " + what + (db_ ? std::string(" (") + sqlite3_errmsg(db_) + ")" : ""));
}

void GpkgWriter::exec(const std::string& sql) {
    char* err = nullptr;
    if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &err) != SQLITE_OK) {
        const std::string msg = err ? err : "?";
        sqlite3_free(err);
        throw Error(Code::OutputExists, "-o '" + path_ + "': write failed (" + msg + ")");
    }
}

void GpkgWriter::open_gdal() {
    if (ds_) return;
    close_sqlite();
    ds_.reset(GDALDataset::FromHandle(
        GDALOpenEx(tmp_.path.c_str(), GDAL_OF_VECTOR | GDAL_OF_UPDATE, nullptr, nullptr, nullptr)));
    if (!ds_) throw Error(Code::OutputExists, "-o '" + path_ + "': cannot open again (" + CPLGetLastErrorMsg() + ")");
    for (Layer& l : layers_)
        if (!(l.ogr = ds_->GetLayerByName(l.name.c_str()))) throw Error(Code::OutputExists, "-o '" + path_ + "': layer " + l.name + " lost");
}

void GpkgWriter::close_gdal() {
    ds_.reset();  // flushes the file
    for (Layer& l : layers_) l.ogr = nullptr;
}

void GpkgWriter::open_sqlite() {
    if (db_) return;
    close_gdal();
    // One thread at a time uses the connection (insert()'s contract): no mutex.
    if (sqlite3_open_v2(tmp_.path.c_str(), &db_, SQLITE_OPEN_READWRITE | SQLITE_OPEN_NOMUTEX, nullptr) != SQLITE_OK)
        fail("cannot open the file");
    // The file is not the output until it is renamed: no journal, no sync (as GDAL writes it).
    exec("PRAGMA synchronous = OFF; PRAGMA journal_mode = OFF; BEGIN");
}

void GpkgWriter::close_sqlite() {
    if (!db_) return;
    for (Layer& l : layers_) {
        if (!l.insert) continue;
        sqlite3_finalize(l.insert);
        sqlite3_finalize(l.insert_batch);
        l.insert = l.insert_batch = nullptr;
        if (!l.count_trigger.empty()) exec(l.count_trigger);
        l.count_trigger.clear();
    }
    // GDAL finds its counts and extents up to date when it opens the file again (a count it
    // does not know, it would count row by row).
    write_counts();
    exec("COMMIT");
    if (sqlite3_close(db_) != SQLITE_OK) fail("cannot close the file");
    db_ = nullptr;
}

// The layer's insert statement; GDAL's trigger that counts the layer's rows one by one is
// set aside until SQLite closes the file (the count is then added at once).
void GpkgWriter::prepare_layer(Layer& l) {
    const std::string trigger = "trigger_insert_feature_count_" + l.name;
    {
        sqlite3_stmt* st = nullptr;
        if (sqlite3_prepare_v2(db_, "SELECT sql FROM sqlite_master WHERE type = 'trigger' AND name = ?", -1, &st, nullptr) != SQLITE_OK)
            fail("cannot read the schema");
        sqlite3_bind_text(st, 1, trigger.c_str(), -1, SQLITE_TRANSIENT);
        if (sqlite3_step(st) == SQLITE_ROW) l.count_trigger = reinterpret_cast<const char*>(sqlite3_column_text(st, 0));
        sqlite3_finalize(st);
    }
    if (!l.count_trigger.empty()) exec("DROP TRIGGER " + sql_name(trigger));
    std::string cols, row;
    if (l.geometry) {
        cols = "\"geom\"";
        row = "?";
    }
    for (const std::string& f : l.field_names) {
        cols += (cols.empty() ? "" : ", ") + sql_name(f);
        row += row.empty() ? "?" : ", ?";
    }
    const std::string head = "INSERT INTO " + sql_name(l.name) + " (" + cols + ") VALUES ";
    std::string many = head;
    for (int i = 0; i < kBatch; ++i) many += (i ? ", (" : "(") + row + ")";
    if (sqlite3_prepare_v2(db_, (head + "(" + row + ")").c_str(), -1, &l.insert, nullptr) != SQLITE_OK ||
        sqlite3_prepare_v2(db_, many.c_str(), -1, &l.insert_batch, nullptr) != SQLITE_OK)
        fail("cannot prepare the rows of " + l.name);
}

std::int32_t GpkgWriter::srs_id() {
    if (srs_id_ >= 0) return srs_id_;
    open_sqlite();
    srs_id_ = 0;
    for (const Layer& l : layers_) {
        if (!l.geometry) continue;
        sqlite3_stmt* st = nullptr;
        if (sqlite3_prepare_v2(db_, "SELECT srs_id FROM gpkg_geometry_columns WHERE lower(table_name) = lower(?)", -1, &st,
                               nullptr) != SQLITE_OK)
            fail("cannot read the geometry columns");
        sqlite3_bind_text(st, 1, l.name.c_str(), -1, SQLITE_TRANSIENT);
        if (sqlite3_step(st) == SQLITE_ROW) srs_id_ = sqlite3_column_int(st, 0);
        sqlite3_finalize(st);
        break;
    }
    return srs_id_;
}

bool GpkgWriter::has_layer(const std::string& name) const {
    for (const Layer& l : layers_)
        if (l.name == name) return true;
    return false;
}

// Binds row r from parameter `param` on; returns the next parameter. Counts the row.
int GpkgWriter::bind_row(sqlite3_stmt* st, int param, const GpkgRows& rows, const GpkgRows::Row& r, Layer& l) {
    if (r.cells != l.field_names.size() || (r.blob_size > 0) != l.geometry)
        throw Error(Code::Failure, "-o '" + path_ + "': a row does not fit layer " + l.name);
    if (l.geometry) sqlite3_bind_blob(st, param++, rows.data_.data() + r.blob, int(r.blob_size), SQLITE_STATIC);
    for (std::uint32_t c = 0; c < r.cells; ++c, ++param) {
        const GpkgRows::Cell& cell = rows.cells_[r.first_cell + c];
        switch (cell.kind) {
            case GpkgRows::Cell::Integer: sqlite3_bind_int64(st, param, cell.i); break;
            case GpkgRows::Cell::Real: sqlite3_bind_double(st, param, cell.d); break;
            case GpkgRows::Cell::Text: sqlite3_bind_text(st, param, rows.data_.data() + cell.at, int(cell.size), SQLITE_STATIC); break;
        }
    }
    ++l.inserted;
    ++l.rows;
    if (l.geometry) {
        const BoxD& b = r.box;
        l.minx = std::min(l.minx, b.minx);
        l.maxx = std::max(l.maxx, b.maxx);
        l.miny = std::min(l.miny, b.miny);
        l.maxy = std::max(l.maxy, b.maxy);
        if (spatial_index_) l.boxes.push_back(rtree_box(b));
    }
    return param;
}

void GpkgWriter::insert(const GpkgRows& rows) {
    if (rows.empty()) return;
    open_sqlite();
    // Layer by layer, each layer's rows in their order (the order of the fids), kBatch rows a
    // statement while there are that many.
    std::vector<std::uint32_t> order(rows.rows_.size());
    std::vector<std::size_t> start(layers_.size() + 1, 0);
    for (const GpkgRows::Row& r : rows.rows_) {
        if (r.layer < 0 || std::size_t(r.layer) >= layers_.size())
            throw Error(Code::Failure, "-o '" + path_ + "': a row of no layer");
        ++start[std::size_t(r.layer) + 1];
    }
    for (std::size_t i = 1; i < start.size(); ++i) start[i] += start[i - 1];
    {
        std::vector<std::size_t> at(start.begin(), start.end() - 1);
        for (std::size_t i = 0; i < rows.rows_.size(); ++i) order[at[std::size_t(rows.rows_[i].layer)]++] = std::uint32_t(i);
    }
    for (std::size_t li = 0; li < layers_.size(); ++li) {
        Layer& l = layers_[li];
        std::size_t i = start[li];
        const std::size_t end = start[li + 1];
        if (i == end) continue;
        if (!l.insert) prepare_layer(l);
        while (i < end) {
            const bool batch = end - i >= std::size_t(kBatch);
            sqlite3_stmt* st = batch ? l.insert_batch : l.insert;
            int param = 1;
            for (std::size_t n = batch ? kBatch : 1; n > 0; --n) param = bind_row(st, param, rows, rows.rows_[order[i++]], l);
            if (sqlite3_step(st) != SQLITE_DONE) fail("write failed in " + l.name);
            sqlite3_reset(st);
        }
        if (spatial_index_ && l.geometry) pack_boxes(l);
    }
}

// The R-tree of a layer whose rows SQLite inserts is written as they go in, on the thread
// that inserts them: every kRtreeChunk boxes (by count, so that the leaves are the same
// whatever rows each call brings) are packed into leaves of their own. The chunks are
// neighbouring features (a face's hatches are consecutive), so the leaves stay compact; the
// levels above them are packed when the file is committed.
void GpkgWriter::pack_boxes(Layer& l) {
    std::size_t done = 0;
    while (l.boxes.size() - done >= kRtreeChunk) {
        if (!l.rtree) l.rtree = std::make_shared<RtreeLoader>(db_, path_, l.name, "geom");
        l.rtree->add(db_, l.boxes.data() + done, kRtreeChunk, l.packed + 1);
        l.packed += std::int64_t(kRtreeChunk);
        done += kRtreeChunk;
    }
    l.boxes.erase(l.boxes.begin(), l.boxes.begin() + std::ptrdiff_t(done));
}

int GpkgWriter::add_layer(const std::string& name, OGRwkbGeometryType type,
                          const std::vector<std::pair<const char*, OGRFieldType>>& fields) {
    open_gdal();
    // GDAL would fill the R-tree row by row (most of the time spent writing a large drawing):
    // it is bulk-loaded once the file is closed (gpkg_rtree.cpp).
    const char* lco[] = {"SPATIAL_INDEX=NO", "FID=fid", "GEOMETRY_NAME=geom", nullptr};
    OGRLayer* l = ds_->CreateLayer(name.c_str(), &srs_, type, const_cast<char**>(lco));
    if (!l) throw Error(Code::OutputExists, "-o '" + path_ + "': cannot create layer " + name);
    Layer layer{l, name, {}, {}, type != wkbNone};
    for (const auto& [field, ftype] : fields) {
        OGRFieldDefn fd(field, ftype);
        if (l->CreateField(&fd) != OGRERR_NONE)
            throw Error(Code::OutputExists, "-o '" + path_ + "': cannot create field " + field + " of layer " + name);
        layer.field_names.emplace_back(field);
    }
    layers_.push_back(std::move(layer));
    return int(layers_.size()) - 1;
}

OGRFeatureDefn* GpkgWriter::definition(int layer) {
    open_gdal();
    return layers_[std::size_t(layer)].ogr->GetLayerDefn();
}

void GpkgWriter::begin() {
    open_gdal();
    ds_->StartTransaction();
}

void GpkgWriter::end() {
    if (ds_->CommitTransaction() != OGRERR_NONE)
        throw Error(Code::OutputExists, "-o '" + path_ + "': write failed (" + CPLGetLastErrorMsg() + ")");
}

void GpkgWriter::put(int layer, OGRFeature& f, const BoxD& box) {
    Layer& l = layers_[std::size_t(layer)];
    f.SetFID(OGRNullFID);
    if (l.ogr->CreateFeature(&f) != OGRERR_NONE)
        throw Error(Code::OutputExists, "-o '" + path_ + "': write failed (" + CPLGetLastErrorMsg() + ")");
    ++l.rows;
    if (spatial_index_) l.boxes.push_back(rtree_box(box));
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
    if (db_) {
        exec(statement);
        return;
    }
    open_gdal();
    CPLErrorReset();
    ds_->ExecuteSQL(statement.c_str(), nullptr, nullptr);
    if (CPLGetLastErrorType() >= CE_Failure)
        throw Error(Code::OutputExists, "-o '" + path_ + "': write failed (" + CPLGetLastErrorMsg() + ")");
}

void GpkgWriter::set_metadata(const char* key, const std::string& value) {
    open_gdal();
    if (ds_->SetMetadataItem(key, value.c_str()) != CE_None)
        throw Error(Code::OutputExists, "-o '" + path_ + "': cannot write the metadata " + key);
}

// What GDAL keeps of a layer it wrote: its count, and the extent of the rows inserted here.
void GpkgWriter::write_counts() {
    for (const Layer& l : layers_) {
        sqlite3_stmt* st = nullptr;
        if (sqlite3_prepare_v2(db_, "UPDATE gpkg_ogr_contents SET feature_count = ? WHERE lower(table_name) = lower(?)", -1,
                               &st, nullptr) != SQLITE_OK)
            fail("cannot prepare the feature count");
        sqlite3_bind_int64(st, 1, l.rows);
        sqlite3_bind_text(st, 2, l.name.c_str(), -1, SQLITE_TRANSIENT);
        int rc = sqlite3_step(st);
        sqlite3_finalize(st);
        if (rc != SQLITE_DONE) fail("cannot write the feature count of " + l.name);
        if (!l.geometry || !l.inserted || !(l.minx <= l.maxx)) continue;
        // Through SQL text made with SQLite's printf, as GDAL writes it (SQLite's own digits and
        // reading, not the shortest text of each double).
        char* sql = sqlite3_mprintf("UPDATE gpkg_contents SET min_x = %.18g, min_y = %.18g, max_x = %.18g, max_y = %.18g "
                                    "WHERE lower(table_name) = lower('%q')", l.minx, l.miny, l.maxx, l.maxy, l.name.c_str());
        rc = sqlite3_exec(db_, sql, nullptr, nullptr, nullptr);
        sqlite3_free(sql);
        if (rc != SQLITE_OK) fail("cannot write the extent of " + l.name);
    }
}

void GpkgWriter::commit() {
    open_sqlite();
    close_sqlite();  // writes the counts and extents
    if (spatial_index_)
        for (Layer& l : layers_) {
            if (!l.geometry) continue;
            if (l.rtree)
                load_rtree(tmp_.path, *l.rtree, l.boxes.data(), l.boxes.size(), l.packed + 1, "fid");
            else
                bulk_load_rtree(tmp_.path, l.name, "geom", "fid", l.boxes);
            std::vector<BoxF>().swap(l.boxes);
            l.rtree.reset();
        }
    tmp_.commit(path_);
}

}  // namespace carto
