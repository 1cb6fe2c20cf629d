// Crest ornaments (carto/crest.hpp): checked on the polygons written to the GeoPackage by
// GEOS (validity, one connected piece per ridge), on the distance of every vertex to its
// ridge, for determinism and locality, and for bad input.
#include <gtest/gtest.h>

#include <ogrsf_frmts.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "carto/crest.hpp"
#include "carto/error.hpp"
#include "carto/pipeline.hpp"
#include "libtex/parallel.hpp"

#include "scratch.hpp"

using namespace carto;
namespace fs = std::filesystem;

namespace {

Options sample_options() {
    Options o;
    o.dem = std::string(RH_SAMPLE_DIR) + "/dem.tif";
    o.partition.path = std::string(RH_SAMPLE_DIR) + "/partition.gpkg";
    o.style = "noisy";  // the quickest style: these tests look at the crests
    o.crest_ornament = kDefaultCrest;
    o.threads = 2;
    return o;
}

const Prepared& sample() {
    static const Prepared p = prepare(sample_options());
    return p;
}

std::string temp_path(const std::string& name) {
    return rh_test::scratch(name);
}

std::string read_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

double distance_to_polyline(const Point& p, const std::vector<Point>& line) {
    double best = INFINITY;
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
        const Point a = line[i], d = line[i + 1] - a;
        const double len2 = tex::dot(d, d);
        const double t = len2 > 0 ? std::clamp(tex::dot(p - a, d) / len2, 0.0, 1.0) : 0.0;
        best = std::min(best, tex::distance(p, a + d * t));
    }
    return best;
}

std::string ornament_bytes(const CrestOrnament& c) {
    std::ostringstream os;
    os.precision(17);
    os << c.ridge << ':';
    for (const auto& ring : c.rings) {
        for (const Point& q : ring) os << q.x << ',' << q.y << ' ';
        os << '|';
    }
    return os.str();
}

// A partition holding only the given lines (no faces: draw_crests reads the lines alone).
Partition lines_only(std::vector<LabelledLine> lines) {
    Partition p;
    p.lines = std::move(lines);
    return p;
}

std::size_t ridges_of(const Partition& p) {
    return std::size_t(std::count_if(p.lines.begin(), p.lines.end(), [](const LabelledLine& l) {
        return l.kind == LineKind::Ridge;
    }));
}

Code error_code(const std::function<void()>& f, std::string* message = nullptr) {
    try {
        f();
    } catch (const Error& e) {
        if (message) *message = e.what();
        return e.code();
    }
    return Code(0);
}

}  // namespace

// Every ridge of the sample becomes exactly one polygon in the GeoPackage's crest layer, as
// GEOS sees it: one valid polygon (no ring crosses itself or another) per ridge_id, and the
// union of a ridge's polygons is a single piece.
TEST(Crest, OneValidPolygonPerRidgeInTheGeoPackage) {
    Options o = sample_options();
    const std::string out = temp_path("one.gpkg");
    o.outputs = {out};
    o.overwrite = true;
    const Stats s = run(o);
    EXPECT_EQ(s.crests, ridges_of(sample().partition));
    ASSERT_GE(s.crests, 5u);

    std::unique_ptr<GDALDataset> ds(GDALDataset::Open(out.c_str(), GDAL_OF_VECTOR));
    ASSERT_TRUE(ds);
    OGRLayer* layer = ds->GetLayerByName("crest");
    ASSERT_TRUE(layer);
    EXPECT_EQ(wkbFlatten(layer->GetGeomType()), wkbPolygon);
    std::map<std::int64_t, int> per_ridge;
    for (auto& f : *layer) {
        const OGRGeometry* g = f->GetGeometryRef();
        ASSERT_TRUE(g);
        EXPECT_TRUE(g->IsValid()) << "ridge " << f->GetFieldAsInteger64("ridge_id");
        EXPECT_GT(g->toPolygon()->get_Area(), 0);
        ++per_ridge[f->GetFieldAsInteger64("ridge_id")];
    }
    EXPECT_EQ(per_ridge.size(), s.crests);
    // ridge_id is the ridge's key (from its points): the key of a ridge line of the partition.
    std::set<std::int64_t> ridge_keys;
    for (const auto& l : sample().partition.lines)
        if (l.kind == LineKind::Ridge) ridge_keys.insert(ridge_key(l.points));
    for (const auto& [ridge, n] : per_ridge) {
        EXPECT_EQ(n, 1) << "ridge " << ridge;
        EXPECT_EQ(ridge_keys.count(ridge), 1u) << "ridge " << ridge;
    }
}

