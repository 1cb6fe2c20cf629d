// Partitioning operators (table 3.2) and their border modes (Fig. 3.4).
#include <gtest/gtest.h>

#include <string>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <random>
#include <set>
#include <thread>

#include "helpers.hpp"

using namespace tex;

namespace {

bool face_inside(const PlanarMap& m, int f, const Region& r, double eps = 1e-9) {
    for (int v : m.faces()[f].vertices) {
        const Point p = m.vertices()[v].point;
        const BBox b = r.bbox().expanded(eps);
        if (!b.contains(p)) return false;
    }
    return true;
}

}  // namespace

TEST(Stripes, WidthCycleAndLabelCyclesAreReproduced) {
    Stripes s = StripesProperties(0, 10, 20, 5);
    SetEdgeLabels(s, {"a", "b"});
    SetFaceLabels(s, {"x", "y", "z"});
    const Region r = Region::rectangle(0, 1, 100, 99);
    const MapPtr m = StripesPartition(s).induce(r);
    // Horizontal stripe lines are the labelled edges; the outline has none.
    std::set<double> ys;
    for (const auto& e : m->edges()) {
        if (e.labels.empty()) continue;
        const double y = m->vertices()[e.source].point.y;
        EXPECT_EQ(y, m->vertices()[e.target].point.y);
        ys.insert(y);
        // Line i (offsets 0, 10, 30, 35, 45, ...) carries label a for even i, b for odd i.
        const int i = y == 10 ? 1 : y == 30 ? 2 : y == 35 ? 3 : y == 45 ? 4 : y == 65 ? 5 : y == 70 ? 6 : 7;
        EXPECT_TRUE(e.labels.has(i % 2 == 0 ? "a" : "b")) << "line at y=" << y;
        EXPECT_EQ(e.labels.size(), 1u);
    }
    EXPECT_EQ(std::vector<double>(ys.begin(), ys.end()), (std::vector<double>{10, 30, 35, 45, 65, 70, 80}));
    // Band i (between line i and i+1) carries face label i mod 3.
    const std::vector<double> offsets = {0, 10, 30, 35, 45, 65, 70, 80, 100};
    const char* names[] = {"x", "y", "z"};
    std::size_t checked = 0;
    for (std::size_t f = 0; f < m->faces().size(); ++f) {
        if (m->faces()[f].unbounded) continue;
        const double cy = Centroid(Face(m, int(f))).y;
        const std::size_t band = std::size_t(std::upper_bound(offsets.begin(), offsets.end(), cy) - offsets.begin()) - 1;
        EXPECT_TRUE(m->faces()[f].labels.has(names[band % 3])) << "band " << band;
        EXPECT_EQ(m->faces()[f].labels.size(), 1u);
        ++checked;
    }
    EXPECT_EQ(checked, 8u);
}

TEST(Stripes, AnchoredToThePlane) {
    // Two neighbouring regions see the same lines.
    Stripes s = StripesProperties(0.3, 7, 3);
    SetEdgeLabels(s, {"line"});
    const Arrangement a = StripesPartition(s);
    auto crossings = [&](const Region& r, double x) {
        std::set<long long> ys;
        for (const auto& c : a(r).curves) {
            if (!c.labels.has("line")) continue;
            for (const auto& p : c.points)
                if (std::abs(p.x - x) < 1e-9) ys.insert(std::llround(p.y * 1e6));
        }
        return ys;
    };
    const auto left = crossings(Region::rectangle(0, 0, 50, 50), 50);
    const auto right = crossings(Region::rectangle(50, 0, 100, 50), 50);
    EXPECT_FALSE(left.empty());
    EXPECT_EQ(left, right);
}

TEST(Grid, BorderModes) {
    const Stripes h = StripesProperties(0, 10), v = StripesProperties(pi / 2, 10);
    const Region r = Region::rectangle(5, 5, 95, 95);
    const MapPtr inside = GridPartition(h, v, KEEP_INSIDE).induce(r);
    const MapPtr outside = GridPartition(h, v, KEEP_OUTSIDE).induce(r);
    const MapPtr crop = GridPartition(h, v, CROP).induce(r);
    const MapPtr cropb = GridPartition(h, v, CROP_ADD_BOUNDARY).induce(r);
    EXPECT_EQ(th::bounded_faces(*inside), 64u);    // cells [10, 90]^2
    EXPECT_EQ(th::bounded_faces(*outside), 100u);  // cells [0, 100]^2
    EXPECT_EQ(th::bounded_faces(*cropb), 100u);    // 64 whole cells + 36 cut ones
    EXPECT_EQ(th::bounded_faces(*crop), 64u);      // cut cells stay open without the outline
    double area = 0;
    for (std::size_t f = 0; f < cropb->faces().size(); ++f) {
        if (cropb->faces()[f].unbounded) continue;
        EXPECT_TRUE(face_inside(*cropb, int(f), r));
        area += th::face_area(*cropb, int(f));
    }
    EXPECT_NEAR(area, r.area(), 1e-9);  // the cropped faces tile the region exactly
    for (const auto& vx : crop->vertices()) EXPECT_TRUE(r.bbox().expanded(1e-9).contains(vx.point));
    for (std::size_t f = 0; f < inside->faces().size(); ++f)
        if (!inside->faces()[f].unbounded) EXPECT_TRUE(face_inside(*inside, int(f), r));
}

TEST(Grid, KeepModesOnARegionWithAHole) {
    const Stripes h = StripesProperties(0, 10), v = StripesProperties(pi / 2, 10);
    const Region r({{0, 0}, {100, 0}, {100, 100}, {0, 100}}, {{{35, 35}, {65, 35}, {65, 65}, {35, 65}}});
    // 16 cells meet the hole, 4 of them lie entirely in it. The kept cells enclose the
    // dropped ones, which leaves one more bounded face in the planar map: the gap.
    auto cells = [](const PlanarMap& m) {
        std::size_t n = 0;
        for (std::size_t f = 0; f < m.faces().size(); ++f)
            n += !m.faces()[f].unbounded && std::abs(th::face_area(m, int(f)) - 100) < 1e-9;
        return n;
    };
    const MapPtr in = GridPartition(h, v, KEEP_INSIDE).induce(r);
    const MapPtr out = GridPartition(h, v, KEEP_OUTSIDE).induce(r);
    EXPECT_EQ(cells(*in), 84u);
    EXPECT_EQ(th::bounded_faces(*in), 85u);
    EXPECT_EQ(cells(*out), 96u);
    EXPECT_EQ(th::bounded_faces(*out), 97u);
    const MapPtr cropb = GridPartition(h, v, CROP_ADD_BOUNDARY).induce(r);
    double area = 0;
    for (std::size_t f = 0; f < cropb->faces().size(); ++f)
        if (!cropb->faces()[f].unbounded) area += th::face_area(*cropb, int(f));
    // The hole is a bounded face of the outline too (area 900): everything else is the region.
    EXPECT_NEAR(area, r.area() + 900, 1e-9);
}

