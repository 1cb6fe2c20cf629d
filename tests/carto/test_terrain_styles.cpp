// The terrain styles (issue 13): scree and slope hachures, checked on the geometry they
// output over a small synthetic slope with a rock face on top, plus the sample run end to end.
//
// The synthetic terrain: 1000 m x 800 m, 5 m cells, falling to the south; the western part
// gentle (35 %), the eastern part steep (80 %), a short ramp between them. A rock face covers
// the top 200 m, and a disc of NoData lies in the middle of the open slope.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <tuple>

#include "carto/error.hpp"
#include "carto/control_fields.hpp"
#include "carto/pipeline.hpp"
#include "libtex/discrete.hpp"

using namespace carto;

namespace {

constexpr double kW = 1000, kH = 800, kCell = 5;
constexpr double kGentle = 0.35, kSteep = 0.80;
constexpr double kRockBottom = 600;            // the face covers y >= 600
const Point kHole{300, 250};                   // the NoData disc
constexpr double kHoleRadius = 60;

double grade(double x) {
    const double t = std::clamp((x - 0.45 * kW) / (0.1 * kW), 0.0, 1.0);
    return kGentle + (kSteep - kGentle) * t;
}

Raster synthetic_dem() {
    Raster r;
    r.width = int(kW / kCell);
    r.height = int(kH / kCell);
    r.gt = {0, kCell, 0, kH, 0, -kCell};
    r.crs_wkt = epsg_wkt(2154);
    r.data.resize(std::size_t(r.width) * r.height);
    for (int row = 0; row < r.height; ++row)
        for (int col = 0; col < r.width; ++col) {
            const Point p = r.to_world(col + 0.5, row + 0.5);
            r.at(col, row) = tex::distance(p, kHole) < kHoleRadius ? NAN : float(1000 + p.y * grade(p.x));
        }
    return r;
}

Partition rock_face() {
    Partition part;
    part.crs_wkt = epsg_wkt(2154);
    RockFace f;
    f.id = 1;
    const std::vector<Point> ring{{0, kRockBottom}, {kW, kRockBottom}, {kW, kH}, {0, kH}};
    f.region = tex::Region(ring);
    for (std::size_t i = 0; i < f.region.outer().size(); ++i)
        f.boundary.push_back({f.region.outer()[i], f.region.outer()[(i + 1) % f.region.outer().size()]});
    f.orientation = M_PI / 2;
    f.density = 0.6;
    part.faces.push_back(std::move(f));
    return part;
}

const Prepared& synthetic() {
    static const Prepared p = [] {
        Prepared q;
        const Raster dem = synthetic_dem();
        q.terrain = compute_terrain(dem);
        q.partition = rock_face();
        q.relief = local_relief(dem, 1000);
        return q;
    }();
    return p;
}

Options options(const std::string& style, unsigned threads = 2, std::uint64_t seed = 0) {
    Options o;
    o.style = style;
    o.threads = threads;
    o.seed = seed;
    return o;
}

// The drawing's rock hatches and its terrain elements (as regions).
struct Split {
    std::vector<Hatch> rock;
    std::vector<tex::Region> elements;
};
Split split(const Drawing& d, Family family) {
    Split s;
    for (const auto& f : d.faces)
        for (const auto& h : f.hatches) {
            if (h.family == family) {
                EXPECT_EQ(f.face_id, kTerrainFaceId);
                s.elements.push_back(tex::Region(h.points));
            } else {
                s.rock.push_back(h);
            }
        }
    return s;
}

const Drawing& scree_drawing() {
    static const Drawing d = hatch(synthetic(), options("scree"));
    return d;
}
const Drawing& hachure_drawing() {
    static const Drawing d = hatch(synthetic(), options("slope-hachures"));
    return d;
}

// Pairs of elements whose boxes come within `pad`, each pair once.
template <class F>
void near_pairs(const std::vector<tex::Region>& e, double pad, F&& f) {
    std::vector<std::size_t> order(e.size());
    for (std::size_t i = 0; i < e.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](auto a, auto b) { return e[a].bbox().xmin < e[b].bbox().xmin; });
    for (std::size_t i = 0; i < order.size(); ++i)
        for (std::size_t j = i + 1; j < order.size(); ++j) {
            const tex::BBox &a = e[order[i]].bbox(), &b = e[order[j]].bbox();
            if (b.xmin > a.xmax + pad) break;
            if (b.ymin > a.ymax + pad || a.ymin > b.ymax + pad) continue;
            f(order[i], order[j]);
        }
}

