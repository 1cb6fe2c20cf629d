// The rock-hatching styles: the design iterations of the seed's Fig. 5.4 (a) to (g), each a
// program of libtex operators.
//
// A style is a controlled arrangement (thesis 5.3): given the control fields it returns the
// arrangement drawn in every face of the cartographic partition. The face is a region whose
// edges carry the labels "ridge", "valley" or "other" (and "owned" on the edges this face
// draws when two faces share them), so that partitions cropped to it with
// CROP_ADD_BOUNDARY see the ridges on their outline. Every stroke a style returns carries
// its family as a label ("fill", "ridge", "valley", "cross"). Fields are read only inside
// the face and just across its border, so editing a field in a window changes the output
// only near that window.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "carto/control_fields.hpp"
#include "carto/terrain.hpp"
#include "libtex/arrangement.hpp"
#include "libtex/curves.hpp"

namespace carto {

// The partition (carto/partition.hpp): a style program reads its face as a labelled region, not
// the partition's types.
struct Partition;

using Polyline = std::vector<Point>;

// Stone and Hachure are the filled outlines of the terrain styles (scree, slope-hachures):
// closed rings drawn filled, no stroke. RidgeLine, Couloir and Cliff are the structure lines
// of the rock style (crest lines, couloirs, cliff tops), written only by the styles that draw
// them, as the terrain families are.
enum class Family { Fill = 0, Ridge = 1, Valley = 2, Cross = 3, Stone = 4, Hachure = 5, RidgeLine = 6, Couloir = 7, Cliff = 8 };
inline constexpr int kFamilies = 9;
// The rock families, always written; the terrain families only when a drawing has them.
inline constexpr int kRockFamilies = 4;
// Whether the family's rings are filled (terrain elements) rather than stroked.
inline bool family_filled(Family f) { return f == Family::Stone || f == Family::Hachure; }
const char* family_name(Family f);
// Suggested stroke width on paper (mm).
double family_width_mm(Family f);

struct Hatch {
    Polyline points;
    bool closed = false;
    Family family = Family::Fill;
};

struct StyleParam {
    std::string name;
    double value;      // default
    std::string unit;  // "mm" (on paper, converted with the scale), "ratio", "deg", "%"
    std::string help;
};

struct StyleInfo {
    std::string name;    // e.g. "bidirectional"
    std::string figure;  // "5.4g"
    std::string title;
    std::vector<StyleParam> params;
    // A terrain style (scree, slope-hachures) draws around the rock faces, over the whole
    // DEM, after the faces are hatched with the default rock style.
    bool terrain = false;
    // The style draws the partition's ridge lines as crest ornaments (carto/crest.hpp, the
    // project's exemplar unless --crest-ornament names another), in a band as high as its
    // parameter crest_band (mm on paper), as --crest-ornament does for any style.
    bool crest_ornament = false;
};

// The control fields f1..fn a style reads (thesis 5.3.1).
struct ControlFields {
    Field orientation;  // hatch direction, radians (axial); face-wise constant
    Field density;      // 0..1, 1 = darkest; face-wise constant
    Field height;       // 0..1: elevation within its neighbourhood (local relief)
    Field roughness;    // 0..1
    Field slope;        // percent
    // The fall line smoothed at map scale (radians, axial), read per cell or per stroke; NaN
    // in the faces whose orientation the partition gives (they keep `orientation`).
    Field fall_line;
    // 1 - hillshade smoothed at map scale (0 lit .. 1 in shade), the input of a tone curve.
    Field shade;
    // The elevation (metres) averaged over a quarter millimetre on paper, the surface whose
    // crease lines (tex::Creases) are the rock's structure.
    Field elevation;
};

// Style parameters resolved to ground units (mm x scale / 1000 for "mm" parameters,
// radians for "deg"), plus kGroundPerMm: ground units per millimetre on paper, for
// programs that turn the families' stroke widths (mm) into ink on the ground.
using ParamValues = std::map<std::string, double>;
inline constexpr const char* kGroundPerMm = "ground_per_mm";
// Set by the pipeline when it hatches: the DEM's cell (ground units, the larger side), for
// programs that trace lines on a lattice no finer than the DEM needs.
inline constexpr const char* kDemCell = "dem_cell";

// A style program: the controlled arrangement (fields) -> arrangement, its parameters
// bound. The arrangement is evaluated on each face of the partition (a labelled region).
using StyleProgram = std::function<tex::Arrangement(const ControlFields&, const ParamValues&)>;

// What a terrain style reads: the terrain fields, the rock faces and the rock hatches drawn
// in them (which its elements must not touch), the map scale and the seed; with `window`,
// it draws only the elements that window owns (those of its tiles whose centre lies in it),
// as a whole run draws them, reading the fields, faces and hatches within its reach
// (TerrainReach) of the window.
struct TerrainInput {
    const Terrain& terrain;
    const Partition& partition;
    const std::vector<Hatch>& rock;
    double scale = 10000;
    std::uint64_t seed = 0;
    std::optional<tex::BBox> window;
};
using TerrainProgram = std::function<std::vector<Hatch>(const TerrainInput&, const ParamValues&)>;
// How far (ground units) beyond a window a terrain style reads, for its parameters and the
// DEM's cell: what a window of the map must hold around it to draw as the whole run does.
using TerrainReach = std::function<double(const ParamValues&, double cell)>;

struct Style {
    StyleInfo info;
    StyleProgram program;
    // Faces are drawn one after the other when set, for a program whose mappers cannot run
    // on several threads (Python styles run in parallel by default: their native operators
    // release the interpreter's lock; python_style(..., serial=True) asks for this).
    bool serial = false;
    // Set for a terrain style: `program` then hatches the rock faces (the default rock
    // style) and `terrain` draws the style's own elements around them, reading as far as
    // `terrain_reach` beyond a window.
    TerrainProgram terrain;
    TerrainReach terrain_reach;
    // What the program is made of, for the edit loop's fingerprints (carto/update.hpp): a
    // digest of a Python style function's source (python_style: its module's, else its own,
    // else its compiled code); empty for the built-ins, which the program's version covers.
    std::string source_digest;
};

// All built-in styles: the rock styles (a) to (g), then the terrain styles; the default is
// (g), bidirectional.
const std::vector<StyleInfo>& styles();
const std::string& default_style();
// Throws carto::Error(UnknownStyle) listing the known names.
const StyleInfo& find_style(const std::string& name);
// The built-in style of that name (see find_style) with its program.
Style builtin_style(const std::string& name);

ParamValues resolve_params(const StyleInfo& s, const std::map<std::string, double>& overrides, double scale);

// The region a style draws a face in: the face's rings, with its border as labelled edges.
tex::Region face_region(const Partition& p, std::size_t face);

// The family a stroke's labels name ("ridgeline", "couloir", "cliff", then "valley" before
// "ridge" before "cross"; else fill).
Family family_of(const tex::Labels& labels);

// Ink on the ground of the curves, or of their segments whose middle lies in `within`
// (when given): length times the family's stroke width (family_width_mm x ground_per_mm),
// overlaps counted twice. What a tone budget spends.
double ink_area(const tex::Curves& c, double ground_per_mm, const tex::Region* within = nullptr);


// The strokes of an evaluated style, their family read from their labels (the second form
// moves the points out of `c`).
std::vector<Hatch> hatches_from_curves(const tex::Curves& c);
std::vector<Hatch> hatches_from_curves(tex::Curves&& c);

// The hatches of one face: the style's arrangement evaluated on face_region (its random
// values follow `seed`, whatever else the process set).
std::vector<Hatch> hatch_face(const tex::Arrangement& style, const Partition& p, std::size_t face,
                              std::uint64_t seed);

}  // namespace carto