TEST(Grid, FaceLabelsFromBothFamilies) {
    Stripes h = StripesProperties(0, 10), v = StripesProperties(pi / 2, 10);
    SetFaceLabels(h, {"h1", "h2"});
    SetFaceLabels(v, {"v1", "v2"});
    const MapPtr m = GridPartition(h, v, KEEP_INSIDE).induce(Region::rectangle(0, 0, 40, 40));
    EXPECT_EQ(th::bounded_faces(*m), 16u);
    for (std::size_t f = 0; f < m->faces().size(); ++f) {
        if (m->faces()[f].unbounded) continue;
        const Point c = Centroid(Face(m, int(f)));
        // Bands are numbered along each family's normal (-sin a, cos a): +y for the
        // horizontal lines (a = 0), -x for the vertical ones (a = pi/2).
        const int i = int(std::floor(c.y / 10)), j = int(std::floor(-c.x / 10));
        const auto& l = m->faces()[f].labels;
        EXPECT_EQ(l.size(), 2u);
        EXPECT_TRUE(l.has(i % 2 ? "h2" : "h1"));
        EXPECT_TRUE(l.has((j % 2 + 2) % 2 ? "v2" : "v1"));
    }
}

TEST(Grid, ParallelFamiliesAreRefused) {
    const Stripes a = StripesProperties(0.5, 10), b = StripesProperties(0.5, 4);
    EXPECT_TEX_ERROR(GridPartition(a, b, CROP)(Region::rectangle(0, 0, 10, 10)), "GridPartition", "parallel");
}

TEST(Uniform, FaceCountFollowsDensityAndSitesRespectTheRadius) {
    // Many faces, so that the cut cells along the border weigh little.
    const double d = 2500.0 / (1000.0 * 1000.0);
    const Region r = Region::rectangle(0, 0, 1000, 1000);
    const MapPtr m = UniformPartition(IrregularProperties(d), CROP_ADD_BOUNDARY).induce(r);
    const double faces = double(th::bounded_faces(*m));
    EXPECT_NEAR(faces, d * r.area(), 0.1 * d * r.area());
    const auto sites = PoissonDiskSites(d, BBox{0, 0, 1000, 1000});
    EXPECT_NEAR(double(sites.size()), 2500, 250);
    const double rad = PoissonDiskRadius(d);
    double min_d2 = 1e300;
    for (std::size_t i = 0; i < sites.size(); ++i)
        for (std::size_t j = i + 1; j < sites.size(); ++j) min_d2 = std::min(min_d2, dot(sites[i] - sites[j], sites[i] - sites[j]));
    EXPECT_GE(std::sqrt(min_d2), rad);
    // No big holes: every point of the box (away from its border) has a site within twice
    // the radius (a maximal sampling would give one within the radius itself).
    double worst = 0;
    for (double x = 100; x <= 900; x += 10)
        for (double y = 100; y <= 900; y += 10) {
            double best = 1e300;
            for (const Point& s : sites) best = std::min(best, dot(s - Point{x, y}, s - Point{x, y}));
            worst = std::max(worst, std::sqrt(best));
        }
    EXPECT_LT(worst, 2 * rad) << "a hole of radius " << worst << " (sampling radius " << rad << ")";
}

TEST(Uniform, SitesAreAFunctionOfThePlane) {
    const double d = 1e-3;
    const auto a = PoissonDiskSites(d, BBox{0, 0, 300, 300});
    const auto b = PoissonDiskSites(d, BBox{150, -100, 500, 300});
    std::set<std::pair<double, double>> sa, sb;
    for (const auto& p : a)
        if (p.x >= 150) sa.insert({p.x, p.y});
    for (const auto& p : b)
        if (p.x <= 300 && p.y >= 0) sb.insert({p.x, p.y});
    EXPECT_FALSE(sa.empty());
    EXPECT_EQ(sa, sb);
}

TEST(Random, PoissonCountFollowsDensity) {
    const double d = 1e-3;
    const auto s = PoissonSites(d, BBox{0, 0, 1000, 1000});
    EXPECT_NEAR(double(s.size()), 1000, 100);  // mean 1000, sd 32
    const MapPtr m = RandomPartition(IrregularProperties(d), KEEP_INSIDE).induce(Region::rectangle(0, 0, 1000, 1000));
    EXPECT_GT(th::bounded_faces(*m), 800u);
    EXPECT_LT(th::bounded_faces(*m), 1000u);
}

TEST(Irregular, KeepOutsideKeepsWholeCellsCoveringTheRegion) {
    const Region r = Region::rectangle(0, 0, 500, 500);
    const MapPtr m = UniformPartition(IrregularProperties(1e-4), KEEP_OUTSIDE).induce(r);
    double area = 0;
    BBox all;
    for (std::size_t f = 0; f < m->faces().size(); ++f) {
        if (m->faces()[f].unbounded) continue;
        area += th::face_area(*m, int(f));
        for (int v : m->faces()[f].vertices) all.add(m->vertices()[v].point);
    }
    EXPECT_GT(area, r.area());
    EXPECT_LT(all.xmin, 0);
    EXPECT_GT(all.xmax, 500);
    // Every point of the region lies in some kept face: probe a lattice.
    for (double x = 5; x < 500; x += 49)
        for (double y = 5; y < 500; y += 49) {
            bool found = false;
            for (std::size_t f = 0; f < m->faces().size() && !found; ++f)
                if (!m->faces()[f].unbounded) found = point_in_ring({x, y}, m->cycle_points(int(f), 0));
            EXPECT_TRUE(found) << x << "," << y;
        }
}

TEST(Irregular, WeightedLabels) {
    Irregular p = IrregularProperties(1e-3);
    SetWeightedFaceLabels(p, {{"dark", 0.25}, {"light", 0.5}});
    const MapPtr m = UniformPartition(p, KEEP_INSIDE).induce(Region::rectangle(0, 0, 1000, 1000));
    std::size_t dark = 0, light = 0, none = 0;
    for (const auto& f : m->faces()) {
        if (f.unbounded) continue;
        if (f.labels.has("dark")) ++dark;
        else if (f.labels.has("light")) ++light;
        else ++none;
    }
    const double n = double(dark + light + none);
    EXPECT_NEAR(dark / n, 0.25, 0.05);
    EXPECT_NEAR(light / n, 0.5, 0.05);
    EXPECT_TEX_ERROR(SetWeightedEdgeLabels(p, {{"a", 0.7}, {"b", 0.6}}), "SetWeightedEdgeLabels", "sum to 1.3");
    EXPECT_TEX_ERROR(SetWeightedVertexLabels(p, {{"a", -0.1}}), "SetWeightedVertexLabels", "-0.1");
}

