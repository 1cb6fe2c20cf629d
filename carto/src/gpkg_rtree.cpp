// Bulk loading of a GeoPackage spatial index.
//
// GDAL 3.6 (Debian bookworm) fills the R*Tree of a GeoPackage row by row, which costs most
// of the time of writing a drawing of a million hatches. Since every bounding box is known
// when the layer is written, the tree is packed here in one go (sort-tile-recursive), and its
// nodes are written straight into the shadow tables of SQLite's rtree module, in the node
// format that module documents (big-endian 16-bit depth and cell count, then cells of a
// 64-bit id and four 32-bit floats). The GeoPackage rtree extension is then declared with the
// triggers of the GeoPackage 1.2 specification, so later edits keep the index up to date.
#include "gpkg_rtree.hpp"

#include <sqlite3.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>

#include "carto/error.hpp"

namespace carto {
namespace {

struct Db {
    sqlite3* db = nullptr;
    ~Db() { sqlite3_close(db); }
};

struct Stmt {
    sqlite3_stmt* s = nullptr;
    ~Stmt() { sqlite3_finalize(s); }
};

[[noreturn]] void fail(sqlite3* db, const std::string& path, const std::string& what) {
    throw Error(Code::OutputExists, "-o '" + path + "': spatial index: " + what + " (" + sqlite3_errmsg(db) + ")");
}

void exec(sqlite3* db, const std::string& path, const std::string& sql) {
    char* err = nullptr;
    if (sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &err) != SQLITE_OK) {
        const std::string msg = err ? err : "?";
        sqlite3_free(err);
        throw Error(Code::OutputExists, "-o '" + path + "': spatial index: " + msg);
    }
}

// Float bounds that contain the double ones (the rtree module rounds the same way).
float down(double v) {
    float f = float(v);
    if (double(f) > v) f = std::nextafter(f, -INFINITY);
    return f;
}
float up(double v) {
    float f = float(v);
    if (double(f) < v) f = std::nextafter(f, INFINITY);
    return f;
}

void put16(unsigned char* p, unsigned v) {
    p[0] = (unsigned char)(v >> 8);
    p[1] = (unsigned char)v;
}
void put64(unsigned char* p, std::int64_t v) {
    for (int i = 7; i >= 0; --i) {
        p[i] = (unsigned char)(v & 0xff);
        v >>= 8;
    }
}
void putf(unsigned char* p, float f) {
    std::uint32_t u;
    std::memcpy(&u, &f, 4);
    p[0] = (unsigned char)(u >> 24);
    p[1] = (unsigned char)(u >> 16);
    p[2] = (unsigned char)(u >> 8);
    p[3] = (unsigned char)u;
}

constexpr int kCell = 8 + 4 * 4;  // a node's cell: id and four floats

}  // namespace

