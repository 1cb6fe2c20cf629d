// Bulk loading of a GeoPackage R-tree (see gpkg_rtree.cpp).
#pragma once

#include <string>
#include <vector>

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

// Builds the spatial index of `table`.`geom` whose features have ids 1..boxes.size() in
// order, in a GeoPackage that GDAL has written and closed without one. Besides the boxes it
// needs 8 bytes a feature (the index of millions of hatches is built within the memory a run
// has at its peak).
void bulk_load_rtree(const std::string& path, const std::string& table, const std::string& geom,
                     const std::string& fid, const std::vector<BoxF>& boxes);

}  // namespace carto