TEST(Partitions, BadParametersAreNamed) {
    EXPECT_TEX_ERROR(StripesProperties(0, 0.0), "StripesProperties", "width 0 ");
    EXPECT_TEX_ERROR(StripesProperties(0, 10, -2), "StripesProperties", "width -2");
    EXPECT_TEX_ERROR(StripesProperties(0, std::vector<double>{}), "StripesProperties", "no width");
    EXPECT_TEX_ERROR(IrregularProperties(0), "IrregularProperties", "density 0 ");
    EXPECT_TEX_ERROR(IrregularProperties(-3), "IrregularProperties", "density -3");
    EXPECT_TEX_ERROR(Region({{0, 0}, {1, 1}}), "Region", "empty region");
    EXPECT_TEX_ERROR(Region({{0, 0}, {1, 1}, {2, 2}}), "Region", "no area");
    EXPECT_TEX_ERROR(ExportSVG(Nothing(), 0, "/tmp/never.svg"), "ExportSVG", "size 0");
}

// ---- Every random partition draws from its own stream ----

namespace {

std::string sites_of(const Arrangement& a) { return ToSVG(a(Region::rectangle(0, 0, 1000, 1000)), 1000); }

}  // namespace

TEST(Streams, TwoIdenticalCallsDrawDifferentSites) {
    StreamScope fresh(0);
    const Irregular p = IrregularProperties(40e-6);
    const Arrangement a = UniformPartition(p, KEEP_OUTSIDE), b = UniformPartition(p, KEEP_OUTSIDE);
    EXPECT_NE(sites_of(a), sites_of(b));
    const Arrangement c = RandomPartition(p, KEEP_OUTSIDE), d = RandomPartition(p, KEEP_OUTSIDE);
    EXPECT_NE(sites_of(c), sites_of(d));
    // Evaluating one again gives the same sites (the stream is fixed at creation).
    EXPECT_EQ(sites_of(a), sites_of(a));
}

TEST(Streams, AnExplicitSeedRepeatsOnPurpose) {
    const Irregular p = IrregularProperties(40e-6);
    EXPECT_EQ(sites_of(UniformPartition(p, KEEP_OUTSIDE, 3)), sites_of(UniformPartition(p, KEEP_OUTSIDE, 3)));
    EXPECT_NE(sites_of(UniformPartition(p, KEEP_OUTSIDE, 3)), sites_of(UniformPartition(p, KEEP_OUTSIDE, 4)));
    EXPECT_EQ(sites_of(RandomPartition(p, KEEP_OUTSIDE, 9)), sites_of(RandomPartition(p, KEEP_OUTSIDE, 9)));
}

TEST(Streams, TheSameScriptGivesTheSameStreams) {
    const Irregular p = IrregularProperties(40e-6);
    auto script = [&] {
        const Arrangement a = UniformPartition(p, KEEP_OUTSIDE);
        const Arrangement b = RandomPartition(p, KEEP_OUTSIDE);
        return sites_of(a) + sites_of(b);
    };
    std::string first, second, third;
    {
        StreamScope fresh(0);
        first = script();
    }
    {
        StreamScope fresh(0);
        second = script();
    }
    const std::uint64_t seed = GetSeed();
    SetSeed(seed);  // SetSeed restarts the numbering too
    third = script();
    SetSeed(seed);
    EXPECT_EQ(first, second);
    EXPECT_EQ(first, third);
    // A scope gives the numbering back: what is created after it is what would have been.
    StreamScope outer(77);
    const std::uint64_t n1 = NextStream();
    {
        StreamScope inner(0);
        NextStream();
        NextStream();
    }
    const std::uint64_t n2 = NextStream();
    StreamScope again(77);
    EXPECT_EQ(NextStream(), n1);
    EXPECT_EQ(NextStream(), n2);
}

TEST(Streams, APartitionBuiltInAMapperTakesItsStreamFromTheCell) {
    // Each face of a grid builds its own uniform partition and evaluates it on one fixed
    // square: what each face draws depends only on the face, not on the thread that visits
    // it nor on the order of visits, and two faces draw differently.
    const Region fixed = Region::rectangle(0, 0, 300, 300);
    std::mutex seen_mutex;
    std::set<std::string> seen;  // what the mapper itself drew, face by face
    auto per_face = MapToFaces(
        [&](const Face&) {
            const Arrangement inner = UniformPartition(IrregularProperties(3e-4), KEEP_INSIDE);
            Curves c = inner(fixed);
            std::lock_guard lock(seen_mutex);
            seen.insert(ToSVG(c, 300));
            return c;
        },
        GridPartition(StripesProperties(0, 250), StripesProperties(pi / 2, 250), KEEP_INSIDE));
    const Region window = Region::rectangle(0, 0, 1000, 1000);
    const unsigned saved = GetThreads();
    SetThreads(1);
    const Curves one = per_face(window);
    SetThreads(2);
    const Curves two = per_face(window);
    SetThreads(saved);
    EXPECT_EQ(ToSVG(one, 1000), ToSVG(two, 1000));
    EXPECT_EQ(seen.size(), 16u);  // two runs of 16 faces: 16 drawings, none alike
    // ... and each is the stream its cell's key names.
    const MapPtr grid = GridPartition(StripesProperties(0, 250), StripesProperties(pi / 2, 250), KEEP_INSIDE).induce(window);
    std::set<std::string> drawings;
    for (std::size_t f = 0; f < grid->faces().size(); ++f) {
        if (grid->faces()[f].unbounded) continue;
        RandomScope cell(grid->faces()[f].key);
        drawings.insert(ToSVG(UniformPartition(IrregularProperties(3e-4), KEEP_INSIDE)(fixed), 300));
    }
    EXPECT_EQ(drawings, seen);
}

