// The Chapter 5 pipeline: a chain of stages, each taking the run plan (carto/plan.hpp) and
// the previous stage's product: prepare (DEM -> terrain, partition), control_fields, hatch
// (the drawing), write_outputs. carto::run is the whole chain; the rockhatch command, the
// Python module and the QGIS plugin all call it, and a tile of a tiled run (carto/tiles.hpp)
// runs the same stages on its part.
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
#include "carto/plan.hpp"
#include "carto/publish.hpp"
#include "carto/progress.hpp"
#include "carto/styles.hpp"
#include "carto/terrain.hpp"

namespace carto {

struct Stats {
    std::size_t faces = 0;
    std::size_t hatches = 0;
    std::size_t crests = 0;           // ridge lines drawn with a crest ornament
    double seconds = 0;
    std::string crs;                  // working CRS name
    std::vector<std::string> notes;   // what was repaired, derived or assumed
    TileStats tiles;                  // of the vector-tile output, when there is one
};

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
    // The fingerprints of the faces drawn, when the plan keeps them (carto/update.hpp).
    std::optional<Fingerprints> fingerprints;
};

// Reads a DEM for the pipeline: refuses one without valid cells, and reprojects a
// geographic DEM to the UTM zone of its centre (notes say so).
Raster load_dem(const std::string& path, std::vector<std::string>* notes = nullptr);
// Orientation and density of every face of p.partition, derived from p.terrain where the
// partition gives none (and which faces follow the fall line: those without an orientation
// given, every face of an `extracted` partition), with notes.
void resolve_face_controls(Prepared& p, bool extracted);
// Refuses a --roughness raster with values outside 0..1 (NoData aside).
void check_roughness(const Raster& r, const std::string& path);

// ---- The stages ----

// 1. Reads the DEM (reprojected to a projected working CRS when geographic), the optional
// rasters and the partition (read, extracted from the DEM, or none); the faces' fingerprints
// when the plan keeps them (keeps_fingerprints).
Prepared prepare(const Plan& plan, const Progress& progress = {});
// 2. The control fields the style reads (thesis 5.3): face-wise orientation and density, the
// relief, roughness and slope, the fall line and the shade smoothed at map scale.
ControlFields control_fields(const Prepared& p, const Plan& plan);
// The face id of the elements a terrain style draws outside the faces.
inline constexpr std::int64_t kTerrainFaceId = -1;
// The area whose rock faces a terrain style drawn in the plan's window reads (their hatches
// are obstacles to its elements): the window, cut to the DEM's extent, grown by the style's
// reach for a DEM of that cell. nullopt without a window or a terrain style.
std::optional<tex::BBox> terrain_read_area(const Plan& plan, const tex::BBox& dem_extent, double cell);
// 3. Hatches the faces (in parallel, deterministic): all of them, or those whose anchor
// (face_anchor) lies in the plan's window; draws the crest ornaments when planned; a terrain
// style then draws its elements around them (those the window owns, exactly as a whole run
// draws them: the faces within terrain_read_area are hatched too, as obstacles, and not
// returned), as one more entry of Drawing::faces with kTerrainFaceId.
Drawing hatch(const Prepared& p, const Plan& plan, const Progress& progress = {});
// Hatches the faces of these indices, in this order (and the crest ornaments of the ridges
// whose ridge_anchor lies in the plan's window, or of every ridge).
Drawing hatch(const Prepared& p, const Plan& plan, const std::vector<int>& faces, const Progress& progress = {});
// 4. Writes the drawing to every output of the plan (the PNG over the terrain's hillshade).
void write_outputs(const Drawing& d, const Prepared& p, const Plan& plan, const Progress& progress = {});
// The run plan of one zoom level of a vector-tile output: the plan's options at the scale of
// zoom `zoom` at `latitude` (zoom_scale), without outputs.
Plan zoom_plan(const Plan& plan, int zoom, double latitude);
// Draws every zoom level of plan.zoom at its own scale (prepare and hatch, as a run) and
// writes the plan's vector-tile outputs; adds the hatches of every level to counts->hatches
// and sets counts->faces to the finest level's. Nothing when the plan has no such output.
TileStats write_zoom_tiles(const Plan& plan, const Progress& progress = {}, Stats* counts = nullptr);
// The whole chain.
Stats run(const Plan& plan, const Progress& progress = {});

// ---- Library entries: the plan made from the options, then the stage ----
Prepared prepare(const Options& o, const Progress& progress = {});  // PlanFor::Drawing
Drawing hatch(const Prepared& p, const Options& o, const Progress& progress = {});  // PlanFor::Drawing
Stats run(const Options& o, const Progress& progress = {});  // PlanFor::Run

}  // namespace carto
