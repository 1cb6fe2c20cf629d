// The run plan: what a run was asked for (Options, the command line's values), resolved once
// into typed values (Plan): the style and the rock style that hatches the faces, their
// parameters in ground units, the crest ornaments' band and exemplar, the outputs and their
// formats. Every stage of the pipeline (carto/pipeline.hpp) and a tile of a tiled run
// (carto/tiles.hpp) take the plan; none re-reads or re-resolves an option. The command, the
// Python module, the QGIS plugin and `rockhatch tiles` build the same plan.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "carto/crest.hpp"
#include "carto/partition.hpp"
#include "carto/publish.hpp"
#include "carto/styles.hpp"

namespace carto {

// More worker threads than this is a typo, not a machine (each thread holds its own buffers).
inline constexpr unsigned kMaxThreads = 1024;

struct Options {
    std::string dem;                     // --dem
    PartitionOptions partition;          // --partition and its layer / field options
    std::string slope, roughness;        // optional rasters (percent, 0..1)
    // --mask: with --partition auto, rock only inside this polygon layer's polygons (land
    // cover; an OSM layer counts only its natural=bare_rock polygons).
    std::string mask;
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
    std::vector<std::string> outputs;    // .gpkg, .svg, .png, .pdf, .mbtiles or DIR/ (vector tiles)
    std::string page;                    // --page for a .pdf output ("" = fitted to the drawing)
    std::string zoom;                    // --zoom for vector tiles ("" = kDefaultZoom)
    bool overwrite = false;
    int png_pixels = 1600;
    bool spatial_index = true;           // R-tree in the GeoPackage
    // Hatch only the faces whose anchor (a point inside the face, face_anchor) lies in this
    // half-open box; a tiled run (carto/tiles.hpp) reads only the data near its box.
    std::optional<tex::BBox> window;
};

enum class OutputFormat { GeoPackage, Svg, Png, Pdf, VectorTiles };
struct Output {
    std::string path;
    OutputFormat format;
};

// Half-side, in millimetres on paper, of the square over which the fall line and the shade
// are averaged for the styles (ControlFields::fall_line, ::shade): the map's scale of detail
// (10 m at 1:10000, 25 m at 1:25000), finer than a coarse cell of the styles.
inline constexpr double kFieldSmoothingMm = 1.0;

inline constexpr const char* kDefaultZoom = "12-16";

struct Plan {
    // The options as given: the stages read their paths, the window, seed and thread count.
    Options options;
    // The style the options select (Options::custom_style, else the built-in by name).
    Style style;
    // The style whose program hatches the rock faces, and its parameters in ground units:
    // `style` with the options' parameters, or for a terrain style the default rock style at
    // its defaults (the terrain style's own parameters are terrain_params).
    StyleInfo rock;
    ParamValues rock_params;
    ParamValues terrain_params;
    // The crest ornaments' band height (ground units) and exemplar, when the run draws them
    // (--crest-ornament, or a style that draws crests).
    std::optional<double> crest_band;
    std::shared_ptr<const CrestExemplar> crest_exemplar;
    std::vector<Output> outputs;
    // The page of the PDF outputs (--page); unset: fitted to the drawing.
    std::optional<PageSize> page;
    // The zoom levels of the vector-tile outputs (--zoom, kDefaultZoom when unset).
    ZoomRange zoom;
    // kFieldSmoothingMm in ground units.
    double field_smoothing = 0;

    bool terrain_style() const { return bool(style.terrain); }
};

// How much make_plan asks of the options: a run needs --dem, --partition and outputs; a
// drawing made in memory (hatch on a Prepared, a library call) needs none of them.
enum class PlanFor { Run, Drawing };

// Resolves and checks the options (every check that needs no file other than the crest
// exemplar, which is read and tried here: a bad input is refused before any work). Throws
// carto::Error with the option's name.
Plan make_plan(const Options& o, PlanFor use = PlanFor::Run);
// The outputs as check_outputs sees them against every file the run reads (DEM, partition,
// slope, roughness, style script, crest exemplar); make_plan calls it, front ends that read a
// style script call it before.
void check_files(const Options& o);

}  // namespace carto
