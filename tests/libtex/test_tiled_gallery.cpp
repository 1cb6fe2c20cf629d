// The proof that a tiled map is the same arrangement (thesis 4.2): every regular gallery
// example without Random, written on a tiled partition and converted over the gallery
// window, gives the same set of whole curves (order and direction aside, labels and side
// labels included) as the planar-map engine; regular result (a), a mask of hatch lines,
// after cutting both drawings where a tile's corner touches a line (a split decided by
// rounding in both engines).
//
// The partitions alone match over the whole window (same border modes). A mapped example
// differs from the engine's only along the window's border, where the engine's finite map
// cuts cells short (a brick whose joint lies outside the window is no face there; an edge of
// the window's border has no neighbour beyond): those are compared on the window less a
// margin of two cells, where the engine sees whole neighbourhoods too.
#include <gtest/gtest.h>

#include <algorithm>
#include <iterator>

#include "gallery.hpp"
#include "gallery_more.hpp"
#include "gallery_teasers.hpp"
#include "libtex/tex.hpp"
#include "tiled_helpers.hpp"

using namespace tex;

namespace {

const Region kWindow = Region::rectangle(0, 0, gallery::kSize, gallery::kSize);
constexpr double kMargin = 600;  // more than two bricks, cells or lozenges
const BBox kInner = Region::rectangle(kMargin, kMargin, gallery::kSize - kMargin, gallery::kSize - kMargin).bbox();
const Region kInnerRegion = Region::rectangle(kMargin, kMargin, gallery::kSize - kMargin, gallery::kSize - kMargin);

Curves engine_example(const std::string& name) {
    return gallery::find(name).build(gallery::default_elements_dir())(kWindow);
}

// The tiled drawing (converted over the inner window with KEEP_OUTSIDE) equals the engine's
// inside the inner window, and is not empty.
// Both are filtered by the same box, a hair inside the window, so that a curve lying on the
// window's side (rounded one way in one engine, the other way in the other) counts alike.
void expect_same_inside(const Curves& tiled_inner, const Curves& engine) {
    const BBox filter = kInner.expanded(-0.01);
    const Curves t = th::inside_box(tiled_inner, filter), e = th::inside_box(engine, filter);
    EXPECT_GT(t.curves.size(), 5u);
    EXPECT_SAME_CURVES(t, e);
}

}  // namespace

TEST(TiledGallery, Grid) {
    // The "grid" example: rows of 200 and 80, columns of 250, KEEP_OUTSIDE.
    const Stripes h = StripesProperties(0, gallery::kSize / 10, gallery::kSize / 25);
    const Stripes v = StripesProperties(pi / 2, gallery::kSize / 8);
    const Curves tiled = GridPartition(h, v, Tiled(KEEP_OUTSIDE))(kWindow);
    EXPECT_SAME_CURVES(tiled, engine_example("grid"));
}

TEST(TiledGallery, Stripes) {
    const Stripes s = StripesProperties(pi / 4, gallery::kSize / 10, gallery::kSize / 30);
    const Curves tiled = StripesPartition(s, Tiled(CROP_ADD_BOUNDARY))(kWindow);
    EXPECT_SAME_CURVES(tiled, engine_example("stripes"));
}

TEST(TiledGallery, BrickWallOfTeaserC) {
    namespace tz = gallery::teasers;
    const TiledMap wall = MapToFaces(
        tz::shrink_brick, MapToEdges(tz::keep_brick_joints, GridPartition(tz::brick_rows(), tz::brick_columns(), Tiled())));
    // Period: 2 rows of 200 by 4 columns of 120; a long and a short course, 1 + 2 bricks.
    EXPECT_EQ(wall.elements().size(), 3u);
    const Curves engine = engine_example("teaser_c");
    expect_same_inside(wall.Convert(kInnerRegion, KEEP_OUTSIDE), engine);
    // Over the whole window every brick of the engine is there (the tiled map adds the bricks
    // the engine's finite map leaves open along the border).
    const auto all = th::whole_curves(wall.Convert(kWindow, KEEP_OUTSIDE)), eng = th::whole_curves(engine);
    std::vector<std::string> missing;
    std::set_difference(eng.begin(), eng.end(), all.begin(), all.end(), std::back_inserter(missing));
    EXPECT_TRUE(missing.empty()) << th::curve_diff(eng, all);
    EXPECT_GT(all.size(), eng.size());
}

