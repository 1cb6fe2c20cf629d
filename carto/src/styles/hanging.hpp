// What the strokes hanging from a line share (a crest line, a cliff top): their direction,
// their lengths, how many stay on lit rock. Private to the style blocks.
#pragma once

#include <algorithm>
#include <optional>

#include "carto/blocks.hpp"

namespace carto::blocks::detail {

inline double clamp01(double v) { return std::clamp(v, 0.0, 1.0); }

// Stroke k hanging from a crest line has (kShortestCrestStroke + (1 - kShortestCrestStroke) x
// ThinRank(k)) of the longest length: golden-ratio ranks spread the lengths evenly, so the ink
// fades down the slope from the line instead of ending in a comb's edge.
inline constexpr double kShortestCrestStroke = 0.35;
// Near a ridge's end the strokes shrink, to this fraction of their length at the end itself,
// growing to their full length (1 - this) x crest_length from it: the fringe tapers with the crest.
inline constexpr double kCrestEndTaper = 0.3;
// A stroke leaves the crest line within 60 degrees of its normal (this cosine): where the fall
// line runs nearly along the crest (a spur falling away), the line is drawn alone; a stroke
// turned off the fall line there would cross the fill strokes and read as a net.
inline constexpr double kCrestStrokeMinCos = 0.5;
// The share of the strokes hanging from a cliff top kept on fully lit rock (all in full shade).
inline constexpr double kLitCliffStrokes = 0.33;

// The direction of a stroke hanging from a line at `foot` into the side `n` (unit normal):
// the fall line read half the longest stroke down that side (on the line itself it averages
// two opposite slopes), the face's orientation when not following it or where it reads NaN;
// none where it runs within 60 degrees of the line.
std::optional<tex::Point> hanging_direction(const ControlFields& f, const FaceReading& face, bool follow,
                                            const tex::Point& foot, const tex::Point& n, double longest);

// The length of stroke k hanging from a line, `base` for the longest: a golden-ratio share
// kShortestCrestStroke .. 1 of it, shorter within `longest` of the line's nearer end
// (`to_end` from stroke k's foot).
double hanging_length(double base, long long k, double spacing, double to_end, double longest);

}  // namespace carto::blocks::detail

namespace carto::blocks {
using detail::clamp01;
using detail::hanging_direction;
using detail::hanging_length;
using detail::kLitCliffStrokes;
}  // namespace carto::blocks