// The style table's form of the option: --style aretes draws the crest ornaments without
// --crest-ornament, its band from its parameter crest_band (mm on paper); the same fill as
// noisy; noisy itself draws none.
TEST(Crest, TheAretesStyleDrawsThemWithItsBand) {
    Options o = sample_options();
    o.crest_ornament.reset();
    o.style = "noisy";
    const Drawing plain = hatch(sample(), o);
    EXPECT_FALSE(plain.crests.has_value());
    o.style = "aretes";
    o.params["crest_band"] = 3;  // 30 m at 1:10000
    const Drawing d = hatch(sample(), o);
    ASSERT_TRUE(d.crests.has_value());
    EXPECT_EQ(d.crests->size(), ridges_of(sample().partition));
    double farthest = 0;
    for (const auto& c : *d.crests)
        for (const auto& ring : c.rings)
            for (const Point& q : ring)
                farthest = std::max(farthest, distance_to_polyline(q, sample().partition.lines[c.ridge].points));
    EXPECT_LE(farthest, 0.75 * 30);
    EXPECT_GT(farthest, 0.4 * 30);  // the 3 mm band: a 2 mm one reaches 10 m at most
    // The same fill as noisy: face for face, hatch for hatch, the same points (bit for bit),
    // closure and family.
    ASSERT_EQ(d.faces.size(), plain.faces.size());
    for (std::size_t k = 0; k < d.faces.size(); ++k) {
        EXPECT_EQ(d.faces[k].face_id, plain.faces[k].face_id);
        ASSERT_EQ(d.faces[k].hatches.size(), plain.faces[k].hatches.size()) << "face " << k;
        for (std::size_t h = 0; h < d.faces[k].hatches.size(); ++h) {
            const Hatch &a = d.faces[k].hatches[h], &b = plain.faces[k].hatches[h];
            EXPECT_TRUE(a.points == b.points) << "face " << k << ", hatch " << h;
            EXPECT_EQ(a.closed, b.closed) << "face " << k << ", hatch " << h;
            EXPECT_EQ(int(a.family), int(b.family)) << "face " << k << ", hatch " << h;
        }
    }
}

// The independent count on the rings themselves: each ornament has exactly one ring that
// no other ring encloses (its outer boundary) and it winds counter-clockwise; every other
// ring lies inside it and winds clockwise (a hole), with no island inside a hole.
TEST(Crest, EachOrnamentIsOneComponentCountedOnItsRings) {
    const Prepared& p = sample();
    const CrestResult r = draw_crests(p.partition, load_crest_exemplar(kDefaultCrest), 20, 0);
    ASSERT_EQ(r.ornaments.size(), ridges_of(p.partition));
    for (const CrestOrnament& c : r.ornaments) {
        int outer = 0;
        for (std::size_t i = 0; i < c.rings.size(); ++i) {
            int depth = 0;
            for (std::size_t j = 0; j < c.rings.size(); ++j)
                if (j != i && tex::point_in_ring(c.rings[i][0], c.rings[j])) ++depth;
            ASSERT_LE(depth, 1) << "ridge " << c.ridge << ": an island inside a hole";
            if (depth == 0) {
                ++outer;
                EXPECT_GT(tex::signed_area(c.rings[i]), 0) << "ridge " << c.ridge;
            } else {
                EXPECT_LT(tex::signed_area(c.rings[i]), 0) << "ridge " << c.ridge;
            }
        }
        EXPECT_EQ(outer, 1) << "ridge " << c.ridge;
    }
}

