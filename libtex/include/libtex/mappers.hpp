// Stock mappers: mapper values the engine provides ready-made, so that a script (C++ or
// Python) hands MapToEdges a native mapper instead of writing the same loop by hand. A
// stock mapper is a plain EdgeMapper (or VertexMapper, FaceMapper): it runs on the worker
// threads like any C++ mapper and its random values are keyed like Random(cell, ...).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "libtex/fields.hpp"
#include "libtex/mapping.hpp"
#include "libtex/region.hpp"

namespace tex {

// The jitter mapper of the thesis's App. E. An edge carrying `label` becomes its curve
// moved by MatchPoints so that its end vertices land on themselves shifted at random: by
// Random(v, -r*across/2, r*across/2, 0) across the direction theta (radians) and
// Random(v, -r*along/2, r*along/2, 1) along it (two edges sharing a vertex move it alike);
// then, when gap < 1, scaled by gap about its middle (a stroke with gaps at both ends).
// Other edges give Nothing(). With gate_min > 0 an edge whose middle (LocationAt(e, 0.5))
// reads below gate_min in `gate`, or NaN, gives Nothing() too (e.g. no hatch on flat ground).
EdgeMapper JitterEdges(const std::string& label, double theta, double across, double along, double r,
                       double gap = 1.0, Field gate = Field(), double gate_min = 0);

// Thinning of a family of parallel lines to a density that varies over the plane, with no
// seam where it changes (issue 16: hatching whose tone follows the shade continuously).
// The lines are those of StripesProperties(theta, spacing): line k at the signed distance
// k * spacing from the origin along the normal (-sin theta, cos theta). An edge lying on
// line k (read at its middle, LocationAt(e, 0.5)) is handed to `inner` when
//     frac(k * (sqrt(5) - 1) / 2) < keep(middle),
// and gives Nothing() otherwise (or where keep is NaN). The golden-ratio sequence spreads
// the kept lines evenly at any fraction: among any n consecutive lines, the kept ones number
// n * keep within about 2 (three-distance theorem), and the lines kept at a fraction are
// among those kept at any larger one, so where keep grows lines are added and none move:
// a line ends where the tone at it falls below its rank, not at a cell border.
// With an `owner` region (one that is not empty), only edges whose middle lies in it
// (Region::contains) are handed on: the cells of a partition that each own the whole edges
// centred in them, so that no stroke is cut where cells meet.
EdgeMapper ThinLines(EdgeMapper inner, double theta, double spacing, Field keep, Region owner = Region());
// The rank of line k in the thinning order of ThinLines, in [0, 1).
double ThinRank(long long k);

// Corner cutting (Chaikin's scheme): `passes` rounds, each replacing every inner corner by the
// points at 1/4 and 3/4 of its two segments. The end points stay where they are, so chains
// that meet at their ends still meet; each round stays inside the previous polyline's hull.
// Fewer than three points are returned as they are.
std::vector<Point> CutCorners(std::vector<Point> pts, int passes);

// Each point of each curve replaced by the mean of the points up to `half_window` before and
// after it along the curve (a closed curve's window wraps round; an open curve's shrinks
// near its ends, which stay where they are). Local: a piece of a curve is smoothed as the
// whole curve is, away from the piece's own ends, so lines traced on a global lattice and
// cut to different windows agree where the windows overlap. Labels are kept.
Curves MovingAverage(const Curves& c, int half_window);

// A curve drawn smooth at the scale `step` (issue 16: a crest line with no stair steps or
// raster kinks): its points every `step` of length from its first point, its last point
// kept (one closer than step / 2 to it dropped), then three rounds of corner cutting. Bends
// and steps shorter than about `step` go, longer shapes stay within step / 4 of the curve;
// the ends stay put. The line does not depend on the way the curve runs: an open curve is
// smoothed from the smaller of its ends (x, then y) and turned back; a closed one as open at
// its smallest point, towards the smaller of that point's neighbours. Each curve of `c` is
// smoothed alone, its labels kept; labelled points are kept as they are.
Curves Smoothed(const Curves& c, double step);

// Mapping along a curve (issue 16: strokes hanging from a crest line): the points every
// `spacing` of its length, the first half a spacing from its start, each handed to
// f(point, unit tangent there, index k from 0, length left to the curve's end), and the
// curves f returns, together in order (each curve of `c` in turn, k from 0 on each). A
// curve shorter than half a spacing has none.
using AlongMapper = std::function<Curves(const Point&, const Point&, long long, double)>;
Curves MapAlong(const Curves& c, double spacing, const AlongMapper& f);

}  // namespace tex