// ---- Evaluated on a face, a cropping partition keeps the labels of the face's edges ----
//
// Thesis App. E (ridge hatching): the sub-cells touching a ridge are found by the label of
// the ridge on their outline. A square face whose right side is labelled "ridge" is cut by
// a grid with CROP_ADD_BOUNDARY: exactly the sub-cells along that side see the label, and
// the outline pieces bound their sub-cells with the sub-cells' own labels.
TEST(PartitionOnFace, OutlineKeepsTheLabelsOfTheFaceEdges) {
    Curves sides = Polyline({{0, 0}, {100, 0}}, false);
    sides.append(Polyline({{100, 0}, {100, 100}}, false));
    sides.append(Polyline({{100, 100}, {0, 100}, {0, 0}}, false));
    sides.curves[1].labels.add("ridge");
    const MapPtr big = PlanarMap::induce(sides);
    Face square;
    for (std::size_t f = 0; f < big->faces().size(); ++f)
        if (!big->faces()[f].unbounded) square = Face(big, int(f));
    ASSERT_TRUE(square.valid());
    Stripes a = StripesProperties(0, 30), b = StripesProperties(pi / 2, 30);
    SetFaceLabels(a, {"cell"});
    const MapPtr sub = GridPartition(a, b, CROP_ADD_BOUNDARY).induce(ToRegion(square));
    int touching = 0, bounded = 0;
    for (std::size_t f = 0; f < sub->faces().size(); ++f) {
        if (sub->faces()[f].unbounded) continue;
        const Face cell(sub, int(f));
        ++bounded;
        EXPECT_TRUE(HasLabel(cell, "cell"));
        const bool on_ridge = HasLabel(IncidentEdges(cell), "ridge");
        EXPECT_EQ(on_ridge, CellBBox(cell).xmax == 100) << Centroid(cell).x << " " << Centroid(cell).y;
        touching += on_ridge;
    }
    EXPECT_EQ(bounded, 16);   // columns 0-30-60-90-100, rows the same
    EXPECT_EQ(touching, 4);
    // A plain region has unlabelled outlines.
    const MapPtr plain = GridPartition(a, b, CROP_ADD_BOUNDARY).induce(Region::rectangle(0, 0, 100, 100));
    for (const auto& e : plain->edges()) EXPECT_FALSE(e.labels.has("ridge"));
}

// A SeedScope gives a call its own seed without touching the global one, in the work items
// it starts too.
TEST(SeedScope, ScopedSeedEqualsTheGlobalSeedAndRestoresIt) {
    const std::uint64_t before = GetSeed();
    const Region r = Region::rectangle(0, 0, 500, 500);
    auto draw = [&] {
        StreamScope fresh(0);
        return ToSVG(MapToFaces([](const Face& f) { return Scale(Contour(f), Random(f, 0.5, 0.9, 0)); },
                                UniformPartition(IrregularProperties(40 / (500.0 * 500.0)), KEEP_OUTSIDE))(r),
                     500);
    };
    SetSeed(7);
    const std::string global = draw();
    SetSeed(before);
    std::string scoped;
    {
        SeedScope s(7);
        EXPECT_EQ(GetSeed(), 7u);
        scoped = draw();
    }
    EXPECT_EQ(GetSeed(), before);
    EXPECT_EQ(scoped, global);
    EXPECT_NE(draw(), global);
}

// A ThreadsScope gives a call its own thread count: parallel_for started on this thread uses
// it, other threads and the next call see the process's setting (issue 17).
TEST(ThreadsScope, ScopedCountOnThisThreadOnlyAndRestored) {
    const unsigned saved = GetThreads();
    SetThreads(3);
    {
        ThreadsScope one(1);
        EXPECT_EQ(GetThreads(), 1u);
        unsigned elsewhere = 0;
        std::thread([&] { elsewhere = GetThreads(); }).join();
        EXPECT_EQ(elsewhere, 3u);
        std::set<std::thread::id> ids;
        std::mutex m;
        parallel_for(64, [&](std::size_t) {
            std::lock_guard lock(m);
            ids.insert(std::this_thread::get_id());
        });
        EXPECT_EQ(ids, std::set<std::thread::id>{std::this_thread::get_id()});
        {
            ThreadsScope nested(2);
            EXPECT_EQ(GetThreads(), 2u);
        }
        EXPECT_EQ(GetThreads(), 1u);
    }
    EXPECT_EQ(GetThreads(), 3u);
    SetThreads(saved);
}

// A nested parallel_for shares its items with the threads of the outermost call that ran out
// of work (one large face among small ones: its cells are split), and each item draws the
// same random values whoever runs it.
TEST(ParallelFor, IdleThreadsHelpANestedCallWithTheSameResults) {
    const ThreadsScope two(2);
    constexpr std::size_t kItems = 64;
    auto nested = [&](std::vector<double>& values, std::set<std::thread::id>* ids, std::mutex* m) {
        parallel_for(kItems, [&](std::size_t i) {
            std::this_thread::sleep_for(std::chrono::microseconds(200));
            values[i] = Random(0, 1) + Random(0, 1) * 1e-3;
            if (ids) {
                std::lock_guard lock(*m);
                ids->insert(std::this_thread::get_id());
            }
        });
    };
    std::vector<double> serial(kItems);
    {
        const ThreadsScope one(1);
        StreamScope s(3);
        parallel_for(2, [&](std::size_t k) {
            if (k == 1) nested(serial, nullptr, nullptr);
        });
    }
    // The outer item 0 ends at once; its thread then waits for work. Item 1's nested call is
    // shared as soon as that thread is idle: tried a few times, it must happen.
    bool helped = false;
    for (int attempt = 0; attempt < 20 && !helped; ++attempt) {
        std::vector<double> shared(kItems);
        std::set<std::thread::id> ids;
        std::mutex m;
        StreamScope s(3);
        parallel_for(2, [&](std::size_t k) {
            if (k == 0) return;
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
            nested(shared, &ids, &m);
        });
        EXPECT_EQ(shared, serial);
        helped = ids.size() == 2;
    }
    EXPECT_TRUE(helped) << "no idle thread took part in the nested call";
}

// An error in a nested item run by a helper reaches the caller; a NoRandomScope open around a
// nested call holds in its items whatever thread runs them.
TEST(ParallelFor, NestedItemsOnHelpersKeepTheCallersScopesAndErrors) {
    const ThreadsScope two(2);
    for (int attempt = 0; attempt < 5; ++attempt) {
        EXPECT_THROW(parallel_for(2,
                                  [&](std::size_t k) {
                                      if (k == 0) return;
                                      std::this_thread::sleep_for(std::chrono::milliseconds(5));
                                      parallel_for(32, [](std::size_t i) {
                                          std::this_thread::sleep_for(std::chrono::microseconds(100));
                                          if (i == 29) throw std::runtime_error("item 29");
                                      });
                                  }),
                     std::runtime_error);
        std::atomic<int> refused{0};
        parallel_for(2, [&](std::size_t k) {
            if (k == 0) return;
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
            const detail::NoRandomScope regular("TiledMap");
            parallel_for(32, [&](std::size_t) {
                std::this_thread::sleep_for(std::chrono::microseconds(100));
                try {
                    GetSeed();
                } catch (const Error&) {
                    ++refused;
                }
            });
        });
        EXPECT_EQ(refused.load(), 32);
    }
}

// SetSeed inside a SavedSeed (a style script run by the pipeline) does not outlive it: the
// global seed and the numbering of the streams come back.
TEST(SavedSeed, SetSeedInsideDoesNotLeak) {
    const std::uint64_t before = GetSeed();
    SetSeed(5);
    std::uint64_t expected;
    {
        StreamScope probe(11);
        NextStream();
        {
            const SavedSeed saved;
            SetSeed(123);
            EXPECT_EQ(GetSeed(), 123u);
            NextStream();
            NextStream();
        }
        EXPECT_EQ(GetSeed(), 5u);
        expected = NextStream();
    }
    StreamScope again(11);
    NextStream();
    EXPECT_EQ(NextStream(), expected);  // the second stream, as if the scope had not been
    SetSeed(before);
}

