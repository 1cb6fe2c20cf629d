// (d) Finer, sparser ridge shapes filled with sub-scale hatching, over the cells of (c).
#include "builtins.hpp"

namespace carto::blocks {

Builtin fine_ridges() {
    return {{"fine-ridges", "5.4d", "finer, sparser ridge shapes filled with sub-scale hatching",
             fill_params(2.0, 0.5) + kCoarse + kPeaks},
            [](const ControlFields& f, const ParamValues& p, const FaceReading& face) {
                return Union(cell_hatching(f, p, face, false, 1.0), ridge_peaks(f, p, face, 0.0));
            }};
}

}  // namespace carto::blocks
