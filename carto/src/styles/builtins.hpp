// The built-in rock styles, one per file (noisy.cpp ... aretes.cpp), each a program over the
// blocks of carto/blocks.hpp.
#pragma once

#include "carto/blocks.hpp"

namespace carto::blocks {

// One built-in style: its description and the body of its program.
struct Builtin {
    StyleInfo info;
    FaceBody body;
    bool valleys = false;
    // A whole program, for a style that draws its face in steps (print): replaces body.
    StyleProgram program;
};
// The built-ins, one per file (noisy.cpp ... bidirectional.cpp).
Builtin noisy();
Builtin ridge_triangles_style();
Builtin density_cells();
Builtin fine_ridges();
Builtin balanced();
Builtin high_ridges();
Builtin bidirectional();
Builtin aretes();
Builtin print();
Builtin rock();

}  // namespace carto::blocks
