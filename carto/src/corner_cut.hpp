// Corner cutting of an open polyline (Chaikin's scheme), shared by the partition extraction
// (rounding generalised borders) and the crest ornaments (smoothing a ridge for its band).
#pragma once

#include <vector>

#include "libtex/geometry.hpp"

namespace carto {

// `passes` rounds of corner cutting at 1/4 and 3/4 of every segment; the two end points stay
// where they are, so chains that meet at their ends still meet. Each pass stays inside the
// previous polyline's hull; a polyline of fewer than three points is left as it is.
inline std::vector<tex::Point> cut_corners(std::vector<tex::Point> pts, int passes) {
    for (int r = 0; r < passes && pts.size() >= 3; ++r) {
        std::vector<tex::Point> next;
        next.reserve(2 * pts.size());
        next.push_back(pts.front());
        for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
            const tex::Point &a = pts[i], &b = pts[i + 1];
            if (i > 0) next.push_back(a * 0.75 + b * 0.25);
            if (i + 2 < pts.size()) next.push_back(a * 0.25 + b * 0.75);
        }
        next.push_back(pts.back());
        pts = std::move(next);
    }
    return pts;
}

}  // namespace carto
