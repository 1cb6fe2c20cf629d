// (g) Bidirectional hatching: (f) plus cross hatches where the terrain is rough.
#include "builtins.hpp"

namespace carto::blocks {

Builtin bidirectional() {
    return {{"bidirectional", "5.4g", "bidirectional hatching: cross hatches where the terrain is rough",
             fill_params(1.5, 0.5) + kCoarse + kPeaks + kBalanced + kHigh + kCross},
            [](const ControlFields& f, const ParamValues& p, const FaceReading& face) {
                return Union(Union(cell_hatching(f, p, face, true, p.at("gap")),
                                   ridge_peaks(f, p, face, p.at("peak_height_gain"))),
                             cross_hatching(f, p, face));
            },
            true};
}

}  // namespace carto::blocks
