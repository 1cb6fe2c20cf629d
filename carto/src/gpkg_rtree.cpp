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

struct Entry {
    std::int64_t id;  // feature id (leaves) or node number (inner nodes)
    float minx, maxx, miny, maxy;
};

std::string quoted(const std::string& s) {
    std::string out = "\"";
    for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

}  // namespace

BoxF rtree_box(const BoxD& b) {
    if (!(b.minx <= b.maxx)) return {1, 0, 1, 0};
    return {down(b.minx), up(b.maxx), down(b.miny), up(b.maxy)};
}

void bulk_load_rtree(const std::string& path, const std::string& table, const std::string& geom,
                     const std::string& fid, const std::vector<BoxF>& boxes) {
    Db d;
    if (sqlite3_open_v2(path.c_str(), &d.db, SQLITE_OPEN_READWRITE, nullptr) != SQLITE_OK)
        fail(d.db, path, "cannot open the file");
    const std::string rtree = "rtree_" + table + "_" + geom;
    exec(d.db, path, "PRAGMA synchronous = OFF; PRAGMA journal_mode = OFF; BEGIN");
    exec(d.db, path, "CREATE VIRTUAL TABLE " + quoted(rtree) + " USING rtree(id, minx, maxx, miny, maxy)");

    // Node size as the module chose it for this database (the length of the empty root).
    int node_size = 0;
    {
        Stmt st;
        const std::string sql = "SELECT length(data) FROM " + quoted(rtree + "_node") + " WHERE nodeno = 1";
        if (sqlite3_prepare_v2(d.db, sql.c_str(), -1, &st.s, nullptr) != SQLITE_OK || sqlite3_step(st.s) != SQLITE_ROW)
            fail(d.db, path, "cannot read the root node");
        node_size = sqlite3_column_int(st.s, 0);
    }
    const int cell = 8 + 4 * 4;
    const int fanout = (node_size - 4) / cell;
    if (fanout < 4) fail(d.db, path, "unexpected node size");

    // The leaves are the features' numbers in `boxes` (4 bytes each), sorted as packed; the
    // levels above are entries of their own (a fanout-th as many).
    std::vector<std::uint32_t> leaves;
    leaves.reserve(boxes.size());
    for (std::size_t i = 0; i < boxes.size(); ++i)
        if (boxes[i].minx <= boxes[i].maxx) leaves.push_back(std::uint32_t(i));  // empty geometry: not indexed
    const std::size_t ids = boxes.size();
    auto leaf_entry = [&](std::uint32_t i) {
        const BoxF& b = boxes[i];
        return Entry{std::int64_t(i) + 1, b.minx, b.maxx, b.miny, b.maxy};
    };
    auto same_entry = [](const Entry& e) { return e; };

    // Sort-tile-recursive packing, level by level, bottom up. Nodes get numbers 2, 3, ...;
    // the root is renumbered 1 at the end, as the module requires. With no entry at all the
    // empty root the module made is kept. A node's cells are a range of its level, kept
    // sorted as packed (no copy of the millions of leaves).
    struct Node {
        std::int64_t no;
        int depth;  // 0 = leaf
        std::size_t begin, end;  // in leaves (depth 0) or levels[depth - 1]
    };
    std::vector<Node> nodes;
    std::vector<std::vector<Entry>> levels;
    std::int64_t next_no = 2;
    // Packs the items of one level (their boxes through `entry`) into nodes; returns their parents.
    auto pack = [&](auto& items, const auto& entry, int depth) {
        const std::size_t n = items.size();
        const std::size_t groups = (n + fanout - 1) / fanout;
        const std::size_t slices = std::size_t(std::ceil(std::sqrt(double(groups))));
        const std::size_t per_slice = slices * std::size_t(fanout);
        std::sort(items.begin(), items.end(), [&](const auto& a, const auto& b) {
            const Entry ea = entry(a), eb = entry(b);
            return (ea.minx + ea.maxx) < (eb.minx + eb.maxx);
        });
        std::vector<Entry> parents;
        for (std::size_t s = 0; s < n; s += per_slice) {
            const std::size_t e = std::min(s + per_slice, n);
            std::sort(items.begin() + std::ptrdiff_t(s), items.begin() + std::ptrdiff_t(e), [&](const auto& a, const auto& b) {
                const Entry ea = entry(a), eb = entry(b);
                return (ea.miny + ea.maxy) < (eb.miny + eb.maxy);
            });
            for (std::size_t k = s; k < e; k += std::size_t(fanout)) {
                const Node node{next_no++, depth, k, std::min(k + fanout, e)};
                Entry p{node.no, INFINITY, -INFINITY, INFINITY, -INFINITY};
                for (std::size_t c_at = node.begin; c_at < node.end; ++c_at) {
                    const Entry c = entry(items[c_at]);
                    p.minx = std::min(p.minx, c.minx);
                    p.maxx = std::max(p.maxx, c.maxx);
                    p.miny = std::min(p.miny, c.miny);
                    p.maxy = std::max(p.maxy, c.maxy);
                }
                parents.push_back(p);
                nodes.push_back(node);
            }
        }
        return parents;
    };
    if (!leaves.empty()) {
        std::vector<Entry> level = pack(leaves, leaf_entry, 0);
        for (int depth = 1; level.size() > 1; ++depth) {
            std::vector<Entry> parents = pack(level, same_entry, depth);
            levels.push_back(std::move(level));
            level = std::move(parents);
        }
    }
    if (!nodes.empty()) {
        // The last node made is the root.
        const std::int64_t root_old = nodes.back().no;
        const int tree_depth = nodes.back().depth;
        auto renumber = [&](std::int64_t no) { return no == root_old ? 1 : no; };
        exec(d.db, path, "DELETE FROM " + quoted(rtree + "_node") + "; DELETE FROM " + quoted(rtree + "_parent") +
                             "; DELETE FROM " + quoted(rtree + "_rowid"));
        Stmt ins_node, ins_parent, ins_rowid;
        if (sqlite3_prepare_v2(d.db, ("INSERT INTO " + quoted(rtree + "_node") + " VALUES (?, ?)").c_str(), -1, &ins_node.s, nullptr) ||
            sqlite3_prepare_v2(d.db, ("INSERT INTO " + quoted(rtree + "_parent") + " VALUES (?, ?)").c_str(), -1, &ins_parent.s, nullptr) ||
            sqlite3_prepare_v2(d.db, ("INSERT INTO " + quoted(rtree + "_rowid") + " VALUES (?, ?)").c_str(), -1, &ins_rowid.s, nullptr))
            fail(d.db, path, "cannot prepare the inserts");
        // The leaf of each feature, written in the order of the ids once the nodes are (rows
        // appended to the _rowid table, kRowidBatch a statement, rather than put all over it).
        std::vector<std::uint32_t> leaf_of(ids + 1, 0);
        constexpr int kRowidBatch = 100;
        Stmt ins_rowids;
        {
            std::string sql = "INSERT INTO " + quoted(rtree + "_rowid") + " VALUES (?, ?)";
            for (int i = 1; i < kRowidBatch; ++i) sql += ", (?, ?)";
            if (sqlite3_prepare_v2(d.db, sql.c_str(), -1, &ins_rowids.s, nullptr)) fail(d.db, path, "cannot prepare the inserts");
        }
        std::vector<unsigned char> blob(static_cast<std::size_t>(node_size));
        auto step = [&](Stmt& st, const char* what) {
            if (sqlite3_step(st.s) != SQLITE_DONE) fail(d.db, path, what);
            sqlite3_reset(st.s);
        };
        for (const Node& node : nodes) {
            std::fill(blob.begin(), blob.end(), 0);
            const std::int64_t no = renumber(node.no);
            if (no == 1) put16(blob.data(), unsigned(tree_depth));
            put16(blob.data() + 2, unsigned(node.end - node.begin));
            unsigned char* p = blob.data() + 4;
            for (std::size_t c_at = node.begin; c_at < node.end; ++c_at) {
                const Entry e = node.depth == 0 ? leaf_entry(leaves[c_at]) : levels[std::size_t(node.depth - 1)][c_at];
                const std::int64_t id = node.depth == 0 ? e.id : renumber(e.id);
                put64(p, id);
                putf(p + 8, e.minx);
                putf(p + 12, e.maxx);
                putf(p + 16, e.miny);
                putf(p + 20, e.maxy);
                p += cell;
                if (node.depth == 0) {
                    leaf_of[std::size_t(id)] = std::uint32_t(no);
                    continue;
                }
                sqlite3_bind_int64(ins_parent.s, 1, id);
                sqlite3_bind_int64(ins_parent.s, 2, no);
                step(ins_parent, "parent insert");
            }
            sqlite3_bind_int64(ins_node.s, 1, no);
            sqlite3_bind_blob(ins_node.s, 2, blob.data(), node_size, SQLITE_TRANSIENT);
            step(ins_node, "node insert");
        }
        std::vector<std::int64_t> ids;
        ids.reserve(kRowidBatch);
        for (std::size_t id = 1; id < leaf_of.size(); ++id) {
            if (leaf_of[id] == 0) continue;  // empty geometry: not indexed
            ids.push_back(std::int64_t(id));
            const bool last = id + 1 == leaf_of.size();
            if (ids.size() < std::size_t(kRowidBatch) && !last) continue;
            Stmt& st = ids.size() == std::size_t(kRowidBatch) ? ins_rowids : ins_rowid;
            for (std::size_t k = 0; k < ids.size(); ++k) {
                if (&st == &ins_rowid) {
                    sqlite3_bind_int64(st.s, 1, ids[k]);
                    sqlite3_bind_int64(st.s, 2, leaf_of[std::size_t(ids[k])]);
                    step(st, "rowid insert");
                    continue;
                }
                sqlite3_bind_int64(st.s, int(2 * k + 1), ids[k]);
                sqlite3_bind_int64(st.s, int(2 * k + 2), leaf_of[std::size_t(ids[k])]);
            }
            if (&st == &ins_rowids) step(st, "rowid insert");
            ids.clear();
        }
    }

    // Declare the extension and keep the index in step with later edits (GeoPackage 1.2).
    const std::string T = quoted(table), G = quoted(geom), I = quoted(fid), R = quoted(rtree);
    const std::string vals = "NEW." + I + ", ST_MinX(NEW." + G + "), ST_MaxX(NEW." + G + "), ST_MinY(NEW." + G +
                             "), ST_MaxY(NEW." + G + ")";
    auto trig = [&](const std::string& suffix) { return quoted(rtree + "_" + suffix); };
    exec(d.db, path,
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
    exec(d.db, path, "COMMIT");
}

}  // namespace carto