// The band is centred on the ridge: no vertex is farther from its ridge than half the band
// height plus what smoothing a sharp corner moved the ridge (bounded here by a quarter of
// the band), and the ornament reaches out at least a third of the band (it is not a line).
TEST(Crest, TheBandStaysWithinItsHeightOfTheRidge) {
    const Prepared& p = sample();
    for (double height : {12.0, 20.0, 35.0}) {
        const CrestResult r = draw_crests(p.partition, load_crest_exemplar(kDefaultCrest), height, 3);
        ASSERT_FALSE(r.ornaments.empty());
        for (const CrestOrnament& c : r.ornaments) {
            double farthest = 0;
            for (const auto& ring : c.rings)
                for (const Point& q : ring)
                    farthest = std::max(farthest, distance_to_polyline(q, p.partition.lines[c.ridge].points));
            EXPECT_LE(farthest, 0.75 * height) << "ridge " << c.ridge << " height " << height;
            EXPECT_GE(farthest, height / 3) << "ridge " << c.ridge << " height " << height;
        }
    }
}

// Same seed, same bytes at one and two threads; another seed, another ornament.
TEST(Crest, SameBytesAtOneAndTwoThreads) {
    Options o = sample_options();
    const std::string a = temp_path("t1.svg"), b = temp_path("t2.svg"), c = temp_path("s9.svg");
    o.overwrite = true;
    o.threads = 1;
    o.outputs = {a};
    run(o);
    o.threads = 2;
    o.outputs = {b};
    run(o);
    o.seed = 9;
    o.outputs = {c};
    run(o);
    const std::string ba = read_bytes(a);
    EXPECT_NE(ba.find("<g id=\"crest\""), std::string::npos);
    EXPECT_EQ(ba, read_bytes(b));
    EXPECT_NE(ba, read_bytes(c));
}

// Local per ridge: a ridge's ornament is keyed by the ridge, not by its place in the
// partition, so reversing the order of the lines or dropping the other ridges leaves it
// byte for byte as it was.
TEST(Crest, EachRidgeIsKeyedByItselfNotByItsOrder) {
    const Partition& part = sample().partition;
    const CrestExemplar ex = load_crest_exemplar(kDefaultCrest);
    const CrestResult all = draw_crests(part, ex, 20, 4);
    std::map<std::string, std::string> by_ridge;  // first point -> ornament (without the index)
    auto key = [&](const Partition& p, const CrestOrnament& c) {
        std::ostringstream os;
        os.precision(17);
        os << p.lines[c.ridge].points.front().x << ',' << p.lines[c.ridge].points.front().y;
        return os.str();
    };
    auto body = [](CrestOrnament c) {
        c.ridge = 0;
        return ornament_bytes(c);
    };
    for (const auto& c : all.ornaments) by_ridge[key(part, c)] = body(c);

    Partition reversed = part;
    std::reverse(reversed.lines.begin(), reversed.lines.end());
    const CrestResult back = draw_crests(reversed, ex, 20, 4);
    // As many ornaments either way, so the loop below meets every ridge.
    ASSERT_EQ(back.ornaments.size(), all.ornaments.size());
    for (const auto& c : back.ornaments) EXPECT_EQ(body(c), by_ridge.at(key(reversed, c)));

    std::vector<LabelledLine> one;
    for (const auto& l : part.lines)
        if (l.kind == LineKind::Ridge && one.empty()) one.push_back(l);
    const Partition alone = lines_only(one);
    const CrestResult r = draw_crests(alone, ex, 20, 4);
    ASSERT_EQ(r.ornaments.size(), 1u);
    EXPECT_EQ(body(r.ornaments[0]), by_ridge.at(key(alone, r.ornaments[0])));
}

