#include "carto/publish.hpp"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>
#include <sqlite3.h>

#include <zlib.h>

#include <algorithm>
#include <atomic>
#include <charconv>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <set>
#include <sstream>

#include <unistd.h>

#include "carto/error.hpp"
#include "carto/raster.hpp"
#include "gdal_scope.hpp"
#include "libtex/parallel.hpp"
#include "temp_file.hpp"
#include "xml_text.hpp"

namespace fs = std::filesystem;

namespace carto {
namespace {

// Features of a vector-tile output gathered in memory rather than in a file (about 2 GB).
constexpr std::size_t kMaxMemoryTileFeatures = 18'000'000;

std::string publish_lower(std::string s) {
    for (auto& c : s) c = char(std::tolower((unsigned char)c));
    return s;
}

// A number of the composition file (PDF units or ground units) to six decimals.
std::string pdf_number(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.6f", v);
    return buf;
}

std::string last_gdal_error(const std::string& fallback) {
    const char* m = CPLGetLastErrorMsg();
    return m && *m ? std::string(m) : fallback;
}

// The layers a drawing's GeoPackage has, in the order the SVG draws them: (layer, name shown,
// filled).
struct LayerRef {
    std::string layer, name;
    bool filled;
    Family family;  // of a hatch layer
};
std::vector<LayerRef> drawing_layers(const Drawing& d) {
    std::vector<LayerRef> out;
    for (int fam = 0; fam < kFamilies; ++fam)
        if (has_family(d, Family(fam)))
            out.push_back({std::string("hatch_") + family_name(Family(fam)), family_name(Family(fam)),
                           family_filled(Family(fam)), Family(fam)});
    if (d.crests) out.push_back({"crest", "crest", true, Family::Fill});
    return out;
}

// Ground coordinates to PDF units on the page.
struct PageMap {
    double k;              // PDF units per ground unit
    double x0, y0;         // the frame's lower-left corner on the page
    double xmin, ymin;     // and on the ground
};

// A number in PDF units to a hundredth (3.5 micrometres).
void append_pdf_number(std::string& s, double v) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, std::round(v * 100) / 100 + 0.0, std::chars_format::fixed, 2);
    s.append(buf, r.ptr);
}

void append_point(std::string& s, const PageMap& m, const Point& p, const char* op) {
    append_pdf_number(s, m.x0 + (p.x - m.xmin) * m.k);
    s += ' ';
    append_pdf_number(s, m.y0 + (p.y - m.ymin) * m.k);
    s += op;
}

// The page content of one layer: its paths in black, strokes with round caps and joins at
// the family's width on paper (as the SVG draws them), filled shapes without a stroke.
std::string layer_content(const Drawing& d, const LayerRef& layer, const PageMap& m) {
    std::string head;
    if (layer.filled) head = "0 g\n";
    else {
        char width[48];  // to a ten-thousandth of a point: the family's width exactly enough
        std::snprintf(width, sizeof width, "0 G 1 J 1 j %.4f w\n", pdf_line_width(family_width_mm(layer.family)));
        head = width;
    }
    if (layer.layer == "crest") {
        // One path per ridge, its holes by the even-odd rule (as the SVG's).
        for (const auto& c : *d.crests) {
            for (const auto& ring : c.rings) {
                for (std::size_t i = 0; i < ring.size(); ++i) append_point(head, m, ring[i], i ? " l\n" : " m\n");
                head += "h\n";
            }
            head += "f*\n";
        }
        return head;
    }
    // Face by face in parallel (formatting the numbers is most of the work), joined in order.
    std::vector<std::string> faces(d.faces.size());
    tex::parallel_for(d.faces.size(), [&](std::size_t k) {
        std::string& t = faces[k];
        for (const auto& h : d.faces[k].hatches) {
            if (h.family != layer.family || h.points.size() < 2) continue;
            for (std::size_t i = 0; i < h.points.size(); ++i) append_point(t, m, h.points[i], i ? " l\n" : " m\n");
            t += layer.filled ? "h f\n" : h.closed ? "h S\n" : "S\n";
        }
    });
    std::size_t size = head.size();
    for (const auto& t : faces) size += t.size();
    head.reserve(size);
    for (const auto& t : faces) head += t;
    return head;
}

