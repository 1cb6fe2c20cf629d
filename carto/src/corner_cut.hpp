// Corner cutting of an open polyline (Chaikin's scheme), shared by the partition extraction
// (rounding generalised borders) and the crest ornaments (smoothing a ridge for its band):
// libtex's CutCorners, the one implementation (the print style's crest line uses it too).
#pragma once

#include <vector>

#include "libtex/mappers.hpp"

namespace carto {

// `passes` rounds of corner cutting at 1/4 and 3/4 of every segment; the two end points stay
// where they are, so chains that meet at their ends still meet.
inline std::vector<tex::Point> cut_corners(std::vector<tex::Point> pts, int passes) {
    return tex::CutCorners(std::move(pts), passes);
}

}  // namespace carto