// Where ridges meet, ornaments do not overlap: at a junction where two ridges continue each
// other and a third leaves at 60 degrees, the straight pair runs on to the node and the
// branch stops short of it; at a Y of three ridges 70, 145 and 145 degrees apart, all three
// stop short. Checked on the rings: no edge of one ornament meets
// an edge of another, and no ornament holds a vertex of another.
TEST(Crest, RidgesMeetingAtANodeDoNotOverlap) {
    auto ridge = [](Point a, Point b) {
        LabelledLine l;
        l.kind = LineKind::Ridge;
        for (int i = 0; i <= 40; ++i) l.points.push_back(a + (b - a) * (i / 40.0));
        return l;
    };
    const Point t{0, 0}, y{3000, 0};
    auto at = [](Point c, double deg, double r) {
        return c + Point{r * std::cos(deg * tex::pi / 180), r * std::sin(deg * tex::pi / 180)};
    };
    const Partition part = lines_only({ridge(t, at(t, 180, 600)), ridge(t, at(t, 0, 600)), ridge(t, at(t, 60, 600)),
                                       ridge(y, at(y, 90, 600)), ridge(y, at(y, 160, 600)), ridge(y, at(y, 305, 600))});
    const double band = 20;
    const CrestResult r = draw_crests(part, load_crest_exemplar(kDefaultCrest), band, 5);
    ASSERT_EQ(r.ornaments.size(), 6u);
    auto segments_meet = [](Point a, Point b, Point c, Point d) {
        const double d1 = tex::cross(b - a, c - a), d2 = tex::cross(b - a, d - a), d3 = tex::cross(d - c, a - c),
                     d4 = tex::cross(d - c, b - c);
        return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0));
    };
    auto inside = [](const std::vector<Point>& ring, Point q) {
        bool in = false;
        for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++)
            if ((ring[i].y > q.y) != (ring[j].y > q.y) &&
                q.x < ring[i].x + (q.y - ring[i].y) * (ring[j].x - ring[i].x) / (ring[j].y - ring[i].y))
                in = !in;
        return in;
    };
    // Every segment of one ring against every segment of the other that reaches its box (two
    // segments can only cross inside both rings' boxes): the same count as all pairs, without
    // the millions of pairs apart (17 s under ASan at -O0; on this drawing the ends cut back
    // at the nodes keep every two rings' boxes apart).
    auto box_of = [](const std::vector<Point>& ring) {
        tex::BBox b;
        for (const Point& p : ring) b.add(p);
        return b;
    };
    auto segments_in = [&](const std::vector<Point>& ring, const tex::BBox& box) {
        std::vector<std::size_t> kept;
        for (std::size_t a = 0; a < ring.size(); ++a) {
            tex::BBox s;
            s.add(ring[a]);
            s.add(ring[(a + 1) % ring.size()]);
            if (s.intersects(box)) kept.push_back(a);
        }
        return kept;
    };
    for (std::size_t i = 0; i < r.ornaments.size(); ++i)
        for (std::size_t j = i + 1; j < r.ornaments.size(); ++j) {
            int meets = 0;
            for (const auto& ra : r.ornaments[i].rings)
                for (const auto& rb : r.ornaments[j].rings) {
                    const tex::BBox ba = box_of(ra), bb = box_of(rb);
                    if (ba.intersects(bb)) {
                        const auto sa = segments_in(ra, bb), sb = segments_in(rb, ba);
                        for (std::size_t a : sa)
                            for (std::size_t b : sb)
                                meets += segments_meet(ra[a], ra[(a + 1) % ra.size()], rb[b], rb[(b + 1) % rb.size()]);
                    }
                    meets += inside(ra, rb[0]) + inside(rb, ra[0]);
                }
            EXPECT_EQ(meets, 0) << "ridges " << r.ornaments[i].ridge << " and " << r.ornaments[j].ridge;
        }
    auto nearest = [&](std::size_t ridge_index, Point node) {
        double best = INFINITY;
        for (const auto& c : r.ornaments)
            if (c.ridge == ridge_index)
                for (const auto& ring : c.rings)
                    for (const Point& q : ring) best = std::min(best, tex::distance(q, node));
        return best;
    };
    EXPECT_LT(nearest(0, t), 0.5 * band);  // the straight pair runs on to the node
    EXPECT_LT(nearest(1, t), 0.5 * band);
    EXPECT_GT(nearest(2, t), 0.45 * band);  // the branch starts a band away (its barbs reach half a band)
    for (std::size_t k = 3; k < 6; ++k) EXPECT_GT(nearest(k, y), 0.45 * band);
}

