// (f) Ridge shapes enhanced on higher ground; the valleys drawn.
#include "builtins.hpp"

namespace carto::blocks {

Builtin high_ridges() {
    return {{"high-ridges", "5.4f", "ridge shapes enhanced on higher ground, valleys drawn",
             fill_params(2.0, 0.5) + kCoarse + kPeaks + kBalanced + kHigh},
            [](const ControlFields& f, const ParamValues& p, const FaceReading& face) {
                return Union(cell_hatching(f, p, face, true, p.at("gap")),
                             ridge_peaks(f, p, face, p.at("peak_height_gain")));
            },
            true};
}

}  // namespace carto::blocks