std::string sql_name(const std::string& s) {
    std::string out = "\"";
    for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

BoxF rtree_box(const BoxD& b) {
    if (!(b.minx <= b.maxx)) return {1, 0, 1, 0};
    return {down(b.minx), up(b.maxx), down(b.miny), up(b.maxy)};
}

RtreeLoader::RtreeLoader(sqlite3* db, const std::string& path, const std::string& table, const std::string& geom)
    : path_(path), table_(table), geom_(geom), rtree_("rtree_" + table + "_" + geom) {
    exec(db, path_, "CREATE VIRTUAL TABLE " + sql_name(rtree_) + " USING rtree(id, minx, maxx, miny, maxy)");
    // Node size as the module chose it for this database (the length of the empty root).
    Stmt st;
    const std::string sql = "SELECT length(data) FROM " + sql_name(rtree_ + "_node") + " WHERE nodeno = 1";
    if (sqlite3_prepare_v2(db, sql.c_str(), -1, &st.s, nullptr) != SQLITE_OK || sqlite3_step(st.s) != SQLITE_ROW)
        fail(db, path_, "cannot read the root node");
    node_size_ = sqlite3_column_int(st.s, 0);
    fanout_ = (node_size_ - 4) / kCell;
    if (fanout_ < 4) fail(db, path_, "unexpected node size");
}

namespace {

// Sorts items[begin, end) by key(entry) as std::sort would with that comparison: the keys
// are computed once and sorted with the items' places (8 bytes to move, not the items); the
// same comparisons give the same order, ties included.
template <class Item, class EntryOf, class Key>
void sort_by_key(std::vector<Item>& items, std::size_t begin, std::size_t end, const EntryOf& entry, const Key& key,
                 std::vector<std::pair<float, std::uint32_t>>& keyed, std::vector<Item>& scratch) {
    keyed.resize(end - begin);
    for (std::size_t i = begin; i < end; ++i) keyed[i - begin] = {key(entry(items[i])), std::uint32_t(i - begin)};
    std::sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    scratch.assign(items.begin() + std::ptrdiff_t(begin), items.begin() + std::ptrdiff_t(end));
    for (std::size_t k = 0; k < keyed.size(); ++k) items[begin + k] = scratch[keyed[k].second];
}

// Sort-tile-recursive packing of `items` (their boxes through `entry`) into groups of at most
// `fanout`, sorted in place as packed: calls group(begin, end) for each group in order.
template <class Item, class EntryOf, class Group>
void str_pack(std::vector<Item>& items, int fanout, const EntryOf& entry, const Group& group) {
    const std::size_t n = items.size();
    const std::size_t groups = (n + std::size_t(fanout) - 1) / std::size_t(fanout);
    const std::size_t slices = std::size_t(std::ceil(std::sqrt(double(groups))));
    const std::size_t per_slice = slices * std::size_t(fanout);
    std::vector<std::pair<float, std::uint32_t>> keyed;
    std::vector<Item> scratch;
    sort_by_key(items, 0, n, entry, [](const RtreeEntry& e) { return e.minx + e.maxx; }, keyed, scratch);
    for (std::size_t s = 0; s < n; s += per_slice) {
        const std::size_t e = std::min(s + per_slice, n);
        sort_by_key(items, s, e, entry, [](const RtreeEntry& r) { return r.miny + r.maxy; }, keyed, scratch);
        for (std::size_t k = s; k < e; k += std::size_t(fanout)) group(k, std::min(k + std::size_t(fanout), e));
    }
}

// The box of entries [begin, end) under node number `no`.
template <class Item, class EntryOf>
RtreeEntry enclosing(const std::vector<Item>& items, std::size_t begin, std::size_t end, std::int64_t no, const EntryOf& entry) {
    RtreeEntry p{no, INFINITY, -INFINITY, INFINITY, -INFINITY};
    for (std::size_t c = begin; c < end; ++c) {
        const RtreeEntry e = entry(items[c]);
        p.minx = std::min(p.minx, e.minx);
        p.maxx = std::max(p.maxx, e.maxx);
        p.miny = std::min(p.miny, e.miny);
        p.maxy = std::max(p.maxy, e.maxy);
    }
    return p;
}

// A node's blob: depth (root only), cell count, cells of an id and four floats.
void fill_node(std::vector<unsigned char>& blob, int depth, bool root, const RtreeEntry* cells, std::size_t n) {
    std::fill(blob.begin(), blob.end(), 0);
    if (root) put16(blob.data(), unsigned(depth));
    put16(blob.data() + 2, unsigned(n));
    unsigned char* p = blob.data() + 4;
    for (std::size_t i = 0; i < n; ++i, p += kCell) {
        put64(p, cells[i].id);
        putf(p + 8, cells[i].minx);
        putf(p + 12, cells[i].maxx);
        putf(p + 16, cells[i].miny);
        putf(p + 20, cells[i].maxy);
    }
}

void step(sqlite3* db, const std::string& path, sqlite3_stmt* st, const char* what) {
    if (sqlite3_step(st) != SQLITE_DONE) fail(db, path, what);
    sqlite3_reset(st);
}

}  // namespace

void RtreeLoader::add(sqlite3* db, const BoxF* boxes, std::size_t n, std::int64_t first_id) {
    std::vector<RtreeEntry> items;
    items.reserve(n);
    for (std::size_t i = 0; i < n; ++i)
        if (boxes[i].minx <= boxes[i].maxx)  // empty geometry: not indexed
            items.push_back({first_id + std::int64_t(i), boxes[i].minx, boxes[i].maxx, boxes[i].miny, boxes[i].maxy});
    if (items.empty()) return;
    if (leaves_.empty()) exec(db, path_, "DELETE FROM " + sql_name(rtree_ + "_node"));  // the module's empty root
    Stmt ins_node;
    if (sqlite3_prepare_v2(db, ("INSERT INTO " + sql_name(rtree_ + "_node") + " VALUES (?, ?)").c_str(), -1, &ins_node.s,
                           nullptr))
        fail(db, path_, "cannot prepare the inserts");
    // The leaves, numbered on from the last; the leaf of each feature for its _rowid row
    // (by id - first_id; -1 for an empty geometry).
    std::vector<std::int64_t> node_of(n, -1);
    std::vector<unsigned char> blob(static_cast<std::size_t>(node_size_));
    const auto same = [](const RtreeEntry& e) { return e; };
    str_pack(items, fanout_, same, [&](std::size_t b, std::size_t e) {
        const std::int64_t no = next_no_++;
        leaves_.push_back(enclosing(items, b, e, no, same));
        fill_node(blob, 0, false, items.data() + b, e - b);
        sqlite3_bind_int64(ins_node.s, 1, no);
        sqlite3_bind_blob(ins_node.s, 2, blob.data(), node_size_, SQLITE_STATIC);
        step(db, path_, ins_node.s, "node insert");
        for (std::size_t c = b; c < e; ++c) node_of[std::size_t(items[c].id - first_id)] = no;
    });
    // Rows of the _rowid table in the order of the ids (appended, not put all over it),
    // kRowidBatch a statement.
    std::vector<std::pair<std::int64_t, std::int64_t>> leaf_of;  // (feature id, node)
    leaf_of.reserve(items.size());
    for (std::size_t i = 0; i < n; ++i)
        if (node_of[i] >= 0) leaf_of.push_back({first_id + std::int64_t(i), node_of[i]});
    constexpr std::size_t kRowidBatch = 100;
    Stmt one, many;
    const std::string ins = "INSERT INTO " + sql_name(rtree_ + "_rowid") + " VALUES (?, ?)";
    std::string ins_many = ins;
    for (std::size_t i = 1; i < kRowidBatch; ++i) ins_many += ", (?, ?)";
    if (sqlite3_prepare_v2(db, ins.c_str(), -1, &one.s, nullptr) ||
        sqlite3_prepare_v2(db, ins_many.c_str(), -1, &many.s, nullptr))
        fail(db, path_, "cannot prepare the inserts");
    std::size_t i = 0;
    for (; i + kRowidBatch <= leaf_of.size(); i += kRowidBatch) {
        for (std::size_t k = 0; k < kRowidBatch; ++k) {
            sqlite3_bind_int64(many.s, int(2 * k + 1), leaf_of[i + k].first);
            sqlite3_bind_int64(many.s, int(2 * k + 2), leaf_of[i + k].second);
        }
        step(db, path_, many.s, "rowid insert");
    }
    for (; i < leaf_of.size(); ++i) {
        sqlite3_bind_int64(one.s, 1, leaf_of[i].first);
        sqlite3_bind_int64(one.s, 2, leaf_of[i].second);
        step(db, path_, one.s, "rowid insert");
    }
}

void RtreeLoader::finish(sqlite3* db, const std::string& fid) {
    const std::string &path = path_, &table = table_, &geom = geom_, &rtree = rtree_;
    if (leaves_.size() == 1) {
        // One leaf is the root, which the module numbers 1.
        const std::int64_t no = leaves_.front().id;
        exec(db, path, "UPDATE " + sql_name(rtree + "_node") + " SET nodeno = 1 WHERE nodeno = " + std::to_string(no) +
                           "; UPDATE " + sql_name(rtree + "_rowid") + " SET nodeno = 1 WHERE nodeno = " + std::to_string(no));
    } else if (leaves_.size() > 1) {
        // The levels above the leaves, packed bottom up; the last node made is the root,
        // numbered 1 as the module requires.
        struct Node {
            std::int64_t no;
            int depth;
            std::size_t level, begin, end;  // its cells: levels[level][begin, end)
        };
        std::vector<std::vector<RtreeEntry>> levels{std::move(leaves_)};
        std::vector<Node> nodes;
        const auto same = [](const RtreeEntry& e) { return e; };
        for (int depth = 1; levels.back().size() > 1; ++depth) {
            std::vector<RtreeEntry>& below = levels.back();
            std::vector<RtreeEntry> parents;
            str_pack(below, fanout_, same, [&](std::size_t b, std::size_t e) {
                const std::int64_t no = next_no_++;
                parents.push_back(enclosing(below, b, e, no, same));
                nodes.push_back({no, depth, levels.size() - 1, b, e});
            });
            levels.push_back(std::move(parents));
        }
        const std::int64_t root_old = nodes.back().no;
        auto renumber = [&](std::int64_t no) { return no == root_old ? 1 : no; };
        Stmt ins_node, ins_parent;
        if (sqlite3_prepare_v2(db, ("INSERT INTO " + sql_name(rtree + "_node") + " VALUES (?, ?)").c_str(), -1, &ins_node.s,
                               nullptr) ||
            sqlite3_prepare_v2(db, ("INSERT INTO " + sql_name(rtree + "_parent") + " VALUES (?, ?)").c_str(), -1,
                               &ins_parent.s, nullptr))
            fail(db, path, "cannot prepare the inserts");
        std::vector<unsigned char> blob(static_cast<std::size_t>(node_size_));
        std::vector<RtreeEntry> cells;
        for (const Node& node : nodes) {
            const std::int64_t no = renumber(node.no);
            cells.assign(levels[node.level].begin() + std::ptrdiff_t(node.begin),
                         levels[node.level].begin() + std::ptrdiff_t(node.end));
            for (RtreeEntry& c : cells) {
                c.id = renumber(c.id);
                sqlite3_bind_int64(ins_parent.s, 1, c.id);
                sqlite3_bind_int64(ins_parent.s, 2, no);
                step(db, path, ins_parent.s, "parent insert");
            }
            fill_node(blob, node.depth, no == 1, cells.data(), cells.size());
            sqlite3_bind_int64(ins_node.s, 1, no);
            sqlite3_bind_blob(ins_node.s, 2, blob.data(), node_size_, SQLITE_STATIC);
            step(db, path, ins_node.s, "node insert");
        }
    }

    // Declare the extension and keep the index in step with later edits (GeoPackage 1.2).
    const std::string T = sql_name(table), G = sql_name(geom), I = sql_name(fid), R = sql_name(rtree);
    const std::string vals = "NEW." + I + ", ST_MinX(NEW." + G + "), ST_MaxX(NEW." + G + "), ST_MinY(NEW." + G +
                             "), ST_MaxY(NEW." + G + ")";
    auto trig = [&](const std::string& suffix) { return sql_name(rtree + "_" + suffix); };
    exec(db, path,
         "CREATE TABLE IF NOT EXISTS gpkg_extensions (table_name TEXT, column_name TEXT, extension_name TEXT NOT NULL, "
         "definition TEXT NOT NULL, scope TEXT NOT NULL, CONSTRAINT ge_tce UNIQUE (table_name, column_name, extension_name));"
         "INSERT INTO gpkg_extensions VALUES ('" + table + "', '" + geom +
             "', 'gpkg_rtree_index', 'http://www.geopackage.org/spec120/#extension_rtree', 'write-only');"
         "CREATE TRIGGER " + trig("insert") + " AFTER INSERT ON " + T + " WHEN (NEW." + G + " NOT NULL AND NOT ST_IsEmpty(NEW." + G +
             ")) BEGIN INSERT OR REPLACE INTO " + R + " VALUES (" + vals + "); END;"
         "CREATE TRIGGER " + trig("update1") + " AFTER UPDATE OF " + G + " ON " + T + " WHEN OLD." + I + " = NEW." + I +
             " AND (NEW." + G + " NOTNULL AND NOT ST_IsEmpty(NEW." + G + ")) BEGIN INSERT OR REPLACE INTO " + R + " VALUES (" +
             vals + "); END;"
         "CREATE TRIGGER " + trig("update2") + " AFTER UPDATE OF " + G + " ON " + T + " WHEN OLD." + I + " = NEW." + I +
             " AND (NEW." + G + " ISNULL OR ST_IsEmpty(NEW." + G + ")) BEGIN DELETE FROM " + R + " WHERE id = OLD." + I + "; END;"
         "CREATE TRIGGER " + trig("update3") + " AFTER UPDATE ON " + T + " WHEN OLD." + I + " != NEW." + I + " AND (NEW." + G +
             " NOTNULL AND NOT ST_IsEmpty(NEW." + G + ")) BEGIN DELETE FROM " + R + " WHERE id = OLD." + I +
             "; INSERT OR REPLACE INTO " + R + " VALUES (" + vals + "); END;"
         "CREATE TRIGGER " + trig("update4") + " AFTER UPDATE ON " + T + " WHEN OLD." + I + " != NEW." + I + " AND (NEW." + G +
             " ISNULL OR ST_IsEmpty(NEW." + G + ")) BEGIN DELETE FROM " + R + " WHERE id IN (OLD." + I + ", NEW." + I + "); END;"
         "CREATE TRIGGER " + trig("delete") + " AFTER DELETE ON " + T + " WHEN OLD." + G + " NOT NULL BEGIN DELETE FROM " + R +
             " WHERE id = OLD." + I + "; END;");
}

namespace {

// Runs fn(db) in one transaction of a connection of its own to the file.
template <class Fn>
void in_transaction(const std::string& path, const Fn& fn) {
    Db d;
    if (sqlite3_open_v2(path.c_str(), &d.db, SQLITE_OPEN_READWRITE, nullptr) != SQLITE_OK)
        fail(d.db, path, "cannot open the file");
    exec(d.db, path, "PRAGMA synchronous = OFF; PRAGMA journal_mode = OFF; BEGIN");
    fn(d.db);
    exec(d.db, path, "COMMIT");
}

}  // namespace

void load_rtree(const std::string& path, RtreeLoader& loader, const BoxF* boxes, std::size_t n, std::int64_t first_id,
                const std::string& fid) {
    in_transaction(path, [&](sqlite3* db) {
        loader.add(db, boxes, n, first_id);
        loader.finish(db, fid);
    });
}

void bulk_load_rtree(const std::string& path, const std::string& table, const std::string& geom,
                     const std::string& fid, const std::vector<BoxF>& boxes) {
    in_transaction(path, [&](sqlite3* db) {
        RtreeLoader loader(db, path, table, geom);
        loader.add(db, boxes.data(), boxes.size(), 1);
        loader.finish(db, fid);
    });
}

}  // namespace carto