// A ridge shorter than the band is skipped and counted in a note; a ridge long enough for
// the band but with a hairpin it cannot follow is skipped too; neither stops the others.
TEST(Crest, ShortAndHairpinRidgesAreSkippedWithANote) {
    const CrestExemplar ex = load_crest_exemplar(kDefaultCrest);
    std::vector<LabelledLine> lines = {
        {{{0, 0}, {300, 10}, {600, 0}}, LineKind::Ridge},       // drawn
        {{{0, 100}, {8, 100}}, LineKind::Ridge},                 // shorter than the band
        {{{0, 200}, {40, 200}, {0, 200.5}}, LineKind::Ridge},    // a hairpin: folds at any smoothing
        {{{0, 300}, {500, 300}}, LineKind::Valley},              // not a ridge
    };
    const CrestResult r = draw_crests(lines_only(lines), ex, 20, 0);
    ASSERT_EQ(r.ornaments.size(), 1u);
    EXPECT_EQ(r.ornaments[0].ridge, 0u);
    ASSERT_EQ(r.notes.size(), 1u);
    EXPECT_NE(r.notes[0].find("1 of 3 ridge line(s)"), std::string::npos) << r.notes[0];
    EXPECT_NE(r.notes[0].find("1 shorter than the band height"), std::string::npos) << r.notes[0];
    EXPECT_NE(r.notes[0].find("1 skipped: no pattern fits"), std::string::npos) << r.notes[0];
}

// Only the ridges whose anchor (the smaller end point) lies in the window are drawn (one
// owner per ridge when a large area is drawn tile by tile), and they are drawn as in the
// whole run.
TEST(Crest, AWindowDrawsTheRidgesAnchoredInIt) {
    const Partition& part = sample().partition;
    const CrestExemplar ex = load_crest_exemplar(kDefaultCrest);
    const tex::BBox b = part.bounds();
    const double xm = 0.5 * (b.xmin + b.xmax);
    const CrestResult whole = draw_crests(part, ex, 20, 0);
    const CrestResult west = draw_crests(part, ex, 20, 0, tex::BBox{b.xmin - 1, b.ymin - 1, xm, b.ymax + 1});
    const CrestResult east = draw_crests(part, ex, 20, 0, tex::BBox{xm, b.ymin - 1, b.xmax + 1, b.ymax + 1});
    EXPECT_GT(west.ornaments.size(), 0u);
    EXPECT_GT(east.ornaments.size(), 0u);
    ASSERT_EQ(west.ornaments.size() + east.ornaments.size(), whole.ornaments.size());
    std::vector<std::string> halves, all;
    for (const auto* r : {&west, &east})
        for (const auto& c : r->ornaments) halves.push_back(ornament_bytes(c));
    for (const auto& c : whole.ornaments) all.push_back(ornament_bytes(c));
    std::sort(halves.begin(), halves.end());
    std::sort(all.begin(), all.end());
    EXPECT_EQ(halves, all);
    // The anchor is a point of the line, whichever way the line runs.
    for (const auto& c : west.ornaments) {
        const auto& pts = part.lines[c.ridge].points;
        const Point a = ridge_anchor(pts);
        EXPECT_TRUE(a == pts.front() || a == pts.back());
        EXPECT_LT(a.x, xm);
        EXPECT_EQ(ridge_anchor({pts.rbegin(), pts.rend()}), a);
    }
}

// Bad exemplars and options: one clear error naming the option, with the exit code of the
// other input errors; nothing is written.
TEST(Crest, BadExemplarsAndOptionsAreRefusedClearly) {
    std::string m;
    EXPECT_EQ(error_code([] { load_crest_exemplar("/nonexistent/crest.svg"); }, &m), Code::InputMissing);
    EXPECT_NE(m.find("--crest-ornament '/nonexistent/crest.svg': no such file"), std::string::npos) << m;

    const std::string junk = temp_path("junk.svg");
    std::ofstream(junk) << "this is not SVG <<<";
    EXPECT_EQ(error_code([&] { load_crest_exemplar(junk); }, &m), Code::InputMissing);
    EXPECT_NE(m.find("--crest-ornament"), std::string::npos) << m;

    const std::string lines = temp_path("lines.svg");
    std::ofstream(lines) << "<svg xmlns=\"http://www.w3.org/2000/svg\"><polyline points=\"0,0 10,5 20,0\"/></svg>";
    EXPECT_EQ(error_code([&] { load_crest_exemplar(lines); }, &m), Code::BadLayer);
    EXPECT_NE(m.find("cannot make one connected crest band"), std::string::npos) << m;

    // Two separate squares: every sequence of pieces has two components or more.
    const std::string apart = temp_path("apart.svg");
    std::ofstream(apart) << "<svg xmlns=\"http://www.w3.org/2000/svg\"><path d=\"M 0 0 L 10 0 L 10 10 L 0 10 Z "
                            "M 0 20 L 10 20 L 10 30 L 0 30 Z\"/></svg>";
    EXPECT_EQ(error_code([&] { load_crest_exemplar(apart); }, &m), Code::BadLayer);

    Options o = sample_options();
    o.outputs = {temp_path("bad.svg")};
    o.overwrite = true;
    o.crest_ornament = "/nonexistent/crest.svg";
    EXPECT_EQ(error_code([&] { run(o); }), Code::InputMissing);
    EXPECT_FALSE(fs::exists(o.outputs[0]));
    o.crest_ornament = kDefaultCrest;
    for (double h : {0.0, -1.0, 1e9, double(NAN)}) {
        o.crest_height_mm = h;
        EXPECT_EQ(error_code([&] { run(o); }, &m), Code::Usage) << h;
        EXPECT_NE(m.find("--crest-height"), std::string::npos) << m;
    }
    o.crest_ornament.reset();
    o.crest_height_mm = 2;
    EXPECT_EQ(error_code([&] { run(o); }, &m), Code::Usage);
    EXPECT_NE(m.find("--crest-height needs --crest-ornament"), std::string::npos) << m;
    // The exemplar is an input: no output may be written onto it.
    std::ofstream(temp_path("mine.svg")) << default_crest_svg();
    o.crest_height_mm.reset();
    o.crest_ornament = temp_path("mine.svg");
    o.outputs = {temp_path("mine.svg")};
    EXPECT_EQ(error_code([&] { run(o); }), Code::OutputExists);
    EXPECT_EQ(read_bytes(temp_path("mine.svg")), default_crest_svg());
}