// `data` as a zlib stream, deflated a megabyte at a time in parallel (each part ends on a
// byte boundary, so the parts join into one stream); the bytes do not depend on the thread
// count.
std::string flate(const std::string& data) {
    constexpr std::size_t kPart = std::size_t(1) << 20;
    const std::size_t n = std::max<std::size_t>(1, (data.size() + kPart - 1) / kPart);
    std::vector<std::string> parts(n);
    std::vector<uLong> adler(n);
    std::atomic<bool> failed{false};
    tex::parallel_for(n, [&](std::size_t i) {
        const std::size_t at = i * kPart, len = std::min(kPart, data.size() - std::min(at, data.size()));
        z_stream z{};
        if (deflateInit2(&z, 6, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY) != Z_OK) {
            failed = true;
            return;
        }
        std::string& out = parts[i];
        out.resize(deflateBound(&z, uLong(len)) + 64);
        z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data() + at));
        z.avail_in = uInt(len);
        z.next_out = reinterpret_cast<Bytef*>(out.data());
        z.avail_out = uInt(out.size());
        const int r = deflate(&z, i + 1 == n ? Z_FINISH : Z_SYNC_FLUSH);
        if (z.avail_in != 0 || (i + 1 == n ? r != Z_STREAM_END : r != Z_OK)) failed = true;
        out.resize(z.total_out);
        deflateEnd(&z);
        adler[i] = adler32(adler32(0, nullptr, 0), reinterpret_cast<const Bytef*>(data.data() + at), uInt(len));
    });
    if (failed) throw Error(Code::Failure, "cannot compress a PDF page");
    std::string out = "\x78\x9c";
    uLong sum = adler32(0, nullptr, 0);
    for (std::size_t i = 0; i < n; ++i) {
        out += parts[i];
        const std::size_t at = i * kPart, len = std::min(kPart, data.size() - std::min(at, data.size()));
        sum = adler32_combine(sum, adler[i], z_off_t(len));
    }
    for (int shift = 24; shift >= 0; shift -= 8) out += char((sum >> shift) & 0xff);
    return out;
}

// A one-page PDF of `w` x `h` units whose content is `content` (Flate-compressed): a layer's
// paths, which the composition inserts into the page (its <PDF> element).
void write_content_pdf(const std::string& path, double w, double h, const std::string& content) {
    const std::string z = flate(content);
    std::string s = "%PDF-1.4\n%\xe2\xe3\xcf\xd3\n";
    std::vector<std::size_t> offsets;
    const auto object = [&](const std::string& body) {
        offsets.push_back(s.size());
        s += std::to_string(offsets.size()) + " 0 obj\n" + body + "\nendobj\n";
    };
    object("<< /Type /Catalog /Pages 2 0 R >>");
    object("<< /Type /Pages /Kids [3 0 R] /Count 1 >>");
    std::string box;
    append_pdf_number(box, w);
    box += ' ';
    append_pdf_number(box, h);
    object("<< /Type /Page /Parent 2 0 R /MediaBox [0 0 " + box + "] /Contents 4 0 R /Resources << >> >>");
    object("<< /Length " + std::to_string(z.size()) + " /Filter /FlateDecode >>\nstream\n" + z + "\nendstream");
    const std::size_t xref = s.size();
    s += "xref\n0 " + std::to_string(offsets.size() + 1) + "\n0000000000 65535 f \n";
    for (std::size_t o : offsets) {
        char line[32];
        std::snprintf(line, sizeof line, "%010zu 00000 n \n", o);
        s += line;
    }
    s += "trailer\n<< /Size " + std::to_string(offsets.size() + 1) + " /Root 1 0 R >>\nstartxref\n" +
         std::to_string(xref) + "\n%%EOF\n";
    std::ofstream f(path, std::ios::binary);
    f.write(s.data(), std::streamsize(s.size()));
    if (!f) throw Error(Code::OutputExists, "'" + path + "': cannot write it");
}

}  // namespace

// ---------------------------------------------------------------------------------------
// PDF