namespace {
// point_in_ring as it was written before its early exit (every segment tested in full).
bool point_in_ring_reference(const Point& p, const std::vector<Point>& ring) {
    bool in = false;
    for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
        const Point& a = ring[i];
        const Point& b = ring[j];
        if (cross(b - a, p - a) == 0.0 && std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) &&
            std::min(a.y, b.y) <= p.y && p.y <= std::max(a.y, b.y))
            return true;
        if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y)) in = !in;
    }
    return in;
}
}  // namespace

// The KEEP_OUTSIDE test of a partition's cells (polygon_meets_region) answers what
// classify_polygon answers, and point_in_ring what its plain form does, on points and cells
// that sit on the region's vertices, edges and horizontals (a lattice) as well as anywhere.
TEST(RegionTests, FastAnswersEqualTheFullOnes) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0, 1);
    std::uniform_int_distribution<int> lattice(0, 20);
    std::size_t meets = 0, cells = 0;
    for (int trial = 0; trial < 60; ++trial) {
        // A star-shaped outer ring (concave) with a square hole, vertices on a lattice.
        std::vector<Point> outer;
        for (int k = 0; k < 12; ++k) {
            const double rad = (k % 2 ? 4 : 8) + lattice(rng) % 3, a = k * pi / 6;
            outer.push_back({std::round(10 + rad * std::cos(a)), std::round(10 + rad * std::sin(a))});
        }
        const Region r(outer, {{{9, 9}, {9, 11}, {11, 11}, {11, 9}}});
        for (int q = 0; q < 400; ++q) {
            const Point p = q % 2 ? Point{double(lattice(rng)), double(lattice(rng))} : Point{20 * u(rng), 20 * u(rng)};
            ASSERT_EQ(point_in_ring(p, r.outer()), point_in_ring_reference(p, r.outer())) << p.x << " " << p.y;
            ASSERT_EQ(point_in_ring(p, r.holes()[0]), point_in_ring_reference(p, r.holes()[0]));
            // A cell: a small quadrilateral near p, sometimes with corners on the lattice.
            const double w = 0.5 + 3 * u(rng);
            std::vector<Point> cell = {p, p + Point{w, 0.3 * u(rng)}, p + Point{w, w}, p + Point{-0.2 * u(rng), w}};
            if (q % 3 == 0) cell = {p, p + Point{w, 0}, p + Point{w, w}, p + Point{0, w}};
            BBox box;
            for (const Point& c : cell) box.add(c);
            const bool fast = polygon_meets_region(cell, box, r);
            ASSERT_EQ(fast, classify_polygon(cell, box, r) != Overlap::Disjoint) << p.x << " " << p.y << " " << w;
            meets += fast;
            ++cells;
        }
    }
    // Both answers occur often.
    EXPECT_GT(meets, cells / 5);
    EXPECT_LT(meets, cells - cells / 5);
}

// A region prepared for many tests (slabs of its rings' segments) answers exactly as the
// plain region does: points on rings, on lattice vertices and horizontal segments, cells
// touching vertices, in holes and outside, rings of a few hundred vertices.
TEST(RegionTests, PreparedRegionAnswersLikeTheRegion) {
    std::mt19937_64 rng(29);
    std::uniform_real_distribution<double> u(0, 1);
    std::uniform_int_distribution<int> lattice(0, 40);
    std::size_t inside = 0, partial = 0, disjoint = 0, contained = 0, queries = 0;
    for (int trial = 0; trial < 40; ++trial) {
        // A wiggly star on a lattice (many vertices, horizontal and vertical runs) with two
        // holes, one of them touching the outer ring's lattice.
        const int n = 40 + 20 * (trial % 10);
        std::vector<Point> outer;
        for (int k = 0; k < n; ++k) {
            const double a = 2 * pi * k / n, rad = 12 + (k % 3) + lattice(rng) % 5;
            outer.push_back({std::round(20 + rad * std::cos(a)), std::round(20 + rad * std::sin(a))});
        }
        std::vector<std::vector<Point>> holes = {{{18, 18}, {18, 22}, {22, 22}, {22, 18}},
                                                 {{26, 15}, {29, 15}, {29, 17}, {26, 17}}};
        Region r;
        try {
            r = Region(outer, holes);
        } catch (const Error&) {
            continue;
        }
        const PreparedRegion pr(r);
        for (int q = 0; q < 600; ++q) {
            const Point p = q % 2 ? Point{double(lattice(rng)), double(lattice(rng))} : Point{40 * u(rng), 40 * u(rng)};
            const bool c = r.contains(p);
            ASSERT_EQ(pr.contains(p), c) << trial << " " << p.x << " " << p.y;
            contained += c;
            // Vertices of the ring itself, and points on its segments' midpoints.
            const Point& v = r.outer()[std::size_t(q) % r.outer().size()];
            ASSERT_EQ(pr.contains(v), r.contains(v));
            const Point mid = (v + r.outer()[(std::size_t(q) + 1) % r.outer().size()]) / 2;
            ASSERT_EQ(pr.contains(mid), r.contains(mid));
            const double w = q % 5 == 0 ? 1.0 : 0.5 + 4 * u(rng);
            std::vector<Point> cell = {p, p + Point{w, 0.3 * u(rng)}, p + Point{w, w}, p + Point{-0.2 * u(rng), w}};
            if (q % 3 == 0) cell = {p, p + Point{w, 0}, p + Point{w, w}, p + Point{0, w}};
            BBox box;
            for (const Point& x : cell) box.add(x);
            const Overlap plain = classify_polygon(cell, box, r);
            ASSERT_EQ(pr.classify_polygon(cell, box), plain) << trial << " " << p.x << " " << p.y << " " << w;
            ASSERT_EQ(pr.polygon_meets_region(cell, box), polygon_meets_region(cell, box, r));
            inside += plain == Overlap::Inside;
            partial += plain == Overlap::Partial;
            disjoint += plain == Overlap::Disjoint;
            ++queries;
        }
    }
    // A locator over regions of many vertices (prepared inside) and small ones answers as a
    // scan of the regions in order does.
    std::vector<Region> regions;
    for (int k = 0; k < 6; ++k) {
        std::vector<Point> ring;
        const int n = k % 2 ? 4 : 90;
        for (int i = 0; i < n; ++i) {
            const double a = 2 * pi * i / n, rad = 6 + (i % 2) * (k % 2 ? 0 : 2);
            ring.push_back({std::round(8 * k + rad * std::cos(a)), std::round(10 + rad * std::sin(a))});
        }
        regions.emplace_back(ring, std::vector<std::vector<Point>>{{{8.0 * k - 1, 9}, {8.0 * k - 1, 11}, {8.0 * k + 1, 11}, {8.0 * k + 1, 9}}});
    }
    const RegionLocator locator(regions);
    const RegionLocator copy = RegionLocator(locator);  // copies share the prepared regions
    for (int q = 0; q < 4000; ++q) {
        const Point p = q % 2 ? Point{double(lattice(rng)) * 1.2 - 8, double(lattice(rng)) * 0.6}
                              : Point{56 * u(rng) - 8, 24 * u(rng)};
        int expected = -1;
        for (std::size_t k = 0; k < regions.size() && expected < 0; ++k)
            if (regions[k].contains(p)) expected = int(k);
        ASSERT_EQ(locator.find(p), expected) << p.x << " " << p.y;
        ASSERT_EQ(copy.find(p), expected);
    }
    // Every answer occurs often.
    EXPECT_GT(inside, queries / 10);
    EXPECT_GT(partial, queries / 10);
    EXPECT_GT(disjoint, queries / 10);
    EXPECT_GT(contained, queries / 10);
}

