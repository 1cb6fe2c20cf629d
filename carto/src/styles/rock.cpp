// Rock: the structure first, then the tone, and no drawn outline. The structure lines come
// first: the crests (the partition's ridges and the crease lines of the elevation), drawn
// wider above walls on their shadow side, with strokes hanging from them on that side; the
// tops of the cliff bands (where the slope passes cliff_slope), with rows of strokes hanging
// down to the band's foot, and the fill below it starting after a seam of paper (no line); the couloirs, thin lines the fill strokes keep away from, so that
// they read as gaps between the rock ribs. The fill and cross strokes of the print style take
// the ink the structure leaves under the tone curve (kRockTone: steeper than print's, lit
// faces nearly white), the fill in rows hanging from the level
// lines of the elevation (toned_hatching with band_height). Where rock meets scree, grass or ice,
// the fill and cross strokes end at an irregular distance from the face's border, inside it or
// past it (FrayedCrop), so the rock ends where its strokes end, in a ragged band across the
// border, instead of along one smooth line; a border with rock across it, or a ridge on it, keeps its strokes to the line.
#include "builtins.hpp"

namespace carto::blocks {

Builtin rock() {
    Builtin b;
    b.info = {"rock", "after 5.4g",
              "rock drawing: crests, couloirs and cliff tops with strokes hanging from them, the print tone, no "
              "drawn outline",
              kRockTone + kToneCells + kBalanced + kCrest + kCliff + kStructure + kCross + kFray + kRows};
    b.program = [](const ControlFields& f, const ParamValues& p) {
        check_tone(p);
        check_fray(p);
        return Arrangement([f, p](const tex::Region& r) {
            const FaceReading face = read_face(f, r);
            const Structure s = given_first(p, structure_lines(f, p, r), r);
            // The partition's ridges (on the face's border) and the crests around the face, with
            // the strokes hanging from them; the cliff tops and theirs; valleys and couloirs.
            tex::Curves cliffs = given_cliffs(f, r);
            cliffs.append(s.cliffs);
            tex::Curves lines = tapered(f, p, tex::Labelled(crest_lines(p)(r), "ridgeline"));
            lines.append(tex::apply_mask(tapered(f, p, s.ridges), r, tex::CROP));
            lines.append(tex::apply_mask(cliffs, r, tex::CROP));
            lines.append(valleys()(r));
            tex::Curves spent = lines;
            spent.append(tex::Crop(crest_strokes(f, p, face, r), tex::CROP)(r));
            spent.append(tex::apply_mask(shadow_strokes(f, p, face, s.ridges), r, tex::CROP));
            spent.append(tex::apply_mask(cliff_strokes(f, p, face, cliffs), r, tex::CROP));
            spent.append(tex::apply_mask(s.couloirs, r, tex::CROP));
            // The tone's fill and cross strokes: ending at the structure lines (not crossing
            // them), kept off the couloirs, frayed at the rock's edge.
            Arrangement fill = tex::Apart(toned_hatching(f, p, face, r, spent), lines, p.at("structure_gap"));
            if (p.at("couloir_gap") > 0) fill = tex::Apart(std::move(fill), s.couloirs, p.at("couloir_gap"));
            fill = tex::Apart(std::move(fill), seam_below(s.feet, p.at("foot_gap")), p.at("foot_gap") / 2);
            tex::Curves out = frayed(f, p, std::move(fill))(r);
            out.append(spent);
            return out;
        });
    };
    return b;
}

}  // namespace carto::blocks
