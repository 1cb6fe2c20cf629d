// Merging operators (table 3.5): which edges Inside and Outside keep in each border mode.
#include <gtest/gtest.h>

#include "helpers.hpp"

using namespace tex;

namespace {

// A2: the square [0, 10]^2. A1: a line crossing it, a short segment inside, one far outside.
Arrangement square() { return Constant(Polyline({{0, 0}, {10, 0}, {10, 10}, {0, 10}}, true)); }
Arrangement strokes() {
    Curves c = Polyline({{-5, 5}, {15, 5}});
    c.append(Polyline({{2, 2}, {4, 2}}));
    c.append(Polyline({{20, 20}, {30, 20}}));
    c.curves[1].labels.add("short");
    return Constant(c);
}
const Region kAny = Region::rectangle(-100, -100, 100, 100);

double len(const Arrangement& a) { return th::length(a(kAny)); }

}  // namespace

TEST(Merge, InsideBorderModes) {
    EXPECT_NEAR(len(Inside(strokes(), square(), CROP)), 10 + 2, 1e-12);
    EXPECT_NEAR(len(Inside(strokes(), square(), CROP_ADD_BOUNDARY)), 10 + 2 + 40, 1e-12);
    EXPECT_NEAR(len(Inside(strokes(), square(), KEEP_INSIDE)), 2, 1e-12);
    EXPECT_NEAR(len(Inside(strokes(), square(), KEEP_OUTSIDE)), 20 + 2, 1e-12);
    for (const auto& c : Inside(strokes(), square(), CROP)(kAny).curves)
        for (const auto& p : c.points) EXPECT_TRUE(BBox({0, 0, 10, 10}).contains(p));
}

TEST(Merge, OutsideBorderModes) {
    EXPECT_NEAR(len(Outside(strokes(), square(), CROP)), 5 + 5 + 10, 1e-12);
    EXPECT_NEAR(len(Outside(strokes(), square(), CROP_ADD_BOUNDARY)), 5 + 5 + 10 + 40, 1e-12);
    EXPECT_NEAR(len(Outside(strokes(), square(), KEEP_INSIDE)), 10, 1e-12);
    EXPECT_NEAR(len(Outside(strokes(), square(), KEEP_OUTSIDE)), 20 + 10, 1e-12);
}

TEST(Merge, LabelsOfKeptEdgesSurvive) {
    const Curves c = Inside(strokes(), square(), CROP)(kAny);
    int labelled = 0;
    for (const auto& cv : c.curves) labelled += cv.labels.has("short");
    EXPECT_EQ(labelled, 1);
    for (const auto& cv : c.curves) EXPECT_FALSE(cv.left.has("\x01libtex-inside"));
}

TEST(Merge, FacesWithoutMaskEdgesInheritTheirStatus) {
    // A small closed square of A1 floating inside the mask (no mask edge on its boundary),
    // and one floating outside.
    Curves c = Polyline({{4, 4}, {6, 4}, {6, 6}, {4, 6}}, true);
    c.append(Polyline({{40, 40}, {42, 40}, {42, 42}, {40, 42}}, true));
    EXPECT_NEAR(len(Inside(Constant(c), square(), CROP)), 8, 1e-12);
    EXPECT_NEAR(len(Outside(Constant(c), square(), CROP)), 8, 1e-12);
    // Mask with a hole: a ring between [0,10]^2 and [3,7]^2.
    Curves ring = Polyline({{0, 0}, {10, 0}, {10, 10}, {0, 10}}, true);
    ring.append(Polyline({{3, 3}, {7, 3}, {7, 7}, {3, 7}}, true));
    // The hole is a bounded face of the mask's planar map too: "inside" means inside any
    // bounded face, so the floating square in the hole is kept.
    EXPECT_NEAR(len(Inside(Constant(c), Constant(ring), CROP)), 8, 1e-12);
}

TEST(Merge, UnionKeepsEverything) {
    EXPECT_EQ(Union(strokes(), square())(kAny).curves.size(), 4u);
}

TEST(Merge, RegionMaskWithHole) {
    const Region r({{0, 0}, {10, 0}, {10, 10}, {0, 10}}, {{{3, 3}, {7, 3}, {7, 7}, {3, 7}}});
    const Curves c = apply_mask(Polyline({{-1, 5}, {11, 5}}), r, CROP);
    EXPECT_NEAR(th::length(c), 6, 1e-12);  // 3 + 3, the hole cut out
}
