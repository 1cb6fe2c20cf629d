// Writers: GeoPackage (one LineString layer per hatch family, and a polygon layer "crest"
// for the crest ornaments), SVG (one group per family and a filled group "crest", true
// scale, CRS and bounds in its metadata) and a PNG preview. All writes are atomic:
// to a temporary file in the same folder, renamed at the end.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "carto/crest.hpp"
#include "carto/raster.hpp"
#include "carto/styles.hpp"

namespace carto {

struct FaceHatches {
    std::int64_t face_id;
    std::vector<Hatch> hatches;
};

// What the edit loop (carto/update.hpp) keeps in a hatch GeoPackage: per face, a digest of
// every input its drawing depends on, and the run's own (program version, CRS, style, plan).
struct Fingerprints {
    std::map<std::string, std::string> run;                    // key -> value (kRunKeys)
    std::vector<std::pair<std::int64_t, std::string>> faces;   // face id, fingerprint
    // Per face of `faces` (when given): the box of its parts as drawn (borders snapped; empty
    // for a face snapping left without area), from which update frames the drawing.
    std::vector<tex::BBox> boxes;
};

struct Drawing {
    std::vector<FaceHatches> faces;
    std::string crs_wkt;
    std::string style;
    double scale = 10000;
    tex::BBox bounds;  // extent of the drawing in the working CRS
    // The crest ornaments, when the run asked for them (written as the polygon layer or
    // group "crest", filled); unset: no such layer or group.
    std::optional<std::vector<CrestOrnament>> crests;
    std::vector<std::string> notes;  // what drawing noted (ridges skipped)
    // The faces' fingerprints, written with the GeoPackage (table rockhatch_faces and the
    // metadata items of Fingerprints::run); unset: none (a tile of a tiled run, a terrain style).
    std::optional<Fingerprints> fingerprints;
};

// Whether the drawing's outputs have a layer (group) for the family: the rock families
// always (an empty layer says "none drawn"), the terrain families when a style drew them.
bool has_family(const Drawing& d, Family f);

// `keep_going(fraction written)` is asked every few thousand features; false cancels
// (Error Cancelled, nothing left behind).
void write_gpkg(const Drawing& d, const std::string& path, bool spatial_index = true,
                const std::function<bool(double)>& keep_going = {});
// The faces of a drawing made on demand, for a GeoPackage written while they are drawn:
// face(k, use) draws face k (0 <= k < faces) and hands it to `use`, on any thread (on the
// calling thread only, in order, when `serial`). The file is what write_gpkg writes for the
// drawing of these faces; an exception of face(k) stops the writing and is rethrown.
struct FaceStream {
    std::string crs_wkt, style;
    std::size_t faces = 0;
    bool serial = false;
    std::function<void(std::size_t k, const std::function<void(const FaceHatches&)>& use)> face;
    // rest() will have fingerprints: the hatch layers' face_id indexes are made before their
    // rows go in (kept up to date while the faces are drawn, not made at the end).
    bool fingerprints = false;
};
// Writes the hatch GeoPackage of the streamed faces: each face's rows are encoded as it is
// drawn and inserted in face order by one thread while later faces are drawn, so that the
// faces are never all in memory. `rest()`, called once every face is written, gives the rest
// of the drawing (its bounds, crests and fingerprints; its faces are not read).
// `keep_going(fraction)` is asked while that rest is written.
void write_gpkg(const FaceStream& faces, const std::function<const Drawing&()>& rest, const std::string& path,
                bool spatial_index = true, const std::function<bool(double)>& keep_going = {});
// Merges hatch GeoPackages written by write_gpkg (the tiles of a tiled run) into one, the
// parts' features one after the other in the order given, each feature's geometry and
// attributes copied bit for bit, with one R-tree per layer (the rock families always, a
// terrain family when a part has it); reads one part at a time. Returns the number of
// hatches and terrain elements.
std::size_t merge_gpkg(const std::vector<std::string>& parts, const std::string& path, bool spatial_index = true,
                       const std::function<bool(double)>& keep_going = {});
// Reads a hatch GeoPackage written by write_gpkg back into a drawing (faces in order of
// first appearance), e.g. to draw a tiled run's merged result as SVG or PNG. Its bounds are
// the frame the file keeps (write_gpkg keeps the drawing's bounds; merge_gpkg the union of
// its parts'), else those of its hatches and crests.
Drawing read_gpkg(const std::string& path, double scale);
void write_svg(const Drawing& d, const std::string& path);

// The fingerprints a hatch GeoPackage keeps; nullopt when it has none (a tiled run's, an
// older version's). `what` names the file in errors.
std::optional<Fingerprints> read_fingerprints(const std::string& path, const std::string& what);
// What replace_faces changed.
struct FaceReplacement {
    std::size_t deleted = 0;  // features removed
    std::size_t written = 0;  // features written
    std::size_t kept = 0;     // features of the faces replaced drawn again as they were: left in place
};
// In a hatch GeoPackage that keeps fingerprints: replaces the features of the hatch layers
// whose face_id is in `faces` by those of d.faces (as write_gpkg writes them, the same bytes;
// a feature the file holds already, the same bytes with the same face, stays where it is;
// with `all`, every feature of the file goes), replaces the fingerprint rows of `faces` by
// those of d.fingerprints->faces, its run metadata by d.fingerprints->run, and the frame by
// d.bounds: all in one SQLite transaction (an interruption leaves the file as it was).
// Features of other faces are not touched. The R-trees follow through their triggers. With
// `undo`, the features and fingerprints it removes, the fids of the features it writes, the
// faces replaced and the file's metadata go to that GeoPackage (replaced if it exists), for
// restore_faces: the features drawn again as they were are in neither.
// The features of some faces in a hatch GeoPackage as replace_faces matches them (a digest of
// each one's bytes), read before the edit: update reads them on a thread of their own while
// the faces are drawn. Null: replace_faces reads them itself.
struct FeatureKeys;
std::shared_ptr<FeatureKeys> read_feature_keys(const std::string& path, const std::vector<std::int64_t>& faces);
FaceReplacement replace_faces(const std::string& path, const std::vector<std::int64_t>& faces, bool all,
                              const Drawing& d, const std::string& undo = "",
                              std::shared_ptr<FeatureKeys> keys = nullptr);
// Undoes the replace_faces that wrote `undo`: removes the features it wrote and the
// fingerprints of the faces it replaced, and puts back the features and fingerprints it
// removed (the same geometry and attributes, hand edits included; new fids) and the
// metadata, in one transaction.
FaceReplacement restore_faces(const std::string& path, const std::string& undo);
// A PNG preview `pixels` wide, over a light hillshade when one is given.
void write_png(const Drawing& d, const std::string& path, int pixels, const Raster* hillshade);

// Throws Error(OutputExists) when the file exists and overwrite is false, or when its
// folder does not exist; `what` names the output in the message (its option).
void check_output(const std::string& path, bool overwrite, const std::string& what = "-o");

// A file a command reads or writes, and the option (or parameter) that names it.
struct FileArg {
    std::string what;  // "--dem", "-o", "OUTPUT"...
    std::string path;  // "" when not given
};

// The outputs of one command, checked before any work: each as check_output, and none
// may be one of the inputs or another output, however it is spelt (./x, a/../x, a symbolic
// or hard link to it). Throws Error(OutputExists) naming both files; inputs that do not
// exist are left to their reader (InputMissing).
void check_outputs(const std::vector<FileArg>& inputs, const std::vector<FileArg>& outputs, bool overwrite);

}  // namespace carto
