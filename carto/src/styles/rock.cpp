// Rock: the structure first, then the tone, and no drawn outline. The crests (ridge lines
// and the strokes on their shadow side) and the tops of the cliff bands (where the slope
// passes cliff_slope, with rows of strokes hanging from them down the fall line) are drawn
// first; the fill and cross strokes of the print style take the ink they leave under the
// tone curve. Where rock meets scree, grass or ice, the fill and cross strokes are drawn back
// from the face's border by an irregular length (FrayedCrop), so the rock ends where its
// strokes end, in a ragged band, instead of along one smooth line; a border with rock across
// it, or a ridge on it, keeps its strokes to the line.
#include "builtins.hpp"

namespace carto::blocks {

Builtin rock() {
    Builtin b;
    b.info = {"rock", "after 5.4g",
              "rock drawing: crests and cliff tops with strokes hanging from them, the print tone, no drawn outline",
              kTone + kToneCells + kBalanced + kCrest + kCliff + kCross + kFray};
    b.program = [](const ControlFields& f, const ParamValues& p) {
        check_tone(p);
        check_fray(p);
        return Arrangement([f, p](const tex::Region& r) {
            const FaceReading face = read_face(f, r);
            tex::Curves spent = tex::Crop(crest_strokes(f, p, face, r), tex::CROP)(r);
            spent.append(crest_lines(p)(r));
            spent.append(valleys()(r));
            const tex::Curves tops = cliff_tops(f, p, r);
            spent.append(tex::apply_mask(cliff_strokes(f, p, face, tops), r, tex::CROP));
            spent.append(tops);
            tex::Curves out = frayed(f, p, toned_hatching(f, p, face, r, spent))(r);
            out.append(spent);
            return out;
        });
    };
    return b;
}

}  // namespace carto::blocks
