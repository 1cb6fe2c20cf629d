// The pipeline on the bundled sample: hatches respect ridges and valleys, follow the density
// and orientation fields, are local, tile exactly and do not depend on the thread count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <numeric>
#include <set>
#include <utility>
#include <vector>

#include "carto/blocks.hpp"
#include "carto/error.hpp"
#include "carto/pipeline.hpp"
#include "carto/raster.hpp"
#include "libtex/tex.hpp"

#include "scratch.hpp"

using namespace carto;

namespace {

Options sample_options(const std::string& style) {
    Options o;
    o.dem = std::string(RH_SAMPLE_DIR) + "/dem.tif";
    o.partition.path = std::string(RH_SAMPLE_DIR) + "/partition.gpkg";
    o.style = style;
    o.threads = 2;
    return o;
}

const Prepared& sample() {
    static const Prepared p = prepare(sample_options(""));
    return p;
}

// A real crossing: each segment's ends lie on opposite sides of the other's line, more than
// a millimetre away (clipped hatches end on the face border, within rounding).
bool proper_cross(const Point& a, const Point& b, const Point& c, const Point& d) {
    const double tol = 1e-3;
    const double lab = tex::norm(b - a), lcd = tex::norm(d - c);
    if (lab == 0 || lcd == 0) return false;
    const double d1 = tex::cross(b - a, c - a) / lab, d2 = tex::cross(b - a, d - a) / lab;
    const double d3 = tex::cross(d - c, a - c) / lcd, d4 = tex::cross(d - c, b - c) / lcd;
    return ((d1 > tol && d2 < -tol) || (d1 < -tol && d2 > tol)) && ((d3 > tol && d4 < -tol) || (d3 < -tol && d4 > tol));
}

double fill_length(const FaceHatches& f) {
    double l = 0;
    for (const auto& h : f.hatches)
        if (h.family == Family::Fill)
            for (std::size_t i = 0; i + 1 < h.points.size(); ++i) l += tex::distance(h.points[i], h.points[i + 1]);
    return l;
}

std::vector<double> ranks(const std::vector<double>& v) {
    std::vector<std::size_t> idx(v.size());
    std::iota(idx.begin(), idx.end(), 0);
    std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) { return v[a] < v[b]; });
    std::vector<double> r(v.size());
    for (std::size_t i = 0; i < idx.size();) {
        std::size_t j = i;
        while (j + 1 < idx.size() && v[idx[j + 1]] == v[idx[i]]) ++j;
        for (std::size_t k = i; k <= j; ++k) r[idx[k]] = (i + j) / 2.0;
        i = j + 1;
    }
    return r;
}

double spearman(const std::vector<double>& a, const std::vector<double>& b) {
    const auto ra = ranks(a), rb = ranks(b);
    const double ma = std::accumulate(ra.begin(), ra.end(), 0.0) / ra.size();
    const double mb = std::accumulate(rb.begin(), rb.end(), 0.0) / rb.size();
    double num = 0, da = 0, db = 0;
    for (std::size_t i = 0; i < ra.size(); ++i) {
        num += (ra[i] - ma) * (rb[i] - mb);
        da += (ra[i] - ma) * (ra[i] - ma);
        db += (rb[i] - mb) * (rb[i] - mb);
    }
    return num / std::sqrt(da * db);
}

const RockFace& face_by_id(const Partition& p, std::int64_t id) {
    for (const auto& f : p.faces)
        if (f.id == id) return f;
    throw std::runtime_error("no face");
}

}  // namespace

TEST(Pipeline, SampleHasLabelledBorders) {
    const Partition& p = sample().partition;
    ASSERT_EQ(p.faces.size(), 20u);
    for (const auto& f : p.faces) {
        int ridge = 0, valley = 0, neighbours = 0;
        for (const auto& s : f.boundary) {
            ridge += s.kind == LineKind::Ridge;
            valley += s.kind == LineKind::Valley;
            neighbours += s.neighbor >= 0;
        }
        EXPECT_GT(ridge, 0) << "face " << f.id;
        EXPECT_GT(valley, 0) << "face " << f.id;
        EXPECT_GT(neighbours, 0) << "face " << f.id;
        EXPECT_TRUE(f.orientation.has_value());
        EXPECT_TRUE(f.density.has_value());
    }
}

TEST(Pipeline, NoHatchCrossesARidgeOrValleyOfItsFace) {
    for (const char* style : {"noisy", "bidirectional", "print"}) {
        const Drawing d = hatch(sample(), sample_options(style));
        const Partition& p = sample().partition;
        // Every hatch segment against the face's ridge and valley segments whose boxes meet the
        // hatch's box (two segments whose boxes are apart cannot cross).
        std::size_t segments = 0, near = 0;
        for (const auto& fh : d.faces) {
            const RockFace& f = face_by_id(p, fh.face_id);
            std::vector<std::pair<tex::BBox, const BoundarySegment*>> lines;
            for (const auto& s : f.boundary) {
                if (s.kind == LineKind::Other) continue;
                tex::BBox b;
                b.add(s.a);
                b.add(s.b);
                lines.emplace_back(b, &s);
            }
            std::vector<const BoundarySegment*> close;
            for (const auto& h : fh.hatches) {
                if (h.family == Family::Valley) continue;  // valleys are drawn on the line itself
                tex::BBox hb;
                for (const auto& q : h.points) hb.add(q);
                close.clear();
                for (const auto& [b, s] : lines)
                    if (b.intersects(hb)) close.push_back(s);
                for (std::size_t i = 0; i + 1 < h.points.size(); ++i, ++segments)
                    for (const BoundarySegment* s : close) {
                        ASSERT_FALSE(proper_cross(h.points[i], h.points[i + 1], s->a, s->b))
                            << style << " face " << f.id << " hatch crosses a " << kind_name(s->kind);
                        ++near;
                    }
            }
        }
        // Measured on the sample: 14,884 segments and 2,265 close pairs (noisy), 45,705 and 2,877
        // (bidirectional), 72,274 and 30,233 (print).
        EXPECT_GT(segments, 10000u) << style;
        EXPECT_GT(near, 1000u) << style << ": few hatches near the ridges and valleys";
    }
}

// Regression: the fine hatching of ridge shapes was clipped to the shape's triangle only,
// so it could spill out of the face where the face is narrower than the triangle.
TEST(Pipeline, EveryHatchStaysInsideItsFace) {
    for (const char* style : {"ridge-triangles", "fine-ridges", "bidirectional", "print"}) {
        const Drawing d = hatch(sample(), sample_options(style));
        const Partition& p = sample().partition;
        std::size_t checked = 0;
        for (const auto& fh : d.faces) {
            const RockFace& f = face_by_id(p, fh.face_id);
            for (const auto& h : fh.hatches)
                for (std::size_t i = 0, n = h.points.size(); i < (h.closed ? 2 * n : 2 * n - 1); ++i) {
                    // Every vertex and every segment's middle (a chord between two border
                    // points of a concave face leaves it in between; a closed stroke has one
                    // more segment): on the border or inside (0.01 m of slack for the
                    // clipping arithmetic), every family alike, print's smoothed crest lines
                    // too (each face draws the part of the line inside it).
                    const double slack = 0.01;
                    const tex::Point q = i % 2 == 0 ? h.points[i / 2]
                                                    : (h.points[i / 2] + h.points[(i / 2 + 1) % n]) / 2;
                    bool ok = f.region.contains(q);
                    for (const auto& s : f.boundary) {
                        if (ok) break;
                        const tex::Point e = s.b - s.a;
                        const double t = std::clamp(tex::dot(q - s.a, e) / tex::dot(e, e), 0.0, 1.0);
                        ok = tex::distance(q, s.a + e * t) < slack;
                    }
                    ASSERT_TRUE(ok) << style << " face " << f.id << " " << family_name(h.family) << " point "
                                    << q.x << "," << q.y << " lies outside its face";
                    ++checked;
                }
        }
        EXPECT_GT(checked, 1000u) << style;
    }
}

TEST(Pipeline, HatchDensityFollowsTheDensityField) {
    const Drawing d = hatch(sample(), sample_options("noisy"));
    std::vector<double> measured, wanted;
    for (const auto& fh : d.faces) {
        const RockFace& f = face_by_id(sample().partition, fh.face_id);
        measured.push_back(fill_length(fh) / f.region.area());
        wanted.push_back(*f.density);
    }
    EXPECT_GE(spearman(measured, wanted), 0.9);
}

