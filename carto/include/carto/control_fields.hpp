// Control fields (seed 5.3.1): functions from a point of the plane to a value. A style is a
// controlled arrangement: it receives the fields and reads them only inside and at the border
// of the face it hatches, which is what makes edits local and tiling exact.
#pragma once

#include <vector>

#include "carto/raster.hpp"
#include "carto/terrain.hpp"
#include "libtex/fields.hpp"

namespace carto {

struct Partition;  // carto/partition.hpp

// libtex's fields: closed forms, grids, face-wise constants and their compositions.
using Field = tex::Field;

// Bilinear, NoData-aware raster field (tex::sample_grid on the raster's own cells, which
// must outlive the field), mapped through value -> (value - offset) / range. Its kind is
// "raster".
Field raster_field(const Raster& r, double offset = 0.0, double range = 1.0);
// The same on a shared raster, which the field keeps alive.
Field raster_field(std::shared_ptr<const Raster> r, double offset = 0.0, double range = 1.0);
// Face-wise constant field: the value of the face containing the point (NaN outside all
// faces). values[i] belongs to p.faces[i] (a tex::RegionField on copies of the regions).
Field face_field(const Partition& p, std::vector<double> values);
// Closed-form fields are plain lambdas; a constant one for convenience.
Field constant_field(double v);


// Relief of each cell within its neighbourhood: (z - min) / (max - min) over the square of
// half-side `radius` (ground units) around it, 0.5 where that square is flat; NaN where z is.
// A local field: editing the elevation somewhere changes it within `radius` only.
Raster local_relief(const Raster& dem, double radius);

// NoData-aware mean over the (2 radius + 1)^2 window of cells around each cell of a
// width x height grid (row-major), by running sums along rows then columns; NaN where the
// cell itself is NoData.
std::vector<float> box_mean(const std::vector<float>& v, int width, int height, int radius);

// The fall line smoothed at map scale: the downhill gradient (slope times the direction of
// the aspect) averaged over the square of half-side `radius` (ground units) around each
// cell, read bilinearly as an angle (radians, 0 = east, counter-clockwise); NaN where that
// mean vanishes or the DEM has no value. Averaging vectors, not angles, keeps a surface
// that turns smoothly free of jumps. Local: an edit of the DEM moves it within `radius`.
Field fall_line_field(const Terrain& t, double radius);
// 1 - hillshade averaged the same way (0 lit, 1 in full shade): the value a tone curve
// turns into ink.
Field shade_field(const Terrain& t, double radius);
// The elevation averaged twice over the square of half-side `radius` (at least one cell):
// smooth enough for its second differences to read crests and couloirs, not their raster steps.
Field elevation_field(const Terrain& t, double radius);

// Fills in the orientation (the mean fall line: downhill aspect weighted by slope) and the
// density (1 - mean hillshade) of the faces that lack them, from samples inside each face.
// Returns how many orientations and densities were derived.
std::pair<std::size_t, std::size_t> derive_face_controls(Partition& p, const Terrain& t);

}  // namespace carto