// ---- A KEEP partition's planar map, built from its cell complex ----
//
// Arrangement::induce of a stripes or grid partition in a KEEP mode traces the map from the
// cell complex (no exact check of the segments, no sort of their ends). It must be the map
// PlanarMap::induce gives for the partition's curves, record for record, and fall back to
// that induction when rounding may have made the complex unclean.

namespace tex::detail {
std::uint64_t complex_inductions();
}

namespace {

// A jittered, rotated polygon around c (convex or not), sometimes with a hole.
Region jittered_region(std::mt19937& rng, const Point& c, double radius) {
    std::uniform_real_distribution<double> u(0, 1);
    const int n = 3 + int(u(rng) * 7);
    const double turn = u(rng) * 6.283185307179586;
    std::vector<Point> outer;
    for (int k = 0; k < n; ++k) {
        const double a = turn + 6.283185307179586 * (k + 0.4 * u(rng)) / n;
        const double r = radius * (0.45 + 0.55 * u(rng));
        outer.push_back({c.x + r * std::cos(a), c.y + r * std::sin(a)});
    }
    std::vector<std::vector<Point>> holes;
    if (u(rng) < 0.3) {
        const double h = 0.08 * radius;
        holes.push_back({{c.x - h, c.y - h}, {c.x - h, c.y + h}, {c.x + h, c.y + h}, {c.x + h, c.y - h}});
    }
    return Region(std::move(outer), std::move(holes));
}

Stripes random_stripes(std::mt19937& rng, double angle, const char* tag) {
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<double> widths;
    for (int k = 0, n = 1 + int(u(rng) * 3); k < n; ++k) widths.push_back(0.5 + 6 * u(rng));
    Stripes s = StripesProperties(angle, widths);
    if (u(rng) < 0.6) SetEdgeLabels(s, {std::string(tag) + "a", std::string(tag) + "b"});
    if (u(rng) < 0.6) SetFaceLabels(s, {std::string(tag) + "x", std::string(tag) + "y", std::string(tag) + "z"});
    return s;
}

// A random region far from the origin and two random stripe families across it; now and
// then axis-aligned (exactly vertical or horizontal lines) or at right angles.
struct GridCase {
    Region region;
    Stripes s1, s2;
};
GridCase random_grid_case(std::mt19937& rng, int k) {
    std::uniform_real_distribution<double> u(0, 1);
    const Point c{(u(rng) - 0.5) * 2e5, (u(rng) - 0.5) * 2e5};
    Region r = jittered_region(rng, c, 5 + 40 * u(rng));
    const double a1 = k % 7 == 0 ? 0.0 : u(rng) * 6.283185307179586;
    const double a2 = k % 11 == 0 ? a1 + 1.5707963267948966 : a1 + 0.2 + u(rng) * 2.7;
    Stripes s1 = random_stripes(rng, a1, "h");
    Stripes s2 = random_stripes(rng, a2, "v");
    return {std::move(r), std::move(s1), std::move(s2)};
}

}  // namespace

TEST(PartitionMaps, CellComplexMapIsTheInducedMap) {
    std::mt19937 rng(20261202);
    std::uniform_real_distribution<double> u(0, 1);
    int cases = 0;
    const std::uint64_t before = detail::complex_inductions();
    for (int k = 0; k < 160; ++k) {
        const auto [r, s1, s2] = random_grid_case(rng, k);
        for (Border b : {KEEP_OUTSIDE, KEEP_INSIDE}) {
            const std::string what = "case " + std::to_string(k) + " " + border_name(b);
            const Arrangement grid = GridPartition(s1, s2, b);
            const Curves grid_curves = grid(r);
            th::expect_same_map(*grid.induce(r), *PlanarMap::induce(grid_curves), (what + " grid").c_str());
            const Arrangement stripes = StripesPartition(s1, b);
            const Curves stripes_curves = stripes(r);
            th::expect_same_map(*stripes.induce(r), *PlanarMap::induce(stripes_curves), (what + " stripes").c_str());
            // An empty partition (KEEP_INSIDE of whole bands) is the empty map either way.
            cases += !grid_curves.curves.empty();
            cases += !stripes_curves.curves.empty();
            if (HasFailure()) return;
        }
    }
    // Every non-empty one took the way through the complex (nothing was close to unclean).
    EXPECT_GT(cases, 400);
    EXPECT_EQ(detail::complex_inductions() - before, std::uint64_t(cases));
}

// A KEEP partition also knows its map's edges without the map (Arrangement::local_edges):
// they must be the map's edges, in its order, curve for curve and key for key, so that a
// mapper reading only its edge (LocalEdgeMapper, e.g. JitterEdges) gives what it gives on
// the map.
void expect_same_edges(const std::vector<LocalEdge>& local, const MapPtr& map, const std::string& what) {
    ASSERT_EQ(local.size(), map->edges().size()) << what;
    for (std::size_t i = 0; i < local.size(); ++i) {
        const LocalEdge e = AsLocalEdge(Edge(map, int(i)));
        const LocalEdge& l = local[i];
        ASSERT_EQ(l.curve.points, e.curve.points) << what << " edge " << i;
        ASSERT_EQ(l.curve.closed, e.curve.closed) << what << " edge " << i;
        ASSERT_TRUE(l.curve.labels == e.curve.labels && l.curve.left == e.curve.left && l.curve.right == e.curve.right)
            << what << " edge " << i;
        ASSERT_EQ(l.key, e.key) << what << " edge " << i;
        ASSERT_EQ(l.source_key, e.source_key) << what << " edge " << i;
        ASSERT_EQ(l.target_key, e.target_key) << what << " edge " << i;
    }
}

