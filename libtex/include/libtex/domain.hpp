// Domain operators: an arrangement evaluated in a fixed frame (the thesis's
// ExportSVGinDomain without the export: svg.hpp writes it).
#pragma once

#include <string>

#include "libtex/arrangement.hpp"
#include "libtex/curves.hpp"
#include "libtex/region.hpp"

namespace tex {

// ---- Filling an outline (the thesis's ExportSVGinDomain(arrangement, frame)) ----
//
// The region a frame bounds: of the frame's closed curves, the one enclosing the largest
// area is the outside and the closed curves lying inside it are holes (one level: an
// island in a hole is not supported). Open curves and labelled points of the frame play no
// part. Throws tex::Error naming `op` when the frame has no closed curve with an area, or
// when a closed curve lies outside the largest one (a region is one piece).
Region FrameRegion(const Curves& frame, const std::string& op = "FrameRegion");
// The arrangement evaluated on the frame's region, its curves cut to that region (CROP:
// what lies outside the frame is cut off) and the frame's outline (the region's rings,
// inside on the left) appended last. Labelled points outside the region are dropped.
Curves EvaluateInDomain(const Arrangement& a, const Curves& frame);
// An arrangement that ignores the region it is evaluated on and returns
// EvaluateInDomain(a, frame): the filled frame as an arrangement, to combine or export in
// a fixed window like any other.
Arrangement InDomain(Arrangement a, Curves frame);

}  // namespace tex