TEST(Pipeline, HatchDirectionsFollowTheOrientationField) {
    // The strokes are jittered (across by a share of the spacing, so light faces stray
    // more: 6 to 9 degrees in the median), single strokes further; a face drawn in another
    // direction would be off by 45 degrees on average.
    const Drawing d = hatch(sample(), sample_options("noisy"));
    std::vector<double> all;
    for (const auto& fh : d.faces) {
        const double theta = *face_by_id(sample().partition, fh.face_id).orientation;
        std::vector<double> errors;
        for (const auto& h : fh.hatches) {
            if (h.family != Family::Fill) continue;
            const Point a = h.points.front(), b = h.points.back();
            if (tex::distance(a, b) < 1e-6) continue;
            double e = std::fmod(std::abs(std::atan2(b.y - a.y, b.x - a.x) - theta), M_PI);
            errors.push_back(std::min(e, M_PI - e) * 180 / M_PI);
        }
        all.insert(all.end(), errors.begin(), errors.end());
        if (errors.size() < 20) continue;  // a sliver face: too few strokes for a median
        std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
        EXPECT_LT(errors[errors.size() / 2], 12.0) << "face " << fh.face_id;
    }
    ASSERT_GT(all.size(), 1000u);
    std::nth_element(all.begin(), all.begin() + all.size() / 2, all.end());
    EXPECT_LT(all[all.size() / 2], 5.0);
}

namespace {

// The hatches of `after` whose points no hatch of `before` has: looked up in a set, as a
// face has thousands of hatches (a scan per hatch cost seconds under the sanitizers).
std::vector<const Hatch*> new_hatches(const std::vector<Hatch>& before, const std::vector<Hatch>& after) {
    auto key = [](const Hatch& h) {
        std::vector<std::pair<double, double>> k;
        k.reserve(h.points.size());
        for (const auto& q : h.points) k.emplace_back(q.x, q.y);
        return k;
    };
    std::set<std::vector<std::pair<double, double>>> seen;
    for (const Hatch& h : before) seen.insert(key(h));
    std::vector<const Hatch*> out;
    for (const Hatch& h : after)
        if (!seen.count(key(h))) out.push_back(&h);
    return out;
}

}  // namespace

// The properties every kind of style keeps: the thesis's final iteration (g) and print.
class EveryStyleKind : public ::testing::TestWithParam<const char*> {};
INSTANTIATE_TEST_SUITE_P(Pipeline, EveryStyleKind, ::testing::Values("bidirectional", "print"));

TEST_P(EveryStyleKind, ChangingAFieldInAWindowChangesOnlyNearby) {
    Prepared changed = sample();
    // Make the terrain very rough in a 150 m box.
    const tex::BBox win{1004300, 6540100, 1004450, 6540250};
    Raster& r = changed.terrain.roughness;
    for (int y = 0; y < r.height; ++y)
        for (int x = 0; x < r.width; ++x)
            if (win.contains(r.to_world(x + 0.5, y + 0.5))) r.at(x, y) = 0.5f;
    const Options o = sample_options(GetParam());
    const Drawing before = hatch(sample(), o), after = hatch(changed, o);
    ASSERT_EQ(before.faces.size(), after.faces.size());
    int changed_faces = 0;
    for (std::size_t i = 0; i < before.faces.size(); ++i) {
        const auto& a = before.faces[i].hatches;
        const auto& b = after.faces[i].hatches;
        bool same = a.size() == b.size();
        for (std::size_t k = 0; same && k < a.size(); ++k) same = a[k].points == b[k].points && a[k].family == b[k].family;
        const RockFace& f = face_by_id(sample().partition, before.faces[i].face_id);
        if (!same) {
            ++changed_faces;
            // Only faces meeting the window (plus one coarse cell of margin) may change.
            EXPECT_TRUE(f.region.bbox().intersects(win.expanded(60))) << "face " << f.id << " changed far away";
            // And within such a face, only hatches near the window.
            for (const Hatch* h : new_hatches(a, b))
                for (const auto& q : h->points) EXPECT_TRUE(win.expanded(60).contains(q));
        }
    }
    EXPECT_GT(changed_faces, 0);
}

// Local control of the height field: the styles read the elevation relative to the lowest
// and highest ground within --relief-radius, so raising the ground in a 100 m box changes
// the drawing only within that radius of it (plus the reach of a coarse cell or a ridge
// shape), not over the whole DEM as a global normalisation did.
TEST(Pipeline, EditingElevationInAWindowChangesOnlyNearby) {
    Raster dem = read_raster(std::string(RH_SAMPLE_DIR) + "/dem.tif", "--dem");
    const tex::BBox win{1004300, 6540100, 1004400, 6540200};
    for (int y = 0; y < dem.height; ++y)
        for (int x = 0; x < dem.width; ++x)
            if (win.contains(dem.to_world(x + 0.5, y + 0.5))) dem.at(x, y) += 150.0f;
    const std::string edited_dem = rh_test::scratch("edited_dem.tif");
    write_geotiff(dem, edited_dem);
    auto changed_faces = [&](double radius, const char* style) {  // faces whose hatches changed
        Options o = sample_options(style);
        o.relief_radius = radius;
        Options e = o;
        e.dem = edited_dem;
        const Drawing before = hatch(prepare(o), o), after = hatch(prepare(e), e);
        EXPECT_EQ(before.faces.size(), after.faces.size());
        const tex::BBox reach = win.expanded(radius + 70);
        int n = 0;
        for (std::size_t i = 0; i < before.faces.size() && i < after.faces.size(); ++i) {
            const auto& a = before.faces[i].hatches;
            const auto& b = after.faces[i].hatches;
            bool same = a.size() == b.size();
            for (std::size_t k = 0; same && k < a.size(); ++k) same = a[k].points == b[k].points;
            if (same) continue;
            ++n;
            const RockFace& f = face_by_id(sample().partition, before.faces[i].face_id);
            EXPECT_TRUE(f.region.bbox().intersects(reach)) << "face " << f.id << " changed far from the edit";
            for (const Hatch* h : new_hatches(a, b))
                for (const auto& q : h->points)
                    EXPECT_TRUE(reach.contains(q)) << "face " << f.id << ": " << q.x << "," << q.y;
        }
        return n;
    };
    EXPECT_GT(changed_faces(150, "high-ridges"), 0);
    // The wider radius too.
    EXPECT_GT(changed_faces(400, "high-ridges"), 0);
    // print also reads the fall line and the shade, averaged over 1 mm on paper (10 m).
    EXPECT_GT(changed_faces(150, "print"), 0);
    std::filesystem::remove(edited_dem);
}

// A bad value computed inside a style is reported with the style, the face and the value,
// as a failure of the run (not as a usage error of the command line).
TEST(Pipeline, AnErrorInAStyleNamesTheStyleTheFaceAndTheValue) {
    auto broken = std::make_shared<Style>();
    broken->info = {"broken", "", "stripes of a width computed per face", {}};
    broken->program = [](const ControlFields&, const ParamValues&) {
        return tex::Arrangement([](const tex::Region& r) {
            const double width = r.area() > 0 ? -2.5 : 1.0;  // a bad spacing, as from a bad field value
            return tex::StripesPartition(tex::StripesProperties(0.0, width))(r);
        });
    };
    Options o = sample_options("");
    o.custom_style = broken;
    try {
        hatch(sample(), o);
        FAIL() << "the style's error was not reported";
    } catch (const Error& e) {
        const std::string m = e.what();
        EXPECT_NE(e.code(), Code::Usage);
        EXPECT_NE(m.find("style 'broken'"), std::string::npos) << m;
        EXPECT_NE(m.find("face "), std::string::npos) << m;
        EXPECT_NE(m.find("-2.5"), std::string::npos) << m;
    }
}