PageSize parse_page(const std::string& text) {
    static const struct {
        const char* name;
        double w, h;
    } iso[] = {{"a0", 841, 1189}, {"a1", 594, 841}, {"a2", 420, 594}, {"a3", 297, 420}, {"a4", 210, 297}, {"a5", 148, 210}};
    const std::string t = publish_lower(text);
    for (const auto& p : iso)
        if (t == p.name) return {std::string(1, 'A') + char(t[1]), p.w, p.h};
    const auto x = t.find('x');
    const auto bad = [&](const std::string& why) {
        return Error(Code::Usage, "--page '" + text + "': " + why);
    };
    if (x == std::string::npos) throw bad("not a page (use A0..A5 or WIDTHxHEIGHT in mm, e.g. 500x700)");
    double w = 0, h = 0;
    try {
        std::size_t n1 = 0, n2 = 0;
        w = std::stod(t.substr(0, x), &n1);
        h = std::stod(t.substr(x + 1), &n2);
        if (n1 != x || n2 != t.size() - x - 1) throw std::invalid_argument("trailing");
    } catch (const std::exception&) {
        throw bad("not a page (use A0..A5 or WIDTHxHEIGHT in mm, e.g. 500x700)");
    }
    if (!(w > 0) || !(h > 0) || !std::isfinite(w) || !std::isfinite(h)) throw bad("sides must be positive");
    if (w > kMaxPdfPageMm || h > kMaxPdfPageMm) {
        std::ostringstream m;
        m << "a PDF page side is at most " << std::lround(kMaxPdfPageMm) << " mm";
        throw bad(m.str());
    }
    return {text, std::min(w, h), std::max(w, h)};
}

PageLayout page_layout(const tex::BBox& frame, double scale, const std::optional<PageSize>& page,
                       const std::string& path) {
    const double fw = frame.width() * 1000.0 / scale, fh = frame.height() * 1000.0 / scale;
    std::ostringstream m;
    m.precision(4);
    if (!page) {
        if (fw <= kMaxPdfPageMm && fh <= kMaxPdfPageMm) return {fw, fh};
        m << "-o '" << path << "': the drawing is " << fw << " x " << fh << " mm at 1:" << std::llround(scale)
          << ", more than a PDF page holds (" << std::lround(kMaxPdfPageMm) << " mm a side); use a smaller scale";
        throw Error(Code::Usage, m.str());
    }
    if (fw <= page->width_mm && fh <= page->height_mm) return {page->width_mm, page->height_mm};
    if (fw <= page->height_mm && fh <= page->width_mm) return {page->height_mm, page->width_mm};
    m << "--page " << page->name << " (" << page->width_mm << " x " << page->height_mm << " mm): the drawing is "
      << fw << " x " << fh << " mm at 1:" << std::llround(scale) << "; use a larger page or a smaller scale";
    throw Error(Code::Usage, m.str());
}

