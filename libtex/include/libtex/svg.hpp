// SVG import and export (table 3.6).
#pragma once

#include <string>

#include "libtex/arrangement.hpp"

namespace tex {

// Loads the curves of an SVG file: paths (all commands, Bézier curves and arcs flattened
// to polylines), lines, polylines, polygons, rects, circles and ellipses, with group and
// element transforms applied. A circle or ellipse carrying a `data-label` or
// `inkscape:label` attribute is a labelled point (its centre), not geometry: this is how
// an element marks its "start" and "end". Other elements with such a label are labelled
// curves (CurveLabeled). Throws tex::Error naming the file when it is missing, does not
// parse or holds no curve.
Curves ImportSVG(const std::string& filename);
// Same, from SVG text (origin names the source in messages).
Curves ParseSVG(const std::string& text, const std::string& origin = "<svg text>");

struct SvgStyle {
    double stroke_width = 2.0;
    bool background = true;  // white background rectangle
};

// SVG text of curves drawn in a size x size window (viewBox 0 0 size size).
std::string ToSVG(const Curves& c, double size, const SvgStyle& style = {});
// Evaluates a on the square [0, size]^2 and writes it to `filename` (atomically: written to
// a temporary file, then renamed). Returns the curves written.
Curves ExportSVG(const Arrangement& a, double size, const std::string& filename,
                 const SvgStyle& style = {});
void ExportSVG(const Curves& c, double size, const std::string& filename,
               const SvgStyle& style = {});

}  // namespace tex