// Faces finish on two threads in any order; the fractions reported while hatching still
// rise. A cheap style makes the faces finish together, where a count taken outside the
// progress lock came out of order (seen in CI on the bundled sample).
TEST(Pipeline, HatchingProgressRisesWhicheverThreadFinishesFirst) {
    auto cheap = std::make_shared<Style>();
    cheap->info = {"cheap", "", "one wide stripe per face", {}};
    cheap->program = [](const ControlFields&, const ParamValues&) {
        return tex::Arrangement(
            [](const tex::Region& r) { return tex::StripesPartition(tex::StripesProperties(0.0, 1e6))(r); });
    };
    Options o = sample_options("");
    o.custom_style = cheap;
    o.threads = 2;
    // Before the fix it failed within 12, 40 and 83 rounds.
    const int rounds = 200;
    for (int round = 0; round < rounds; ++round) {
        std::vector<double> fractions;
        hatch(sample(), o, [&](double f, const std::string& stage) {
            if (stage == "hatching") fractions.push_back(f);
            return true;
        });
        ASSERT_EQ(fractions.size(), sample().partition.faces.size());
        ASSERT_TRUE(std::is_sorted(fractions.begin(), fractions.end())) << "round " << round;
        ASSERT_DOUBLE_EQ(fractions.back(), 0.9);
    }
}

TEST_P(EveryStyleKind, TwoHalvesGiveTheSameHatchesAsTheWhole) {
    Options o = sample_options(GetParam());
    const Drawing whole = hatch(sample(), o);
    const tex::BBox b = sample().partition.bounds();
    // Split in the middle, and exactly through the anchor of one face: that face goes to the
    // tile whose window starts there (half-open windows), and only to it.
    const RockFace& f0 = sample().partition.faces.front();
    std::vector<double> splits = {b.center().x, face_anchor(f0).x};
    for (const double mid : splits) {
        SCOPED_TRACE(mid);
        o.window = tex::BBox{b.xmin - 1, b.ymin - 1, mid, b.ymax + 1};
        const Drawing left = hatch(sample(), o);
        o.window = tex::BBox{mid, b.ymin - 1, b.xmax + 1, b.ymax + 1};
        const Drawing right = hatch(sample(), o);
        EXPECT_GT(left.faces.size(), 0u);
        EXPECT_GT(right.faces.size(), 0u);
        ASSERT_EQ(left.faces.size() + right.faces.size(), whole.faces.size());
        std::map<std::int64_t, const FaceHatches*> parts;
        for (const auto& f : left.faces) parts[f.face_id] = &f;
        for (const auto& f : right.faces) parts[f.face_id] = &f;
        if (mid == face_anchor(f0).x)
            EXPECT_TRUE(std::any_of(right.faces.begin(), right.faces.end(),
                                    [&](const FaceHatches& f) { return f.face_id == f0.id; }));
        for (const auto& f : whole.faces) {
            ASSERT_TRUE(parts.count(f.face_id));
            const auto& h = parts[f.face_id]->hatches;
            ASSERT_EQ(h.size(), f.hatches.size());
            for (std::size_t k = 0; k < h.size(); ++k) {
                EXPECT_EQ(h[k].points, f.hatches[k].points);
                EXPECT_EQ(h[k].family, f.hatches[k].family);
                EXPECT_EQ(h[k].closed, f.hatches[k].closed);
            }
        }
    }
}

TEST_P(EveryStyleKind, SameHatchesWithOneOrTwoThreads) {
    Options o = sample_options(GetParam());
    o.threads = 1;
    const Drawing one = hatch(sample(), o);
    o.threads = 2;
    const Drawing two = hatch(sample(), o);
    ASSERT_EQ(one.faces.size(), two.faces.size());
    for (std::size_t i = 0; i < one.faces.size(); ++i) {
        ASSERT_EQ(one.faces[i].hatches.size(), two.faces[i].hatches.size());
        for (std::size_t k = 0; k < one.faces[i].hatches.size(); ++k)
            EXPECT_EQ(one.faces[i].hatches[k].points, two.faces[i].hatches[k].points);
    }
}

// A run uses its own thread count and a style program's SetSeed stays inside it: the process's
// GetThreads() and GetSeed() are what they were (issue 17), and the drawing is the same.
TEST(Pipeline, HatchLeavesThreadsAndSeedAsTheyWere) {
    const unsigned threads = tex::GetThreads();
    const std::uint64_t seed = tex::GetSeed();
    tex::SetThreads(3);
    tex::SetSeed(9);
    Options o = sample_options("bidirectional");
    o.threads = 1;
    const Drawing plain = hatch(sample(), o);
    auto seeding = std::make_shared<Style>(builtin_style("bidirectional"));
    const StyleProgram program = seeding->program;
    seeding->program = [program](const ControlFields& f, const ParamValues& p) {
        tex::SetSeed(123);  // as a style script may
        return program(f, p);
    };
    o.custom_style = seeding;
    const Drawing seeded = hatch(sample(), o);
    EXPECT_EQ(tex::GetThreads(), 3u);
    EXPECT_EQ(tex::GetSeed(), 9u);
    ASSERT_EQ(plain.faces.size(), seeded.faces.size());
    for (std::size_t i = 0; i < plain.faces.size(); ++i) {
        ASSERT_EQ(plain.faces[i].hatches.size(), seeded.faces[i].hatches.size());
        for (std::size_t k = 0; k < plain.faces[i].hatches.size(); ++k)
            EXPECT_EQ(plain.faces[i].hatches[k].points, seeded.faces[i].hatches[k].points);
    }
    // An error in the style: the same.
    seeding->program = [](const ControlFields&, const ParamValues&) -> tex::Arrangement {
        tex::SetSeed(124);
        throw Error(Code::Failure, "broken style");
    };
    EXPECT_THROW(hatch(sample(), o), Error);
    EXPECT_EQ(tex::GetThreads(), 3u);
    EXPECT_EQ(tex::GetSeed(), 9u);
    tex::SetThreads(threads);
    tex::SetSeed(seed);
}

TEST(Pipeline, RidgeShapesFallIntoTheDarkerFace) {
    const Drawing d = hatch(sample(), sample_options("ridge-triangles"));
    const Partition& p = sample().partition;
    int with_triangles = 0;
    for (const auto& fh : d.faces) {
        const RockFace& f = face_by_id(p, fh.face_id);
        const bool has = std::any_of(fh.hatches.begin(), fh.hatches.end(), [](const Hatch& h) { return h.family == Family::Ridge; });
        if (!has) continue;
        ++with_triangles;
        // The face is darker than the face across at least one of its ridges.
        bool darker = false;
        for (const auto& s : f.boundary)
            if (s.kind == LineKind::Ridge && s.neighbor >= 0 && *f.density > *p.faces[s.neighbor].density) darker = true;
        EXPECT_TRUE(darker) << "face " << f.id;
    }
    EXPECT_GT(with_triangles, 3);
}

// Ink per face as a printer lays it: stroke length x the family's width on the ground over
// the face's area, for faces of at least 25 mm2 on paper (smaller ones are specks of tone).
std::vector<std::pair<const RockFace*, double>> ink_per_face(const Drawing& d, const Partition& p, double scale) {
    std::vector<std::pair<const RockFace*, double>> out;
    const double mm = scale / 1000.0;
    for (const auto& fh : d.faces) {
        const RockFace& f = face_by_id(p, fh.face_id);
        const double area = f.region.area();
        if (area < 25 * mm * mm) continue;
        double ink = 0;
        for (const auto& h : fh.hatches)
            for (std::size_t i = 0, n = h.points.size(); i + 1 < n + (h.closed ? 1 : 0); ++i)
                ink += tex::distance(h.points[i], h.points[(i + 1) % n]) * family_width_mm(h.family) * mm;
        out.push_back({&f, ink / area});
    }
    return out;
}

// The tone of print: no face above the ceiling at any scale, darker faces darker.
TEST(Pipeline, PrintInkStaysUnderTheCeilingAtEveryScale) {
    for (const double scale : {10000.0, 25000.0, 50000.0}) {
        SCOPED_TRACE(scale);
        Options o = sample_options("print");
        o.scale = scale;
        const auto ink = ink_per_face(hatch(sample(), o), sample().partition, scale);
        ASSERT_GT(ink.size(), 5u);
        std::vector<double> measured, wanted;
        double darkest = 0;
        for (const auto& [f, cover] : ink) {
            EXPECT_LT(cover, 0.45) << "face " << f->id;
            darkest = std::max(darkest, cover);
            measured.push_back(cover);
            wanted.push_back(*f->density);  // 1 - mean hillshade
        }
        EXPECT_GT(darkest, 0.2);  // a tone, not an empty drawing
        EXPECT_GE(spearman(measured, wanted), 0.8);
    }
    // The ceiling is a parameter: lowered, it holds too.
    Options o = sample_options("print");
    o.params = {{"ink_max", 0.2}};
    for (const auto& [f, cover] : ink_per_face(hatch(sample(), o), sample().partition, o.scale))
        EXPECT_LT(cover, 0.22) << "face " << f->id;
}