double stroke_half_width(const Hatch& h, double scale) { return family_width_mm(h.family) * scale / 1000 / 2; }

// Down-slope direction of the synthetic terrain at p (its exact gradient).
Point fall(const Point& p) {
    const double eps = 0.5;
    const double gx = ((p.y) * grade(p.x + eps) - (p.y) * grade(p.x - eps)) / (2 * eps), gy = grade(p.x);
    const double n = std::hypot(gx, gy);
    return {-gx / n, -gy / n};
}

double half_area(const std::vector<tex::Region>& e, bool steep, double* count) {
    double a = 0, n = 0;
    for (const auto& r : e) {
        const Point c = tex::disc::Centroid(r);
        if (steep ? c.x > 0.6 * kW : c.x < 0.4 * kW) a += r.area(), ++n;
    }
    *count = n;
    return n > 0 ? a / n : 0;
}

}  // namespace

TEST(TerrainStyles, TableAndParameters) {
    for (const char* name : {"scree", "slope-hachures"}) {
        const StyleInfo& s = find_style(name);
        EXPECT_TRUE(s.terrain) << name;
        EXPECT_TRUE(builtin_style(name).terrain) << name;
        for (const auto& p : s.params) EXPECT_FALSE(p.help.empty()) << name << " " << p.name;
    }
    EXPECT_FALSE(find_style("bidirectional").terrain);
    // mm on paper become ground metres at the scale; the contour interval is in ground metres.
    const ParamValues v = resolve_params(find_style("slope-hachures"), {{"interval", 50}}, 25000);
    EXPECT_DOUBLE_EQ(v.at("interval"), 50);
    EXPECT_DOUBLE_EQ(v.at("spacing_min"), 0.45 * 25);
    EXPECT_THROW(resolve_params(find_style("slope-hachures"), {{"interval", 0}}, 10000), Error);
}

TEST(TerrainStyles, BadParametersGiveOneLineErrors) {
    auto message = [](const std::string& style, std::map<std::string, double> params) -> std::string {
        Options o = options(style);
        o.params = std::move(params);
        try {
            hatch(synthetic(), o);
        } catch (const Error& e) {
            EXPECT_EQ(e.code(), Code::Usage);
            return e.what();
        }
        return "";
    };
    EXPECT_EQ(message("slope-hachures", {{"spacing_min", 2}}),
              "--param spacing_min: must not exceed spacing_max for style 'slope-hachures'");
    EXPECT_EQ(message("scree", {{"stone_min", 1}}), "--param stone_min: must not exceed stone_max for style 'scree'");
    EXPECT_EQ(message("scree", {{"shade_weight", 2}}), "--param shade_weight: must not exceed 1 for style 'scree'");
}

// The terrain elements of a drawing as rings, sorted (a multiset to compare).
std::vector<std::vector<Point>> element_rings(const Drawing& d) {
    std::vector<std::vector<Point>> out;
    for (const auto& f : d.faces)
        if (f.face_id == kTerrainFaceId)
            for (const auto& h : f.hatches) out.push_back(h.points);
    std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) {
        return std::lexicographical_compare(a.begin(), a.end(), b.begin(), b.end(), [](const Point& p, const Point& q) {
            return std::tie(p.x, p.y) < std::tie(q.x, q.y);
        });
    });
    return out;
}

