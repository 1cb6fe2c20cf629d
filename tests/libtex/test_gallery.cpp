// The Appendix A gallery: every example runs and is deterministic whatever the thread count.
#include <gtest/gtest.h>

#include <set>

#include "gallery.hpp"
#include "helpers.hpp"

using namespace tex;

namespace {

std::string render(const gallery::Example& e) {
    const Arrangement a = e.build(gallery::default_elements_dir());
    return ToSVG(a(Region::rectangle(0, 0, gallery::kSize, gallery::kSize)), gallery::kSize);
}

class GalleryTest : public ::testing::TestWithParam<std::string> {};

}  // namespace

TEST_P(GalleryTest, SameBytesWithOneOrTwoThreadsAndAcrossRuns) {
    const auto& e = gallery::find(GetParam());
    const unsigned saved = GetThreads();
    SetThreads(1);
    const std::string one = render(e);
    SetThreads(2);
    const std::string two = render(e);
    const std::string again = render(e);
    SetThreads(saved);
    EXPECT_EQ(one, two);
    EXPECT_EQ(two, again);
    EXPECT_GT(one.size(), 2000u) << "the drawing is nearly empty";
    // A different seed gives a different drawing for the random examples.
    static const std::set<std::string> no_random = {"stripes", "grid", "teaser_c", "teaser_h", "combine_b"};
    if (!no_random.count(e.name)) {
        const std::uint64_t seed = GetSeed();
        SetSeed(seed + 7);
        const std::string other = render(e);
        SetSeed(seed);
        EXPECT_NE(one, other);
    }
}

INSTANTIATE_TEST_SUITE_P(Appendix, GalleryTest,
                         ::testing::Values("stripes", "grid", "uniform", "random", "puzzle", "rosettes",
                                           "cracks", "bimodal", "crosses", "curves", "clusters", "overview",
                                           "combine_a", "combine_b", "combine_c"));
INSTANTIATE_TEST_SUITE_P(Teasers, GalleryTest,
                         ::testing::Values("teaser_a", "teaser_b", "teaser_c", "teaser_d", "teaser_e",
                                           "teaser_f", "teaser_g", "teaser_h"));

TEST(Gallery, ExpectedStructure) {
    // Puzzle: a 16 x 16 grid in which every other vertical edge is removed row by row.
    const Arrangement p = gallery::find("puzzle").build(gallery::default_elements_dir());
    const Curves c = p(Region::rectangle(0, 0, gallery::kSize, gallery::kSize));
    // KEEP_OUTSIDE on a window aligned with the grid: 17 x 16 horizontal + 16 x 17 vertical
    // edges, half of the vertical ones removed.
    EXPECT_EQ(c.curves.size(), std::size_t(17 * 16 + 16 * 17 / 2));
    // Rosettes: only circles (closed curves) on free ends of the stars.
    const Curves r = gallery::find("rosettes").build(gallery::default_elements_dir())(
        Region::rectangle(0, 0, gallery::kSize, gallery::kSize));
    for (const auto& cv : r.curves) EXPECT_TRUE(cv.closed);
    EXPECT_EQ(r.curves.size() % 1, 0u);
}

TEST(Gallery, UnknownExample) { EXPECT_TEX_ERROR(gallery::find("nope"), "gallery", "'nope'"); }