namespace {
// Median angle (degrees) between the fill strokes and the axis `want` gives at their middle.
template <class Want>
double median_fill_angle(const Drawing& d, Want want) {
    std::vector<double> e;
    for (const auto& fh : d.faces)
        for (const auto& h : fh.hatches) {
            if (h.family != Family::Fill) continue;
            const Point a = h.points.front(), b = h.points.back();
            const double w = want(fh.face_id, (a + b) / 2);
            if (tex::distance(a, b) < 1e-6 || std::isnan(w)) continue;
            const double x = std::fmod(std::abs(std::atan2(b.y - a.y, b.x - a.x) - w), M_PI);
            e.push_back(std::min(x, M_PI - x) * 180 / M_PI);
        }
    if (e.size() < 1000) return NAN;
    std::nth_element(e.begin(), e.begin() + e.size() / 2, e.end());
    return e[e.size() / 2];
}
}  // namespace

// Where the partition gives no orientation, print's strokes follow the local fall line
// (better than one direction per face); where it gives one, they keep it.
TEST(Pipeline, PrintStrokesFollowTheFallLineWhereNoOrientationIsGiven) {
    Prepared derived = sample();
    derived.orientation_derived.assign(derived.partition.faces.size(), true);
    const Raster& aspect = derived.terrain.aspect;
    auto fall_line = [&](std::int64_t, const Point& q) { return aspect.sample(q); };
    Options o = sample_options("print");
    const double follow = median_fill_angle(hatch(derived, o), fall_line);
    o.params = {{"follow_fall_line", 0}};
    const double per_face = median_fill_angle(hatch(derived, o), fall_line);
    EXPECT_LT(follow, 12.0);
    EXPECT_LT(follow, per_face - 1.0);
    // Given orientations are kept (the sample's partition gives one per face).
    auto given = [&](std::int64_t id, const Point&) { return *face_by_id(sample().partition, id).orientation; };
    EXPECT_LT(median_fill_angle(hatch(sample(), sample_options("print")), given), 5.0);
}

namespace {
double to_segments(const Point& q, const std::vector<std::pair<Point, Point>>& segs) {
    double best = 1e300;
    for (const auto& [a, b] : segs) {
        const Point e = b - a;
        const double t = std::clamp(tex::dot(q - a, e) / std::max(tex::dot(e, e), 1e-300), 0.0, 1.0);
        best = std::min(best, tex::distance(q, a + e * t));
    }
    return best;
}
}  // namespace

// Issue 16: print draws each ridge as one smooth crest line (every ridge of the partition
// covered, no kinks) and hangs its strokes from it on the darker side only.
// The ends of print's crest line pieces that join nothing. Each face draws the part of a
// ridge's line inside it, so a piece ends where another begins (at the face border it
// crosses, within 0.001 mm on paper), or within 0.3 mm of an end or a fork of the ridges
// (a vertex that no other ridge segment, or more than one, continues). A crest line piece
// is a ridge-family stroke of more than two points or one that ends on a ridge; the
// strokes hanging from the line end away from it. `ends` gets the number of piece ends.
std::size_t loose_crest_ends(const Drawing& d, const Partition& p, double mm, std::size_t& ends) {
    std::vector<std::pair<Point, Point>> ridges;
    std::map<std::pair<double, double>, int> degree;
    std::set<std::pair<std::pair<double, double>, std::pair<double, double>>> unique_ridges;
    for (const auto& f : p.faces)
        for (const auto& s : f.boundary) {
            if (s.kind != LineKind::Ridge) continue;
            ridges.push_back({s.a, s.b});
            auto ka = std::make_pair(s.a.x, s.a.y), kb = std::make_pair(s.b.x, s.b.y);
            if (kb < ka) std::swap(ka, kb);
            if (!unique_ridges.insert({ka, kb}).second) continue;
            ++degree[ka];
            ++degree[kb];
        }
    std::vector<Point> ridge_ends;
    for (const auto& [k, n] : degree)
        if (n != 2) ridge_ends.push_back({k.first, k.second});
    std::vector<Point> piece_ends;
    for (const auto& fh : d.faces)
        for (const auto& h : fh.hatches)
            if (h.family == Family::Ridge &&
                (h.points.size() > 2 || to_segments(h.points.back(), ridges) < 0.01 * mm)) {
                piece_ends.push_back(h.points.front());
                piece_ends.push_back(h.points.back());
            }
    ends = piece_ends.size();
    std::size_t loose = 0;
    for (std::size_t i = 0; i < piece_ends.size(); ++i) {
        bool met = false;
        for (std::size_t j = 0; j < piece_ends.size() && !met; ++j)
            met = j != i && tex::distance(piece_ends[i], piece_ends[j]) < 1e-3 * mm;
        for (std::size_t j = 0; j < ridge_ends.size() && !met; ++j)
            met = tex::distance(piece_ends[i], ridge_ends[j]) < 0.3 * mm;
        loose += !met;
    }
    return loose;
}

TEST(Pipeline, PrintDrawsRidgesAsSmoothCrestLinesWithStrokesOnTheDarkSide) {
    const Partition& p = sample().partition;
    for (const double scale : {10000.0, 25000.0}) {
        SCOPED_TRACE(scale);
        const double mm = scale / 1000;
        Options o = sample_options("print");
        o.scale = scale;
        const Drawing d = hatch(sample(), o);
        std::vector<std::pair<Point, Point>> ridges;
        for (const auto& f : p.faces)
            for (const auto& s : f.boundary)
                if (s.kind == LineKind::Ridge) ridges.push_back({s.a, s.b});
        ASSERT_GT(ridges.size(), 10u);
        // A crest line runs along a ridge from end to end; a stroke leaves it.
        std::vector<std::pair<Point, Point>> line_segs;
        std::vector<double> turn;
        std::size_t lines = 0, dark = 0, lit = 0;
        for (const auto& fh : d.faces) {
            const RockFace& f = face_by_id(p, fh.face_id);
            for (const auto& h : fh.hatches) {
                if (h.family != Family::Ridge) continue;
                const bool line = h.points.size() > 2 || to_segments(h.points.back(), ridges) < 0.01 * mm;
                if (line) {
                    ++lines;
                    for (std::size_t i = 0; i + 1 < h.points.size(); ++i) {
                        line_segs.push_back({h.points[i], h.points[i + 1]});
                        if (i + 2 < h.points.size()) {
                            const Point u = h.points[i + 1] - h.points[i], v = h.points[i + 2] - h.points[i + 1];
                            turn.push_back(std::abs(std::atan2(tex::cross(u, v), tex::dot(u, v))) * 180 / M_PI);
                        }
                    }
                    continue;
                }
                // A stroke: its foot on a ridge of its own face, in the darker face of the two.
                double to_own = 1e300;
                const BoundarySegment* nearest = nullptr;
                for (const auto& s : f.boundary) {
                    if (s.kind != LineKind::Ridge) continue;
                    const double dist = to_segments(h.points.front(), {{s.a, s.b}});
                    if (dist < to_own) to_own = dist, nearest = &s;
                }
                ASSERT_TRUE(nearest) << "face " << f.id;
                EXPECT_LT(to_own, 0.25 * mm) << "face " << f.id;
                const bool darker =
                    nearest->neighbor < 0 ? *f.density >= 0.5 : *f.density > *p.faces[nearest->neighbor].density;
                ++(darker ? dark : lit);
            }
        }
        // Dark sides carry the strokes (Swiss-style: dark sides denser).
        EXPECT_GT(dark, 100u);
        EXPECT_GT(dark, 5 * lit);
        // Every ridge is under a crest line, within 0.25 mm on paper, all along.
        ASSERT_GT(lines, 0u);
        std::size_t samples = 0, far = 0;
        for (const auto& [a, b] : ridges) {
            const int n = std::max(1, int(tex::distance(a, b) / (0.2 * mm)));
            for (int k = 0; k <= n; ++k, ++samples)
                far += to_segments(a + (b - a) * (double(k) / n), line_segs) > 0.25 * mm;
        }
        EXPECT_EQ(far, 0u) << "of " << samples;
        // Continuous: the pieces each face draws join into lines.
        std::size_t ends = 0;
        EXPECT_EQ(loose_crest_ends(d, p, mm, ends), 0u) << "of " << ends << " ends of crest line pieces";
        // Smooth: no kink of the raster or the partition's corners left in the lines.
        std::sort(turn.begin(), turn.end());
        ASSERT_GT(turn.size(), 100u);
        EXPECT_LT(turn[turn.size() * 99 / 100], 20.0);
        EXPECT_LT(turn.back(), 45.0);
    }
}

