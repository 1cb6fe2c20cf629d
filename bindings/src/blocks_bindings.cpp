// rockhatch.carto.blocks: the building blocks of the rock styles (carto/blocks.hpp) for the
// style scripts of styles/. A script is a program over these native blocks and libtex's
// operators; the blocks are the built-in styles' own, so a script that composes them as a
// built-in does draws what that built-in draws, byte for byte.
//
// The blocks build arrangements: nothing is evaluated when they are called, so they keep the
// interpreter's lock; the arrangements they return run natively wherever they are evaluated.
#include "carto/blocks.hpp"

#include <utility>

#include "common.hpp"

namespace rhpy {

namespace {

using namespace carto;
using carto::blocks::FaceReading;

// A parameter table as the scripts write theirs: a list of (name, default, unit, help)
// tuples, which `+` concatenates.
py::list table(const std::vector<StyleParam>& params) {
    py::list out;
    for (const auto& p : params) out.append(py::make_tuple(p.name, p.value, p.unit, p.help));
    return out;
}

}  // namespace

void bind_blocks(py::module_& m) {
    m.doc() = "The building blocks of the rock styles (carto/blocks.hpp): controlled arrangements in the "
              "thesis's App. E idiom that the built-in styles and the scripts of styles/ compose. Parameter "
              "tables are lists of (name, default, unit, help); `params` arguments are a style's parameters in "
              "ground units (what style(fields, params) receives).";

    // ---- Parameter tables (defaults follow App. E at 1:10000) ----
    m.def(
        "fill_params", [](double length, double jitter) { return table(blocks::fill_params(length, jitter)); },
        py::arg("length"), py::arg("jitter"), "the parameters of the fill hatching, its length (mm) and jitter given");
    m.attr("TRIANGLES") = table(blocks::kTriangles);
    m.attr("COARSE") = table(blocks::kCoarse);
    m.attr("TONE_CELLS") = table(blocks::kToneCells);
    m.attr("PEAKS") = table(blocks::kPeaks);
    m.attr("BALANCED") = table(blocks::kBalanced);
    m.attr("HIGH") = table(blocks::kHigh);
    m.attr("TONE") = table(blocks::kTone);
    m.attr("ROCK_TONE") = table(blocks::kRockTone);
    m.attr("CREST") = table(blocks::kCrest);
    m.attr("CROSS") = table(blocks::kCross);
    m.attr("FRAY") = table(blocks::kFray);
    m.attr("ROWS") = table(blocks::kRows);
    m.attr("CLIFF") = table(blocks::kCliff);
    m.attr("STRUCTURE") = table(blocks::kStructure);

    // ---- What a style reads about its face ----
    py::class_<FaceReading>(m, "FaceReading",
                            "The orientation and density read inside a face, the highest relief on its outer ring")
        .def(py::init([](double theta, double density, double height) { return FaceReading{theta, density, height}; }),
             py::arg("theta") = 0.0, py::arg("density") = 0.5, py::arg("height") = 0.5)
        .def_readwrite("theta", &FaceReading::theta, "hatch direction (radians)")
        .def_readwrite("density", &FaceReading::density, "0..1, 1 = darkest")
        .def_readwrite("height", &FaceReading::height, "0..1, the highest relief on the outer ring")
        .def("__repr__", [](const FaceReading& f) {
            return "FaceReading(theta=" + std::to_string(f.theta) + ", density=" + std::to_string(f.density) +
                   ", height=" + std::to_string(f.height) + ")";
        });
    m.def("read_face", &blocks::read_face, py::arg("fields"), py::arg("region"),
          "what the style reads about the face `region` (defaults where the fields have no value)");
    m.def("spacing_for", &blocks::spacing_for, py::arg("params"), py::arg("density"), py::arg("height"),
          py::arg("linear"), "hatch spacing from density and height (App. E stripes_cycle; linear: from (e) on)");
    m.def("check_tone", &blocks::check_tone, py::arg("params"),
          "raises RockhatchError (usage) unless the tone parameters describe a curve under its ceiling");
    m.def("tone_coverage", &blocks::tone_coverage, py::arg("params"), py::arg("shade"),
          "ink coverage of the tone curve for a shade in 0..1");
    m.def("darker_across", &blocks::darker_across, py::arg("fields"), py::arg("face"), py::arg("edge"),
          py::arg("cell"), "whether the face is the darker side of the ridge edge of a cell inside it");
    m.def(
        "ridge_foot",
        [](const ControlFields& f, const FaceReading& face, const tex::Vertex& v) {
            const blocks::RidgeFoot foot = blocks::ridge_foot(f, face, v);
            return py::make_tuple(foot.dark, foot.has_into ? py::cast(foot.into) : py::none());
        },
        py::arg("fields"), py::arg("face"), py::arg("vertex"),
        "(dark, into): whether the vertex lies on a ridge on its darker side, and the edge leaving it into the "
        "face (None when there is none)");

    // ---- Arrangements ----
    m.def(
        "noisy_lines",
        [](const std::string& label, double theta, double spacing, double length, double r, double gap,
           const py::object& slope, double slope_min) {
            return blocks::noisy_lines(label, theta, spacing, length, r, gap,
                                       slope.is_none() ? tex::Field() : to_field(slope), slope_min);
        },
        py::arg("label"), py::arg("theta"), py::arg("spacing"), py::arg("length"), py::arg("r"), py::arg("gap") = 1.0,
        py::arg("slope") = py::none(), py::arg("slope_min") = 0.0,
        "one axis of a jittered grid: lines labelled `label` every `spacing` at theta, broken every `length`, "
        "jittered by r; no hatch where the slope is below slope_min (when > 0)");
    m.def("cell_hatching", &blocks::cell_hatching, py::arg("fields"), py::arg("params"), py::arg("face"),
          py::arg("linear"), py::arg("gap"),
          "coarse jittered cells, each hatched with the spacing of the relief at its centre");
    m.def("ridge_triangles", &blocks::ridge_triangles, py::arg("fields"), py::arg("params"), py::arg("face"),
          "(b) triangles falling from the ridges into the darker face");
    m.def("ridge_peaks", &blocks::ridge_peaks, py::arg("fields"), py::arg("params"), py::arg("face"), py::arg("gain"),
          "(d) ridge shapes hanging from the dark ridges, filled with sub-scale hatching; gain grows them on "
          "high ground (f)");
    m.def("crest_lines", &blocks::crest_lines, py::arg("params"),
          "each ridge on the face's border smoothed at crest_smoothing, cut to the face");
    m.def("crest_strokes", &blocks::crest_strokes, py::arg("fields"), py::arg("params"), py::arg("face"),
          py::arg("region"), "shadow-side strokes hanging from the crest lines down the fall line");
    m.def("toned_hatching", &blocks::toned_hatching, py::arg("fields"), py::arg("params"), py::arg("face"),
          py::arg("region"), py::arg("spent"),
          "coarse jittered cells, each hatched so that its ink follows the tone of its shade under ink_max, "
          "`spent` (crests, valleys) counted");
    m.def("cliff_tops", &blocks::cliff_tops, py::arg("fields"), py::arg("params"), py::arg("region"),
          "the tops of the cliff bands around the face (the level line slope = cliff_slope where the ground falls "
          "into the band) over its box grown by structure_margin, smoothed, labelled cliff, uncut");
    m.def("cliff_feet", &blocks::cliff_feet, py::arg("fields"), py::arg("params"), py::arg("region"),
          "the feet of the cliff bands around the face (the same level line as cliff_tops where the band falls "
          "onto gentler ground), smoothed, labelled cliff_foot, uncut");
    m.def("seam_below", &blocks::seam_below, py::arg("feet"), py::arg("width"),
          "the centre lines of the seams of white paper under the feet: each foot moved width / 2 off its band");
    py::class_<blocks::Structure>(m, "Structure", "The structure lines around a face, uncut")
        .def_readonly("ridges", &blocks::Structure::ridges, "crest lines (labelled ridgeline)")
        .def_readonly("couloirs", &blocks::Structure::couloirs, "couloir lines (labelled couloir)")
        .def_readonly("cliffs", &blocks::Structure::cliffs, "cliff tops (labelled cliff)")
        .def_readonly("feet", &blocks::Structure::feet, "the cliff bands' feet (labelled cliff_foot)");
    m.def("structure_margin", &blocks::structure_margin, py::arg("params"),
          "how far beyond a face's box its structure lines are traced (ground units)");
    m.def("structure_lines", &blocks::structure_lines, py::arg("fields"), py::arg("params"), py::arg("region"),
          "the crests and couloirs (crease lines of the elevation) and cliff tops around the face, uncut; "
          "given ridges, valleys and cliff tops first");
    m.def("given_first", &blocks::given_first, py::arg("params"), py::arg("structure"), py::arg("region"),
          "the structure less its crests (couloirs) along a ridge (valley) of the face's border");
    m.def("given_cliffs", &blocks::given_cliffs, py::arg("fields"), py::arg("region"),
          "the cliffs on the face's border, each turned with the ground falling on its left, labelled cliff");
    m.def("tapered", &blocks::tapered, py::arg("fields"), py::arg("params"), py::arg("lines"),
          "crest lines widened on their shadow side above walls, tapering to their ends");
    m.def("shadow_strokes", &blocks::shadow_strokes, py::arg("fields"), py::arg("params"), py::arg("face"),
          py::arg("lines"), "strokes hanging from crest lines on their shadow side down the fall line");
    m.def("cliff_strokes", &blocks::cliff_strokes, py::arg("fields"), py::arg("params"), py::arg("face"),
          py::arg("tops"), "rows of strokes hanging from cliff tops down the fall line");
    m.def("check_fray", &blocks::check_fray, py::arg("params"),
          "raises RockhatchError (usage) unless 0 <= fray_min <= fray_max and fray_beyond <= 1");
    m.def("frayed", &blocks::frayed, py::arg("fields"), py::arg("params"), py::arg("arrangement"),
          "the arrangement cut to the face, its strokes ending irregularly across the rock's edge "
          "(fray_min .. fray_max back from it, or past it for the share fray_beyond; not where a face lies "
          "across or a ridge or cliff lies on the border)");
    m.def("valleys", &blocks::valleys, "(f) the valleys the face owns");
    m.def("cross_hatching", &blocks::cross_hatching, py::arg("fields"), py::arg("params"), py::arg("face"),
          "(g) cross hatches in the coarse cells rough enough, denser when rougher");

    // ---- Programs ----
    m.def(
        "per_face",
        [](const ControlFields& fields, const ParamValues& params, py::function body, bool with_valleys) {
            PyRef ref(std::move(body));
            blocks::FaceBody native = [ref](const ControlFields& f, const ParamValues& p, const FaceReading& face) {
                py::gil_scoped_acquire gil;
                py::object r = ref.get()(f, p, face);
                if (!py::isinstance<tex::Arrangement>(r))
                    throw py::type_error("per_face: the body returned " + type_name(r) +
                                         "; it must return the Arrangement drawn in the face");
                return r.cast<tex::Arrangement>();
            };
            return blocks::per_face(std::move(native), with_valleys)(fields, params);
        },
        py::arg("fields"), py::arg("params"), py::arg("body"), py::arg("with_valleys") = false,
        "the arrangement drawn in each face: body(fields, params, face) with the face read once, cut to the face; "
        "with_valleys adds the face's valleys uncut");
}

}  // namespace rhpy