TEST(TerrainStyles, WindowsTogetherDrawTheWholeRunsElements) {
    // Local control: the elements are thrown over one grid of tiles anchored in the working
    // CRS, so four windows that cover the plane (half-open, meeting off the tile lines) draw
    // exactly the whole run's elements between them, none twice, at any thread count. The
    // windows meet across the scree band; the short contour interval gives the hachures
    // tiles of about 230 m, many to a window (at the defaults, 788 m: two windows).
    const double inf = 1e15;
    const std::vector<tex::BBox> quarters{
        {-inf, -inf, 430, 560}, {430, -inf, inf, 560}, {-inf, 560, 430, inf}, {430, 560, inf, inf}};
    std::vector<std::pair<std::string, std::map<std::string, double>>> cases{
        {"scree", {}}, {"slope-hachures", {{"interval", 5}}}, {"slope-hachures", {}}};
    for (const auto& [style, params] : cases) {
        Options o = options(style, 2, 5);
        o.params = params;
        const auto whole = element_rings(hatch(synthetic(), o));
        ASSERT_GT(whole.size(), 200u) << style;
        std::vector<std::vector<Point>> joined;
        std::size_t windows_with_elements = 0;
        for (std::size_t k = 0; k < quarters.size(); ++k) {
            o.window = quarters[k];
            o.threads = unsigned(1 + k % 2);
            const auto part = element_rings(hatch(synthetic(), o));
            windows_with_elements += !part.empty();
            joined.insert(joined.end(), part.begin(), part.end());
        }
        o.window.reset();
        EXPECT_GE(windows_with_elements, 2u) << style;
        std::sort(joined.begin(), joined.end(), [](const auto& a, const auto& b) {
            return std::lexicographical_compare(a.begin(), a.end(), b.begin(), b.end(),
                                                [](const Point& p, const Point& q) { return std::tie(p.x, p.y) < std::tie(q.x, q.y); });
        });
        ASSERT_EQ(joined.size(), whole.size()) << style;
        EXPECT_TRUE(joined == whole) << style << ": a window drew other elements than the whole run";
    }
}

TEST(Scree, StonesLieBelowTheRockAndOverlapNothing) {
    const Split s = split(scree_drawing(), Family::Stone);
    ASSERT_GT(s.elements.size(), 300u);
    ASSERT_GT(s.rock.size(), 100u);
    const double reach = 8.0 * 10;  // 8 mm at 1:10000
    for (const auto& r : s.elements) {
        for (const Point& q : r.outer()) {
            EXPECT_LT(q.y, kRockBottom) << "a stone in the rock face";
            EXPECT_GT(q.y, kRockBottom - reach - kCell) << "a stone beyond the scree band";
        }
    }
    // No two stones touch: the smallest distance between neighbours is positive.
    double closest = INFINITY;
    near_pairs(s.elements, 1.0, [&](std::size_t i, std::size_t j) {
        closest = std::min(closest, tex::disc::Distance(s.elements[i], s.elements[j]));
    });
    EXPECT_GT(closest, 0.0);
    // No stone comes under the ink of a rock hatch (its centre line within half its width).
    std::size_t checked = 0;
    for (const auto& h : s.rock) {
        tex::BBox hb;
        for (const Point& q : h.points) hb.add(q);
        for (const auto& r : s.elements) {
            const tex::BBox& b = r.bbox();
            if (b.xmin > hb.xmax + 2 || hb.xmin > b.xmax + 2 || b.ymin > hb.ymax + 2 || hb.ymin > b.ymax + 2) continue;
            ++checked;
            std::vector<Point> pts = h.points;
            if (h.closed) pts.push_back(pts.front());
            EXPECT_GT(tex::disc::Distance(tex::disc::Polyline{pts, false}, r), stroke_half_width(h, 10000))
                << "family " << family_name(h.family) << " hatch from " << pts.front().x << "," << pts.front().y
                << " to " << pts.back().x << "," << pts.back().y << " (" << pts.size() << " points), stone at " << tex::disc::Centroid(r).x << ","
                << tex::disc::Centroid(r).y;
        }
    }
    EXPECT_GT(checked, 0u) << "no stone near a rock hatch: the test would not see an overlap";
}