// On an extracted partition ridges meet in junctions of three faces, where a ridge edge of one
// face runs along two others: the crest line pieces still join (each face's edges end where
// the face across changes, so both sides smooth the same line).
TEST(Pipeline, PrintCrestLinePiecesJoinOnAnExtractedPartition) {
    Options o = sample_options("print");
    o.partition.path = "auto";
    o.scale = 25000;
    const Prepared pr = prepare(o);
    const Drawing d = hatch(pr, o);
    std::size_t ends = 0;
    EXPECT_EQ(loose_crest_ends(d, pr.partition, o.scale / 1000, ends), 0u) << "of " << ends;
    EXPECT_GT(ends, 50u);
}

// Issue 16's measure of tone (bench/print_quality.py): over 100 m blocks at least half rock,
// the ink (stroke length x width) ranks with the mean shade, 1 - hillshade on a 10 m
// lattice, with Spearman's rho of at least 0.8. At 1:50000 a 3 mm tone cell is 150 m wide and
// the blocks followed their cells more than their shade (0.77); 2 mm cells give 0.83.
TEST(Pipeline, PrintInkFollowsTheShadeOverHundredMetreBlocksAtOneToFiftyThousand) {
    Options o = sample_options("print");
    o.scale = 50000;
    const Prepared pr = prepare(o);
    const Drawing d = hatch(pr, o);
    const double block = 100, step = 10, mm = o.scale / 1000;
    auto key = [&](const Point& q) { return std::make_pair(std::floor(q.x / block), std::floor(q.y / block)); };
    std::map<std::pair<double, double>, double> ink, shade;
    std::map<std::pair<double, double>, int> rock;
    for (const auto& fh : d.faces)
        for (const auto& h : fh.hatches)
            for (std::size_t i = 0; i + 1 < h.points.size(); ++i)
                ink[key((h.points[i] + h.points[i + 1]) / 2)] +=
                    tex::distance(h.points[i], h.points[i + 1]) * family_width_mm(h.family) * mm;
    for (const auto& f : pr.partition.faces) {
        const tex::BBox b = f.region.bbox();
        for (double x = std::floor(b.xmin / step) * step + step / 2; x < b.xmax; x += step)
            for (double y = std::floor(b.ymin / step) * step + step / 2; y < b.ymax; y += step) {
                const Point q{x, y};
                if (!f.region.contains(q)) continue;
                const double h = pr.terrain.hillshade.sample(q);
                if (std::isnan(h)) continue;
                ++rock[key(q)];
                shade[key(q)] += 1 - h;
            }
    }
    std::vector<double> block_ink, block_shade;
    for (const auto& [k, n] : rock)
        if (n >= 0.5 * (block / step) * (block / step)) {
            block_ink.push_back(ink[k] / (n * step * step));
            block_shade.push_back(shade[k] / n);
        }
    ASSERT_GT(block_ink.size(), 200u);
    EXPECT_GE(spearman(block_ink, block_shade), 0.8);
}

// The tone budget divides a cell's ink by the cell's area inside the face: a face with a
// hole, a concave notch, and a cell reaching out of it.
TEST(Pipeline, AreaWithinCountsOnlyThePartOfTheFaceInTheCell) {
    // A 10 x 10 square less a 2 x 2 hole at (1..3, 1..3), with a notch (4..6 x 8..10) cut from
    // its top edge: area 100 - 4 - 4 = 92.
    const tex::Region face({{0, 0}, {10, 0}, {10, 10}, {6, 10}, {6, 8}, {4, 8}, {4, 10}, {0, 10}},
                           {{{1, 1}, {1, 3}, {3, 3}, {3, 1}}});
    EXPECT_NEAR(face.area_within(tex::Region({{-5, -5}, {20, -5}, {20, 20}, {-5, 20}})), 92, 1e-9);
    // The cell 0..4 x 0..4 holds 16 less the hole: 12.
    EXPECT_NEAR(face.area_within(tex::Region({{0, 0}, {4, 0}, {4, 4}, {0, 4}})), 12, 1e-9);
    // A cell over the notch reaching out of the face: 3..7 x 7..10 less the notch, 12 - 4.
    EXPECT_NEAR(face.area_within(tex::Region({{3, 7}, {7, 7}, {7, 12}, {3, 12}})), 8, 1e-9);
    // A cell clockwise, and one outside the face.
    EXPECT_NEAR(face.area_within(tex::Region({{0, 4}, {0, 0}, {4, 0}, {4, 4}})), 12, 1e-9);
    EXPECT_NEAR(face.area_within(tex::Region({{20, 20}, {21, 20}, {21, 21}, {20, 21}})), 0, 1e-12);
}

TEST(Pipeline, PrintRefusesAToneCurveAboveItself) {
    Options o = sample_options("print");
    o.params = {{"tone_min", 0.5}, {"tone_max", 0.2}};
    try {
        hatch(sample(), o);
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), Code::Usage);
        EXPECT_NE(std::string(e.what()).find("tone_min=0.5 is above tone_max=0.2"), std::string::npos) << e.what();
    }
}

TEST(Pipeline, StylesAndParameters) {
    // The seven rock styles of Fig. 5.4, print, aretes (crest ornaments), rock (structure
    // first, no drawn outline: the default), then the two terrain styles.
    EXPECT_EQ(styles().size(), 12u);
    EXPECT_EQ(std::count_if(styles().begin(), styles().end(), [](const StyleInfo& s) { return s.crest_ornament; }), 1);
    EXPECT_EQ(std::count_if(styles().begin(), styles().end(), [](const StyleInfo& s) { return s.terrain; }), 2);
    EXPECT_EQ(default_style(), "rock");
    EXPECT_EQ(find_style("5.4a").name, "noisy");
    EXPECT_EQ(find_style("c").name, "density-cells");
    try {
        find_style("watercolour");
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), Code::UnknownStyle);
        EXPECT_NE(std::string(e.what()).find("'watercolour'"), std::string::npos);
    }
    // Millimetres on paper become ground units at the scale.
    const ParamValues v = resolve_params(find_style("noisy"), {{"spacing_min", 0.5}}, 25000);
    EXPECT_DOUBLE_EQ(v.at("spacing_min"), 12.5);
    EXPECT_DOUBLE_EQ(v.at("spacing_max"), 1.5 * 25);
    EXPECT_THROW(resolve_params(find_style("noisy"), {{"spacing_min", -1}}, 10000), Error);
    EXPECT_THROW(resolve_params(find_style("noisy"), {{"peak_spacing", 1}}, 10000), Error);
}

TEST(Fields, FaceWiseRasterAndClosedFormFieldsDriveAStyle) {
    const Partition& part = sample().partition;
    std::vector<double> ids;
    for (const auto& f : part.faces) ids.push_back(double(f.id));
    const Field which = face_field(part, ids);
    for (const auto& f : part.faces) EXPECT_EQ(which(interior_point(f)), double(f.id));
    EXPECT_TRUE(std::isnan(which({0, 0})));
    // A controlled arrangement applied to other fields: a closed-form orientation of 30
    // degrees everywhere and a constant density.
    const double theta = 30 * M_PI / 180;
    const ControlFields fields{constant_field(theta), constant_field(0.8), raster_field(sample().relief),
                               raster_field(sample().terrain.roughness), raster_field(sample().terrain.slope)};
    const Style s = builtin_style("noisy");
    const ParamValues p = resolve_params(s.info, {{"jitter", 0.0}}, 10000);
    const auto hatches = hatch_face(s.program(fields, p), part, 3, 0);
    ASSERT_GT(hatches.size(), 10u);
    for (const auto& h : hatches) {
        const Point d = h.points.back() - h.points.front();
        if (tex::norm(d) < 1) continue;
        double e = std::fmod(std::abs(std::atan2(d.y, d.x) - theta), M_PI);
        EXPECT_LT(std::min(e, M_PI - e), 1e-6);  // no jitter: exactly along the field
    }
}

