// Face polygons from the border chains: the rings of each face, its shells and holes in
// world coordinates, and their OGR form (step 4 of carto/extract.hpp).
#pragma once

#include <ogr_geometry.h>

#include <memory>
#include <vector>

#include "borders.hpp"
#include "carto/raster.hpp"

namespace carto::extraction {

struct OrientedChain {
    int chain;
    bool reversed;
};

// The rings of one face, face on the right of each chain in grid coordinates (so outer rings
// come out counter-clockwise in the world, holes clockwise). At a corner where the face
// touches itself diagonally, the ring turns to keep the face's two cells joined, which makes
// shell and hole touch at that point (valid) rather than a ring cross itself.
std::vector<std::vector<Point>> face_rings(const std::vector<Chain>& chains,
                                           const std::vector<int>& mine, int f);

struct FacePolygon {
    std::vector<Point> outer;
    std::vector<std::vector<Point>> holes;
};

std::unique_ptr<OGRPolygon> to_ogr(const FacePolygon& fp);

// The polygons of face f in world coordinates: one shell per ring of positive area, each
// hole given to the shell containing it.
std::vector<FacePolygon> face_polygons(const std::vector<Chain>& chains,
                                       const std::vector<int>& mine, int f, const Raster& grid);

}  // namespace carto::extraction
