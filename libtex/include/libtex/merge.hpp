// Merging operators (thesis 3.5, table 3.5).
#pragma once

#include <string>
#include <vector>

#include "libtex/arrangement.hpp"
#include "libtex/fields.hpp"
#include "libtex/partitions.hpp"

namespace tex {

// All the curves of a1 and a2.
Arrangement Union(Arrangement a1, Arrangement a2);
// Union under its name in the thesis's Chapter 4 (the Microprocessor script uses both).
inline Arrangement Merge(Arrangement a1, Arrangement a2) { return Union(std::move(a1), std::move(a2)); }
// Edges of a1 inside the bounded faces of a2. CROP cuts a1's curves along a2's face
// boundaries; CROP_ADD_BOUNDARY also adds those boundaries; KEEP_INSIDE keeps the edges of
// a1's planar map lying entirely inside; KEEP_OUTSIDE keeps those that meet the inside.
Arrangement Inside(Arrangement a1, Arrangement a2, Border b);
// Same as Inside with "outside the bounded faces of a2".
Arrangement Outside(Arrangement a1, Arrangement a2, Border b);

// a evaluated on the region and cut to it: CROP cuts its curves at the region's boundary,
// CROP_ADD_BOUNDARY also adds the boundary (with the labels of a face's edges when the
// region comes from a face), KEEP_INSIDE / KEEP_OUTSIDE keep the edges of a's planar map
// lying wholly inside / meeting the inside. A region's own outline as the mask, so it costs
// one crop, not a planar map of the outline (Inside(a, outline, b) means the same).
Arrangement Crop(Arrangement a, Border b);
// a evaluated on the region and cut to it (CROP), then every end of an open curve on the
// region's rim (within `min` of it) drawn back along the curve to a random depth in
// [min, max] from the rim, so that the curves end irregularly in a band inside the rim
// instead of drawing it (rock drawing has no outline); a curve that never gets that deep
// goes, so the band also thins out. The rim is the border less its edges labelled one of
// `hard` (a structure line drawn there) and less where `across` has a value just beyond it
// (another face goes on there); the default `across` (NaN everywhere) leaves all of it. The
// depths are keyed by the end point, the operator's stream and the seed: the same on any
// thread and in any tiling. With `beyond` > 0, that share of the rim's ends (a draw of their
// own) is drawn on past the rim instead, its last segment continued straight to the same
// depth outside the region, where the way is free (not back into the region, not onto
// another face) and the stroke crosses the rim at 60 degrees or more (a slanting stroke
// drawn on would run along the rim's outside, a hair on the edge): the curves then end on
// both sides of the rim, and the band keeps on average the ink a plain crop leaves
// (beyond = 1/2). Throws tex::Error naming FrayedCrop
// for a band or share out of range.
Arrangement FrayedCrop(Arrangement a, double min, double max, Field across = Field(),
                       std::vector<std::string> hard = {}, double beyond = 0);
// FrayedCrop(a, ...)(r) for curves already in hand: the same stream (taken now, as creating
// the operator takes it), the same result, without a copy of the curves.
Curves FrayedCrop(Curves curves, const Region& r, double min, double max, Field across = Field(),
                  std::vector<std::string> hard = {}, double beyond = 0);
// The curves of a (evaluated on the region) less their parts within `distance` of any of
// `lines` (a gap left along them, as a couloir is drawn in rock), cut exactly where they
// enter that buffer (the union of the capsules round the lines' segments); a curve that
// never comes near is kept as it is. Throws tex::Error naming Apart for a distance that is
// not positive.
Arrangement Apart(Arrangement a, Curves lines, double distance);
// The curves of a (evaluated on the region) cut where the field f crosses a multiple of
// `step`, as hachures hang in rows from the level lines of the elevation: at each crossing
// the piece on the lower side starts on the level line and the piece on the higher side ends
// `gap` (a length along the curve) before it. f is read at the curve's points and every
// `sampling` between them (0: at its points only). The levels are the plane's, so any region
// or tile cuts a curve at the same points; a stretch where f has no value is not cut. Throws
// tex::Error naming CutAtLevels for a step that is not positive or a negative gap or sampling.
Arrangement CutAtLevels(Arrangement a, Field f, double step, double gap, double sampling = 0);
// The region itself as an arrangement: its boundary, as the labelled edges of the face it
// comes from when it has them (Region::with_edges), else its rings.
Arrangement Outline();

// The mask computation shared by the merges and the cropping partitions: `subject` curves
// cut by the boundaries of the bounded faces of `mask_map`; returns the kept pieces.
enum class MaskSide { Inside, Outside };
Curves apply_mask(const Curves& subject, const PlanarMap& mask_map, MaskSide side, Border b);
// Same, with a region as the mask; the second form may move the curves it keeps whole out
// of `subject` instead of copying them.
Curves apply_mask(const Curves& subject, const Region& region, Border b);
Curves apply_mask(Curves&& subject, const Region& region, Border b);

}  // namespace tex

namespace tex::detail {
// Within this scope (on this thread) every crop goes through the exact planar map, not the
// crossing-by-crossing path; for the tests that compare both.
class ExactCropScope {
public:
    ExactCropScope();
    ~ExactCropScope();
    ExactCropScope(const ExactCropScope&) = delete;
    ExactCropScope& operator=(const ExactCropScope&) = delete;

private:
    bool saved_;
};
bool exact_crops_only();
// How many crops this thread cut crossing by crossing.
std::uint64_t fast_crops();
// Within this scope (on this thread) a CROP of open polylines goes through the general
// crossing path instead of the walk along each curve; for the tests that compare both.
class GeneralCropScope {
public:
    GeneralCropScope();
    ~GeneralCropScope();
    GeneralCropScope(const GeneralCropScope&) = delete;
    GeneralCropScope& operator=(const GeneralCropScope&) = delete;

private:
    bool saved_;
};
// How many crops this thread cut by walking open polylines.
std::uint64_t polyline_crops();
// Within this scope (on this thread) the exact path of a CROP always builds its joint
// planar map, instead of cutting the curves at their exact crossings when every contact is
// a simple one; for the tests that compare both.
class JointMapScope {
public:
    JointMapScope();
    ~JointMapScope();
    JointMapScope(const JointMapScope&) = delete;
    JointMapScope& operator=(const JointMapScope&) = delete;

private:
    bool saved_;
};
// How many crops this thread cut at exact crossings without the joint map, and how many
// pieces along the mask they gave.
std::uint64_t exact_crossing_crops();
std::uint64_t pieces_cut_along_mask();
// How many segments of subject curves this thread's merges searched one by one (against the
// mask, or against each other for the edges of KEEP modes). A curve whose box meets no mask
// segment, or that meets no other curve's box and is plainly simple, is classified whole and
// adds nothing: the cost of a merge follows its curves and crossings, not its points.
std::uint64_t segments_searched();
}  // namespace tex::detail
