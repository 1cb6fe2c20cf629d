// Stock mappers: mapper values the engine provides ready-made, so that a script (C++ or
// Python) hands MapToEdges a native mapper instead of writing the same loop by hand. A
// stock mapper is a plain EdgeMapper (or VertexMapper, FaceMapper): it runs on the worker
// threads like any C++ mapper and its random values are keyed like Random(cell, ...).
#pragma once

#include <string>

#include "libtex/fields.hpp"
#include "libtex/mapping.hpp"

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

}  // namespace tex
