// Bulk loading of a GeoPackage R-tree (see gpkg_rtree.cpp).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

struct sqlite3;

namespace carto {

struct BoxD {
    double minx, maxx, miny, maxy;  // minx > maxx: empty geometry
};

// A box as the R-tree keeps it: floats that contain the double bounds (half the memory of
// a BoxD for the millions of boxes a drawing has).
struct BoxF {
    float minx, maxx, miny, maxy;  // minx > maxx: empty geometry
};
BoxF rtree_box(const BoxD& b);
// A name quoted for SQL ("a""b").
std::string sql_name(const std::string& s);

// An entry of an R-tree node: a feature id (leaves) or a node number, and its box.
struct RtreeEntry {
    std::int64_t id;
    float minx, maxx, miny, maxy;
};

// The spatial index of `table`.`geom` of a GeoPackage, written while its features are: the
// features' boxes come in batches (add), each packed into leaves of its own (sort-tile-
// recursive) that are written at once with the _rowid rows of their features; finish packs
// the levels above the leaves, writes the root and declares the extension with its triggers.
// Every call runs on the database `db` (open, in a transaction; not necessarily the same
// connection each time). `path` names the output in errors.
class RtreeLoader {
public:
    RtreeLoader(sqlite3* db, const std::string& path, const std::string& table, const std::string& geom);
    // The features first_id, first_id + 1, ... with these boxes (empty ones are not indexed).
    void add(sqlite3* db, const BoxF* boxes, std::size_t n, std::int64_t first_id);
    void finish(sqlite3* db, const std::string& fid);

private:
    std::string path_, table_, geom_, rtree_;
    int node_size_ = 0, fanout_ = 0;
    std::vector<RtreeEntry> leaves_;  // the leaf nodes: number and box
    std::int64_t next_no_ = 2;   // 1 is the root's
};

// Builds the spatial index of `table`.`geom` whose features have ids 1..boxes.size() in
// order, in a GeoPackage that GDAL has written and closed without one. Besides the boxes it
// needs 8 bytes a feature (the index of millions of hatches is built within the memory a run
// has at its peak).
void bulk_load_rtree(const std::string& path, const std::string& table, const std::string& geom,
                     const std::string& fid, const std::vector<BoxF>& boxes);
// The last boxes of a loader's layer (features first_id, ...) and its finish, in one
// transaction of a connection of its own to the file at `path` (closed by GDAL and SQLite).
void load_rtree(const std::string& path, RtreeLoader& loader, const BoxF* boxes, std::size_t n, std::int64_t first_id,
                const std::string& fid);

}  // namespace carto
