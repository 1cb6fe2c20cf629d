// (a) Noisy hatching: one axis of a jittered grid per face, its spacing from the face's
// density and relief.
#include "builtins.hpp"

namespace carto::blocks {

Builtin noisy() {
    return {{"noisy", "5.4a", "noisy hatching: one axis of a jittered grid per face", fill_params(3.0, 1.0)},
            [](const ControlFields& f, const ParamValues& p, const FaceReading& face) {
                return noisy_lines("fill", face.theta, spacing_for(p, face.density, face.height, false),
                                   p.at("length"), p.at("jitter"), 1.0, f.slope, p.at("slope_min"));
            }};
}

}  // namespace carto::blocks