TEST(Scree, StonesKeepTheGapAcrossTheParallelTiles) {
    // The scree is thrown tile by tile, in phases, tiles of a phase in parallel: stones of
    // neighbouring tiles must keep the gap as stones of one tile do. gap_min (0.1 mm at
    // 1:10000) is the smallest gap anywhere; the stones span several tiles (16 stones plus
    // gaps, 152 m here).
    const Split s = split(scree_drawing(), Family::Stone);
    tex::BBox extent;
    for (const auto& r : s.elements) extent.add(tex::disc::Centroid(r));
    ASSERT_GT(extent.width(), 4 * 152.0) << "the stones should span several tiles";
    const double gap_min = 0.10 * 10;
    double closest = INFINITY;
    std::size_t pairs = 0;
    // Neighbours: boxes within three gaps (the test sees many pairs near the gap).
    near_pairs(s.elements, 3 * gap_min, [&](std::size_t i, std::size_t j) {
        ++pairs;
        closest = std::min(closest, tex::disc::Distance(s.elements[i], s.elements[j]));
    });
    EXPECT_GT(pairs, 100u);
    EXPECT_GE(closest, gap_min * (1 - 1e-9));
}

TEST(Scree, DenserAndLargerOnSteeperGround) {
    const Split s = split(scree_drawing(), Family::Stone);
    double n_gentle = 0, n_steep = 0;
    const double a_gentle = half_area(s.elements, false, &n_gentle), a_steep = half_area(s.elements, true, &n_steep);
    // Both halves are 400 m wide: the counts compare densities.
    EXPECT_GT(n_steep, 1.3 * n_gentle) << n_steep << " stones steep, " << n_gentle << " gentle";
    EXPECT_GT(a_steep, 1.3 * a_gentle) << "mean stone area steep " << a_steep << ", gentle " << a_gentle;
}

TEST(Scree, GivenAreasReplaceTheBand) {
    // A scree polygon far from the rock, across the ramp: stones only there, none in the band.
    Prepared p = synthetic();
    const tex::Region given = tex::Region::rectangle(400, 100, 700, 200);
    p.partition.scree = {given};
    const Split s = split(hatch(p, options("scree")), Family::Stone);
    ASSERT_GT(s.elements.size(), 100u);
    for (const auto& r : s.elements)
        for (const Point& q : r.outer()) {
            EXPECT_TRUE(q.x >= 400 - kCell && q.x <= 700 + kCell && q.y >= 100 - kCell && q.y <= 200 + kCell)
                << q.x << "," << q.y;
        }
}

TEST(SlopeHachures, StrokesNeverTouchAndAvoidRockAndNoData) {
    const Split s = split(hachure_drawing(), Family::Hachure);
    ASSERT_GT(s.elements.size(), 300u);
    const Raster& dem = synthetic().terrain.elevation;
    for (const auto& r : s.elements)
        for (const Point& q : r.outer()) {
            EXPECT_LT(q.y, kRockBottom) << "a hachure in the rock face";
            EXPECT_FALSE(std::isnan(dem.nearest(q))) << "a hachure in NoData at " << q.x << "," << q.y;
            EXPECT_GE(tex::distance(q, kHole), kHoleRadius - kCell);
        }
    double closest = INFINITY;
    near_pairs(s.elements, 1.0, [&](std::size_t i, std::size_t j) {
        closest = std::min(closest, tex::disc::Distance(s.elements[i], s.elements[j]));
    });
    EXPECT_GT(closest, 0.0) << "two hachures touch";
}

TEST(SlopeHachures, StrokesOfNeighbouringBandsKeepTheContourGap) {
    // The bands are thrown in parallel and the contour gap (0.12 mm, 1.2 m at 1:10000) is
    // enforced afterwards, band after band: strokes of two bands never come nearer than it.
    const Split s = split(hachure_drawing(), Family::Hachure);
    const Raster& dem = synthetic().terrain.elevation;
    const double interval = 20, gap = 0.12 * 10;
    std::vector<long long> band;
    for (const auto& r : s.elements) band.push_back((long long)std::floor(dem.sample(tex::disc::Centroid(r)) / interval));
    double closest = INFINITY;
    std::size_t pairs = 0;
    near_pairs(s.elements, 3 * gap, [&](std::size_t i, std::size_t j) {
        if (band[i] == band[j]) return;
        ++pairs;
        closest = std::min(closest, tex::disc::Distance(s.elements[i], s.elements[j]));
    });
    EXPECT_GT(pairs, 50u) << "few strokes of two bands near each other: the test would see little";
    EXPECT_GE(closest, gap * (1 - 1e-9));
}

