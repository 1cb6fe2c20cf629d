#include "gallery_synthesis.hpp"
#include "gallery.hpp"

#include <cmath>
#include <vector>

namespace gallery::synthesis {

using namespace tex;

namespace {

SynthesisOptions options(std::optional<int> components, std::optional<int> holes) {
    SynthesisOptions o;
    o.components = components;
    o.holes = holes;
    o.event_grouping = kEventGrouping;
    o.randomness = kRandomness;
    return o;
}

Curves ring(double r, int n) {
    std::vector<Point> p;
    for (int i = 0; i < n; ++i) {
        const double a = 2 * pi * i / n;
        p.push_back({1000 + r * std::cos(a), 1000 + r * std::sin(a)});
    }
    return Polyline(p, true);
}

Curves wave(double y, double amplitude, int n) {
    std::vector<Point> p;
    for (int i = 0; i <= n; ++i) {
        const double x = 150 + 1700.0 * i / n;
        p.push_back({x, y + amplitude * std::sin(2 * pi * (x - 150) / 850)});
    }
    return Polyline(p, false);
}

}  // namespace

Arrangement circle(const std::string& dir) {
    const Curves vine = gallery::element(dir + "/synth_vine.svg");
    SynthesisOptions round = options(1, std::nullopt);
    round.closed_pattern = true;
    Curves c = SynthesizeAlongCurve(vine, ring(750, 360), 150, round);
    c.append(SynthesizeAlongCurve(vine, ring(430, 360), 120, options(1, 0)));
    return Constant(c);
}

Arrangement curve(const std::string& dir) {
    const Curves vine = gallery::element(dir + "/synth_vine.svg");
    Curves c = SynthesizeAlongCurve(vine, wave(650, 180, 400), 130, options(1, std::nullopt));
    c.append(SynthesizeAlongCurve(vine, wave(1350, 180, 400), 130, options(1, 0)));
    return Constant(c);
}

Arrangement rectangle(const std::string& dir) {
    const Curves ladder = gallery::element(dir + "/synth_ladder.svg");
    return Constant(Translate(SynthesizeInRectangle(ladder, 1600, 1600, 160, options(1, std::nullopt)), {200, 200}));
}

}  // namespace gallery::synthesis