// The rock style has no drawn outline: where no face lies across a border and no ridge lies
// on it, fill and cross strokes end at least fray_min from it, spread over the band up to
// fray_max on both sides of it (fray_beyond's share past it); the same drawing on any number
// of threads.
// The distance from p to the segment ab.
double to_segment(const Point& p, const Point& a, const Point& b) {
    const Point ab = b - a;
    const double t = std::clamp(tex::dot(p - a, ab) / std::max(tex::dot(ab, ab), 1e-300), 0.0, 1.0);
    return tex::distance(p, a + ab * t);
}

// The distance from p to the nearest of the region's rings.
double to_ring(const tex::Region& r, const Point& p) {
    double best = 1e300;
    auto ring = [&](const std::vector<Point>& pts) {
        for (std::size_t i = 0; i < pts.size(); ++i) best = std::min(best, to_segment(p, pts[i], pts[(i + 1) % pts.size()]));
    };
    ring(r.outer());
    for (const auto& h : r.holes()) ring(h);
    return best;
}

TEST(Pipeline, TheRockStyleDrawsNoOutline) {
    Options o = sample_options("rock");
    o.threads = 1;
    const Drawing d = hatch(sample(), o);
    o.threads = 2;
    const Drawing d2 = hatch(sample(), o);
    const Partition& part = sample().partition;
    const double mm = o.scale / 1000;
    // The outer border: segments with no face across, and no ridge or valley on them.
    std::vector<std::pair<Point, Point>> rim;
    for (const auto& f : part.faces)
        for (const auto& s : f.boundary)
            if (s.neighbor < 0 && s.kind == LineKind::Other) rim.push_back({s.a, s.b});
    ASSERT_GT(rim.size(), 100u);
    // The rim's segments by 2 mm cells (each in the cells its box, grown by 2 mm, covers).
    const double cell = 2 * mm;
    std::map<std::pair<long long, long long>, std::vector<std::size_t>> cells;
    for (std::size_t k = 0; k < rim.size(); ++k) {
        const auto& [a, b] = rim[k];
        for (long long x = (long long)std::floor((std::min(a.x, b.x) - cell) / cell);
             x <= (long long)std::floor((std::max(a.x, b.x) + cell) / cell); ++x)
            for (long long y = (long long)std::floor((std::min(a.y, b.y) - cell) / cell);
                 y <= (long long)std::floor((std::max(a.y, b.y) + cell) / cell); ++y)
                cells[{x, y}].push_back(k);
    }
    auto to_rim = [&](const Point& p) {
        double best = 1e300;
        const auto it = cells.find({(long long)std::floor(p.x / cell), (long long)std::floor(p.y / cell)});
        if (it == cells.end()) return best;
        for (std::size_t k : it->second) best = std::min(best, to_segment(p, rim[k].first, rim[k].second));
        return best;
    };
    std::size_t ends = 0, shallow = 0, deep = 0, too_close = 0, outside = 0, crosses = 0, crosses_outside = 0;
    for (std::size_t k = 0; k < d.faces.size(); ++k) {
        std::size_t index = 0;
        while (index < part.faces.size() && part.faces[index].id != d.faces[k].face_id) ++index;
        ASSERT_LT(index, part.faces.size());
        const tex::Region region = face_region(part, index);
        ASSERT_EQ(d.faces[k].hatches.size(), d2.faces[k].hatches.size());
        for (std::size_t i = 0; i < d.faces[k].hatches.size(); ++i) {
            const Hatch& h = d.faces[k].hatches[i];
            ASSERT_EQ(h.points, d2.faces[k].hatches[i].points);
            if (h.family != Family::Fill && h.family != Family::Cross) continue;
            for (const Point& e : {h.points.front(), h.points.back()}) {
                const double dist = to_rim(e);
                if (dist > 2 * mm) continue;
                ++ends;
                too_close += dist < 0.2 * mm - 1e-6;
                shallow += dist >= 0.2 * mm - 1e-6 && dist < 0.45 * mm;
                deep += dist >= 0.45 * mm && dist <= 0.75 * mm + 1e-6;
                outside += !region.contains(e);
                if (h.family == Family::Cross) ++crosses, crosses_outside += !region.contains(e) && to_ring(region, e) > 1e-6 * mm;
            }
        }
    }
    ASSERT_GT(ends, 1000u);
    EXPECT_LT(double(too_close) / double(ends), 0.01) << too_close << " of " << ends;
    // Ragged: the ends spread over the band (the rest, farther than 0.75 mm, end on their own:
    // the rows end many strokes near the border too), on both sides of the border.
    EXPECT_GT(double(shallow) / double(ends), 0.12) << shallow << " of " << ends;
    EXPECT_GT(double(deep) / double(ends), 0.12) << deep << " of " << ends;
    const double band = double(shallow + deep);
    EXPECT_GT(double(outside) / band, 0.07) << outside << " of " << band;
    EXPECT_LT(double(outside) / band, 0.6) << outside << " of " << band;
    // Only fill strokes go past the border: a cross stroke there reads as a stray hair.
    EXPECT_GT(crosses, 20u);
    EXPECT_EQ(crosses_outside, 0u);
}

// The rock style's fill hangs in rows from the level lines of the elevation (tex::CutAtLevels):
// many strokes start on a level line, their lower ends ragged; the rows keep the tone (each
// tone cell's strokes shortened to its ink exactly).
TEST(Pipeline, TheRockStyleHangsItsFillInRowsAndKeepsTheTone) {
    Options o = sample_options("rock");
    o.params = {{"band_wander", 0}};  // level lines of the elevation itself
    const Drawing rows = hatch(sample(), o);
    const Plan plan = make_plan(o, PlanFor::Drawing);
    const ControlFields f = control_fields(sample(), plan);
    const double mm = o.scale / 1000, band = 1.2 * mm;
    auto fill_tops = [&](const Drawing& d) {
        std::size_t strokes = 0, on_level = 0, specks = 0;
        std::vector<double> drops;
        for (const auto& face : d.faces)
            for (const auto& h : face.hatches) {
                if (h.family != Family::Fill || h.points.size() < 2) continue;
                const double z0 = f.elevation(h.points.front()), z1 = f.elevation(h.points.back());
                if (std::isnan(z0) || std::isnan(z1)) continue;
                ++strokes;
                const double top = std::max(z0, z1), phase = std::fmod(top, band) / band;
                if (std::min(phase, 1 - phase) < 0.01) {
                    ++on_level;
                    drops.push_back(std::abs(z0 - z1) / band);
                    double length = 0;
                    for (std::size_t i = 1; i < h.points.size(); ++i) length += tex::distance(h.points[i - 1], h.points[i]);
                    specks += length < 0.2 * mm;
                }
            }
        return std::make_tuple(strokes, on_level, drops, specks);
    };
    const auto [n, on, drops, specks] = fill_tops(rows);
    ASSERT_GT(n, 5000u);
    // No specks in the rows: a stroke shorter than twice its width goes whole.
    EXPECT_LT(double(specks) / double(on), 0.02) << specks << " of " << on;
    // Without rows a stroke's top lies within 1 % of a band of a level line 2 % of the time.
    EXPECT_GT(double(on) / double(n), 0.3) << on << " of " << n;
    // Ragged lower ends: the drops of the strokes hanging from a level line spread.
    const double mean = std::accumulate(drops.begin(), drops.end(), 0.0) / double(drops.size());
    double var = 0;
    for (double v : drops) var += (v - mean) * (v - mean);
    EXPECT_GT(std::sqrt(var / double(drops.size())), 0.1);
    const auto [pn, pon, pdrops, pspecks] = fill_tops(hatch(sample(), sample_options("print")));
    EXPECT_LT(double(pon) / double(pn), 0.04) << pon << " of " << pn;
    // No rows where the ground is gentler than band_slope (here: anywhere).
    Options slabs = o;
    slabs.params["band_slope"] = 10000;
    const auto [sn, son, sdrops, sspecks] = fill_tops(hatch(sample(), slabs));
    EXPECT_LT(double(son) / double(sn), 0.04) << son << " of " << sn;
    // The tone: each face's fill and cross ink within 15 % of print's on rock's tone curve
    // (tone_gamma 2), face by face (large faces).
    Options print_options = sample_options("print");
    print_options.params["tone_gamma"] = 2;
    const Drawing print = hatch(sample(), print_options);
    auto ink = [](const FaceHatches& fh) {
        double sum = 0;
        for (const auto& h : fh.hatches)
            if (h.family == Family::Fill || h.family == Family::Cross)
                for (std::size_t i = 1; i < h.points.size(); ++i)
                    sum += tex::distance(h.points[i - 1], h.points[i]) * family_width_mm(h.family);
        return sum;
    };
    ASSERT_EQ(rows.faces.size(), print.faces.size());
    std::size_t compared = 0;
    for (std::size_t k = 0; k < rows.faces.size(); ++k) {
        const double a = ink(rows.faces[k]), b = ink(print.faces[k]);
        if (b < 20 * mm) continue;  // under 20 mm2 of ink on paper (length in ground units x width in mm)
        ++compared;
        EXPECT_NEAR(a / b, 1.0, 0.15) << "face " << rows.faces[k].face_id;
    }
    EXPECT_GT(compared, 5u);
}

