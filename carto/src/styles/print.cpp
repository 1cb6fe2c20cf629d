// Print: the drawing of issue 16 after (g). Ink follows the shade through a tone curve
// under a ceiling, strokes follow the fall line, crests are drawn as a smooth line with
// strokes falling from it on its dark side. The face is drawn in two steps: the crests and
// valleys first, then the fill and cross hatching in the ink they leave under the ceiling.
#include "builtins.hpp"

namespace carto::blocks {

Builtin print() {
    Builtin b;
    b.info = {"print", "after 5.4g",
              "print tone: ink follows the shade under a ceiling, strokes along the fall line, crests",
              kTone + kToneCells + kBalanced + kCrest + kCross};
    b.program = [](const ControlFields& f, const ParamValues& p) {
        check_tone(p);
        return Arrangement([f, p](const tex::Region& r) {
            const FaceReading face = read_face(f, r);
            tex::Curves spent = tex::Crop(crest_strokes(f, p, face, r), tex::CROP)(r);
            spent.append(crest_lines(p)(r));
            spent.append(valleys()(r));
            tex::Curves out = tex::Crop(toned_hatching(f, p, face, r, spent), tex::CROP)(r);
            out.append(spent);
            return out;
        });
    };
    return b;
}

}  // namespace carto::blocks