void expect_same_curves(const Curves& a, const Curves& b, const std::string& what) {
    ASSERT_EQ(a.curves.size(), b.curves.size()) << what;
    for (std::size_t i = 0; i < a.curves.size(); ++i) {
        ASSERT_EQ(a.curves[i].points, b.curves[i].points) << what << " curve " << i;
        ASSERT_TRUE(a.curves[i].labels == b.curves[i].labels && a.curves[i].left == b.curves[i].left &&
                    a.curves[i].right == b.curves[i].right)
            << what << " curve " << i;
    }
}

TEST(PartitionMaps, KeepPartitionsKnowTheirMapsEdges) {
    std::mt19937 rng(20261206);
    std::uniform_real_distribution<double> u(0, 1);
    int cases = 0;
    for (int k = 0; k < 120; ++k) {
        const auto [r, s1, s2] = random_grid_case(rng, k);
        for (Border b : {KEEP_OUTSIDE, KEEP_INSIDE}) {
            const std::string what = "case " + std::to_string(k) + " " + border_name(b);
            for (const Arrangement& a : {GridPartition(s1, s2, b), StripesPartition(s1, b)}) {
                const auto edges = a.local_edges(r);
                ASSERT_TRUE(edges.has_value()) << what;
                expect_same_edges(*edges, a.induce(r), what);
                if (HasFailure()) return;
                cases += !edges->empty();
            }
        }
    }
    EXPECT_GT(cases, 300);
    // CROP modes cut cells, and an unclean complex is not its map: no edges without the map,
    // but for the stripes cut by CROP alone (parallel lines: each piece is an edge).
    const Region r({{0, 0}, {90, 10}, {70, 80}, {10, 60}});
    for (Border b : {CROP, CROP_ADD_BOUNDARY})
        EXPECT_FALSE(GridPartition(StripesProperties(0.4, 7), StripesProperties(2.0, 5), b).local_edges(r)) << border_name(b);
    EXPECT_FALSE(StripesPartition(StripesProperties(0.4, 7), CROP_ADD_BOUNDARY).local_edges(r));
    EXPECT_FALSE(GridPartition(StripesProperties(0.7, 3), StripesProperties(0.7 + 2e-9, 4), KEEP_OUTSIDE)
                     .local_edges(Region::rectangle(0, 0, 30, 30)));
}

// Stripes cut by CROP: parallel lines, so each piece the crop leaves is an edge of the map
// on its own; the partition hands those pieces over as the map's edges, in its order and
// with its keys, for jittered (not convex) regions, regions whose vertices lie on the lines
// (pieces that share an end, lines along a side), and with a label asked for.
TEST(PartitionMaps, StripesCutByCropKnowTheirMapsEdges) {
    std::mt19937 rng(20261208);
    std::uniform_real_distribution<double> u(0, 1);
    int cases = 0, pieces = 0;
    for (int k = 0; k < 120; ++k) {
        const auto [r, s1, s2] = random_grid_case(rng, k);
        const std::string what = "case " + std::to_string(k);
        const Arrangement a = StripesPartition(s1, CROP);
        const auto edges = a.local_edges(r);
        ASSERT_TRUE(edges.has_value()) << what;
        expect_same_edges(*edges, a.induce(r), what);
        if (HasFailure()) return;
        cases += !edges->empty();
        pieces += int(edges->size());
    }
    EXPECT_GT(cases, 100);
    EXPECT_GT(pieces, 1000);
    // Horizontal and vertical lines through the vertices of a notched square, and along its sides.
    const Region notched({{0, 0}, {8, 0}, {8, 8}, {6, 8}, {4, 4}, {2, 8}, {0, 8}});
    for (double angle : {0.0, 1.5707963267948966, 0.7853981633974483}) {
        Stripes s = StripesProperties(angle, 2.0, 2.0);
        SetEdgeLabels(s, {"a", "b"});
        const Arrangement a = StripesPartition(s, CROP);
        const std::string what = "notched, angle " + std::to_string(angle);
        const auto edges = a.local_edges(notched);
        ASSERT_TRUE(edges.has_value()) << what;
        expect_same_edges(*edges, a.induce(notched), what);
        // With a label: the map's edges with it, in its order.
        const auto some = a.local_edges(notched, intern_label("b"));
        ASSERT_TRUE(some.has_value()) << what;
        std::vector<LocalEdge> expected;
        for (const LocalEdge& e : *edges)
            if (e.curve.labels.has(intern_label("b"))) expected.push_back(e);
        ASSERT_EQ(some->size(), expected.size()) << what;
        for (std::size_t i = 0; i < expected.size(); ++i) {
            EXPECT_EQ((*some)[i].curve.points, expected[i].curve.points) << what;
            EXPECT_EQ((*some)[i].key, expected[i].key) << what;
        }
        EXPECT_FALSE(expected.empty()) << what;
    }
}

TEST(PartitionMaps, AnEdgeLocalMapperRunsWithoutTheMapAndGivesWhatTheMapGives) {
    // JitterEdges reads only its edge: MapToEdges of it over a KEEP grid builds no planar map,
    // and gives the curves the same mapper gives when it is run on the map's edges (a plain
    // EdgeMapper around it), for the styles' noisy lines with a gate field as well.
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0, 1);
    const Field gate = [](const Point& p) { return std::sin(p.x / 3) + std::cos(p.y / 5); };
    const SeedScope seed(11);
    for (int k = 0; k < 40; ++k) {
        const Region r = jittered_region(rng, {(u(rng) - 0.5) * 1e4, (u(rng) - 0.5) * 1e4}, 5 + 40 * u(rng));
        const double theta = u(rng) * 6.283185307179586, across = 0.5 + 2 * u(rng), along = 2 + 6 * u(rng);
        const EdgeMapper jitter = JitterEdges("fill", theta, across, along, 0.8, 0.9, gate, k % 2 ? 0.0 : 0.2);
        const EdgeMapper on_the_map = [jitter](const Edge& e) { return jitter(e); };
        Stripes lines = StripesProperties(theta, across);
        SetEdgeLabels(lines, {"fill"});
        const Arrangement grid =
            GridPartition(lines, StripesProperties(theta + 1.5707963267948966, along), KEEP_OUTSIDE);
        const std::uint64_t before = detail::complex_inductions();
        const Curves local = MapToEdges(jitter, grid)(r);
        EXPECT_EQ(detail::complex_inductions(), before) << "case " << k << ": the map was built";
        const Curves mapped = MapToEdges(on_the_map, grid)(r);
        EXPECT_EQ(detail::complex_inductions(), before + 1) << "case " << k;
        ASSERT_FALSE(local.curves.empty()) << "case " << k;
        expect_same_curves(local, mapped, "case " + std::to_string(k));
        if (HasFailure()) return;
    }
}

