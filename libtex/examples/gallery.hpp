// The thesis's Appendix A examples (and the overview of Fig. 3.1) written with libtex.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "libtex/tex.hpp"

namespace gallery {

struct Example {
    std::string name;          // file stem of the output
    std::string title;         // name in the thesis
    double published_seconds;  // Appendix A time; 0: "< 1 sec"; -1: not published
    // The script: builds the arrangement (loads its SVG elements from `elements`).
    std::function<tex::Arrangement(const std::string& elements)> script;
    // Runs the script as a fresh program would: its partitions' random streams are
    // numbered from the start, whatever was built before.
    tex::Arrangement build(const std::string& elements) const {
        tex::StreamScope fresh(0);
        return script(elements);
    }
};

// Output size of every example (the thesis's `size = 2000`).
inline constexpr double kSize = 2000;

const std::vector<Example>& examples();

// The three textures of "Combining" (for the tests of the merges): rounded squares turned
// at random in a grid at angle theta, waves along stripes, circles of random sizes on a
// uniform partition.
tex::Arrangement squares(const std::string& elements, double theta, double width);
tex::Arrangement waves(const std::string& elements, double theta, double width);
tex::Arrangement circles(const std::string& elements, double density);
// The example with that name; throws tex::Error when there is none.
const Example& find(const std::string& name);
// Default folder of the SVG elements (the source tree).
std::string default_elements_dir();

// An SVG element of the gallery (ImportSVG of `path`), drawn `ElementDetail()` times finer:
// with detail k, every segment of a smooth stretch becomes k pieces of the cubic through its
// neighbours (Catmull-Rom), so a polygon standing for a circle gets k times its points and
// stays on its circle to within a fraction of its old error; a straight stretch between two
// corners (turns of 40 degrees or more) stays straight, with k - 1 points along it. The
// benchmarks time every script at two details, since a merge's cost must follow curves
// and crossings, not points. Detail 1 (the default) is ImportSVG itself.
tex::Curves element(const std::string& path);
// The detail of element(); set before building the examples (not thread-safe to change
// while an example builds).
void SetElementDetail(int k);
int ElementDetail();

}  // namespace gallery
