// (b) Noisy hatching plus triangles falling from the ridges into the darker face.
#include "builtins.hpp"

namespace carto::blocks {

Builtin ridge_triangles_style() {
    return {{"ridge-triangles", "5.4b", "noisy hatching plus triangles falling from ridges into the darker face",
             fill_params(3.0, 1.0) + kTriangles},
            [](const ControlFields& f, const ParamValues& p, const FaceReading& face) {
                return Union(noisy_lines("fill", face.theta, spacing_for(p, face.density, face.height, false),
                                         p.at("length"), p.at("jitter"), 1.0, f.slope, p.at("slope_min")),
                             ridge_triangles(f, p, face));
            }};
}

}  // namespace carto::blocks
