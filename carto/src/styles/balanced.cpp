// (e) Balanced density: the relief acts linearly, hatches are broken into strokes.
#include "builtins.hpp"

namespace carto::blocks {

Builtin balanced() {
    return {{"balanced", "5.4e", "balanced density: linear height term, hatches broken into strokes",
             fill_params(2.0, 0.5) + kCoarse + kPeaks + kBalanced},
            [](const ControlFields& f, const ParamValues& p, const FaceReading& face) {
                return Union(cell_hatching(f, p, face, true, p.at("gap")), ridge_peaks(f, p, face, 0.0));
            }};
}

}  // namespace carto::blocks
