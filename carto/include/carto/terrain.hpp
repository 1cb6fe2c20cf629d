// Terrain control fields computed from a DEM in a projected CRS (metres).
#pragma once

#include "carto/raster.hpp"

namespace carto {

struct Terrain {
    Raster elevation;  // metres
    Raster slope;      // percent (100 * tan)
    Raster aspect;     // downhill direction, radians, math angle (0 = east, counter-clockwise)
    Raster roughness;  // 0..1: vector ruggedness (dispersion of the surface normals, 3x3)
    Raster hillshade;  // 0..1: illumination from the north-west, 45 degrees high
};

// Slope, aspect, roughness and hillshade by Horn's 3x3 gradient. Cells next to NoData or
// to the raster edge use the available neighbours (edge cells are mirrored); cells whose
// own value is NoData stay NoData.
Terrain compute_terrain(const Raster& dem);

}  // namespace carto