void write_pdf(const Drawing& d, const std::string& path, const std::optional<PageSize>& page) {
    register_gdal();
    if (d.bounds.empty() || !(d.bounds.width() > 0) || !(d.bounds.height() > 0))
        throw Error(Code::Failure, "-o '" + path + "': nothing to draw (the drawing has no extent)");
    const double mm_per_unit = 1000.0 / d.scale;
    const double fw = d.bounds.width() * mm_per_unit, fh = d.bounds.height() * mm_per_unit;
    const PageLayout pl = page_layout(d.bounds, d.scale, page, path);
    const double pw = pl.width_mm, ph = pl.height_mm;
    const double pt = 72.0 / 25.4;  // PDF units per mm
    const double x0 = (pw - fw) / 2 * pt, y0 = (ph - fh) / 2 * pt, x1 = x0 + fw * pt, y1 = y0 + fh * pt;
    const tex::BBox& b = d.bounds;

    // Each layer's paths as a page of its own (written by carto: GDAL's own vector writer sets
    // the whole graphics state for every feature, several times slower and larger), inserted
    // by the composition into the georeferenced page under the layer's optional content.
    const std::vector<LayerRef> layers = drawing_layers(d);
    const PageMap map{mm_per_unit * pt, x0, y0, b.xmin, b.ymin};
    std::vector<std::unique_ptr<TempFile>> pages;
    for (const LayerRef& layer : layers) {
        pages.push_back(std::make_unique<TempFile>(path, "." + layer.name + ".pdf"));
        write_content_pdf(pages.back()->path, pw * pt, ph * pt, layer_content(d, layer, map));
    }

    std::string x = "<PDFComposition>\n  <Metadata>\n    <Producer>rockhatch " RH_VERSION_STRING "</Producer>\n";
    std::ostringstream subject;
    subject << "rock drawing, style " << d.style << ", 1:" << d.scale << ", " << crs_name(d.crs_wkt);
    x += "    <Subject>" + xml_escape(subject.str()) + "</Subject>\n";
    x += "    <Title>" + xml_escape(fs::path(path).stem().string()) + "</Title>\n  </Metadata>\n  <LayerTree>\n";
    for (std::size_t i = 0; i < layers.size(); ++i)
        x += "    <Layer id=\"L" + std::to_string(i) + "\" name=\"" + xml_escape(layers[i].name) + "\"/>\n";
    x += "  </LayerTree>\n  <Page>\n    <DPI>72</DPI>\n    <Width>" + pdf_number(pw * pt) + "</Width>\n    <Height>" +
         pdf_number(ph * pt) + "</Height>\n";
    x += "    <Georeferencing id=\"g\">\n      <SRS dataAxisToSRSAxisMapping=\"1,2\">" + xml_escape(d.crs_wkt) + "</SRS>\n";
    x += "      <BoundingBox x1=\"" + pdf_number(x0) + "\" y1=\"" + pdf_number(y0) + "\" x2=\"" + pdf_number(x1) + "\" y2=\"" + pdf_number(y1) + "\"/>\n";
    // The frame's corners, in the order of a ring (the neatline readers take from them).
    const double corner[4][4] = {{x0, y0, b.xmin, b.ymin}, {x0, y1, b.xmin, b.ymax}, {x1, y1, b.xmax, b.ymax},
                                 {x1, y0, b.xmax, b.ymin}};
    for (const auto& c : corner)
        x += "      <ControlPoint x=\"" + pdf_number(c[0]) + "\" y=\"" + pdf_number(c[1]) + "\" GeoX=\"" + pdf_number(c[2]) + "\" GeoY=\"" +
             pdf_number(c[3]) + "\"/>\n";
    x += "    </Georeferencing>\n    <Content>\n";
    for (std::size_t i = 0; i < layers.size(); ++i)
        x += "      <IfLayerOn layerId=\"L" + std::to_string(i) + "\">\n        <PDF dataset=\"" +
             xml_escape(pages[i]->path) + "\"/>\n      </IfLayerOn>\n";
    x += "    </Content>\n  </Page>\n</PDFComposition>\n";
    TempFile xml(path, ".xml");
    {
        std::ofstream f(xml.path, std::ios::binary);
        f << x;
        if (!f) throw Error(Code::OutputExists, "-o '" + path + "': cannot write next to it");
    }

    GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("PDF");
    if (!drv) throw Error(Code::Failure, "-o '" + path + "': this GDAL has no PDF driver");
    TempFile out(path, ".pdf");
    {
        const QuietGdal quiet;
        CPLErrorReset();
        char** opts = CSLSetNameValue(nullptr, "COMPOSITION_FILE", xml.path.c_str());
        GDALDataset* ds = drv->Create(out.path.c_str(), 0, 0, 0, GDT_Unknown, opts);
        CSLDestroy(opts);
        if (!ds) throw Error(Code::OutputExists, "-o '" + path + "': " + last_gdal_error("the PDF driver failed"));
        GDALClose(GDALDataset::ToHandle(ds));
        std::error_code ec;
        if (fs::file_size(out.path, ec) == 0 || ec)
            throw Error(Code::OutputExists, "-o '" + path + "': " + last_gdal_error("the PDF driver wrote nothing"));
    }
    out.commit(path);
}

// ---------------------------------------------------------------------------------------
// Vector tiles

