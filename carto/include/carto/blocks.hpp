// Building blocks of the rock styles: controlled mappers and arrangements in the thesis's
// idiom (App. E), each a small composition of libtex operators. The built-in styles
// (carto/src/styles/*.cpp) and the Python style scripts (styles/*.py, through
// rockhatch.carto.blocks) are programs over these blocks.
#pragma once

#include <string>
#include <vector>

#include "carto/styles.hpp"
#include "libtex/tex.hpp"

namespace carto::blocks {

using tex::Arrangement;

// Parameter lists (defaults follow App. E at 1:10000).
std::vector<StyleParam> fill_params(double length_mm, double jitter);
extern const std::vector<StyleParam> kTriangles, kCoarse, kPeaks, kBalanced, kHigh, kCross, kTone, kCrest;
// The band across the rock's edge where fill strokes end (frayed).
extern const std::vector<StyleParam> kFray;
// Cliff bands: where the slope passes cliff_slope, their tops and the strokes hanging from them.
extern const std::vector<StyleParam> kCliff;
// Rows of fill strokes hanging from the level lines of the elevation (toned_hatching with
// band_height > 0, tex::CutAtLevels).
extern const std::vector<StyleParam> kRows;
// rock's tone: kTone with a steeper curve (tone_gamma 2): lit faces nearly white, shaded ones
// dark, as in Swiss rock drawing; with print's linear curve the fixed ink of the structure
// lines weighs more against the shade (rho 0.70 against 0.82 on Nordkette at 1:25000).
extern const std::vector<StyleParam> kRockTone;
// print's tone cells: kCoarse's parameters, 2 mm wide (3 mm cells, 150 m at 1:50000, let the
// ink of a block follow its cell more than its own shade: rho 0.77 on the sample there).
extern const std::vector<StyleParam> kToneCells;
std::vector<StyleParam> operator+(std::vector<StyleParam> a, const std::vector<StyleParam>& b);

// What a style reads about the face it draws (the region it is evaluated on): the
// orientation and density at a point inside it, the highest relief on its outer ring.
struct FaceReading {
    double theta = 0;    // hatch direction (radians)
    double density = 0.5;
    double height = 0.5;
};
FaceReading read_face(const ControlFields& f, const tex::Region& r);

// Hatch spacing from density and height (App. E `stripes_cycle`; `linear` from (e) on).
double spacing_for(const ParamValues& p, double density, double height, bool linear);

// One axis of a jittered grid: lines labelled `label` every `spacing` at theta, broken
// every `length`, jittered by r (App. E "noisy hatching", tex::JitterEdges); with a slope
// field and slope_min > 0, no hatch where the middle of a piece is flatter.
Arrangement noisy_lines(const std::string& label, double theta, double spacing, double length, double r,
                        double gap = 1.0, Field slope = Field(), double slope_min = 0);

// Coarse jittered cells each hatched with the spacing of the relief at its centre (App. E
// "multiscale density variations"; `linear` and `gap` from (e) on).
Arrangement cell_hatching(const ControlFields& f, const ParamValues& p, const FaceReading& face, bool linear,
                          double gap);

// Whether the face is the darker side of the ridge edge e of a cell inside it: the density
// just across e (NaN: no face there) against the face's own.
bool darker_across(const ControlFields& f, const FaceReading& face, const tex::Edge& e, const tex::Face& cell);

// (b) triangles falling from the ridges into the darker face: cells of a grid at theta and
// theta + 45 degrees cut by the face, kept when they touch a ridge on its darker side.
Arrangement ridge_triangles(const ControlFields& f, const ParamValues& p, const FaceReading& face);

// (d) ridge shapes: triangles hanging from the dark ridges where stripes at theta meet
// them, filled with sub-scale hatching; `gain` grows them on high ground (f).
Arrangement ridge_peaks(const ControlFields& f, const ParamValues& p, const FaceReading& face, double gain);

// Whether a vertex lies on a ridge on the darker side of it (`dark`), and the edge that
// leaves it into the face (`into`, when `has_into`): where ridge shapes and crest strokes
// hang from.
struct RidgeFoot {
    bool dark = false;
    bool has_into = false;
    tex::Edge into;
};
RidgeFoot ridge_foot(const ControlFields& f, const FaceReading& face, const tex::Vertex& v);
// The crest line: each ridge on the face's border smoothed at crest_smoothing
// (tex::Smoothed, the same line from both faces), its ends where the ridge ends, cut to the
// face: each face draws its part, the two faces along a ridge the whole line between them.
Arrangement crest_lines(const ParamValues& p);
// Shadow-side strokes: along each ridge of the face `region` on its darker side, every
// crest_spacing along the crest line (as crest_lines draws it), one stroke from the line into
// the face down the local fall line (read crest_length / 2 inside the face), its length
// crest_length x (1 + crest_height_gain x relief) x a golden-ratio share 0.35 .. 1, shorter
// near the ridge's ends; none where the fall line runs within 30 degrees of the crest. The
// lit side gets none (Swiss-style: dark sides denser).
Arrangement crest_strokes(const ControlFields& f, const ParamValues& p, const FaceReading& face,
                          const tex::Region& region);
// Throws a usage error naming the style `print` unless the tone parameters describe a curve
// under its ceiling (tone_min <= tone_max, ink_max and gap in (0, 1]).
void check_tone(const ParamValues& p);
// The tone curve: ink coverage (stroke area over area) for a shade in 0..1,
// tone_min + (tone_max - tone_min) x shade^tone_gamma.
double tone_coverage(const ParamValues& p, double shade);
// Coarse jittered cells, each hatched so that its ink follows the tone of the shade at its
// centre under the ceiling ink_max, the ink `spent` has in the cell (crests, valleys; over
// the cell's area inside the face `region`) included, with at least min_gap between fill
// strokes; fill strokes run along the fall line read at the cell's centre and are turned to
// the fall line at their middles (AlignToField) when follow_fall_line > 0, else along the
// face's orientation (and are turned onto it: break-point jitter shifts strokes without
// tilting them). With the kRows parameters (band_height...), the fill strokes are also cut
// where the elevation, its level lines wandering by band_wander, crosses a multiple of
// band_height (tex::CutAtLevels), laid band_ragged denser and shortened from their lower ends
// by random shares until the cell's fill ink is the tone's exactly.
Arrangement toned_hatching(const ControlFields& f, const ParamValues& p, const FaceReading& face,
                           const tex::Region& region, const tex::Curves& spent);

// The tops of the cliff bands around the face `region`: the level line slope = cliff_slope
// of the elevation field's slope, differenced over cliff_smoothing either side (the DEM's own
// slope wanders round every cell-sized bump) (tex::IsoLines on a lattice of a quarter of crest_smoothing, or of the
// DEM's cell when that is coarser: the same in a tile as in the whole), where the ground
// falls into the band (the steeper side lower, on the line's left), traced over the face's
// box grown by structure_margin, smoothed locally (tex::MovingAverage over crest_smoothing),
// pieces shorter than cliff_min_length dropped; labelled "cliff", uncut.
tex::Curves cliff_tops(const ControlFields& f, const ParamValues& p, const tex::Region& region);
// The feet of the cliff bands, from the same level line: where the band (on the line's left)
// lies higher and falls onto ground gentler by cliff_break; labelled "cliff_foot", uncut.
tex::Curves cliff_feet(const ControlFields& f, const ParamValues& p, const tex::Region& region);
// The centre lines of the seams of white paper under the feet: each foot moved half `width`
// to its right (down, off the band). The rock style keeps its fill width / 2 from them, so the
// band's strokes reach the foot and the slope's start `width` below it; no line is drawn.
tex::Curves seam_below(const tex::Curves& feet, double width);
// Strokes hanging from cliff tops into their bands: every crest_spacing along each top, one
// stroke down the fall line (read half a stroke below the top), as long as the band is high
// (to where the slope falls under cliff_slope again, at most cliff_length) x a golden-ratio
// share 0.35 .. 1, shorter near the top's ends, a third of them kept on lit rock and all in
// full shade: cliff bands read as rows of strokes across the slope, dense in shadow.
// Labelled "ridge".
tex::Curves cliff_strokes(const ControlFields& f, const ParamValues& p, const FaceReading& face,
                          const tex::Curves& tops);
// The structure lines of the rock (issue 46): crests and couloirs, the crease lines of the
// elevation (tex::Creases on a lattice of half crest_smoothing, or of half the DEM's cell
// (kDemCell) when that is coarser, where the slope changes by at least crease_bend across
// 1 mm on paper), and the cliff tops and feet (cliff_tops, cliff_feet). Each is traced
// over the face's box grown by structure_margin, smoothed locally (tex::MovingAverage over
// crest_smoothing) and kept when at least crease_min_length (cliff_min_length) long, so that a
// line crossing several faces is the same line in each and in any tile; crests within
// crest_smoothing of a cliff top are left to it. Uncut: cut them to the face.
extern const std::vector<StyleParam> kStructure;
struct Structure {
    tex::Curves ridges;    // labelled "ridgeline"
    tex::Curves couloirs;  // labelled "couloir"
    tex::Curves cliffs;    // labelled "cliff"
    tex::Curves feet;      // the cliff bands' feet, labelled "cliff_foot"
};
double structure_margin(const ParamValues& p);
Structure structure_lines(const ControlFields& f, const ParamValues& p, const tex::Region& region);
// Given lines come first: the structure less its crests within crest_smoothing of a ridge on
// the face's border, its couloirs within it of a valley there and its cliff tops within it of
// a cliff there, pieces left shorter than crease_min_length (cliff_min_length) dropped (the
// partition's lines are drawn instead).
Structure given_first(const ParamValues& p, const Structure& s, const tex::Region& region);
// The cliffs the partition gives on the face's border (edges labelled "cliff"), each turned so
// that the ground falls on its left as it does below a cliff top, labelled "cliff": those
// whose band (the lower side) lies in the face, or in no face (then the face above draws it).
tex::Curves given_cliffs(const ControlFields& f, const tex::Region& region);
// Crest lines drawn wider where they stand above a wall, on the wall's shadow side: along
// each line, one more stroke beside it toward the darker side, offset by up to 0.1 mm in
// proportion to the wall below (the fall over 1 mm on paper; the whole offset from two thirds
// of 150 %) and to the distance from the line's ends (over 1 mm), drawn where the offset
// reaches 0.05 mm. The offset stays under the stroke's width, so on paper the pair is one
// shape whose width follows the wall: the line swells above the walls and thins to its ends.
// Labelled as the lines are; uncut.
tex::Curves tapered(const ControlFields& f, const ParamValues& p, const tex::Curves& lines);
// Strokes hanging from crest lines on their shadow side (the side whose shade, read half a
// stroke away, is darker), every crest_spacing, as crest_strokes hangs them from the
// partition's ridges, a third of them kept on lit rock. Labelled "ridge"; uncut.
tex::Curves shadow_strokes(const ControlFields& f, const ParamValues& p, const FaceReading& face,
                           const tex::Curves& lines);
// Throws a usage error unless 0 <= fray_min <= fray_max and fray_beyond <= 1.
void check_fray(const ParamValues& p);
// The arrangement a, cut to the face, its strokes drawn back from the rock's edge by a
// random length in [fray_min, fray_max], or for the share fray_beyond of them drawn on past
// it by that much (tex::FrayedCrop): where no face lies across the border (the density field
// has no value there) and no ridge or cliff lies on it, strokes end irregularly in a band
// across the border instead of drawing it, and the band keeps the ink of the tone.
Arrangement frayed(const ControlFields& f, const ParamValues& p, Arrangement a);

// (f) the valleys the face owns (a valley between two faces is drawn once).
Arrangement valleys();

// (g) cross hatches in the coarse cells rough enough, denser when rougher.
Arrangement cross_hatching(const ControlFields& f, const ParamValues& p, const FaceReading& face);

// A style program from the arrangement it draws in one face (read_face done once per face),
// cut to the face; with `valleys`, the face's valleys (which lie on its border) added uncut.
using FaceBody = std::function<Arrangement(const ControlFields&, const ParamValues&, const FaceReading&)>;
StyleProgram per_face(FaceBody body, bool with_valleys = false);

}  // namespace carto::blocks