namespace {
// The terrain of a synthetic DEM 600 m square with 5 m cells (EPSG:2154), its elevation z(x, y)
// at the cells' centres, and no face yet.
Prepared synthetic_terrain(const std::function<double(const Point&)>& z) {
    constexpr double kSide = 600, kCell = 5;
    Raster dem;
    dem.width = dem.height = int(kSide / kCell);
    dem.gt = {0, kCell, 0, kSide, 0, -kCell};
    dem.crs_wkt = epsg_wkt(2154);
    dem.data.resize(std::size_t(dem.width) * std::size_t(dem.height));
    for (int row = 0; row < dem.height; ++row)
        for (int col = 0; col < dem.width; ++col) dem.at(col, row) = float(z(dem.to_world(col + 0.5, row + 0.5)));
    Prepared prepared;
    prepared.terrain = compute_terrain(dem);
    prepared.relief = local_relief(dem, 1000);
    prepared.partition.crs_wkt = dem.crs_wkt;
    return prepared;
}
}  // namespace

// A cliff band across a slope: 600 m square, 5 m cells, the ground falling to the south at
// 30 %, at 150 % between y = 250 and y = 350. Its top is found at y = 350 and its foot at
// y = 250, each running across the slope with the band on its left; the rock style's fill
// keeps foot_gap off the foot.
TEST(Pipeline, TheRockStyleFindsTheTopAndTheFootOfACliffBand) {
    constexpr double kTop = 350, kFoot = 250, kCell = 5;
    Prepared prepared = synthetic_terrain(
        [&](const Point& q) { return 1000 + 0.3 * q.y + 1.2 * std::clamp(q.y - kFoot, 0.0, kTop - kFoot); });
    RockFace face;
    face.id = 1;
    face.region = tex::Region(std::vector<Point>{{50, 50}, {550, 50}, {550, 550}, {50, 550}});
    for (std::size_t i = 0; i < 4; ++i) face.boundary.push_back({face.region.outer()[i], face.region.outer()[(i + 1) % 4]});
    face.orientation = -M_PI / 2;
    face.density = 0.6;
    prepared.partition.faces.push_back(face);

    Options o;
    o.style = "rock";
    o.threads = 2;
    const Plan plan = make_plan(o, PlanFor::Drawing);
    ParamValues p = plan.rock_params;
    p[kDemCell] = kCell;
    const ControlFields f = control_fields(prepared, plan);
    const blocks::Structure s = blocks::structure_lines(f, p, face_region(prepared.partition, 0));
    // Each line near its level, running across the slope: a top westward (the band, lower,
    // on its left), a foot eastward (the band, higher, on its left).
    auto check = [&](const tex::Curves& lines, const char* label, double level, double direction) {
        double length = 0, along = 0;
        for (const auto& c : lines.curves) {
            EXPECT_TRUE(c.labels.has(label));
            for (std::size_t i = 0; i < c.points.size(); ++i) {
                EXPECT_NEAR(c.points[i].y, level, 10.0) << label;
                if (i == 0) continue;
                const Point d = c.points[i] - c.points[i - 1];
                length += tex::norm(d);
                along += d.x * direction;
            }
        }
        EXPECT_GT(length, 400.0) << label;
        EXPECT_GT(along, 0.95 * length) << label;
    };
    check(s.cliffs, "cliff", kTop, -1);
    check(s.feet, "cliff_foot", kFoot, 1);
    // Below the foot the fill starts foot_gap (0.15 mm, 1.5 m at 1:10000) under it; above it,
    // the band's fill reaches the foot. Without the gap, the fill runs across the seam.
    const double gap = p.at("foot_gap");
    EXPECT_NEAR(gap, 1.5, 1e-9);
    const tex::Curves seams = blocks::seam_below(s.feet, gap);
    ASSERT_EQ(seams.curves.size(), s.feet.curves.size());
    for (const auto& c : seams.curves)
        for (const Point& q : c.points) EXPECT_NEAR(q.y, kFoot - gap / 2, 10.0);
    auto fill_near = [](const Drawing& d, const tex::Curves& lines, double within) {
        auto seg_distance = [](const Point& q, const Point& a, const Point& b) {
            const Point ab = b - a;
            const double t = std::clamp(tex::dot(q - a, ab) / std::max(tex::dot(ab, ab), 1e-300), 0.0, 1.0);
            return tex::distance(q, a + ab * t);
        };
        std::size_t n = 0;
        for (const auto& fh : d.faces)
            for (const auto& h : fh.hatches) {
                if (h.family != Family::Fill) continue;
                for (std::size_t i = 1; i < h.points.size(); ++i) {
                    const Point a = h.points[i - 1], b = h.points[i];
                    bool near = false;
                    for (const auto& c : lines.curves)
                        for (std::size_t k = 1; k < c.points.size() && !near; ++k) {
                            const Point u = c.points[k - 1], v = c.points[k];
                            near = proper_cross(a, b, u, v) || seg_distance(a, u, v) < within ||
                                   seg_distance(b, u, v) < within || seg_distance(u, a, b) < within ||
                                   seg_distance(v, a, b) < within;
                        }
                    n += near;
                }
            }
        return n;
    };
    const Drawing with_gap = hatch(prepared, plan);
    EXPECT_EQ(fill_near(with_gap, seams, 0.45 * gap), 0u);
    // The band's strokes end at the foot: within a fifth of the gap above it.
    tex::Curves above = blocks::seam_below(s.feet, -0.4 * gap);
    EXPECT_GT(fill_near(with_gap, above, 0.2 * gap), 20u);
    Options no_gap = o;
    no_gap.params["foot_gap"] = 0.02;
    EXPECT_GT(fill_near(hatch(prepared, make_plan(no_gap, PlanFor::Drawing)), seams, 0.45 * gap), 20u);
}

