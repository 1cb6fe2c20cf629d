// Seed 004's figures 1a-1g (see gallery_discrete.hpp). Each program is the seed's, line for
// line where it can be: a greedy distribution of a pinning, a shaping and a check.
#include "gallery_discrete.hpp"

#include "gallery.hpp"

namespace gallery::discrete {
using namespace tex::disc;
using tex::Curves;
using tex::Point;
using tex::Region;

Region image() {
    return Image(kSize, kSize);
}

namespace {

// A tapered stroke: thin ends, `width` in the middle.
ThicknessFn tapered(double width) {
    return [width](double t) { return width * (0.25 + 0.75 * std::sin(tex::pi * t)); };
}

// Points inside the image (a stream line stops at its border).
PointCheck in_image() {
    const RegionSet frame({image()});
    return Overlap(frame);
}

tex::Arrangement outlines(const Figure& f) {
    Curves c = ToCurves(f.main);
    c.append(ToCurves(f.other));
    return tex::Constant(std::move(c));
}

}  // namespace

Figure fig_1a() {
    RegionSet hatches;
    greedy_distribution(hatches, CountUpTo(1000), RandomPinning(image()),
                        Translation(BuiltinHatch(kHatchLength, kHatchWidth)),
                        Not(Overlap(hatches)));
    return {hatches, {}};
}

Figure fig_1b() {
    RegionSet rectangles, hatches;
    greedy_distribution(rectangles, CountUpTo(25), Sequence(RegularPinning(image(), 5, 5)),
                        Translation(BuiltinRectangle(kRectWidth, kRectHeight)),
                        Not(Overlap(rectangles)));
    greedy_distribution(hatches, CountUpTo(1000), RandomPinning(image()),
                        Translation(BuiltinHatch(kHatchLength, kHatchWidth)),
                        And(Not(Overlap(hatches)), Overlap(rectangles)));
    return {hatches, rectangles};
}

Figure fig_1c() {
    const Figure b = fig_1b();
    RegionSet hatches = b.main, hatches_orth;
    greedy_distribution(hatches_orth, CountUpTo(3000), RandomPinning(image()),
                        Translation(Rotation(BuiltinHatch(kHatchLength, kHatchWidth), tex::pi / 2)),
                        And(Not(Overlap(hatches)), Not(Overlap(hatches_orth))));
    return {hatches, hatches_orth};
}

Figure fig_1d(const std::string& elements) {
    const Region user = UserRegion(gallery::element(elements + "/leaf.svg"));
    // One random operator per statement: their streams are numbered in the order they are
    // made, and C++ leaves the order of a call's arguments open.
    const RealGen angle = RandomR(0, 2 * tex::pi);
    const RealGen size = RandomR(0.3, 1.2);
    const std::function<Region()> shape =
        Compose(Rotation(angle), Compose(Scale(size), Const(user)));
    RegionSet shapes;
    greedy_distribution(shapes, CountUpTo(4000), RandomPinning(image()), Translation(shape),
                        Not(Overlap(shapes)));
    return {shapes, {}};
}

Figure circle_distribution() {
    RegionSet circles, relaxed_circles;
    greedy_distribution(circles, CountUpTo(kCircleDarts), RandomPinning(image()),
                        Translation(BuiltinCircle(kCircleRadius)), Not(Overlap(circles)));
    relaxation(circles, relaxed_circles, CountUpTo(kRelaxSteps), VoronoiCells(image().bbox()),
               Repinning([](const Region& r) { return Centroid(r); }));
    return {relaxed_circles, circles};
}

Figure fig_1e() {
    const Figure c = circle_distribution();
    const std::vector<Region> cells = VoronoiCells(c.main.regions(), image().bbox());
    const RealGen factor = RandomR(0.55, 0.9);
    RegionSet shapes;
    for (const auto& cell : cells) shapes.add(Scale(cell, factor()));
    return {shapes, {}};
}

Figure fig_1f() {
    const RegionSet relaxed_circles = circle_distribution().main;
    RegionSet stream_lines;
    const PointCheck free =
        And(in_image(), And(Not(Overlap(relaxed_circles)),
                            Not(MinimalDistance(stream_lines, kStreamWidth / 2 + kStreamGap))));
    const Shaping shaping = stream_line(TangentFlowField(relaxed_circles, kFlowStep), free,
                                        kStreamLength, tapered(kStreamWidth), 6 * kFlowStep);
    greedy_distribution(
        stream_lines, CountUpTo(2000), RandomPinning(image()), shaping,
        And(Not(Overlap(relaxed_circles)), Not(MinimalDistance(stream_lines, kStreamGap))));
    return {stream_lines, relaxed_circles};
}

Figure fig_1g() {
    const RegionSet relaxed_circles = circle_distribution().main;
    const FlowField flow = TangentFlowField(relaxed_circles, kFlowStep);
    // First set: from the circles' contours, at 30 degrees to the flow.
    RegionSet stream_lines;
    const std::vector<Point> pins = RegularPinning1D(Contour(relaxed_circles), 1.0 / 30);
    const FlowField turned = Compose(Rotation(tex::pi / 6), flow);
    greedy_distribution(
        stream_lines, CountUpTo((long long)pins.size()), Sequence(pins),
        stream_line(turned, And(in_image(), Not(MinimalDistance(stream_lines, kStreamWidth))),
                    kStreamLength / 2, tapered(kStreamWidth * 0.8), 4 * kFlowStep),
        Not(MinimalDistance(stream_lines, kStreamGap)));
    // Second set: from the first set's contours, along the flow, stopping at the first set.
    RegionSet scnd_strlines;
    const std::vector<Point> pins2 = RegularPinning1D(Contour(stream_lines), 1.0 / 40);
    greedy_distribution(scnd_strlines, CountUpTo((long long)pins2.size()), Sequence(pins2),
                        stream_line(flow, And(in_image(), Not(Overlap(stream_lines))),
                                    kStreamLength / 3, tapered(kStreamWidth * 0.5), 3 * kFlowStep),
                        Not(MinimalDistance(scnd_strlines, kStreamGap)));
    return {stream_lines, scnd_strlines};
}

tex::Arrangement arrangement_1a(const std::string&) {
    return outlines(fig_1a());
}
tex::Arrangement arrangement_1b(const std::string&) {
    return outlines({fig_1b().main, {}});
}
tex::Arrangement arrangement_1c(const std::string&) {
    return outlines(fig_1c());
}
tex::Arrangement arrangement_1d(const std::string& elements) {
    return outlines(fig_1d(elements));
}
tex::Arrangement arrangement_1e(const std::string&) {
    return outlines(fig_1e());
}
tex::Arrangement arrangement_1f(const std::string&) {
    return outlines(fig_1f());
}
tex::Arrangement arrangement_1g(const std::string&) {
    return outlines(fig_1g());
}

}  // namespace gallery::discrete
