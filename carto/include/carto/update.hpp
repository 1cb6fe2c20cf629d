// The edit loop (rockhatch update): a run's GeoPackage keeps, per face, a fingerprint of every
// input the face's drawing depends on; `update` redraws exactly the faces whose fingerprint
// changed, appeared or went away, and replaces their features in one transaction, leaving
// every other feature (hand edits included) as it is.
//
// A face's fingerprint is a digest (128 bits, not cryptographic) of:
// - the run's plan: program version, working CRS, the DEM's grid, the style (and the bytes of
//   its script), its parameters, scale, seed, relief radius, the partition's options;
// - the face as digitised (rings, id, orientation, density, anchor: its borders before they
//   are snapped to its neighbours' and labelled by the lines), and within its box grown by
//   the context margin (tile_context_margin: the style's reach, the terrain kernels, the
//   snap) what the other faces and the labelled lines put there, as digitised: the segments
//   of their rings and of the lines in that box, whether each corner of the box lies in the
//   faces, their ids and controls (snapping and labelling are local: from these follow the
//   borders as drawn);
// - the DEM's cells (and the --slope / --roughness cells) as their files hold them, in
//   blocks of 8 x 8 cells, under that box grown by the halo (tile_halo_cells: the relief
//   radius or the style's reach) and two cells more, the box taken to the file's CRS by
//   its outline (so no raster is reprojected to fingerprint the faces).
// These are the inputs a tile of a tiled run reads to draw a face exactly as the whole run
// does (carto/tiles.hpp); the bounds are generous, so a face whose fingerprint is unchanged
// draws the same bytes.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "carto/output.hpp"
#include "carto/partition.hpp"
#include "carto/pipeline.hpp"
#include "carto/plan.hpp"
#include "carto/progress.hpp"
#include "carto/raster.hpp"

namespace carto {

// Whether a run of this plan keeps fingerprints in its GeoPackage: a GeoPackage output, and
// a drawing made of faces alone (no terrain style, whose elements depend on every face, no
// crest ornaments, drawn per ridge).
bool keeps_fingerprints(const Plan& plan);

// The rasters the fingerprints digest: the --dem, --slope and --roughness files as they hold
// them (their own grids and CRSs; slope and roughness when given), and the working grid.
struct FingerprintRasters {
    RasterInfo grid;  // the working grid (WorkingGrid::grid)
    Raster dem;
    std::optional<Raster> slope, roughness;
};
FingerprintRasters read_fingerprint_rasters(const Options& o, const WorkingGrid& grid);

// The fingerprints of the faces the plan draws (those whose anchor lies in its window, or
// all), in partition order, from the partition as digitised (PartitionOptions::as_digitised:
// not snapped, not labelled; its orientations and densities as given) and the rasters' files.
Fingerprints face_fingerprints(const Plan& plan, const Partition& digitised, const FingerprintRasters& rasters);
// The partition as digitised, for face_fingerprints.
Partition read_digitised(const Options& o, const std::string& working_wkt);
// Sets fp.boxes: per face id, the box of its parts in `drawn` (the partition as a run reads
// it, snapped) that the plan draws; empty for an id none of whose parts is drawn there.
void set_drawn_boxes(Fingerprints& fp, const Plan& plan, const Partition& drawn);

struct UpdateOptions {
    // Redraw every face and drop every feature (hand edits included); also accepts a file
    // of another version, CRS or style.
    bool reset = false;
    // Faces redrawn whatever their fingerprint (the faces selected in QGIS).
    std::vector<std::int64_t> faces;
    // A GeoPackage to write what the update replaces to, so that restore_faces can undo it
    // (the QGIS plugin's Undo); "" none.
    std::string undo;
};

struct UpdateReport {
    std::size_t faces = 0;      // faces of the plan (in its window)
    std::size_t redrawn = 0;    // faces drawn again (changed, appeared, asked for)
    std::size_t appeared = 0;   // of which new since the file was written
    std::size_t removed = 0;    // faces gone: their features removed
    std::size_t deleted = 0;    // features removed
    std::size_t written = 0;    // features written
    std::size_t kept = 0;       // features of redrawn faces drawn again as they were (left in place)
    std::vector<std::int64_t> redrawn_ids, removed_ids;
    double seconds = 0;
    std::string crs;
    std::vector<std::string> notes;
};

// Brings the plan's GeoPackage output (written by a run of the same plan) up to date with
// the inputs, and rewrites its SVG, PNG and PDF outputs from the updated layers. Refuses
// (Error Usage) a file of another program version, CRS or style unless reset; a file
// without fingerprints (a tiled run's, an older version's); a plan that keeps none
// (keeps_fingerprints). An error or a cancellation leaves the GeoPackage as it was.
UpdateReport update(const Plan& plan, const UpdateOptions& u, const Progress& progress = {});
// The same from the options: their plan, the outputs being the files to update.
UpdateReport update(const Options& o, const UpdateOptions& u, const Progress& progress = {});

}  // namespace carto