TEST(PartitionMaps, AMapperOfOneLabelReadsOnlyTheEdgesWithIt) {
    // A LocalEdgeMapper with `only` maps the edges without that label to nothing: the
    // partition leaves them out of its edges (the others in the map's order, key for key),
    // the function never sees them, and the curves are those of the same mapper run on every
    // edge of the map.
    std::mt19937 rng(20261207);
    std::uniform_real_distribution<double> u(0, 1);
    const LabelId fill = intern_label("fill");
    int labelled = 0, unlabelled = 0;
    for (int k = 0; k < 40; ++k) {
        const Region r = jittered_region(rng, {(u(rng) - 0.5) * 1e4, (u(rng) - 0.5) * 1e4}, 5 + 40 * u(rng));
        const double theta = u(rng) * 6.283185307179586, across = 0.5 + 2 * u(rng), along = 2 + 6 * u(rng);
        Stripes lines = StripesProperties(theta, across);
        SetEdgeLabels(lines, {"fill"});
        const std::string what = "case " + std::to_string(k);
        for (const Arrangement& a : {GridPartition(lines, StripesProperties(theta + 1.5707963267948966, along), KEEP_OUTSIDE),
                                     GridPartition(StripesProperties(theta + 1.2, along), lines, KEEP_INSIDE),
                                     StripesPartition(lines, KEEP_OUTSIDE)}) {
            const auto all = a.local_edges(r);
            const auto some = a.local_edges(r, fill);
            ASSERT_TRUE(all && some) << what;
            std::vector<LocalEdge> expected;
            for (const LocalEdge& e : *all)
                if (e.curve.labels.has(fill)) expected.push_back(e);
            ASSERT_EQ(some->size(), expected.size()) << what;
            for (std::size_t i = 0; i < expected.size(); ++i) {
                ASSERT_EQ((*some)[i].curve.points, expected[i].curve.points) << what << " edge " << i;
                ASSERT_EQ((*some)[i].key, expected[i].key) << what << " edge " << i;
                ASSERT_EQ((*some)[i].source_key, expected[i].source_key) << what << " edge " << i;
                ASSERT_EQ((*some)[i].target_key, expected[i].target_key) << what << " edge " << i;
            }
            labelled += int(expected.size());
            unlabelled += int(all->size() - expected.size());
            // The function sees only labelled edges, with or without the map.
            std::atomic<int> calls{0}, strangers{0};
            const EdgeMapper only = LocalEdgeMapper(
                [&, fill](const LocalEdge& e, Curves& out) {
                    ++calls;
                    if (!e.curve.labels.has(fill)) ++strangers;
                    out.append(Polyline(e.curve.points));
                },
                fill);
            const Curves local = MapToEdges(only, a)(r);
            EXPECT_EQ(calls.load(), int(expected.size())) << what;
            const Curves mapped = MapToEdges([only](const Edge& e) { return only(e); }, a)(r);
            EXPECT_EQ(strangers.load(), 0) << what;
            expect_same_curves(local, mapped, what);
            if (HasFailure()) return;
        }
    }
    EXPECT_GT(labelled, 1000);
    EXPECT_GT(unlabelled, 1000);
}

TEST(PartitionMaps, CropModesAndVoronoiInduceFromTheirCurves) {
    // CROP modes cut cells, and Voronoi complexes carry no proof of cleanness: both induce
    // their map from the curves (the same map, by definition), never through the complex.
    const Region r({{0, 0}, {90, 10}, {70, 80}, {10, 60}});
    const std::uint64_t before = detail::complex_inductions();
    const Stripes s1 = StripesProperties(0.4, 7), s2 = StripesProperties(2.0, 5);
    for (Border b : {CROP, CROP_ADD_BOUNDARY}) {
        const Arrangement grid = GridPartition(s1, s2, b);
        th::expect_same_map(*grid.induce(r), *PlanarMap::induce(grid(r)), border_name(b));
    }
    const Arrangement voronoi = UniformPartition(IrregularProperties(0.01), KEEP_OUTSIDE, 3);
    th::expect_same_map(*voronoi.induce(r), *PlanarMap::induce(voronoi(r)), "voronoi");
    EXPECT_EQ(detail::complex_inductions(), before);
}

TEST(PartitionMaps, UncleanComplexesFallBackToTheGeneralInduction) {
    const std::uint64_t before = detail::complex_inductions();
    // Nearly parallel families: the vertices of the grid are computed with an error that
    // is no longer small against the widths.
    {
        const Region r = Region::rectangle(0, 0, 30, 30);
        const Arrangement grid =
            GridPartition(StripesProperties(0.7, 3), StripesProperties(0.7 + 2e-9, 4), KEEP_OUTSIDE);
        const MapPtr m = grid.induce(r);
        th::expect_same_map(*m, *PlanarMap::induce(grid(r)), "nearly parallel");
    }
    // Huge coordinates: a metre is a few units in the last place of 1e14.
    for (Border b : {KEEP_OUTSIDE, KEEP_INSIDE}) {
        const Region r = Region::rectangle(1e14, 1e14, 1e14 + 20, 1e14 + 20);
        const Arrangement grid = GridPartition(StripesProperties(0.3, 1), StripesProperties(1.8, 1.5), b);
        th::expect_same_map(*grid.induce(r), *PlanarMap::induce(grid(r)), "huge grid");
        const Arrangement stripes = StripesPartition(StripesProperties(0.3, 1), b);
        th::expect_same_map(*stripes.induce(r), *PlanarMap::induce(stripes(r)), "huge stripes");
    }
    EXPECT_EQ(detail::complex_inductions(), before) << "an unclean complex was traced without the check";
    // The same partitions at ordinary coordinates do take the complex's way.
    const Region r = Region::rectangle(0, 0, 20, 20);
    GridPartition(StripesProperties(0.3, 1), StripesProperties(1.8, 1.5), KEEP_OUTSIDE).induce(r);
    EXPECT_EQ(detail::complex_inductions(), before + 1);
}

TEST(PartitionMaps, MappingOverTheComplexMapIsThreadIndependent) {
    // MapToEdges over a KEEP grid (the maps the styles' noisy lines come from), nested in a
    // MapToFaces as the styles do: same bytes at 1 and 2 threads.
    const Stripes s1 = StripesProperties(0.35, 4, 2), s2 = StripesProperties(0.35 + 1.5707963267948966, 9);
    const Arrangement inner = MapToEdges([](const Edge& e) { return ToCurve(e); }, GridPartition(s1, s2, KEEP_OUTSIDE));
    const Arrangement outer = MapToFaces([inner](const Face& f) { return Crop(inner, CROP)(f); },
                                         GridPartition(StripesProperties(0.35, 40), StripesProperties(1.92, 40), KEEP_OUTSIDE));
    const Region r({{0, 0}, {200, 20}, {180, 170}, {30, 150}});
    const unsigned saved = GetThreads();
    SetThreads(1);
    const std::string one = ToSVG(outer(r), 400);
    SetThreads(2);
    const std::string two = ToSVG(outer(r), 400);
    SetThreads(saved);
    EXPECT_GT(one.size(), 1000u);
    EXPECT_EQ(one, two);
}