ZoomRange parse_zoom_range(const std::string& text) {
    const auto bad = [&](const std::string& why) { return Error(Code::Usage, "--zoom '" + text + "': " + why); };
    const auto number = [&](const std::string& s) {
        if (s.empty() || s.size() > 2 || !std::all_of(s.begin(), s.end(), [](char c) { return std::isdigit((unsigned char)c); }))
            throw bad("not a zoom range (use Z or Z1-Z2, e.g. 12-16)");
        const int z = std::stoi(s);
        if (z > 22) throw bad("zoom levels are 0..22");
        return z;
    };
    const auto dash = text.find('-');
    ZoomRange r;
    if (dash == std::string::npos) r.min = r.max = number(text);
    else {
        r.min = number(text.substr(0, dash));
        r.max = number(text.substr(dash + 1));
    }
    if (r.min > r.max) throw bad("the first zoom level is above the last");
    return r;
}

double zoom_scale(int z, double latitude_deg) {
    // The ground a pixel of a 256-pixel Web Mercator tile covers at the equator, zoom 0.
    constexpr double kEquatorPixelM = 2 * M_PI * 6378137.0 / 256;
    return kEquatorPixelM * std::cos(latitude_deg * M_PI / 180) / std::ldexp(1.0, z) / (kWebPixelMm / 1000);
}

