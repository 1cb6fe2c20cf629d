// A partition of the rock areas from the DEM alone (issue 6): the rock mask, the ridge and
// thalweg network, the faces between them with labelled borders, and a hatching orientation
// and density per face, in the data model `rockhatch --partition` reads.
//
// Everything runs on the DEM's grid (in a projected working CRS) and is deterministic: no
// random numbers, no threads, ties broken by cell index.
//
//  1. rock mask: cells whose slope and roughness (averaged over about 25 m) reach the
//     thresholds, optionally inside a user's polygon layer; closed over about 15 m by a disc
//     (crests and couloir floors are less steep than the walls); rock specks smaller than the
//     minimum area are dropped and enclosed gaps smaller than it are filled; then, within the
//     width of that window and closing of the edge, the slope and roughness over about 10 m (3 cells at least)
//     decide, so the edge lies on the terrain's breaks of slope (a cliff's foot or top), and
//     the same clean-up runs over a disc of one cell;
//  2. thalwegs: contributing area by multiple flow directions on the smoothed DEM
//     (depressions up to `max_fill` deep crossed by priority flood); a line starts where the
//     area reaches `thalweg_area` and the flow converges, and follows its D8 path down;
//     ridges: the same on the inverted DEM with `ridge_area`. Short branches and branches
//     alongside a bigger line are pruned. Thalweg heads are prolonged up their couloir floor
//     and ridge feet down their crest (cross-profile concavity) until they meet a line of the
//     other kind, leave the rock or reach the grid's edge, so that lines split the rock instead
//     of dangling in it (a head in a hole of the rock first walks into the rock); where the
//     crest or floor fades the walk finishes by steepest descent (ascent);
//  3. faces: the rock cells cut by the line cells (4-connected pieces), line cells given to a
//     neighbouring face, faces smaller than the minimum area merged into the neighbour they
//     share most border with;
//  4. polygons: the borders between faces are traced once as chains of cell edges, simplified
//     (Douglas-Peucker, half a cell) and shared by the two faces, so faces tile the mask
//     exactly; chains are labelled piece by piece: ridge or valley where they run along ridge
//     or thalweg cells for at least 40 m (3 cells), else other; the rock outline too (an
//     arête is often the edge of the steep area), unless `label_outline` is off; the steepest
//     finish of a ridge labels no border (it cuts a flank, not an arête);
//  5. per face: orientation from the mean fall line, density from 1 - mean hillshade.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "carto/partition.hpp"
#include "carto/progress.hpp"
#include "carto/raster.hpp"
#include "carto/terrain.hpp"

