// The table of built-in styles (one program per file in styles/), the parameters' units,
// and what the pipeline needs around a program: the labelled region of a face and the
// families of the strokes it returns.
#include "carto/styles.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "carto/error.hpp"
#include "carto/partition.hpp"
#include "libtex/random.hpp"
#include "builtins.hpp"
#include "terrain_tools.hpp"

namespace carto {
namespace {

const std::vector<blocks::Builtin>& builtins() {
    static const std::vector<blocks::Builtin> all = {
        blocks::noisy(),       blocks::ridge_triangles_style(), blocks::density_cells(), blocks::fine_ridges(),
        blocks::balanced(),    blocks::high_ridges(),           blocks::bidirectional(),
        blocks::print(),       blocks::aretes(),                blocks::rock(),
    };
    return all;
}

const std::vector<terrain::Builtin>& terrain_builtins() {
    static const std::vector<terrain::Builtin> all = {terrain::scree(), terrain::slope_hachures()};
    return all;
}

const std::string kDefaultStyle = "rock";

}  // namespace

const char* family_name(Family f) {
    switch (f) {
        case Family::Fill: return "fill";
        case Family::Ridge: return "ridge";
        case Family::Valley: return "valley";
        case Family::Cross: return "cross";
        case Family::Stone: return "stone";
        case Family::Hachure: return "hachure";
        case Family::RidgeLine: return "ridgeline";
        case Family::Couloir: return "couloir";
        case Family::Cliff: return "cliff";
    }
    return "?";
}

double family_width_mm(Family f) {
    switch (f) {
        case Family::Fill: return 0.10;
        case Family::Ridge: return 0.12;
        case Family::Valley: return 0.25;
        case Family::Cross: return 0.08;
        // Filled rings: the outline is not stroked (the width is the PNG preview's minimum).
        case Family::Stone: return 0.0;
        case Family::Hachure: return 0.0;
        case Family::RidgeLine: return 0.12;
        case Family::Couloir: return 0.08;
        case Family::Cliff: return 0.12;
    }
    return 0.1;
}

const std::vector<StyleInfo>& styles() {
    static const std::vector<StyleInfo> all = [] {
        std::vector<StyleInfo> v;
        for (const auto& b : builtins()) v.push_back(b.info);
        for (const auto& b : terrain_builtins()) v.push_back(b.info);
        return v;
    }();
    return all;
}

const std::string& default_style() { return kDefaultStyle; }

const StyleInfo& find_style(const std::string& name) {
    for (const auto& s : styles())
        if (s.name == name || (!s.figure.empty() && (s.figure == name || "5.4" + name == s.figure))) return s;
    std::string names;
    for (const auto& s : styles()) names += (names.empty() ? "" : ", ") + s.name;
    throw Error(Code::UnknownStyle, "--style: unknown style '" + name + "' (known: " + names + ")");
}

Style builtin_style(const std::string& name) {
    const StyleInfo& info = find_style(name);
    for (const auto& b : builtins())
        if (b.info.name == info.name) return {b.info, b.program ? b.program : blocks::per_face(b.body, b.valleys)};
    for (const auto& b : terrain_builtins())
        if (b.info.name == info.name) {
            // The rock faces are hatched with the default style, then the terrain is drawn.
            Style s = builtin_style(default_style());
            s.info = b.info;
            s.terrain = b.program;
            s.terrain_reach = b.reach;
            return s;
        }
    throw Error(Code::UnknownStyle, "--style: unknown style '" + name + "'");
}

ParamValues resolve_params(const StyleInfo& s, const std::map<std::string, double>& overrides, double scale) {
    ParamValues out;
    for (const auto& kv : overrides) {
        const std::string& k = kv.first;  // not a structured binding: clang 14 cannot capture one
        const bool known = std::any_of(s.params.begin(), s.params.end(), [&](const StyleParam& p) { return p.name == k; });
        if (!known) throw Error(Code::UnknownStyle, "--param: style '" + s.name + "' has no parameter '" + k + "'");
    }
    for (const auto& p : s.params) {
        double v = p.value;
        if (auto it = overrides.find(p.name); it != overrides.end()) v = it->second;
        if (!std::isfinite(v) || ((p.unit == "mm" || p.unit == "m") && v <= 0) || ((p.unit == "ratio" || p.unit == "%") && v < 0)) {
            std::ostringstream m;
            m << "--param " << p.name << ": " << v << " is not a valid value (" << p.unit << ") for style '" << s.name
              << "'";
            throw Error(Code::Usage, m.str());
        }
        double ground = v;
        if (p.unit == "mm") ground = v * scale / 1000.0;
        if (p.unit == "deg") ground = v * M_PI / 180.0;
        // A valid value can still overflow (1e308 mm at 1:10000) or vanish (1e-300 mm at
        // 1:1e-30) in ground units: the styles would get an infinite or zero spacing.
        if (!std::isfinite(ground) || (p.unit == "mm" && !(ground > 0))) {
            std::ostringstream m;
            m << "--param " << p.name << ": " << v << " " << p.unit << " at 1:" << scale
              << " is out of range in ground units for style '" << s.name << "'";
            throw Error(Code::Usage, m.str());
        }
        out[p.name] = ground;
    }
    out[kGroundPerMm] = scale / 1000.0;
    return out;
}

tex::Region face_region(const Partition& p, std::size_t face) {
    const RockFace& f = p.faces[face];
    // Runs of border segments with the same kind and owner become one labelled edge. A
    // border shared with another face is owned by the face with the smaller id, so that
    // what lies on it (a valley) is drawn once. A ridge run also ends where the face across
    // changes: both faces along a ridge then see the same edge (in opposite directions), and
    // a style that draws its own part of a line along it (print's crest) draws the same line.
    tex::Curves edges;
    std::size_t k = 0;
    auto labels_of = [&](const BoundarySegment& s) {
        tex::Labels l;
        l.add(kind_name(s.kind));
        if (s.neighbor < 0 || f.id < p.faces[std::size_t(s.neighbor)].id) l.add("owned");
        return l;
    };
    auto add_ring = [&](std::size_t n) {
        // Segments k .. k + n - 1 of f.boundary belong to this ring, in order.
        if (n == 0) return;
        std::vector<tex::Labels> l(n);
        std::vector<std::int64_t> across(n);  // the face across a ridge segment, else -2
        for (std::size_t i = 0; i < n; ++i) {
            const BoundarySegment& b = f.boundary[k + i];
            l[i] = labels_of(b);
            across[i] = b.kind == LineKind::Ridge ? std::int64_t(b.neighbor) : -2;
        }
        auto same = [&](std::size_t i, std::size_t j) { return l[i] == l[j] && across[i] == across[j]; };
        std::size_t start = 0;
        while (start < n && same(start, (start + n - 1) % n)) ++start;
        if (start == n) {  // one kind all round: a closed edge
            tex::Curve c;
            for (std::size_t i = 0; i < n; ++i) c.points.push_back(f.boundary[k + i].a);
            c.closed = true;
            c.labels = l[0];
            edges.curves.push_back(std::move(c));
        } else {
            for (std::size_t s = 0; s < n;) {
                const std::size_t i0 = (start + s) % n;
                tex::Curve c;
                c.labels = l[i0];
                c.points.push_back(f.boundary[k + i0].a);
                std::size_t len = 0;
                while (s + len < n && same((start + s + len) % n, i0)) {
                    c.points.push_back(f.boundary[k + (start + s + len) % n].b);
                    ++len;
                }
                edges.curves.push_back(std::move(c));
                s += len;
            }
        }
        k += n;
    };
    // label_boundaries lists the segments ring by ring, zero-length ones left out.
    auto ring_segments = [](const std::vector<Point>& ring) {
        std::size_t n = 0;
        for (std::size_t i = 0; i < ring.size(); ++i) n += ring[i] != ring[(i + 1) % ring.size()];
        return n;
    };
    add_ring(ring_segments(f.region.outer()));
    for (const auto& h : f.region.holes()) add_ring(ring_segments(h));
    return f.region.with_edges(std::move(edges));
}

std::vector<Hatch> hatches_from_curves(const tex::Curves& c) { return hatches_from_curves(tex::Curves(c)); }

std::vector<Hatch> hatches_from_curves(tex::Curves&& c) {
    std::vector<Hatch> out;
    out.reserve(c.curves.size());
    for (auto& cv : c.curves) {
        if (cv.points.size() < 2) continue;
        out.push_back(Hatch{std::move(cv.points), cv.closed, family_of(cv.labels)});
    }
    return out;
}

Family family_of(const tex::Labels& labels) {
    static const tex::LabelId ridge = tex::intern_label("ridge"), valley = tex::intern_label("valley"),
                              cross = tex::intern_label("cross"), ridgeline = tex::intern_label("ridgeline"),
                              couloir = tex::intern_label("couloir"), cliff = tex::intern_label("cliff");
    if (labels.has(ridgeline)) return Family::RidgeLine;
    if (labels.has(couloir)) return Family::Couloir;
    if (labels.has(cliff)) return Family::Cliff;
    if (labels.has(valley)) return Family::Valley;
    if (labels.has(ridge)) return Family::Ridge;
    if (labels.has(cross)) return Family::Cross;
    return Family::Fill;
}

double ink_area(const tex::Curves& c, double ground_per_mm, const tex::Region* within) {
    double ink = 0;
    for (const auto& cv : c.curves) {
        const std::size_t n = cv.points.size();
        if (n < 2) continue;
        const double width = family_width_mm(family_of(cv.labels)) * ground_per_mm;
        for (std::size_t i = 0; i + 1 < n + (cv.closed ? 1 : 0); ++i) {
            const Point& a = cv.points[i];
            const Point& b = cv.points[(i + 1) % n];
            if (within && !within->contains((a + b) * 0.5)) continue;
            ink += tex::distance(a, b) * width;
        }
    }
    return ink;
}

std::vector<Hatch> hatch_face(const tex::Arrangement& style, const Partition& p, std::size_t face,
                              std::uint64_t seed) {
    tex::SeedScope scoped_seed(seed);
    // Streams of the partitions a program creates are numbered per face, whatever thread
    // draws it, and keyed by the face's extent, not its id: the same face saved in another
    // format (a shapefile numbers features from 0, and may turn rings round) draws the same.
    const tex::BBox box = p.faces[face].region.bbox();
    tex::StreamScope streams(
        tex::hash_point(tex::hash_point(0x46414345ULL, {box.xmin, box.ymin}), {box.xmax, box.ymax}));
    return hatches_from_curves(style(face_region(p, face)));
}

}  // namespace carto