double dem_latitude(const std::string& dem) {
    register_gdal();
    const QuietGdal quiet;
    DatasetPtr ds(static_cast<GDALDataset*>(GDALOpenEx(dem.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
    if (!ds) throw Error(Code::InputMissing, "--dem '" + dem + "': " + last_gdal_error("cannot read it"));
    double gt[6];
    const OGRSpatialReference* crs = ds->GetSpatialRef();
    if (!crs || ds->GetGeoTransform(gt) != CE_None) throw Error(Code::NoCrs, "--dem '" + dem + "': no CRS or no georeferencing");
    OGRSpatialReference src(*crs), wgs;
    wgs.SetWellKnownGeogCS("WGS84");
    src.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    wgs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    std::unique_ptr<OGRCoordinateTransformation> ct(OGRCreateCoordinateTransformation(&src, &wgs));
    const double cx = ds->GetRasterXSize() / 2.0, cy = ds->GetRasterYSize() / 2.0;
    double x = gt[0] + cx * gt[1] + cy * gt[2], y = gt[3] + cx * gt[4] + cy * gt[5];
    if (!ct || !ct->Transform(1, &x, &y) || !std::isfinite(y))
        throw Error(Code::NoCrs, "--dem '" + dem + "': its centre has no latitude");
    return y;
}

TileStats mbtiles_stats(const std::string& path) {
    TileStats s;
    sqlite3* db = nullptr;
    if (sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
        sqlite3_close(db);
        throw Error(Code::InputMissing, "'" + path + "': cannot open as MBTiles");
    }
    sqlite3_stmt* st = nullptr;
    const char* sql =
        "SELECT zoom_level, tile_column, tile_row, length(tile_data) FROM tiles ORDER BY length(tile_data) DESC";
    if (sqlite3_prepare_v2(db, sql, -1, &st, nullptr) == SQLITE_OK) {
        while (sqlite3_step(st) == SQLITE_ROW) {
            const auto n = std::size_t(sqlite3_column_int64(st, 3));
            if (s.tiles == 0) {
                s.largest = n;
                s.largest_z = sqlite3_column_int(st, 0);
                s.largest_x = sqlite3_column_int(st, 1);
                s.largest_y = (1 << s.largest_z) - 1 - sqlite3_column_int(st, 2);  // TMS row to XYZ
            }
            ++s.tiles;
            s.bytes += n;
        }
    }
    sqlite3_finalize(st);
    sqlite3_close(db);
    return s;
}

TileStats write_vector_tiles(const std::vector<ZoomDrawing>& zooms, const std::string& output, const std::string& name,
                             const std::function<bool(double)>& keep_going) {
    register_gdal();
    std::string path = output;  // a folder's name without its trailing slash
    while (path.size() > 1 && path.back() == '/') path.pop_back();
    if (zooms.empty()) throw Error(Code::Usage, "-o '" + path + "': no zoom level to write");
    std::set<int> seen;
    for (const auto& z : zooms)
        if (z.zoom < 0 || z.zoom > 22 || !seen.insert(z.zoom).second)
            throw Error(Code::Usage, "-o '" + path + "': zoom " + std::to_string(z.zoom) + " twice or out of 0..22");
    const bool mbtiles = publish_lower(fs::path(path).extension().string()) == ".mbtiles";
    GDALDriver* drv = GetGDALDriverManager()->GetDriverByName(mbtiles ? "MBTiles" : "MVT");
    if (!drv) throw Error(Code::Failure, "-o '" + path + "': this GDAL cannot write vector tiles");

    TempFile out(path, mbtiles ? ".mbtiles" : "");
    struct DirCleanup {
        std::string dir;
        bool keep = false;
        ~DirCleanup() {
            std::error_code ec;
            if (!keep && !dir.empty()) fs::remove_all(dir, ec);
        }
    } dir_cleanup{mbtiles ? "" : out.path};

    TileStats stats;
    const QuietGdal quiet;
    static std::atomic<unsigned long> counter{0};
    const std::string memory_db = "/vsimem/rockhatch-mvt-" + std::to_string(::getpid()) + "-" +
                                  std::to_string(counter++) + ".db";
    struct MemoryCleanup {
        const std::string& path;
        ~MemoryCleanup() { VSIUnlink(path.c_str()); }
    } memory_cleanup{memory_db};
    {
        char** opts = nullptr;
        opts = CSLSetNameValue(opts, "MINZOOM", std::to_string(*seen.begin()).c_str());
        opts = CSLSetNameValue(opts, "MAXZOOM", std::to_string(*seen.rbegin()).c_str());
        opts = CSLSetNameValue(opts, "NAME", name.c_str());
        opts = CSLSetNameValue(opts, "DESCRIPTION", "rock drawing by rockhatch, each zoom level drawn at its own scale");
        opts = CSLSetNameValue(opts, "TYPE", "overlay");
        opts = CSLSetNameValue(opts, "MAX_SIZE", "500000");
        // The driver gathers the features tile by tile in a temporary SQLite database: in
        // memory it is three times as fast as in a file (a system call per page). About 110
        // bytes a feature: in memory up to kMaxMemoryTileFeatures, else in a file beside the
        // output.
        std::size_t total = 0;
        for (const ZoomDrawing& z : zooms) {
            DatasetPtr src(static_cast<GDALDataset*>(
                GDALOpenEx(z.gpkg.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
            if (src)
                for (OGRLayer* l : src->GetLayers()) total += std::size_t(std::max<GIntBig>(0, l->GetFeatureCount()));
        }
        if (total <= kMaxMemoryTileFeatures) opts = CSLSetNameValue(opts, "TEMPORARY_DB", memory_db.c_str());
        CPLErrorReset();
        DatasetPtr ds(drv->Create(out.path.c_str(), 0, 0, 0, GDT_Unknown, opts));
        CSLDestroy(opts);
        if (!ds) throw Error(Code::OutputExists, "-o '" + path + "': " + last_gdal_error("cannot create the tiles"));
        std::size_t done = 0;
        for (const ZoomDrawing& z : zooms) {
            DatasetPtr src(static_cast<GDALDataset*>(
                GDALOpenEx(z.gpkg.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
            if (!src) throw Error(Code::InputMissing, "zoom " + std::to_string(z.zoom) + ": cannot read '" + z.gpkg + "'");
            for (OGRLayer* sl : src->GetLayers()) {
                std::string lname = sl->GetName();
                if (lname.rfind("hatch_", 0) == 0) lname = lname.substr(6);
                else if (lname != "crest") continue;
                char** lopts = nullptr;
                lopts = CSLSetNameValue(lopts, "MINZOOM", std::to_string(z.zoom).c_str());
                lopts = CSLSetNameValue(lopts, "MAXZOOM", std::to_string(z.zoom).c_str());
                lopts = CSLSetNameValue(lopts, "NAME", lname.c_str());
                OGRLayer* dl = ds->CreateLayer((lname + "_z" + std::to_string(z.zoom)).c_str(), sl->GetSpatialRef(),
                                               sl->GetGeomType(), lopts);
                CSLDestroy(lopts);
                if (!dl) throw Error(Code::OutputExists, "-o '" + path + "': " + last_gdal_error("cannot add a layer"));
                OGRFieldDefn face("face_id", OFTInteger64), width("width_mm", OFTReal);
                dl->CreateField(&face);
                dl->CreateField(&width);
                const OGRFeatureDefn* sd = sl->GetLayerDefn();
                const int sface = sd->GetFieldIndex(lname == "crest" ? "ridge_id" : "face_id");
                const int swidth = sd->GetFieldIndex("width_mm");
                Family fam = Family::Fill;
                for (int k = 0; k < kFamilies; ++k)
                    if (lname == family_name(Family(k))) fam = Family(k);
                const double default_width = lname == "crest" ? 0.0 : family_width_mm(fam);
                if (dl->StartTransaction() != OGRERR_NONE)
                    throw Error(Code::OutputExists, "-o '" + path + "': " + last_gdal_error("cannot write a layer"));
                sl->ResetReading();
                OGRFeature feat(dl->GetLayerDefn());
                for (auto& f : *sl) {
                    feat.SetGeometry(f->GetGeometryRef());
                    if (sface >= 0) feat.SetField(0, f->GetFieldAsInteger64(sface));
                    feat.SetField(1, swidth >= 0 ? f->GetFieldAsDouble(swidth) : default_width);
                    feat.SetFID(OGRNullFID);
                    if (dl->CreateFeature(&feat) != OGRERR_NONE)
                        throw Error(Code::OutputExists, "-o '" + path + "': " + last_gdal_error("cannot write a feature"));
                    ++stats.features;
                }
                if (dl->CommitTransaction() != OGRERR_NONE)
                    throw Error(Code::OutputExists, "-o '" + path + "': " + last_gdal_error("cannot write a layer"));
            }
            ++done;
            // Most of the work is the tiling, when the dataset closes; reading is a fifth.
            if (keep_going && !keep_going(0.2 * double(done) / double(zooms.size())))
                throw Error(Code::Cancelled, "cancelled");
        }
        CPLErrorReset();
        GDALDataset* raw = ds.release();
        GDALClose(GDALDataset::ToHandle(raw));
        if (CPLGetLastErrorType() == CE_Failure)
            throw Error(Code::OutputExists, "-o '" + path + "': " + last_gdal_error("cannot write the tiles"));
    }
    if (mbtiles) {
        // How the levels were drawn, for a page that shows them (web/app.js): the scale where a
        // pixel of a 256-pixel tile is kWebPixelMm.
        sqlite3* db = nullptr;
        char sql[160];
        std::snprintf(sql, sizeof sql,
                      "INSERT INTO metadata (name, value) VALUES ('pixel_mm', '%g'), ('tile_px', '256')", kWebPixelMm);
        const bool ok = sqlite3_open_v2(out.path.c_str(), &db, SQLITE_OPEN_READWRITE, nullptr) == SQLITE_OK &&
                        sqlite3_exec(db, sql, nullptr, nullptr, nullptr) == SQLITE_OK;
        sqlite3_close(db);
        if (!ok) throw Error(Code::OutputExists, "-o '" + path + "': cannot complete the tiles' metadata");
        const std::size_t features = stats.features;
        stats = mbtiles_stats(out.path);
        stats.features = features;
    }
    if (!mbtiles && fs::exists(fs::symlink_status(path))) {
        // --overwrite of a folder: only one of tiles (the MVT driver's metadata.json) is replaced.
        std::error_code ec;
        if (!fs::is_directory(path) || !fs::exists(fs::path(path) / "metadata.json"))
            throw Error(Code::OutputExists, "-o '" + path + "': exists and is not a folder of vector tiles");
        fs::remove_all(path, ec);
        if (ec) throw Error(Code::OutputExists, "-o '" + path + "': cannot replace it (" + ec.message() + ")");
    }
    out.commit(path);
    dir_cleanup.keep = true;
    return stats;
}

}  // namespace carto
