#include "carto/update.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <future>
#include <iterator>
#include <map>
#include <memory>
#include <set>
#include <vector>

#include <ogr_spatialref.h>

#include "carto/error.hpp"
#include "carto/publish.hpp"
#include "carto/tiles.hpp"
#include "libtex/parallel.hpp"
#include "source_digest.hpp"

namespace carto {
// Named, not anonymous: a unity build compiles this file with others.
namespace fingerprint_impl {

// DEM cells are digested in square blocks of this side: a face's window is rounded out to
// whole blocks (a generous bound), and a block is digested once for every face.
constexpr int kBlock = 8;

std::uint64_t mix(std::uint64_t x) {
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ULL;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebULL;
    x ^= x >> 31;
    return x;
}

// A 128-bit digest in two lanes (splitmix64's finaliser): fast, deterministic, not
// cryptographic (a fingerprint detects edits, it does not defend against forgery).
struct Digest {
    std::uint64_t a = 0x243f6a8885a308d3ULL, b = 0x13198a2e03707344ULL;
    void add(std::uint64_t v) {
        a = mix(a + v);
        b = mix(b ^ (v * 0x9e3779b97f4a7c15ULL + 0x632be59bd9b4e019ULL)) + a;
    }
    void add(double v) {
        std::uint64_t u;
        std::memcpy(&u, &v, sizeof u);
        add(u);
    }
    void add(std::int64_t v) { add(std::uint64_t(v)); }
    void add(int v) { add(std::uint64_t(std::int64_t(v))); }
    void add(const Point& p) {
        add(p.x);
        add(p.y);
    }
    void add(const std::string& s) {
        add(std::uint64_t(s.size()));
        for (std::size_t i = 0; i < s.size(); i += 8) {
            std::uint64_t w = 0;
            std::memcpy(&w, s.data() + i, std::min<std::size_t>(8, s.size() - i));
            add(w);
        }
    }
    void add(const Digest& d) {
        add(d.a);
        add(d.b);
    }
    std::string hex() const {
        char buf[33];
        std::snprintf(buf, sizeof buf, "%016llx%016llx", (unsigned long long)a, (unsigned long long)b);
        return buf;
    }
};

// A face as digitised: id, rings, controls, anchor.
Digest face_digest(const RockFace& f) {
    Digest d;
    d.add(f.id);
    d.add(std::uint64_t(f.region.outer().size()));
    for (const Point& q : f.region.outer()) d.add(q);
    d.add(std::uint64_t(f.region.holes().size()));
    for (const auto& h : f.region.holes()) {
        d.add(std::uint64_t(h.size()));
        for (const Point& q : h) d.add(q);
    }
    d.add(int(f.orientation.has_value()));
    d.add(f.orientation.value_or(0.0));
    d.add(int(f.density.has_value()));
    d.add(f.density.value_or(0.0));
    d.add(int(f.anchor.has_value()));
    d.add(f.anchor.value_or(Point{}));
    return d;
}

// Whether a segment's box meets a box.
bool meets(const Point& a, const Point& b, const tex::BBox& box) {
    return std::max(a.x, b.x) >= box.xmin && std::min(a.x, b.x) <= box.xmax && std::max(a.y, b.y) >= box.ymin &&
           std::min(a.y, b.y) <= box.ymax;
}

// What a face's drawing can read of another face within its box: the other face's id and
// controls, the segments of its rings (as digitised) that come into the box, and whether
// each corner of the box lies in it. Inside the box, the other face is fixed by these (a
// point of the box is in it by the parity of the segments between the point and a corner),
// so an edit of its far parts does not redraw this face. Its snapped and labelled borders
// there follow from these, the lines' segments and the snap (all local).
// A face that does not come into the box (no segment, no corner in it) adds nothing.
void add_face_within(Digest& digest, const RockFace& f, const tex::BBox& box) {
    Digest d;
    bool inside = false;
    auto ring = [&](const std::vector<Point>& r, std::uint64_t which) {
        for (std::size_t i = 0; i < r.size(); ++i) {
            const Point& a = r[i];
            const Point& b = r[(i + 1) % r.size()];
            if (!meets(a, b, box)) continue;
            inside = true;
            d.add(which);
            d.add(std::uint64_t(i));
            d.add(a);
            d.add(b);
        }
    };
    ring(f.region.outer(), 0);
    for (std::size_t h = 0; h < f.region.holes().size(); ++h) ring(f.region.holes()[h], h + 1);
    for (const Point& corner : {Point{box.xmin, box.ymin}, Point{box.xmax, box.ymin}, Point{box.xmax, box.ymax},
                                Point{box.xmin, box.ymax}}) {
        const bool in = f.region.contains(corner);
        inside = inside || in;
        d.add(int(in));
    }
    if (!inside) return;
    digest.add(f.id);
    digest.add(int(f.orientation.has_value()));
    digest.add(f.orientation.value_or(0.0));
    digest.add(int(f.density.has_value()));
    digest.add(f.density.value_or(0.0));
    digest.add(d);
}

// A labelled line's segments that come into the box (lines label the faces' borders, within
// the snap of them).
void add_line_within(Digest& d, const LabelledLine& l, const tex::BBox& box) {
    d.add(int(l.kind));
    for (std::size_t i = 0; i + 1 < l.points.size(); ++i)
        if (meets(l.points[i], l.points[i + 1], box)) {
            d.add(std::uint64_t(i));
            d.add(l.points[i]);
            d.add(l.points[i + 1]);
        }
}

// The digests of a raster's blocks of kBlock x kBlock cells (NoData as one value).
struct BlockDigests {
    int nx = 0, ny = 0;
    std::vector<Digest> blocks;
    explicit BlockDigests(const Raster& r) {
        nx = (r.width + kBlock - 1) / kBlock;
        ny = (r.height + kBlock - 1) / kBlock;
        blocks.resize(std::size_t(nx) * std::size_t(ny));
        tex::parallel_for(std::size_t(ny), [&](std::size_t by) {
            for (int bx = 0; bx < nx; ++bx) {
                Digest d;
                for (int row = int(by) * kBlock; row < std::min(r.height, int(by + 1) * kBlock); ++row)
                    for (int col = bx * kBlock; col < std::min(r.width, (bx + 1) * kBlock); ++col) {
                        const float v = r.at(col, row);
                        std::uint32_t u = 0x7fc00000u;  // every NoData alike
                        if (!std::isnan(v)) std::memcpy(&u, &v, sizeof u);
                        d.add(std::uint64_t(u));
                    }
                blocks[by * std::size_t(nx) + std::size_t(bx)] = d;
            }
        });
    }
};

// The blocks of the raster under a box of its CRS grown by `halo` cells, in order; a raster
// that is not north-up: every block.
void add_blocks(Digest& d, const Raster& r, const BlockDigests& b, const tex::BBox& box, int halo) {
    int c0 = 0, c1 = r.width - 1, r0 = 0, r1 = r.height - 1;
    if (r.north_up()) {
        const auto col = [&](double x) { return (x - r.gt[0]) / r.gt[1]; };
        const auto row = [&](double y) { return (y - r.gt[3]) / r.gt[5]; };
        const double ca = col(box.xmin), cb = col(box.xmax), ra = row(box.ymin), rb = row(box.ymax);
        c0 = std::max(c0, int(std::floor(std::min(ca, cb))) - halo);
        c1 = std::min(c1, int(std::floor(std::max(ca, cb))) + halo);
        r0 = std::max(r0, int(std::floor(std::min(ra, rb))) - halo);
        r1 = std::min(r1, int(std::floor(std::max(ra, rb))) + halo);
    }
    if (c0 > c1 || r0 > r1) {
        d.add(std::uint64_t(0));  // the box misses the raster
        return;
    }
    for (int by = r0 / kBlock; by <= r1 / kBlock; ++by)
        for (int bx = c0 / kBlock; bx <= c1 / kBlock; ++bx) {
            d.add(int(bx));
            d.add(int(by));
            d.add(b.blocks[std::size_t(by) * std::size_t(b.nx) + std::size_t(bx)]);
        }
}

std::string number(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

// Every value of the plan a face's drawing depends on, as text (its digest is the plan's).
std::string plan_text(const Plan& plan, const RasterInfo& dem, bool slope, bool roughness) {
    const Options& o = plan.options;
    std::string t = "version=" RH_VERSION_STRING "+" RH_SOURCE_DIGEST "\nstyle=" + plan.style.info.name + "\nrock=" + plan.rock.name + "\n";
    if (!o.style_file.empty()) {
        std::ifstream in(o.style_file, std::ios::binary);
        Digest script;
        script.add(std::string(std::istreambuf_iterator<char>(in), {}));
        t += "script=" + script.hex() + "\n";
    }
    if (!plan.style.source_digest.empty()) t += "style_source=" + plan.style.source_digest + "\n";
    for (const auto& [k, v] : plan.rock_params) t += "param." + k + "=" + number(v) + "\n";
    for (const auto& [k, v] : plan.terrain_params) t += "terrain." + k + "=" + number(v) + "\n";
    t += "scale=" + number(o.scale) + "\nseed=" + std::to_string(o.seed) + "\nrelief_radius=" + number(o.relief_radius) +
         "\nfield_smoothing=" + number(plan.field_smoothing) + "\n";
    const PartitionOptions& po = o.partition;
    t += "partition=" + std::string(po.path == "auto" ? "auto" : "file") + "\nfaces_layer=" + po.faces_layer +
         "\nlines_layer=" + po.lines_layer + "\nlabel_field=" + po.label_field + "\nid_field=" + po.id_field +
         "\norientation_field=" + po.orientation_field + "\norientation_layer=" + po.orientation_layer +
         "\ndensity_field=" + po.density_field + "\ndensity_layer=" + po.density_layer +
         "\nrepair=" + std::to_string(int(po.repair)) + "\nsnap=" + number(po.snap) + "\n";
    if (po.path == "auto") t += "mask=" + o.mask + "\n";
    t += "crs=" + dem.crs_wkt + "\ndem=" + std::to_string(dem.width) + "x" + std::to_string(dem.height);
    for (double g : dem.gt) t += " " + number(g);
    t += "\nslope=" + std::to_string(int(slope)) + "\nroughness=" + std::to_string(int(roughness)) + "\n";
    return t;
}

// The options of the run as command-line arguments, one a line, files by absolute path:
// what the QGIS plugin passes to update (outputs aside: the file is the output).
std::string command_text(const Options& o) {
    std::vector<std::string> a;
    const auto file = [&](const char* opt, const std::string& path) {
        if (path.empty()) return;
        a.push_back(opt);
        std::error_code ec;
        const bool plain = path.rfind("/vsi", 0) != 0 && path != "auto" && path != "none";
        const std::filesystem::path abs = plain ? std::filesystem::absolute(path, ec) : std::filesystem::path(path);
        a.push_back(ec ? path : abs.string());
    };
    const auto text = [&](const char* opt, const std::string& v) {
        if (v.empty()) return;
        a.push_back(opt);
        a.push_back(v);
    };
    file("--dem", o.dem);
    file("--partition", o.partition.path);
    const PartitionOptions& po = o.partition;
    text("--faces-layer", po.faces_layer);
    text("--lines-layer", po.lines_layer);
    if (po.label_field != "kind") text("--label-field", po.label_field);
    text("--id-field", po.id_field);
    text("--orientation-field", po.orientation_field);
    text("--orientation-layer", po.orientation_layer);
    text("--density-field", po.density_field);
    text("--density-layer", po.density_layer);
    text("--scree-layer", po.scree_layer);
    text("--snap", number(po.snap));
    if (!po.repair) a.push_back("--no-repair");
    file("--mask", o.mask);
    file("--slope", o.slope);
    file("--roughness", o.roughness);
    text("--style", o.style);
    file("--script", o.style_file);
    for (const auto& [k, v] : o.params) text("--param", k + "=" + number(v));
    if (o.crest_ornament) text("--crest-ornament", *o.crest_ornament);
    if (o.crest_height_mm) text("--crest-height", number(*o.crest_height_mm));
    text("--scale", number(o.scale));
    text("--relief-radius", number(o.relief_radius));
    text("--seed", std::to_string(o.seed));
    if (o.window)
        text("--window", number(o.window->xmin) + "," + number(o.window->ymin) + "," + number(o.window->xmax) + "," +
                             number(o.window->ymax));
    std::string t;
    for (const auto& s : a) t += (t.empty() ? "" : "\n") + s;
    return t;
}

// The faces a plan draws: those whose anchor lies in its window, or all (hatch's rule).
std::vector<int> drawn_faces(const Plan& plan, const Partition& part) {
    std::vector<int> out;
    for (std::size_t i = 0; i < part.faces.size(); ++i)
        if (!plan.options.window || owns(*plan.options.window, face_anchor(part.faces[i]))) out.push_back(int(i));
    return out;
}

// The items whose boxes meet a box, through a uniform grid of buckets.
class BoxIndex {
public:
    BoxIndex(const std::vector<tex::BBox>& boxes, double cell) : boxes_(boxes), cell_(std::max(cell, 1e-9)) {
        for (const auto& b : boxes) all_.add(b);
        if (all_.empty()) return;
        nx_ = std::min(4096, std::max(1, int(std::ceil(all_.width() / cell_)) + 1));
        ny_ = std::min(4096, std::max(1, int(std::ceil(all_.height() / cell_)) + 1));
        buckets_.resize(std::size_t(nx_) * std::size_t(ny_));
        for (std::size_t i = 0; i < boxes.size(); ++i)
            if (!boxes[i].empty()) each(boxes[i], [&](std::vector<int>& v) { v.push_back(int(i)); });
    }
    // Ascending indices of the items whose boxes meet `b`.
    std::vector<int> find(const tex::BBox& b) const {
        std::vector<int> out;
        if (all_.empty() || !b.intersects(all_)) return out;
        each(b, [&](const std::vector<int>& v) {
            for (int i : v)
                if (boxes_[std::size_t(i)].intersects(b)) out.push_back(i);
        });
        std::sort(out.begin(), out.end());
        out.erase(std::unique(out.begin(), out.end()), out.end());
        return out;
    }

private:
    template <class F>
    void each(const tex::BBox& b, F f) const {
        const auto ix = [&](double x) { return std::clamp(int((x - all_.xmin) / all_.width() * (nx_ - 1e-9)), 0, nx_ - 1); };
        const auto iy = [&](double y) { return std::clamp(int((y - all_.ymin) / all_.height() * (ny_ - 1e-9)), 0, ny_ - 1); };
        const int x0 = all_.width() > 0 ? ix(b.xmin) : 0, x1 = all_.width() > 0 ? ix(b.xmax) : 0;
        const int y0 = all_.height() > 0 ? iy(b.ymin) : 0, y1 = all_.height() > 0 ? iy(b.ymax) : 0;
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x)
                f(const_cast<std::vector<int>&>(buckets_[std::size_t(y) * std::size_t(nx_) + std::size_t(x)]));
    }
    const std::vector<tex::BBox>& boxes_;
    double cell_;
    tex::BBox all_;
    int nx_ = 1, ny_ = 1;
    std::vector<std::vector<int>> buckets_;
};

}  // namespace fingerprint_impl

using namespace fingerprint_impl;

bool keeps_fingerprints(const Plan& plan) {
    if (plan.terrain_style() || plan.crest_band) return false;
    return std::any_of(plan.outputs.begin(), plan.outputs.end(),
                       [](const Output& o) { return o.format == OutputFormat::GeoPackage; });
}

FingerprintRasters read_fingerprint_rasters(const Options& o, const WorkingGrid& grid) {
    FingerprintRasters r;
    r.grid = grid.grid;
    r.dem = read_raster(o.dem, "--dem");
    if (!o.slope.empty()) r.slope = read_raster(o.slope, "--slope");
    if (!o.roughness.empty()) r.roughness = read_raster(o.roughness, "--roughness");
    return r;
}

// A raster file's cells digested by blocks, and the way from the working CRS to its own.
struct SourceBlocks {
    const Raster& raster;
    BlockDigests blocks;
    std::unique_ptr<OGRCoordinateTransformation> to_file;  // none: the file is in the working CRS
    SourceBlocks(const Raster& r, const std::string& working_wkt) : raster(r), blocks(r) {
        if (same_crs(r.crs_wkt, working_wkt)) return;
        OGRSpatialReference from, to;
        from.importFromWkt(working_wkt.c_str());
        to.importFromWkt(r.crs_wkt.c_str());
        from.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
        to.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
        to_file.reset(OGRCreateCoordinateTransformation(&from, &to));
        if (!to_file) throw Error(Code::NoCrs, "cannot take the working CRS to the raster's CRS for the fingerprints");
    }
    // A box of the working CRS in the file's CRS: the box of its outline (kSides points a side).
    tex::BBox to_file_box(const tex::BBox& b) const {
        if (!to_file) return b;
        constexpr int kSides = 4;
        std::vector<double> x, y;
        for (int k = 0; k < kSides; ++k) {
            const double t = double(k) / kSides;
            for (const Point& q : {Point{b.xmin + t * b.width(), b.ymin}, Point{b.xmax, b.ymin + t * b.height()},
                                   Point{b.xmax - t * b.width(), b.ymax}, Point{b.xmin, b.ymax - t * b.height()}}) {
                x.push_back(q.x);
                y.push_back(q.y);
            }
        }
        std::vector<int> ok(x.size());
        to_file->Transform(x.size(), x.data(), y.data(), nullptr, ok.data());
        tex::BBox out;
        for (std::size_t i = 0; i < x.size(); ++i)
            if (ok[i] && std::isfinite(x[i]) && std::isfinite(y[i])) out.add(Point{x[i], y[i]});
        return out;
    }
};

Partition read_digitised(const Options& o, const std::string& working_wkt) {
    PartitionOptions po = o.partition;
    po.as_digitised = true;
    return load_partition(po, working_wkt);
}

void set_drawn_boxes(Fingerprints& fp, const Plan& plan, const Partition& drawn) {
    std::map<std::int64_t, tex::BBox> box;
    for (int i : drawn_faces(plan, drawn)) box[drawn.faces[std::size_t(i)].id].add(drawn.faces[std::size_t(i)].region.bbox());
    fp.boxes.clear();
    for (const auto& [id, digest] : fp.faces) {
        const auto it = box.find(id);
        fp.boxes.push_back(it == box.end() ? tex::BBox{} : it->second);
    }
}

Fingerprints face_fingerprints(const Plan& plan, const Partition& part, const FingerprintRasters& rasters) {
    const RasterInfo& dem = rasters.grid;
    const Raster* slope = rasters.slope ? &*rasters.slope : nullptr;
    const Raster* roughness = rasters.roughness ? &*rasters.roughness : nullptr;
    Fingerprints fp;
    Digest plan_digest;
    plan_digest.add(plan_text(plan, dem, slope != nullptr, roughness != nullptr));
    fp.run["version"] = RH_VERSION_STRING "+" RH_SOURCE_DIGEST;
    fp.run["crs"] = crs_name(dem.crs_wkt);
    fp.run["style"] = plan.style.info.name;
    fp.run["plan"] = plan_digest.hex();
    fp.run["command"] = command_text(plan.options);

    const double cell = std::min(std::abs(dem.gt[1]), std::abs(dem.gt[5]));
    const double margin = tile_context_margin(plan, cell);
    const int halo = tile_halo_cells(plan, cell);
    std::vector<tex::BBox> face_boxes, line_boxes;
    for (const auto& f : part.faces) face_boxes.push_back(f.region.bbox());
    for (const auto& l : part.lines) {
        tex::BBox b;
        for (const Point& q : l.points) b.add(q);
        line_boxes.push_back(b);
    }
    const BoxIndex face_index(face_boxes, std::max(margin, cell)), line_index(line_boxes, std::max(margin, cell));

    // Each file's cells under a face's box grown by the halo, plus two working cells for the
    // bilinear neighbours of the reprojection, and two of the file's own cells.
    std::vector<std::unique_ptr<SourceBlocks>> sources;
    sources.push_back(std::make_unique<SourceBlocks>(rasters.dem, dem.crs_wkt));
    if (slope) sources.push_back(std::make_unique<SourceBlocks>(*slope, dem.crs_wkt));
    if (roughness) sources.push_back(std::make_unique<SourceBlocks>(*roughness, dem.crs_wkt));

    const std::vector<int> drawn = drawn_faces(plan, part);
    // The faces' boxes in each file's CRS (PROJ's transformations are not shared between threads).
    std::vector<std::vector<tex::BBox>> file_boxes(sources.size(), std::vector<tex::BBox>(drawn.size()));
    for (std::size_t k = 0; k < drawn.size(); ++k) {
        const tex::BBox grown = part.faces[std::size_t(drawn[k])].region.bbox().expanded(margin + (halo + 2) * cell);
        for (std::size_t s = 0; s < sources.size(); ++s) file_boxes[s][k] = sources[s]->to_file_box(grown);
    }
    std::vector<Digest> each(drawn.size());
    tex::parallel_for(drawn.size(), [&](std::size_t k) {
        const RockFace& f = part.faces[std::size_t(drawn[k])];
        const tex::BBox box = f.region.bbox().expanded(margin);
        Digest d;
        d.add(plan_digest);
        d.add(face_digest(f));
        for (int j : face_index.find(box))
            if (j != drawn[k]) add_face_within(d, part.faces[std::size_t(j)], box);
        d.add(std::uint64_t(0xfeedULL));
        for (int j : line_index.find(box)) add_line_within(d, part.lines[std::size_t(j)], box);
        for (std::size_t s = 0; s < sources.size(); ++s) {
            if (file_boxes[s][k].empty()) {
                d.add(std::uint64_t(1));  // the box could not be taken to the file's CRS: every block
                add_blocks(d, sources[s]->raster, sources[s]->blocks, sources[s]->raster.bounds().expanded(1), 0);
            } else {
                add_blocks(d, sources[s]->raster, sources[s]->blocks, file_boxes[s][k], 2);
            }
        }
        each[k] = d;
    });
    // One fingerprint per face id: the parts of a face that share its id (a repaired
    // self-intersecting polygon) are drawn, and so redrawn, together.
    std::map<std::int64_t, std::size_t> row;
    std::vector<Digest> rows;
    for (std::size_t k = 0; k < drawn.size(); ++k) {
        const std::int64_t id = part.faces[std::size_t(drawn[k])].id;
        const auto [it, fresh] = row.emplace(id, rows.size());
        if (fresh) {
            rows.emplace_back();
            fp.faces.emplace_back(id, "");
        }
        rows[it->second].add(each[k]);
    }
    for (std::size_t i = 0; i < rows.size(); ++i) fp.faces[i].second = rows[i].hex();
    return fp;
}

UpdateReport update(const Options& o, const UpdateOptions& u, const Progress& progress) {
    // The outputs are the files to update: they exist (never an input, still checked).
    Options checked = o;
    checked.overwrite = true;
    return update(make_plan(checked), u, progress);
}

UpdateReport update(const Plan& plan, const UpdateOptions& u, const Progress& progress) {
    const auto t0 = std::chrono::steady_clock::now();
    const tex::ThreadsScope threads(plan.options.threads);
    const Output* gpkg = nullptr;
    for (const Output& out : plan.outputs) {
        if (out.format == OutputFormat::VectorTiles)
            throw Error(Code::Usage, "-o '" + out.path + "': update rewrites a GeoPackage and the SVG, PNG and PDF drawn "
                                     "from it; vector tiles are drawn per zoom level (run rockhatch again)");
        if (out.format != OutputFormat::GeoPackage) continue;
        if (gpkg) throw Error(Code::Usage, "-o '" + out.path + "': update takes one GeoPackage (also '" + gpkg->path + "')");
        gpkg = &out;
    }
    if (!gpkg) throw Error(Code::Usage, "update needs the GeoPackage a run wrote (-o NAME.gpkg)");
    if (plan.terrain_style())
        throw Error(Code::Usage, "--style " + plan.style.info.name + ": a terrain style's elements depend on every face; "
                                 "update redraws faces of rock styles only (run rockhatch again)");
    if (plan.crest_band)
        throw Error(Code::Usage, "--crest-ornament: crest ornaments are drawn per ridge, not per face; update redraws "
                                 "faces only (run rockhatch again)");
    const std::string& path = gpkg->path;
    if (!std::filesystem::exists(path))
        throw Error(Code::InputMissing, "-o '" + path + "': no such file (update reads the GeoPackage a run wrote)");
    const std::optional<Fingerprints> stored = read_fingerprints(path, "-o");
    if (!stored)
        throw Error(Code::BadLayer, "-o '" + path + "': keeps no fingerprints (written by rockhatch tiles or an older "
                                    "version); write it again with a whole run (rockhatch ... --overwrite)");

    // The fingerprints read the partition as digitised (no border snapped or labelled) and the
    // raster files as they are; the faces to redraw are read as a tile of a tiled run reads
    // its faces (prepare_around): snapped, with the DEM reprojected and its terrain computed
    // under them alone. A PNG beside the file (the whole hillshade under the drawing), an
    // extracted partition or rasters a window cannot read take the whole run's preparation.
    const Options& o = plan.options;
    const WorkingGrid grid = working_grid(raster_info(o.dem, "--dem"));
    const bool png = std::any_of(plan.outputs.begin(), plan.outputs.end(),
                                 [](const Output& out) { return out.format == OutputFormat::Png; });
    const bool around = o.partition.path != "auto" && o.partition.path != "none" && !png &&
                        rasters_read_by_window(o, grid);
    Prepared whole;
    Partition read;
    std::optional<Fingerprints> fingerprints;
    if (around) {
        if (progress && !progress(0.0, "reading the partition")) throw Error(Code::Cancelled, "cancelled while reading");
        std::optional<FingerprintRasters> rasters;
        tex::parallel_for(2, [&](std::size_t item) {
            if (item == 0) rasters = read_fingerprint_rasters(o, grid);
            else read = read_digitised(o, grid.grid.crs_wkt);
        });
        if (!read.bounds().intersects(grid.grid.bounds()))
            throw Error(Code::NoOverlap, "--partition '" + o.partition.path + "' does not overlap --dem '" + o.dem + "'");
        fingerprints = face_fingerprints(plan, read, *rasters);
    } else {
        whole = prepare(plan, progress);
        fingerprints = std::move(whole.fingerprints);
    }
    const Partition& part = around ? read : whole.partition;

    const Fingerprints& now = *fingerprints;
    if (!u.reset)
        for (const char* key : {"version", "crs", "style"}) {
            const auto was = stored->run.find(key);
            const std::string old = was == stored->run.end() ? std::string("none") : was->second;
            if (old != now.run.at(key)) {
                const std::string k = key == std::string("version") ? "program version" : key == std::string("crs") ? "CRS" : key;
                throw Error(Code::Usage, "-o '" + path + "': written with " + k + " " + old + ", this update's is " +
                                             now.run.at(key) + ": refusing to update (--reset redraws every face)");
            }
        }
    UpdateReport r;
    r.crs = crs_name(part.crs_wkt);
    if (around) {
        if (grid.reprojected()) r.notes.push_back(grid.note());
        r.notes.insert(r.notes.end(), part.notes.begin(), part.notes.end());
    } else {
        r.notes = whole.notes;
    }
    std::map<std::int64_t, std::string> before(stored->faces.begin(), stored->faces.end());
    // Face id -> the drawn faces (parts) of that id: as digitised (around), or as drawn.
    std::map<std::int64_t, std::vector<int>> index;
    for (int i : drawn_faces(plan, part)) index[part.faces[std::size_t(i)].id].push_back(i);
    const std::set<std::int64_t> forced(u.faces.begin(), u.faces.end());
    std::set<std::int64_t> current;
    for (const auto& [id, fp] : now.faces) current.insert(id);
    for (std::int64_t id : forced)
        if (!current.count(id))
            throw Error(Code::Usage, "--face " + std::to_string(id) + ": no such face in --partition '" +
                                         plan.options.partition.path + "'" + (plan.options.window ? " (and --window)" : ""));
    std::vector<int> redraw;
    Drawing d;
    d.fingerprints = Fingerprints{now.run, {}};
    for (const auto& [id, fp] : now.faces) {
        const auto was = before.find(id);
        const bool appeared = was == before.end();
        if (u.reset || appeared || was->second != fp || forced.count(id)) {
            // (A face left without area by snapping has no part drawn.)
            if (const auto parts = index.find(id); parts != index.end())
                redraw.insert(redraw.end(), parts->second.begin(), parts->second.end());
            r.redrawn_ids.push_back(id);
            d.fingerprints->faces.emplace_back(id, fp);
            r.appeared += appeared;
        }
    }
    for (const auto& [id, fp] : before)
        if (!current.count(id)) r.removed_ids.push_back(id);
    r.faces = now.faces.size();
    r.redrawn = redraw.size();
    // The box of each face as drawn (the frame is their union): a redrawn face's from the
    // partition it is drawn from, another's as the file keeps it.
    std::map<std::int64_t, tex::BBox> box_of;
    for (std::size_t i = 0; i < stored->faces.size() && i < stored->boxes.size(); ++i)
        box_of[stored->faces[i].first] = stored->boxes[i];
    if (!around)
        for (std::size_t i = 0; i < now.faces.size() && i < now.boxes.size(); ++i) box_of[now.faces[i].first] = now.boxes[i];
    r.removed = r.removed_ids.size();
    std::sort(redraw.begin(), redraw.end());  // in partition order, as a run draws them
    std::vector<std::int64_t> replaced = r.redrawn_ids;
    replaced.insert(replaced.end(), r.removed_ids.begin(), r.removed_ids.end());
    // The file's features of those faces are read on a thread of their own while the faces are
    // drawn (when the run may use more than one).
    std::future<std::shared_ptr<FeatureKeys>> keys;
    if (!u.reset && !replaced.empty() && tex::GetThreads() > 1)
        keys = std::async(std::launch::async, [&path, &replaced] { return read_feature_keys(path, replaced); });
    if (!redraw.empty()) {
        Drawing drawn;
        if (around) {
            // The faces within the context margin of those redrawn, read again as a tile reads
            // them, and the DEM under them; the redrawn ones drawn in partition order.
            tex::BBox reach;
            for (int i : redraw) reach.add(part.faces[std::size_t(i)].region.bbox());
            const double cell = std::min(std::abs(grid.grid.gt[1]), std::abs(grid.grid.gt[5]));
            PartitionOptions po = o.partition;
            po.filter = reach.expanded(tile_context_margin(plan, cell));
            const Prepared p = prepare_around(plan, grid, po, std::nullopt);
            const std::set<std::int64_t> ids(r.redrawn_ids.begin(), r.redrawn_ids.end());
            std::vector<int> chosen;
            for (std::int64_t id : ids) box_of[id] = tex::BBox{};
            for (int i : drawn_faces(plan, p.partition)) {
                const RockFace& f = p.partition.faces[std::size_t(i)];
                if (!ids.count(f.id)) continue;
                chosen.push_back(i);
                box_of[f.id].add(f.region.bbox());
            }
            drawn = hatch(p, plan, chosen, progress);
        } else {
            drawn = hatch(whole, plan, redraw, progress);
        }
        d.faces = std::move(drawn.faces);
        d.style = drawn.style;
        d.crs_wkt = drawn.crs_wkt;
        d.scale = drawn.scale;
    }
    for (const auto& [id, fp] : d.fingerprints->faces) d.fingerprints->boxes.push_back(box_of[id]);
    // The frame of the whole drawing, as a run makes it: the boxes of the faces drawn.
    for (const auto& [id, fp] : now.faces)
        if (const auto b = box_of.find(id); b != box_of.end() && !b->second.empty()) d.bounds.add(b->second);
    if (progress && !progress(0.92, "writing")) throw Error(Code::Cancelled, "cancelled during writing");
    const FaceReplacement written = replace_faces(path, replaced, u.reset, d, u.undo, keys.valid() ? keys.get() : nullptr);
    r.deleted = written.deleted;
    r.written = written.written;
    r.kept = written.kept;
    // The drawings beside it, from the updated layers.
    std::optional<Drawing> drawing;
    for (const Output& out : plan.outputs) {
        if (out.format == OutputFormat::GeoPackage) continue;
        if (!drawing) drawing = read_gpkg(path, plan.options.scale);
        switch (out.format) {
            case OutputFormat::Svg: write_svg(*drawing, out.path); break;
            case OutputFormat::Png: write_png(*drawing, out.path, plan.options.png_pixels, &whole.terrain.hillshade); break;
            case OutputFormat::Pdf: write_pdf(*drawing, out.path, plan.page); break;
            default: break;
        }
    }
    if (progress) progress(1.0, "done");
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return r;
}

}  // namespace carto
