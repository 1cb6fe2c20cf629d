// The Chapter 5 pipeline as one library function: the rockhatch command, the Python module
// and the QGIS plugin all call carto::run.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "carto/output.hpp"
#include "carto/partition.hpp"
#include "carto/terrain.hpp"

namespace carto {

// More worker threads than this is a typo, not a machine (each thread holds its own buffers).
inline constexpr unsigned kMaxThreads = 1024;

struct Options {
    std::string dem;                     // --dem
    PartitionOptions partition;          // --partition and its layer / field options
    std::string slope, roughness;        // optional rasters (percent, 0..1)
    std::string style;                   // "" = default style
    // A style defined outside the built-ins (a Python style script); replaces `style`.
    std::shared_ptr<const Style> custom_style;
    // The style script custom_style was read from (--script): an input no output may replace.
    std::string style_file;
    std::map<std::string, double> params;  // --param name=value
    // --crest-ornament: draw every ridge line as a synthesised band (carto/crest.hpp), from the
    // project's exemplar (kDefaultCrest) or an SVG file; unset: no crest ornaments.
    std::optional<std::string> crest_ornament;
    // --crest-height: height of that band, mm on paper (kDefaultCrestHeightMm when unset).
    std::optional<double> crest_height_mm;
    double scale = 10000;                // --scale (1:scale)
    // Half-side (ground units) of the square over which elevation is normalised into the
    // styles' height field (--relief-radius): local, so an edit moves the output nearby only.
    double relief_radius = 1000;
    std::uint64_t seed = 0;              // --seed
    unsigned threads = 0;                // --threads (0 = all; at most kMaxThreads)
    std::vector<std::string> outputs;    // .gpkg, .svg, .png
    bool overwrite = false;
    int png_pixels = 1600;
    bool spatial_index = true;           // R-tree in the GeoPackage
    // Hatch only the faces whose anchor (a point inside the face, face_anchor) lies in this
    // half-open box; a tiled run (carto/tiles.hpp) reads only the data near its box.
    std::optional<tex::BBox> window;
};

struct Stats {
    std::size_t faces = 0;
    std::size_t hatches = 0;
    std::size_t crests = 0;           // ridge lines drawn with a crest ornament
    double seconds = 0;
    std::string crs;                  // working CRS name
    std::vector<std::string> notes;   // what was repaired, derived or assumed
};

// Progress: fraction in [0, 1] and a stage name; return false to cancel.
using Progress = std::function<bool(double, const std::string&)>;

// The data a style runs on, once read and prepared.
struct Prepared {
    Terrain terrain;  // in the working CRS
    Partition partition;
    // Elevation within its neighbourhood (Options::relief_radius), the styles' height field.
    Raster relief;
    // Per face: true when the partition gave no orientation and derive_face_controls put in
    // the face's mean fall line; strokes there may follow the local fall line instead.
    std::vector<bool> orientation_derived;
    std::vector<std::string> notes;
    // The whole DEM's extent in the working CRS when the terrain is a window of it (a tile of
    // a tiled run); empty: the terrain's own.
    tex::BBox extent;
    // A tile of a tiled run given the user's --window: its terrain is framed by what it drew,
    // as the whole run in that window is, not by `extent`.
    bool user_window = false;
};

// Half-side, in millimetres on paper, of the square over which the fall line and the shade
// are averaged for the styles (ControlFields::fall_line, ::shade): the map's scale of detail
// (10 m at 1:10000, 25 m at 1:25000), finer than a coarse cell of the styles.
inline constexpr double kFieldSmoothingMm = 1.0;

// Reads a DEM for the pipeline: refuses one without valid cells, and reprojects a
// geographic DEM to the UTM zone of its centre (notes say so).
Raster load_dem(const std::string& path, std::vector<std::string>* notes = nullptr);
// The style the options select: custom_style, else the built-in named by `style`.
Style selected_style(const Options& o);
// The height of the crest ornaments' band (ground units) when the run draws them
// (--crest-ornament or a style that draws crests): --crest-height, else the style's
// crest_band, else kDefaultCrestHeightMm.
std::optional<double> crest_band(const Options& o);
// Validates the options that need no file (style, parameters, scale, outputs).
void validate(const Options& o);
// The outputs as check_outputs sees them against every file the run reads (DEM, partition,
// slope, roughness, style script); validate calls it, front ends that read a style script
// call it before.
void check_files(const Options& o);
// Orientation and density of every face of p.partition, derived from p.terrain where the
// partition gives none (and which faces follow the fall line), with notes.
void resolve_face_controls(Prepared& p, const Options& o);
// Refuses a --roughness raster with values outside 0..1 (NoData aside).
void check_roughness(const Raster& r, const std::string& path);
// Reads the DEM (reprojected to a projected working CRS when geographic), the optional
// rasters and the partition.
Prepared prepare(const Options& o, const Progress& progress = {});
// The face id of the elements a terrain style draws outside the faces.
inline constexpr std::int64_t kTerrainFaceId = -1;
// The area whose rock faces a terrain style drawn in Options::window reads (their hatches
// are obstacles to its elements): the window, cut to the DEM's extent, grown by the style's
// reach for a DEM of that cell. nullopt without a window or a terrain style.
std::optional<tex::BBox> terrain_read_area(const Options& o, const tex::BBox& dem_extent, double cell);
// Hatches the faces (in parallel, deterministic): all of them, or those whose anchor
// (face_anchor) lies in Options::window; draws the crest ornaments when asked; a terrain
// style then draws its elements around them (those Options::window owns, exactly as a whole
// run draws them: the faces within terrain_read_area are hatched too, as obstacles, and not
// returned), as one more entry of Drawing::faces with kTerrainFaceId.
Drawing hatch(const Prepared& p, const Options& o, const Progress& progress = {});
// Hatches the faces of these indices, in this order (and the crest ornaments of the ridges
// whose ridge_anchor lies in Options::window, or of every ridge).
Drawing hatch(const Prepared& p, const Options& o, const std::vector<int>& faces, const Progress& progress = {});
// Everything: validate, prepare, hatch, write.
Stats run(const Options& o, const Progress& progress = {});

}  // namespace carto