TEST(SlopeHachures, FollowTheFallLine) {
    const Split s = split(hachure_drawing(), Family::Hachure);
    // Each stroke's long axis (its two farthest points) against the fall line at its centre.
    std::size_t along = 0;
    for (const auto& r : s.elements) {
        const auto& o = r.outer();
        Point a = o[0], b = o[0];
        double best = -1;
        for (std::size_t i = 0; i < o.size(); ++i)
            for (std::size_t j = i + 1; j < o.size(); ++j)
                if (tex::distance(o[i], o[j]) > best) best = tex::distance(o[i], o[j]), a = o[i], b = o[j];
        const Point axis = (b - a) / tex::norm(b - a);
        along += std::abs(tex::dot(axis, fall(tex::disc::Centroid(r)))) > std::cos(20 * M_PI / 180);
    }
    EXPECT_GT(double(along), 0.95 * double(s.elements.size())) << along << " of " << s.elements.size();
}

TEST(SlopeHachures, CloserAndHeavierOnSteeperGround) {
    const Split s = split(hachure_drawing(), Family::Hachure);
    double n_gentle = 0, n_steep = 0;
    const double a_gentle = half_area(s.elements, false, &n_gentle), a_steep = half_area(s.elements, true, &n_steep);
    // Strokes run from contour to contour: shorter on the steep side, but more and wider.
    double ink_gentle = a_gentle * n_gentle, ink_steep = a_steep * n_steep;
    EXPECT_GT(n_steep, 1.5 * n_gentle) << n_steep << " strokes steep, " << n_gentle << " gentle";
    EXPECT_GT(ink_steep, 1.3 * ink_gentle) << "ink steep " << ink_steep << ", gentle " << ink_gentle;
}

TEST(SlopeHachures, StrokesSpanOneContourBand) {
    const Split s = split(hachure_drawing(), Family::Hachure);
    const Raster& dem = synthetic().terrain.elevation;
    const double interval = 20, slack = 0.5;  // m: the contours are traced linearly, the DEM read bilinearly
    ASSERT_GT(s.elements.size(), 100u);
    for (const auto& r : s.elements) {
        // The band of the stroke's middle (its ring's centroid), and every point of the ring
        // in that band: a stroke from one band across a contour into the next fails.
        Point mid{0, 0};
        for (const Point& q : r.outer()) mid = mid + q;
        mid = mid / double(r.outer().size());
        const double band = std::floor(dem.sample(mid) / interval);
        for (const Point& q : r.outer()) {
            const double z = dem.sample(q);
            EXPECT_GE(z, band * interval - slack);
            EXPECT_LE(z, (band + 1) * interval + slack);
        }
    }
}

TEST(TerrainStyles, SameSeedSameElementsAtOneAndTwoThreads) {
    for (const char* style : {"scree", "slope-hachures"}) {
        const Drawing a = hatch(synthetic(), options(style, 1, 7)), b = hatch(synthetic(), options(style, 2, 7));
        const Drawing c = hatch(synthetic(), options(style, 2, 8));
        ASSERT_EQ(a.faces.size(), b.faces.size());
        for (std::size_t i = 0; i < a.faces.size(); ++i) {
            ASSERT_EQ(a.faces[i].hatches.size(), b.faces[i].hatches.size()) << style;
            for (std::size_t k = 0; k < a.faces[i].hatches.size(); ++k)
                ASSERT_EQ(a.faces[i].hatches[k].points, b.faces[i].hatches[k].points) << style;
        }
        EXPECT_NE(a.faces.back().hatches.size() == c.faces.back().hatches.size() &&
                      a.faces.back().hatches.front().points == c.faces.back().hatches.front().points,
                  true)
            << style << ": another seed should give other elements";
    }
}

TEST(TerrainStyles, RunOnTheSample) {
    Options o;
    o.dem = std::string(RH_SAMPLE_DIR) + "/dem.tif";
    o.partition.path = std::string(RH_SAMPLE_DIR) + "/partition.gpkg";
    const Prepared p = prepare(o);
    const std::vector<std::string> styles{"scree", "slope-hachures"};
    for (const std::string& style : styles) {
        o.style = style;
        const Drawing d = hatch(p, o);
        ASSERT_EQ(d.faces.back().face_id, kTerrainFaceId);
        EXPECT_GT(d.faces.back().hatches.size(), 1000u) << style;
    }
}