TEST(TiledGallery, PuzzleWallBeforeItsRandomFlip) {
    Stripes l1 = StripesProperties(0.0, gallery::kSize / 16);
    Stripes l2 = StripesProperties(pi / 2, gallery::kSize / 16);
    SetEdgeLabels(l1, {"h1", "h2"});
    SetEdgeLabels(l2, {"v1", "v2"});
    // The puzzle script's first mapper (gallery.cpp), run by both engines.
    auto grid_to_wall = [](const Edge& e) {
        const auto around = IncidentEdges(TargetVertex(e));
        if ((HasLabel(e, "v1") && HasLabel(around, "h1")) || (HasLabel(e, "v2") && HasLabel(around, "h2")))
            return Nothing();
        return ToCurve(e);
    };
    const Curves engine = MapToEdges(grid_to_wall, GridPartition(l1, l2, KEEP_OUTSIDE))(kWindow);
    const TiledMap wall = MapToEdges(grid_to_wall, GridPartition(l1, l2, Tiled()));
    expect_same_inside(wall.Convert(kInnerRegion, KEEP_OUTSIDE), engine);
}

TEST(TiledGallery, CrossesWithoutJitter) {
    const Curves cross = ImportSVG(gallery::default_elements_dir() + "/cross.svg");
    Stripes l1 = StripesProperties(0, gallery::kSize / 10);
    Stripes l2 = StripesProperties(pi / 2, gallery::kSize / 18);
    SetFaceLabels(l1, {"h1", "h2"});
    SetFaceLabels(l2, {"v1", "v2"});
    // The "regular crosses" script with its random scale and turn fixed at their middles.
    auto face_to_cross = [cross](const Face& f) {
        const bool one_in_two =
            (HasLabel(f, "v1") && HasLabel(f, "h1")) || (HasLabel(f, "v2") && HasLabel(f, "h2"));
        if (!one_in_two) return Nothing();
        const Curves e = Scale(cross, 1.4);
        return MatchPoint(e, BBoxCenter(e), BBoxCenter(f));
    };
    const Curves engine = MapToFaces(face_to_cross, GridPartition(l1, l2, KEEP_OUTSIDE))(kWindow);
    const TiledMap crosses = MapToFaces(face_to_cross, GridPartition(l1, l2, Tiled()));
    expect_same_inside(crosses.Convert(kInnerRegion, KEEP_OUTSIDE), engine);
}

TEST(TiledGallery, TrianglesAndBeeHive) {
    const TiledMap lozenges = GridPartition(StripesProperties(pi / 3, 200), StripesProperties(-pi / 3, 200), Tiled());
    const TiledMap triangles = Union(lozenges, MapToFaces(gallery::more::split_diagonal, lozenges));
    expect_same_inside(triangles.Convert(kInnerRegion, KEEP_OUTSIDE), engine_example("triangles"));
    // The bee hive: the dual bar of every inner edge, mapped on the triangles.
    auto dual = [](const Edge& e) {
        return IsBoundary(e) ? Nothing() : Polyline({Centroid(LeftFace(e)), Centroid(RightFace(e))});
    };
    expect_same_inside(MapToEdges(dual, triangles).Convert(kInnerRegion, KEEP_OUTSIDE), engine_example("bee_hive"));
}

TEST(TiledGallery, WallpaperP4m) {
    // Bumps laid both ways along every edge of the square grid turned 45 degrees (the gallery's
    // stroke_along / stroke_against, written out).
    const Curves bump = ImportSVG(gallery::default_elements_dir() + "/bump.svg");
    auto along = [bump](const Edge& e) {
        return MatchPoints(bump, PointLabeled(bump, "start"), PointLabeled(bump, "end"), Location(SourceVertex(e)),
                           Location(TargetVertex(e)));
    };
    auto against = [bump](const Edge& e) {
        return MatchPoints(bump, PointLabeled(bump, "end"), PointLabeled(bump, "start"), Location(SourceVertex(e)),
                           Location(TargetVertex(e)));
    };
    const TiledMap grid = GridPartition(StripesProperties(pi / 4, 200), StripesProperties(-pi / 4, 200), Tiled());
    const TiledMap p4m = Union(MapToEdges(along, grid), MapToEdges(against, grid));
    expect_same_inside(p4m.Convert(kInnerRegion, KEEP_OUTSIDE), engine_example("wallpaper_p4m"));
}

