// Step 4 of carto/extract.hpp: the faces' polygons from their labelled border chains, each
// face generalised as far as it stays a valid polygon above the minimum area.
#pragma once

#include <string>
#include <vector>

#include "borders.hpp"
#include "carto/raster.hpp"
#include "polygons.hpp"

namespace carto::extraction {

struct OutlineOptions {
    double simplify = 1;    // Douglas-Peucker tolerance of the full generalisation, in cells
    int smooth_rounds = 2;  // smoothing rounds of the full generalisation
    double min_area = 0;    // m2 on the ground: no face or hole of a face below it
};

struct Outlines {
    std::vector<std::vector<FacePolygon>> faces;  // per face index, its polygons (one)
    std::string note;  // how many faces kept borders closer to their cell edges ("" when none)
};

// Every chain is first placed at its fullest generalisation (Chain::shapes, level 0). A face
// whose polygon is invalid (two of its borders crossing) or falls under the minimum area
// moves its chains one level back, and the faces across those chains are rebuilt; at the
// last level its chains' ends go back to their cell corners, which gives the face its cell
// edges exactly. `chains` keep the level they end at (Chain::shape()).
Outlines face_outlines(std::vector<Chain>& chains, int nfaces, const BorderPlaces& places,
                       const Raster& grid, const OutlineOptions& o);

}  // namespace carto::extraction
