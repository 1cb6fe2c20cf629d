// The rock-hatching styles: the design iterations of the seed's Fig. 5.4 (a) to (g).
//
// A style is a controlled arrangement (seed 5.3): given the control fields (face-wise
// orientation and density, elevation, roughness) it returns, for one face, the hatches of
// that face. It reads the fields only inside the face and at its boundary, so changing a
// field in a window changes the output only near that window.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "carto/fields.hpp"
#include "carto/hatching.hpp"
#include "carto/partition.hpp"

namespace carto {

enum class Family { Fill = 0, Ridge = 1, Valley = 2, Cross = 3 };
inline constexpr int kFamilies = 4;
const char* family_name(Family f);
// Suggested stroke width on paper (mm).
double family_width_mm(Family f);

struct Hatch {
    Polyline points;
    bool closed = false;
    Family family = Family::Fill;
};

struct StyleParam {
    std::string name;
    double value;      // default
    std::string unit;  // "mm" (on paper, converted with the scale), "ratio", "deg"
    std::string help;
};

struct StyleInfo {
    std::string name;    // e.g. "bidirectional"
    std::string figure;  // "5.4g"
    std::string title;
    std::vector<StyleParam> params;
};

// All built-in styles, (a) to (g); the default is the last one.
const std::vector<StyleInfo>& styles();
const std::string& default_style();
// Throws carto::Error(UnknownStyle) listing the known names.
const StyleInfo& find_style(const std::string& name);

// The control fields f1..fn a style is applied to (seed 5.3: a style is the controlled
// arrangement f1..fn -> arrangement).
struct ControlFields {
    Field orientation;  // hatch direction, radians (axial); face-wise constant in practice
    Field density;      // 0..1, 1 = darkest; face-wise constant in practice
    Field height;       // 0..1 normalised elevation
    Field roughness;    // 0..1
};

// What a style reads about one face, evaluated from the fields inside the face and just
// across its border (the seed reads orientation and density at the face's centroid).
struct FaceControls {
    double orientation;  // hatch direction, radians (axial)
    double density;      // 0..1, 1 = darkest
    double height;       // 0..1, highest point of the face's boundary in the DEM's range
    // Density of the face across boundary segment i (NaN: none).
    std::function<double(int)> neighbour_density;
    // Feature id of the face across boundary segment i (-1: none).
    std::function<std::int64_t(int)> neighbour_id;
    Field height_field;     // 0..1 normalised elevation
    Field roughness_field;  // 0..1
};

// Style parameters resolved to ground units (mm x scale / 1000 for "mm" parameters).
using ParamValues = std::map<std::string, double>;
ParamValues resolve_params(const StyleInfo& s, const std::map<std::string, double>& overrides, double scale);

// Evaluates the fields for one face; neighbour_id comes from the partition's adjacency.
FaceControls face_controls(const RockFace& face, const ControlFields& f,
                           std::function<std::int64_t(int)> neighbour_id);

// The hatches of one face.
std::vector<Hatch> hatch_face(const StyleInfo& style, const ParamValues& p, const RockFace& face,
                              const FaceControls& c, std::uint64_t seed);

// Feature id of the face across boundary segment i of a face (-1: none).
using NeighbourId = std::function<std::int64_t(int)>;
// A style bound to its fields, parameters and seed: the hatches of one face. It is called
// for several faces at once, from several threads.
using FaceHatcher = std::function<std::vector<Hatch>(const RockFace&, const NeighbourId&)>;

// A style as the seed's controlled arrangement (f1..fn) -> arrangement: its description
// (name, parameters and their defaults) and the function binding it to the control
// fields. Built-in styles and styles written in Python (rockhatch --script) share it.
struct Style {
    StyleInfo info;
    std::function<FaceHatcher(const ControlFields&, const ParamValues&, std::uint64_t seed)> bind;
};
// The built-in style of that name (see find_style) as a Style.
Style builtin_style(const std::string& name);

}  // namespace carto