// A user's exemplar (an SVG file) is used as given, and the run without --crest-ornament
// writes no crest layer or group (its outputs are those of before).
TEST(Crest, AUserExemplarAndNoCrestWhenNotAsked) {
    const std::string mine = temp_path("blob.svg");
    // A spine with a bump holding a hole, a bump on the other side and a last bump: cut at its
    // topological events, the pieces between the spine-only cuts repeat, so a long ridge is
    // one component with any number of holes.
    std::ofstream(mine) << "<svg xmlns=\"http://www.w3.org/2000/svg\"><path fill-rule=\"evenodd\" d=\""
                           "M 0 -4 L 60 -4 L 60 -10 L 80 -10 L 80 -4 L 120 -4 L 120 4 L 105 4 L 105 10 L 95 10 "
                           "L 95 4 L 40 4 L 40 10 L 20 10 L 20 4 L 0 4 Z M 25 5 L 35 5 L 35 8 L 25 8 Z\"/></svg>";
    Options o = sample_options();
    o.crest_ornament = mine;
    o.crest_height_mm = 1.5;
    o.outputs = {temp_path("user.svg")};
    o.overwrite = true;
    const Stats s = run(o);
    EXPECT_EQ(s.crests, ridges_of(sample().partition));
    // The crest group drawn from the user's exemplar is not the default exemplar's: a run
    // that read the file but drew the default would pass the lines above.
    auto crest_group = [](const std::string& svg) {
        const std::size_t from = svg.find("<g id=\"crest\"");
        return from == std::string::npos ? std::string() : svg.substr(from, svg.find("</g>", from) - from);
    };
    const std::string user = crest_group(read_bytes(o.outputs[0]));
    EXPECT_GT(user.size(), 1000u);
    o.crest_ornament = kDefaultCrest;
    o.outputs = {temp_path("default.svg")};
    const Stats d = run(o);
    EXPECT_EQ(d.crests, s.crests);
    const std::string standard = crest_group(read_bytes(o.outputs[0]));
    EXPECT_GT(standard.size(), 1000u);
    EXPECT_NE(user, standard);

    o.crest_ornament.reset();
    o.crest_height_mm.reset();
    o.outputs = {temp_path("none.svg"), temp_path("none.gpkg")};
    const Stats n = run(o);
    EXPECT_EQ(n.crests, 0u);
    EXPECT_EQ(read_bytes(o.outputs[0]).find("crest"), std::string::npos);
    std::unique_ptr<GDALDataset> ds(GDALDataset::Open(o.outputs[1].c_str(), GDAL_OF_VECTOR));
    ASSERT_TRUE(ds);
    EXPECT_EQ(ds->GetLayerByName("crest"), nullptr);
}