// A crest above a wall that steepens eastwards: the shadow edge the rock style adds to the
// crest line lies on the wall's side, its offset grows with the wall, continuously, up to
// 0.1 mm, and from nothing at the line's ends.
TEST(Pipeline, TheRockStyleWidensACrestLineWithTheWallBelowIt) {
    constexpr double kSide = 600, kCrest = 300;
    const Prepared prepared = synthetic_terrain([&](const Point& q) {
        const double wall = 2.0 * q.x / kSide;  // the fall south of the crest, 0 to 200 %
        return q.y >= kCrest ? 1000 - 0.1 * (q.y - kCrest) : 1000 - wall * (kCrest - q.y);
    });
    Options o;
    o.style = "rock";
    const Plan plan = make_plan(o, PlanFor::Drawing);
    const ControlFields f = control_fields(prepared, plan);
    const ParamValues& p = plan.rock_params;
    const double mm = p.at(kGroundPerMm);
    tex::Curve crest;
    for (double x = 50; x <= 550; x += 2) crest.points.push_back({x, kCrest});
    crest.labels.add("ridgeline");
    tex::Curves lines;
    lines.curves.push_back(crest);
    const tex::Curves out = blocks::tapered(f, p, lines);
    ASSERT_GE(out.curves.size(), 2u);
    std::map<double, double> offset;  // x -> offset of the shadow edge (ground units)
    for (std::size_t k = 1; k < out.curves.size(); ++k) {
        EXPECT_TRUE(out.curves[k].labels.has("ridgeline"));
        for (const Point& q : out.curves[k].points) {
            EXPECT_LT(q.y, kCrest) << "on the wall's side";
            offset[std::round(q.x)] = kCrest - q.y;
        }
    }
    double widest = 0;
    std::set<long> widths;
    double last = 0;
    for (const auto& [x, d] : offset) {
        EXPECT_LE(d, 0.1 * mm * (1 + 1e-9));
        widest = std::max(widest, d);
        widths.insert(std::lround(d / (0.01 * mm)));
        // Growing with the wall eastwards (but for the ramp down at the east end).
        if (x < 550 - 1.0 * mm) EXPECT_GE(d, last - 1e-6 * mm) << x;
        last = d;
    }
    EXPECT_NEAR(widest, 0.1 * mm, 0.01 * mm);
    EXPECT_GE(widths.size(), 5u) << "a continuous width, not a few steps";
    // The edge shows from half the width (0.05 mm) on: it starts where the wall reaches about
    // a third of a full one (x = 150 on the DEM's cells, later on the smoothed elevation;
    // none on the gentle west half) and stops where the width falls under that towards the
    // east end (0.5 mm from it).
    EXPECT_GE(offset.begin()->second, 0.05 * mm * (1 - 1e-9));
    EXPECT_GT(offset.begin()->first, 140.0);
    EXPECT_LT(offset.begin()->first, 300.0);
    EXPECT_NEAR(offset.rbegin()->first, 550.0 - 0.5 * mm, 3.0);
}

// The rock style's structure lines: crests on crests and couloirs in couloirs of the DEM, one
// line across the faces it crosses (traced in each face's grown box, the same points where
// two boxes overlap), written as their own layers.
TEST(Pipeline, TheRockStructureLinesFollowTheTerrainAndCrossFaces) {
    const Options o = sample_options("rock");
    const Plan plan = make_plan(o, PlanFor::Drawing);
    const ControlFields f = control_fields(sample(), plan);
    const ParamValues& p = plan.rock_params;
    const Partition& part = sample().partition;
    const double mm = o.scale / 1000;
    std::size_t ridge_points = 0, on_crest = 0, ridge_in_floor = 0, couloir_points = 0, in_floor = 0,
                couloir_on_crest = 0, shared = 0;
    std::vector<blocks::Structure> all;
    for (std::size_t i = 0; i < part.faces.size(); ++i) all.push_back(blocks::structure_lines(f, p, face_region(part, i)));
    auto across = [&](const tex::Curve& c, std::size_t i) {
        const Point t = c.points[std::min(i + 1, c.points.size() - 1)] - c.points[i > 0 ? i - 1 : 0];
        const double l = tex::norm(t);
        return Point{-t.y / l * mm, t.x / l * mm};
    };
    // Each point of the lines: counted, and whether it stands above (below) the ground 1 mm
    // either side across the line.
    auto profile = [&](const tex::Curves& lines, const char* label, std::size_t& points, std::size_t& above,
                       std::size_t& below) {
        for (const auto& c : lines.curves) {
            EXPECT_TRUE(c.labels.has(label));
            for (std::size_t k = 0; k < c.points.size(); ++k) {
                const Point q = c.points[k], n = across(c, k);
                const double z = f.elevation(q), a = f.elevation(q + n), b = f.elevation(q - n);
                if (std::isnan(z) || std::isnan(a) || std::isnan(b)) continue;
                ++points;
                above += z > a && z > b;
                below += z < a && z < b;
            }
        }
    };
    for (const auto& s : all) {
        profile(s.ridges, "ridgeline", ridge_points, on_crest, ridge_in_floor);
        profile(s.couloirs, "couloir", couloir_points, couloir_on_crest, in_floor);
    }
    ASSERT_GT(ridge_points, 200u);
    ASSERT_GT(couloir_points, 200u);
    // Higher than the ground 1 mm on either side across the line (a crest), or lower (a couloir
    // floor), for most points (the rest where the line fades, near its ends); hardly ever the
    // other way round.
    EXPECT_GT(double(on_crest) / double(ridge_points), 0.7) << on_crest << " of " << ridge_points;
    EXPECT_LT(double(ridge_in_floor) / double(ridge_points), 0.03) << ridge_in_floor << " of " << ridge_points;
    EXPECT_GT(double(in_floor) / double(couloir_points), 0.55) << in_floor << " of " << couloir_points;
    EXPECT_LT(double(couloir_on_crest) / double(couloir_points), 0.03) << couloir_on_crest << " of " << couloir_points;
    // Given lines first: the sample's couloirs run along its partition's valleys, and none of
    // them is drawn within crest_smoothing of a valley on the face's border.
    const double snap = p.at("crest_smoothing");
    std::size_t near_before = 0, near_after = 0;
    for (std::size_t i = 0; i < all.size(); ++i) {
        auto near_valley = [&](const Point& q) {
            for (const auto& s : part.faces[i].boundary) {
                if (s.kind != LineKind::Valley) continue;
                const Point ab = s.b - s.a;
                const double t = std::clamp(tex::dot(q - s.a, ab) / std::max(tex::dot(ab, ab), 1e-300), 0.0, 1.0);
                if (tex::distance(q, s.a + ab * t) < snap * (1 - 1e-9)) return true;
            }
            return false;
        };
        const tex::Region r = face_region(part, i);
        for (const auto& c : tex::apply_mask(all[i].couloirs, r, tex::CROP).curves)
            for (const Point& q : c.points) near_before += near_valley(q);
        for (const auto& c : blocks::given_first(p, all[i], r).couloirs.curves)
            for (const Point& q : c.points) near_after += near_valley(q);
    }
    EXPECT_GT(near_before, 20u);
    EXPECT_EQ(near_after, 0u);
    // Where two faces' boxes overlap (away from the grown boxes' edges), their crest lines
    // are the same points.
    const double margin = blocks::structure_margin(p);
    for (std::size_t i = 0; i < all.size(); ++i)
        for (std::size_t j = i + 1; j < all.size(); ++j) {
            const tex::BBox both = part.faces[i].region.bbox().intersection(part.faces[j].region.bbox());
            if (!(both.xmin < both.xmax && both.ymin < both.ymax)) continue;
            std::vector<Point> mine;
            for (const auto& c : all[i].ridges.curves)
                for (const Point& q : c.points)
                    if (both.contains(q)) mine.push_back(q);
            for (const auto& c : all[j].ridges.curves)
                for (const Point& q : c.points) {
                    if (!both.contains(q)) continue;
                    double best = 1e300;
                    for (const Point& m : mine) best = std::min(best, tex::distance(m, q));
                    EXPECT_LT(best, 1e-6 * mm) << "faces " << i << " " << j;
                    ++shared;
                }
        }
    EXPECT_GT(shared, 50u) << "margin " << margin;
    // Written as their own layers by the rock style only.
    const Drawing d = hatch(sample(), o);
    std::map<Family, std::size_t> n;
    for (const auto& fh : d.faces)
        for (const auto& h : fh.hatches) ++n[h.family];
    EXPECT_GT(n[Family::RidgeLine], 10u);
    // The sample is a noisy cone: its slope hovers round cliff_slope without breaking, so it
    // has (almost) no cliff top; without the break of slope, its noise drew dozens.
    EXPECT_GT(n[Family::Cliff], 0u);
    EXPECT_LT(n[Family::Cliff], 6u);
    Options no_break = o;
    no_break.params["cliff_break"] = 0;
    std::size_t wandering = 0;
    for (const auto& fh : hatch(sample(), no_break).faces)
        for (const auto& h : fh.hatches) wandering += h.family == Family::Cliff;
    EXPECT_GT(wandering, 30u);
    for (const auto& fh : hatch(sample(), sample_options("print")).faces)
        for (const auto& h : fh.hatches) EXPECT_LT(int(h.family), kRockFamilies);
}
