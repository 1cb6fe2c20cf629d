// SVG import and export (table 3.6).
#pragma once

#include <string>

#include "libtex/arrangement.hpp"
#include "libtex/domain.hpp"

namespace tex {

// Loads the curves of an SVG file: paths (all commands, Bézier curves and arcs flattened
// to polylines), lines, polylines, polygons, rects, circles and ellipses, with group and
// element transforms applied. A circle or ellipse carrying a `data-label` or
// `inkscape:label` attribute is a labelled point (its centre), not geometry: this is how
// an element marks its "start" and "end". Other elements with such a label are labelled
// curves (CurveLabeled). A `data-face-label` attribute labels the inside of the element's
// closed curves (it goes on the side of each closed curve the enclosed face lies on, so the
// face a planar map induces inside gets it; open curves ignore it). Throws tex::Error
// naming the file when it is missing, does not parse or holds no curve.
Curves ImportSVG(const std::string& filename);
// Same, from SVG text (origin names the source in messages).
Curves ParseSVG(const std::string& text, const std::string& origin = "<svg text>");

// Appends v to s as SVG exports write coordinates: fixed three decimals (rounded exactly,
// like std::to_chars with precision 3), trailing zeros and a bare point dropped, |v| below
// 0.0005 and non-finite values written as 0. Several times faster than std::to_chars with
// a precision (drawings of millions of points spend much of their export time here).
void append_svg_number(std::string& s, double v);

struct SvgStyle {
    double stroke_width = 2.0;
    bool background = true;  // white background rectangle
};

// SVG text of curves drawn in a size x size window (viewBox 0 0 size size).
std::string ToSVG(const Curves& c, double size, const SvgStyle& style = {});
// SVG text of curves drawn in the window `view` (viewBox xmin ymin width height, the
// drawing as large as the window). ToSVG(c, size) is ToSVG(c, {0, 0, size, size}).
std::string ToSVG(const Curves& c, const BBox& view, const SvgStyle& style = {});
// Evaluates a on the square [0, size]^2 and writes it to `filename` (atomically: written to
// a temporary file, then renamed). Returns the curves written.
Curves ExportSVG(const Arrangement& a, double size, const std::string& filename,
                 const SvgStyle& style = {});
void ExportSVG(const Curves& c, double size, const std::string& filename,
               const SvgStyle& style = {});

// Evaluates a in the frame (EvaluateInDomain) and writes it to `filename` (atomically, as
// ExportSVG) with a viewBox covering the frame's bounding box grown by `margin` on every
// side (the SVG's width and height are the viewBox's). Returns the curves written. Throws
// tex::Error naming ExportSVGinDomain when the frame bounds no region or margin is
// negative or not finite.
Curves ExportSVGinDomain(const Arrangement& a, const Curves& frame, const std::string& filename,
                         double margin = 10, const SvgStyle& style = {});

}  // namespace tex
