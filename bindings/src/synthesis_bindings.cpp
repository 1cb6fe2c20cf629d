// rockhatch.tex: topology-constrained synthesis along curves (seed 002).
//
// Both operators take their options as keywords, read once by `options` below (names and
// defaults are those of tex::SynthesisOptions).
#include "common.hpp"

namespace rhpy {
namespace {

using namespace tex;

template <class T>
std::optional<T> optional_of(const py::handle& v) {
    if (v.is_none()) return std::nullopt;
    return v.cast<T>();
}

SynthesisOptions options(const py::kwargs& kw, const char* op) {
    SynthesisOptions o;
    for (const auto& [key, value] : kw) {
        const std::string k = py::str(key);
        if (k == "components") o.components = optional_of<int>(value);
        else if (k == "holes") o.holes = optional_of<int>(value);
        else if (k == "closed_pattern") o.closed_pattern = value.cast<bool>();
        else if (k == "autocorrelation") o.autocorrelation = value.cast<double>();
        else if (k == "slicing") {
            const std::string s = value.cast<std::string>();
            if (s == "topology") o.slicing = Slicing::Topology;
            else if (s == "uniform") o.slicing = Slicing::Uniform;
            else throw Error(op, "slicing must be 'topology' or 'uniform', not '" + s + "'");
        } else if (k == "slicing_lines") o.slicing_lines = value.cast<int>();
        else if (k == "event_grouping") o.event_grouping = optional_of<double>(value);
        else if (k == "thin_portal") o.thin_portal = value.cast<double>();
        else if (k == "alpha") o.alpha = value.cast<double>();
        else if (k == "length_tolerance") o.length_tolerance = value.cast<double>();
        else if (k == "max_length_deviation") o.max_length_deviation = value.cast<double>();
        else if (k == "randomness") o.randomness = value.cast<double>();
        else if (k == "seed") o.seed = optional_of<std::uint64_t>(value);
        else throw py::type_error(std::string(op) + "() got an unexpected keyword argument '" + k + "'");
    }
    return o;
}

constexpr const char* kOptionsDoc = R"doc(
Options (keywords)
------------------
components : int or None, default 1
    Connected components of the result (None: free).
holes : int or None, default None
    Holes of the result, counted in the plane (None: free).
closed_pattern : bool, default False
    On a closed curve, the pattern goes all the way round.
autocorrelation : float, default 0
    Weight of the penalty on repeated runs of pieces (0: off).
slicing : {'topology', 'uniform'}, default 'topology'
    Cuts between groups of topological events, or slicing_lines equal cuts.
slicing_lines : int, default 8
event_grouping : float or None, default None
    Events closer than this fraction of the exemplar's width form one group. None: chosen
    from the exemplar (the seed's 0.2 when its pieces meet the request, else finer).
thin_portal : float, default 0
    Cuts whose narrowest portal is thinner than this (output units) are dropped.
alpha : float, default 0.8
    Weight of the portal-position term against the tangent term of a join's cost.
length_tolerance, max_length_deviation : float, default 0.05, 0.25
    The pieces' natural length is within length_tolerance of the curve's (a fraction),
    widened up to max_length_deviation when nothing reaches it; then stretched exactly.
randomness : float, default 0.1
    Seeded variation of the join costs (fraction of the mean join cost).
seed : int or None, default None
    Seed of that variation; None keys it by the curve and the global seed.

Raises
------
TexError
    On bad input, when no sequence of pieces meets the constraints, and when the curve
    turns too tightly for the band (the pattern would fold over itself).
)doc";

}  // namespace

void bind_synthesis(py::module_& m) {
    // Docstrings must outlive the module's definition: kept in statics.
    static const std::string along_doc = std::string(R"doc(A pattern from an exemplar in a band along a curve, with a guaranteed topology (seed 002).

Parameters
----------
exemplar : Curves
    Closed curves: polygons with holes (e.g. ImportSVG). Scaled so its height is band_height.
curve : Curves
    One polyline, open or closed (e.g. Polyline(points) or ToCurve(edge) in a mapper).
band_height : float
    Height of the band centred on the curve.

Returns
-------
Curves
    Closed curves: outer contours counter-clockwise, holes clockwise.
)doc") + kOptionsDoc;
    static const std::string rectangle_doc = std::string(R"doc(A pattern filling [0, width] x [0, height]: synthesis along U, then along V (seed 002, 6.2).

The constraints hold for the final pattern. The exemplar must be able to repeat across its
height (e.g. rails and rungs), else TexError.
)doc") + kOptionsDoc;
    m.def(
        "SynthesizeAlongCurve",
        [](const Curves& exemplar, const Curves& curve, double band_height, const py::kwargs& kw) {
            const SynthesisOptions o = options(kw, "SynthesizeAlongCurve");
            py::gil_scoped_release release;
            return SynthesizeAlongCurve(exemplar, curve, band_height, o);
        },
        py::arg("exemplar"), py::arg("curve"), py::arg("band_height"),
        along_doc.c_str());
    m.def(
        "SynthesizeInRectangle",
        [](const Curves& exemplar, double width, double height, double row_height, const py::kwargs& kw) {
            const SynthesisOptions o = options(kw, "SynthesizeInRectangle");
            py::gil_scoped_release release;
            return SynthesizeInRectangle(exemplar, width, height, row_height, o);
        },
        py::arg("exemplar"), py::arg("width"), py::arg("height"), py::arg("row_height"),
        rectangle_doc.c_str());
}

}  // namespace rhpy