TEST(TiledGallery, RegularResultA) {
    // Horizontal hatching outside tiles turned 45 degrees and shrunk: a mask on a common
    // period of 15 and 200 (600), and faces of a map of overlapping turned squares.
    auto turn = [](const Face& f) { return Rotate(Contour(f), pi / 4); };
    auto reduce = [](const Face& f) { return Scale(Contour(f), 0.8); };
    const TiledMap tiles = MapToFaces(
        reduce, MapToFaces(turn, GridPartition(StripesProperties(0, 200), StripesProperties(pi / 2, 200), Tiled())));
    const TiledMap hatching = Outside(StripesPartition(StripesProperties(0, 15), Tiled()), tiles, CROP);
    EXPECT_NEAR(std::abs(hatching.period1().y), 600, 1e-9);
    // As whole curves, like the other examples: the mask's pieces of hatching lines are
    // joined again where only the period cut them. One degenerate case is set aside: a
    // tile's corner lying exactly on a hatch line. Whether the line is split there is decided
    // by rounding, in the engine as in the mask (the engine splits the line y = 780 at the
    // corner x = 1133.1371 and not the line y = 1380 at the same corner one period up), so
    // both drawings are cut at every tile corner that lies on them before they are compared.
    std::vector<Point> corners;
    for (const auto& c : tiles.Convert(kWindow, KEEP_OUTSIDE).curves)
        corners.insert(corners.end(), c.points.begin(), c.points.end());
    const Curves tiled = th::split_at_points(hatching.Convert(kInnerRegion, KEEP_OUTSIDE), corners);
    const Curves engine = th::split_at_points(engine_example("regular_a"), corners);
    expect_same_inside(tiled, engine);
    // Without that cut, the two differ at those corners only: a handful of curves.
    const auto a = th::whole_curves(th::inside_box(hatching.Convert(kInnerRegion, KEEP_OUTSIDE), kInner.expanded(-0.01)));
    const auto b = th::whole_curves(th::inside_box(engine_example("regular_a"), kInner.expanded(-0.01)));
    std::vector<std::string> only;
    std::set_symmetric_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(only));
    EXPECT_LE(only.size(), 20u) << th::curve_diff(a, b);
}

TEST(TiledGallery, RegularResultBIsNotPeriodicAndSaysSo) {
    // Horizontal hatching 40 apart in the tiles of a lattice turned 45 degrees: the periods
    // project on the hatching's normal to 400 * sqrt(2), an irrational number of hatching
    // periods, so no translation of the lattice maps the hatching onto itself: the engine's
    // drawing has no two independent periods and no tiled map can stand for it.
    namespace mo = gallery::more;
    const Curves wobble = ImportSVG(gallery::default_elements_dir() + "/wobble.svg");
    const TiledMap grid = GridPartition(mo::chevron_lines(pi / 4, "h"), mo::chevron_lines(-pi / 4, "v"), Tiled());
    try {
        mo::regular_b_on(grid, wobble, 40);
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("MapToFaces"), std::string::npos) << m;
        EXPECT_NE(m.find("every 40 "), std::string::npos) << m;
        EXPECT_NE(m.find("(-565.685, 565.685)"), std::string::npos) << m;
        EXPECT_NE(m.find("not periodic"), std::string::npos) << m;
    }
}

TEST(TiledGallery, RegularResultBWithCommensurableHatching) {
    // The same script with the hatching 200 * sqrt(2) / 7 (about 40.4) apart: both periods
    // then hold 14 hatching periods, the tiled map keeps its lattice and equals the engine.
    // (Tiled.SubPartitionOnACoarserLattice in test_tiled.cpp: a spacing that needs a coarser
    // lattice.)
    namespace mo = gallery::more;
    const Curves wobble = ImportSVG(gallery::default_elements_dir() + "/wobble.svg");
    const double spacing = 200 * std::sqrt(2.0) / 7;
    const TiledMap tiled =
        mo::regular_b_on(GridPartition(mo::chevron_lines(pi / 4, "h"), mo::chevron_lines(-pi / 4, "v"), Tiled()),
                         wobble, spacing);
    const Curves engine = mo::regular_b_on(
        GridPartition(mo::chevron_lines(pi / 4, "h"), mo::chevron_lines(-pi / 4, "v"), KEEP_OUTSIDE), wobble,
        spacing)(kWindow);
    expect_same_inside(tiled.Convert(kInnerRegion, KEEP_OUTSIDE), engine);
}

TEST(TiledGallery, ChevronStagesOnALatticeTurned45Degrees) {
    // Each stage of regular result (b) on its own: the chevron rule (which reads the labels
    // around an edge's target), the shrunk chevrons, the hatching.
    namespace mo = gallery::more;
    const double spacing = 200 * std::sqrt(2.0) / 7;
    auto hatch = [spacing](const Face& f) { return mo::hatch_tile(f, spacing); };
    const TiledMap t1 =
        MapToEdges(mo::chevron_rule, GridPartition(mo::chevron_lines(pi / 4, "h"), mo::chevron_lines(-pi / 4, "v"), Tiled()));
    const Arrangement e1 = MapToEdges(
        mo::chevron_rule, GridPartition(mo::chevron_lines(pi / 4, "h"), mo::chevron_lines(-pi / 4, "v"), KEEP_OUTSIDE));
    expect_same_inside(t1.Convert(kInnerRegion, KEEP_OUTSIDE), e1(kWindow));
    const TiledMap t2 = MapToFaces(mo::chevron_shrink, t1);
    const Arrangement e2 = MapToFaces(mo::chevron_shrink, e1);
    expect_same_inside(t2.Convert(kInnerRegion, KEEP_OUTSIDE), e2(kWindow));
    expect_same_inside(MapToFaces(hatch, t2).Convert(kInnerRegion, KEEP_OUTSIDE), MapToFaces(hatch, e2)(kWindow));
}