namespace carto {

struct ExtractOptions {
    std::string dem;               // DEM path, read when `raster` is not set
    std::optional<Raster> raster;  // or an in-memory DEM (any CRS; geographic is reprojected)
    std::string mask;              // optional polygon layer: rock only inside its polygons
    double min_slope = 70;         // percent (70 % = 35 degrees)
    double min_roughness = 0.001;  // vector ruggedness 0..1
    double min_area_mm2 = 16;      // on paper at 1:scale: specks, gaps and faces below it
    double scale = 10000;          // map scale denominator
    double thalweg_area = 6000;    // m2 of contributing area that starts a thalweg (>= 50 cells)
    double ridge_area = 20000;     // m2 of "inverted" contributing area that starts a ridge (>= 100 cells)
    double smooth = 10;            // m: smoothing of the DEM the flow runs on (0: none)
    double converge = 1.2;         // a line starts where the area is >= this x that beside it
    bool extend_ridges = true;     // prolong ridge feet down their crest to a thalweg
    bool label_outline = true;     // label rock-outline borders along a ridge / thalweg too
    double max_fill = 30;          // m: deeper depressions (and prominences) stop the flow
    double simplify = 0.8;         // Douglas-Peucker tolerance of the borders, in cells (above
                                   // 0.71, half a cell's diagonal, one-cell stair steps go)
    int smooth_rounds = 3;         // corner-cutting passes that round the generalised borders
    bool terrain_edge = true;      // the mask's edge on the terrain (step 1), not the wide mean's
    std::string what = "--dem";    // how error messages name the DEM
};

// The extraction's tuning options as the command line spells them, one table for
// `rockhatch partition` and `rockhatch tiles --partition auto`: --mask, --min-slope,
// --min-roughness, --min-area, --thalweg-area, --ridge-area, --max-fill, --smooth, --converge,
// --simplify (each with a value) and the flags --no-ridge-extension, --no-outline-labels,
// --smooth-edge (the mask's edge where the wide mean puts it: terrain_edge off).
struct ExtractOptionName {
    std::string name;
    bool takes_value;
};
const std::vector<ExtractOptionName>& extract_option_names();

// Sets the option `name` of the table above from its command-line value (ignored for a flag);
// returns false when `name` is not in the table. Throws Error(Usage) when a number does not
// parse (the ranges are checked by extract_partition).
bool set_extract_option(ExtractOptions& o, const std::string& name, const std::string& value);

struct ExtractResult {
    Partition partition;          // faces (orientation and density set) and labelled lines
    Terrain terrain;              // of the working DEM
    Raster rock;                  // the rock mask on the working grid: 1 rock, 0 not, NaN NoData
    Raster faces;                 // face index per cell (-1 outside the faces)
    std::vector<int> line_cells;  // per cell: 0 none, 1 ridge, 2 thalweg (whole DEM)
    // Per line of `partition.lines`: the face numbers on its two sides (the face of a
    // partition face is its id - 1; -1: outside the rock), e.g. to keep the borders of some
    // faces only (a tile of a tiled extraction).
    std::vector<std::array<int, 2>> line_faces;
    // The traced ridge and thalweg network inside the rock, whether or not it borders faces
    // (lines ending inside a face do not cut it), simplified to about a cell.
    std::vector<LabelledLine> network;
    std::vector<std::string> notes;
};

// The ranges of the numbers (Error(Usage) naming the option); extract_partition checks them first.
void check_extract_options(const ExtractOptions& o);

// Throws carto::Error: InputMissing (no such DEM or mask), NoCrs (DEM or mask without a
// CRS), BadLayer (all-NoData DEM, mask without polygons, no rock under the thresholds),
// Usage (bad option value), Cancelled (progress returned false).
ExtractResult extract_partition(const ExtractOptions& o, const Progress& progress = {});

// The outputs of `rockhatch partition` (-o, and --png when not empty) against its inputs
// (the DEM path, the mask): check_outputs, before any work.
void check_extract_files(const ExtractOptions& o, const std::string& out, const std::string& png, bool overwrite);

// Writes layers `faces` (polygons: id, fall_line = azimuth of the face's mean fall line in
// degrees, shade = 1 - its mean hillshade, area in m2), `lines` (kind = ridge / valley /
// other) and `mask` (the union of the faces) to a GeoPackage, atomically (temporary file
// renamed at the end) and with a fixed timestamp, so the same partition gives the same bytes.
// fall_line and shade are what the faces were derived with, for reading: rockhatch does not
// take them as given, so hatching the file follows the terrain exactly as `--partition auto`
// does (the print style's strokes follow the local fall line, not one direction per face).
// With `fixed_controls` they are written as `orientation` and `density` instead, the
// attributes rockhatch reads as given: each face is then hatched in its one direction.
// With `network`, also a layer `network` (kind = ridge / valley) of the traced lines.
void write_partition_gpkg(const Partition& p, const std::string& path, bool overwrite,
                          const std::vector<LabelledLine>* network = nullptr, bool fixed_controls = false);

// A PNG preview `pixels` wide: the hillshade, each face tinted, its borders drawn in red
// (ridge), blue (valley) or grey (other). Written atomically.
void write_partition_png(const ExtractResult& r, const std::string& path, int pixels);

// Azimuth in degrees (0 = north, clockwise, in [0, 360)) of a math angle (0 = east, counter-clockwise).
double azimuth_degrees(double math_angle);

}  // namespace carto
