// (c) Density varying inside faces: coarse jittered cells, each hatched with the relief at
// its centre; the ridge triangles of (b).
#include "builtins.hpp"

namespace carto::blocks {

Builtin density_cells() {
    return {{"density-cells", "5.4c", "density varying inside faces: a coarse jittered grid, each cell hatched",
             fill_params(2.0, 0.5) + kCoarse + kTriangles},
            [](const ControlFields& f, const ParamValues& p, const FaceReading& face) {
                return Union(cell_hatching(f, p, face, false, 1.0), ridge_triangles(f, p, face));
            }};
}

}  // namespace carto::blocks
