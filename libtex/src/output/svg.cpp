// SVG import (elements to curves) and export (curves to a drawing).
#include "libtex/svg.hpp"

#include <tinyxml2.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>

#include "libtex/error.hpp"
#include "libtex/merge.hpp"

namespace tex {
namespace {

// ---------------------------------------------------------------------------------------
// Import

struct Ctx {
    std::string origin;
    Curves* out;
};

[[noreturn]] void fail(const std::string& origin, const std::string& what) {
    throw Error("ImportSVG", "'" + origin + "': " + what);
}

// Tokeniser for path data and point lists: numbers and command letters.
class Tokens {
public:
    Tokens(const char* s, const std::string& origin) : p_(s ? s : ""), origin_(origin) {}
    void skip() {
        while (*p_ && (std::isspace((unsigned char)*p_) || *p_ == ',')) ++p_;
    }
    bool done() { skip(); return *p_ == 0; }
    bool at_command() { skip(); return std::isalpha((unsigned char)*p_) && *p_ != 'e' && *p_ != 'E'; }
    bool at_number() {
        skip();
        return *p_ && (std::isdigit((unsigned char)*p_) || *p_ == '-' || *p_ == '+' || *p_ == '.');
    }
    char command() { skip(); return *p_++; }
    double number() {
        skip();
        char* end = nullptr;
        const double v = std::strtod(p_, &end);
        if (end == p_) fail(origin_, std::string("expected a number at '") + std::string(p_).substr(0, 20) + "'");
        if (!std::isfinite(v)) fail(origin_, std::string("not a finite number at '") + std::string(p_).substr(0, 20) + "'");
        p_ = end;
        return v;
    }
    // Arc flags may be written without separators ("a1 1 0 00 1 1").
    double flag() {
        skip();
        if (*p_ == '0' || *p_ == '1') return double(*p_++ - '0');
        fail(origin_, "bad arc flag");
    }

private:
    const char* p_;
    std::string origin_;
};

Affine parse_transform(const char* s, const std::string& origin) {
    Affine m;
    if (!s) return m;
    std::string str(s);
    std::size_t pos = 0;
    while (true) {
        const std::size_t open = str.find('(', pos);
        if (open == std::string::npos) break;
        const std::size_t close = str.find(')', open);
        if (close == std::string::npos) fail(origin, "unterminated transform '" + str + "'");
        std::string name = str.substr(pos, open - pos);
        name.erase(0, name.find_first_not_of(" \t\n\r,"));
        name.erase(name.find_last_not_of(" \t\n\r,") + 1);
        const std::string args = str.substr(open + 1, close - open - 1);
        Tokens t(args.c_str(), origin);
        std::vector<double> v;
        while (t.at_number()) v.push_back(t.number());
        Affine k;
        auto need = [&](std::size_t lo, std::size_t hi) {
            if (v.size() < lo || v.size() > hi) fail(origin, "bad arguments to transform " + name);
        };
        if (name == "matrix") {
            need(6, 6);
            k = {v[0], v[2], v[4], v[1], v[3], v[5]};
        } else if (name == "translate") {
            need(1, 2);
            k = Affine::translation({v[0], v.size() > 1 ? v[1] : 0.0});
        } else if (name == "scale") {
            need(1, 2);
            k = Affine::scaling(v[0], v.size() > 1 ? v[1] : v[0], {0, 0});
        } else if (name == "rotate") {
            need(1, 3);
            const Point c = v.size() == 3 ? Point{v[1], v[2]} : Point{0, 0};
            k = Affine::rotation(v[0] * pi / 180, c);
        } else if (name == "skewX") {
            need(1, 1);
            k = {1, std::tan(v[0] * pi / 180), 0, 0, 1, 0};
        } else if (name == "skewY") {
            need(1, 1);
            k = {1, 0, 0, std::tan(v[0] * pi / 180), 1, 0};
        } else {
            fail(origin, "unknown transform '" + name + "'");
        }
        m = m.then_after(k);
        pos = close + 1;
    }
    return m;
}

double attr(const tinyxml2::XMLElement* e, const char* name, const std::string& origin, double def = 0.0) {
    const char* s = e->Attribute(name);
    if (!s) return def;
    char* end = nullptr;
    const double v = std::strtod(s, &end);
    if (end == s) return def;
    if (!std::isfinite(v)) fail(origin, std::string("attribute ") + name + " '" + s + "' is not a finite number");
    return v;
}

// The number of pieces of a flattened curve: x rounded up and clamped to [lo, hi] before
// it becomes an int (x is +inf when a radius dwarfs the tolerance, NaN when both are 0).
int pieces(double x, int lo, int hi) {
    if (!(x > lo)) return lo;
    if (x >= hi) return hi;
    return int(std::ceil(x));
}

const char* label_of(const tinyxml2::XMLElement* e) {
    if (const char* l = e->Attribute("data-label")) return l;
    if (const char* l = e->Attribute("inkscape:label")) return l;
    return nullptr;
}

// Flattening: polylines within `tol` of the true curve (tolerance set per file).
struct Flattener {
    double tol;
    void cubic(std::vector<Point>& out, Point p0, Point p1, Point p2, Point p3) const {
        const double len = distance(p0, p1) + distance(p1, p2) + distance(p2, p3);
        const double tol = std::min(this->tol, 2e-3 * len + 1e-300);
        const int n = pieces(std::sqrt(len / tol), 2, 256);
        for (int i = 1; i <= n; ++i) {
            const double t = double(i) / n, u = 1 - t;
            out.push_back(p0 * (u * u * u) + p1 * (3 * u * u * t) + p2 * (3 * u * t * t) + p3 * (t * t * t));
        }
    }
    void quad(std::vector<Point>& out, Point p0, Point p1, Point p2) const {
        cubic(out, p0, p0 + (p1 - p0) * (2.0 / 3), p2 + (p1 - p2) * (2.0 / 3), p2);
    }
    // SVG elliptical arc (implementation notes of the SVG 1.1 specification, F.6.5).
    void arc(std::vector<Point>& out, Point p0, double rx, double ry, double phi_deg, bool large,
             bool sweep, Point p1) const {
        if (p0 == p1) return;
        rx = std::abs(rx);
        ry = std::abs(ry);
        if (rx == 0 || ry == 0) {
            out.push_back(p1);
            return;
        }
        const double phi = phi_deg * pi / 180, cs = std::cos(phi), sn = std::sin(phi);
        const Point d = (p0 - p1) / 2;
        const Point q{cs * d.x + sn * d.y, -sn * d.x + cs * d.y};
        const double lam = q.x * q.x / (rx * rx) + q.y * q.y / (ry * ry);
        if (lam > 1) {
            rx *= std::sqrt(lam);
            ry *= std::sqrt(lam);
        }
        const double num = rx * rx * ry * ry - rx * rx * q.y * q.y - ry * ry * q.x * q.x;
        const double den = rx * rx * q.y * q.y + ry * ry * q.x * q.x;
        double k = den > 0 ? std::sqrt(std::max(0.0, num / den)) : 0;
        if (large == sweep) k = -k;
        const Point cq{k * rx * q.y / ry, -k * ry * q.x / rx};
        const Point c{cs * cq.x - sn * cq.y + (p0.x + p1.x) / 2, sn * cq.x + cs * cq.y + (p0.y + p1.y) / 2};
        auto angle = [](Point u, Point v) {
            const double a = std::atan2(cross(u, v), dot(u, v));
            return a;
        };
        const Point u{(q.x - cq.x) / rx, (q.y - cq.y) / ry};
        const Point v{(-q.x - cq.x) / rx, (-q.y - cq.y) / ry};
        const double t0 = angle({1, 0}, u);
        double dt = angle(u, v);
        if (!sweep && dt > 0) dt -= 2 * pi;
        if (sweep && dt < 0) dt += 2 * pi;
        const double r = std::max(rx, ry);
        const int n = pieces(std::abs(dt) / (2 * std::acos(std::max(-1.0, 1 - tol / r))), 2, 256);
        for (int i = 1; i <= n; ++i) {
            const double t = t0 + dt * i / n;
            const double x = rx * std::cos(t), y = ry * std::sin(t);
            out.push_back(i == n ? p1 : Point{cs * x - sn * y + c.x, sn * x + cs * y + c.y});
        }
    }
    std::vector<Point> ellipse(Point c, double rx, double ry) const {
        const double r = std::max(rx, ry);
        const double tol = std::min(this->tol, 2e-3 * r);  // small circles stay round
        const int n = pieces(2 * pi / (2 * std::acos(std::max(-1.0, 1 - tol / r))), 12, 512);
        std::vector<Point> pts;
        for (int i = 0; i < n; ++i) {
            const double t = 2 * pi * i / n;
            pts.push_back({c.x + rx * std::cos(t), c.y + ry * std::sin(t)});
        }
        return pts;
    }
};

void parse_path(const char* d, const std::string& origin, const Flattener& fl,
                std::vector<std::pair<std::vector<Point>, bool>>& subpaths) {
    Tokens t(d, origin);
    Point cur{0, 0}, start{0, 0}, last_ctrl{0, 0};
    char prev = 0;
    std::vector<Point> pts;
    auto flush = [&](bool closed) {
        if (pts.size() >= 2) subpaths.emplace_back(pts, closed);
        pts.clear();
    };
    char cmd = 0;
    Point base{0, 0};
    auto rd = [&]() {
        const double x = t.number();
        const double y = t.number();
        return base + Point{x, y};
    };
    while (!t.done()) {
        if (t.at_command()) cmd = t.command();
        else if (cmd == 0) fail(origin, "path data does not start with a command");
        const bool rel = std::islower((unsigned char)cmd) != 0;
        base = rel ? cur : Point{0, 0};
        switch (std::toupper((unsigned char)cmd)) {
            case 'M': {
                flush(false);
                cur = rd();
                start = cur;
                pts = {cur};
                cmd = rel ? 'l' : 'L';  // further pairs are line-tos
                break;
            }
            case 'L': {
                cur = rd();
                pts.push_back(cur);
                break;
            }
            case 'H': cur = Point{(rel ? cur.x : 0) + t.number(), cur.y}; pts.push_back(cur); break;
            case 'V': cur = Point{cur.x, (rel ? cur.y : 0) + t.number()}; pts.push_back(cur); break;
            case 'C': {
                const Point c1 = rd();
                const Point c2 = rd();
                const Point p = rd();
                if (pts.empty()) pts = {cur};
                fl.cubic(pts, cur, c1, c2, p);
                last_ctrl = c2;
                cur = p;
                break;
            }
            case 'S': {
                const bool smooth = std::strchr("CcSs", prev) != nullptr;
                const Point c1 = smooth ? cur * 2 - last_ctrl : cur;
                const Point c2 = rd();
                const Point p = rd();
                if (pts.empty()) pts = {cur};
                fl.cubic(pts, cur, c1, c2, p);
                last_ctrl = c2;
                cur = p;
                break;
            }
            case 'Q': {
                const Point c1 = rd();
                const Point p = rd();
                if (pts.empty()) pts = {cur};
                fl.quad(pts, cur, c1, p);
                last_ctrl = c1;
                cur = p;
                break;
            }
            case 'T': {
                const bool smooth = std::strchr("QqTt", prev) != nullptr;
                const Point c1 = smooth ? cur * 2 - last_ctrl : cur;
                const Point p = rd();
                if (pts.empty()) pts = {cur};
                fl.quad(pts, cur, c1, p);
                last_ctrl = c1;
                cur = p;
                break;
            }
            case 'A': {
                const double rx = t.number(), ry = t.number(), rot = t.number();
                const bool large = t.flag() != 0, sweep = t.flag() != 0;
                const Point p = rd();
                if (pts.empty()) pts = {cur};
                fl.arc(pts, cur, rx, ry, rot, large, sweep, p);
                cur = p;
                break;
            }
            case 'Z': {
                if (pts.size() >= 2 && pts.back() == start) pts.pop_back();
                flush(true);
                cur = start;
                pts.clear();
                break;
            }
            default: fail(origin, std::string("unknown path command '") + cmd + "'");
        }
        prev = cmd;
        if (std::toupper((unsigned char)cmd) == 'Z') cmd = 0;
    }
    flush(false);
}

void walk(const tinyxml2::XMLElement* e, const Affine& parent, const Flattener& fl, Ctx& ctx) {
    for (; e; e = e->NextSiblingElement()) {
        std::string name = e->Name();
        if (auto colon = name.find(':'); colon != std::string::npos) name = name.substr(colon + 1);
        if (name == "defs" || name == "metadata" || name == "title" || name == "desc" ||
            name == "namedview" || name == "style" || name == "clipPath" || name == "mask" ||
            name == "symbol" || name == "marker" || name == "pattern")
            continue;
        const Affine m = parent.then_after(parse_transform(e->Attribute("transform"), ctx.origin));
        const char* label = label_of(e);
        std::vector<std::pair<std::vector<Point>, bool>> subpaths;
        if (name == "g" || name == "svg" || name == "a") {
            walk(e->FirstChildElement(), m, fl, ctx);
            continue;
        } else if (name == "path") {
            parse_path(e->Attribute("d"), ctx.origin, fl, subpaths);
        } else if (name == "line") {
            subpaths.push_back({{{attr(e, "x1", ctx.origin), attr(e, "y1", ctx.origin)}, {attr(e, "x2", ctx.origin), attr(e, "y2", ctx.origin)}}, false});
        } else if (name == "polyline" || name == "polygon") {
            Tokens t(e->Attribute("points"), ctx.origin);
            std::vector<Point> pts;
            while (t.at_number()) {
                const double x = t.number();
                if (!t.at_number()) fail(ctx.origin, "odd number of coordinates in <" + name + ">");
                pts.push_back({x, t.number()});
            }
            subpaths.push_back({pts, name == "polygon"});
        } else if (name == "rect") {
            // Percent sizes (a page background) depend on the viewport: not an element.
            const char* ws = e->Attribute("width");
            const char* hs = e->Attribute("height");
            if ((ws && std::strchr(ws, '%')) || (hs && std::strchr(hs, '%'))) continue;
            const double x = attr(e, "x", ctx.origin), y = attr(e, "y", ctx.origin), w = attr(e, "width", ctx.origin), h = attr(e, "height", ctx.origin);
            subpaths.push_back({{{x, y}, {x + w, y}, {x + w, y + h}, {x, y + h}}, true});
        } else if (name == "circle" || name == "ellipse") {
            const Point c{attr(e, "cx", ctx.origin), attr(e, "cy", ctx.origin)};
            if (label) {
                const Point at = m(c);
                if (!std::isfinite(at.x) || !std::isfinite(at.y))
                    fail(ctx.origin, "<" + name + "> has coordinates out of range once transformed");
                ctx.out->points.push_back({at, Labels{label}});
                continue;
            }
            const double rx = name == "circle" ? attr(e, "r", ctx.origin) : attr(e, "rx", ctx.origin);
            const double ry = name == "circle" ? attr(e, "r", ctx.origin) : attr(e, "ry", ctx.origin);
            if (rx <= 0 || ry <= 0) continue;
            subpaths.push_back({fl.ellipse(c, rx, ry), true});
        } else {
            continue;  // text, images and unknown elements carry no curves
        }
        const char* face_label = e->Attribute("data-face-label");
        for (auto& [pts, closed] : subpaths) {
            if (pts.size() < 2) continue;
            Curve c;
            c.points.reserve(pts.size());
            for (const auto& p : pts) {
                c.points.push_back(m(p));
                // Finite numbers can overflow in a transform (scale(1e300)).
                if (!std::isfinite(c.points.back().x) || !std::isfinite(c.points.back().y))
                    fail(ctx.origin, "<" + name + "> has coordinates out of range once transformed");
            }
            c.closed = closed;
            if (label) c.labels.add(label);
            // The face a closed curve encloses gets the label: the inside is on the left of
            // a counter-clockwise ring (positive signed area), on the right otherwise.
            if (face_label && closed && c.points.size() >= 3) {
                const double area = signed_area(c.points);
                if (area > 0) c.left.add(face_label);
                else if (area < 0) c.right.add(face_label);
            }
            ctx.out->curves.push_back(std::move(c));
        }
    }
}

// A first pass finds the drawing's extent so that curves are flattened to a tolerance
// relative to the element's size (one thousandth of its bounding-box diagonal).
double coarse_extent(const tinyxml2::XMLElement* root, const std::string& origin) {
    Curves tmp;
    Ctx ctx{origin, &tmp};
    walk(root, Affine{}, Flattener{1e30}, ctx);
    const BBox b = tmp.bbox();
    if (b.empty()) return 0;
    return std::hypot(b.width(), b.height());
}

}  // namespace

void append_svg_number(std::string& s, double v) {
    if (std::abs(v) < 5e-4 || !std::isfinite(v)) v = 0;
    char buf[400];  // DBL_MAX has 309 digits before the point
    char* end = nullptr;
    // |v| = mant x 2^(exp - 1075) with the 53-bit integer mant of its bits: v x 1000 is
    // mant x 1000 (below 2^63) shifted right by 1075 - exp bits, so the thousandths are an
    // integer division whose remainder decides the rounding exactly (half to even, as
    // std::to_chars does). Out of that range (|v| >= 2^52), std::to_chars itself.
    std::uint64_t bits = 0;
    std::memcpy(&bits, &v, sizeof bits);
    const int exp = int((bits >> 52) & 0x7ff);
    const int shift = 1075 - exp;
    if (v != 0 && shift >= 1 && shift <= 63) {
        const std::uint64_t mant = (bits & ((std::uint64_t(1) << 52) - 1)) | (std::uint64_t(1) << 52);
        const std::uint64_t scaled = mant * 1000u;
        const std::uint64_t rest = scaled & ((std::uint64_t(1) << shift) - 1), half = std::uint64_t(1) << (shift - 1);
        std::uint64_t q = scaled >> shift;
        if (rest > half || (rest == half && (q & 1u))) ++q;
        char* p = buf;
        if (v < 0) *p++ = '-';
        p = std::to_chars(p, buf + sizeof buf, q / 1000).ptr;
        const unsigned frac = unsigned(q % 1000);
        if (frac) {
            *p++ = '.';
            *p++ = char('0' + frac / 100);
            *p++ = char('0' + frac / 10 % 10);
            *p++ = char('0' + frac % 10);
            while (p[-1] == '0') --p;
        }
        end = p;
    } else {
        end = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, 3).ptr;
        while (end > buf && end[-1] == '0') --end;
        if (end > buf && end[-1] == '.') --end;
    }
    s.append(buf, end);
}

Curves ParseSVG(const std::string& text, const std::string& origin) {
    tinyxml2::XMLDocument doc;
    if (doc.Parse(text.c_str(), text.size()) != tinyxml2::XML_SUCCESS)
        fail(origin, std::string("not well-formed XML (") + doc.ErrorStr() + ")");
    const tinyxml2::XMLElement* root = doc.RootElement();
    if (!root || std::string(root->Name()).find("svg") == std::string::npos)
        fail(origin, "the root element is not <svg>");
    const double extent = coarse_extent(root, origin);
    Curves out;
    out.origin = origin;
    Ctx ctx{origin, &out};
    walk(root, Affine{}, Flattener{extent > 0 ? extent * 1e-3 : 1.0}, ctx);
    if (out.curves.empty()) fail(origin, "the file holds no curve");
    return out;
}

Curves ImportSVG(const std::string& filename) {
    std::ifstream in(filename, std::ios::binary);
    if (!in) throw Error("ImportSVG", "'" + filename + "': cannot open the file");
    std::stringstream ss;
    ss << in.rdbuf();
    return ParseSVG(ss.str(), filename);
}

std::string ToSVG(const Curves& c, double size, const SvgStyle& style) {
    BBox view;
    view.add(Point{0, 0});
    view.add(Point{size, size});
    return ToSVG(c, view, style);
}

std::string ToSVG(const Curves& c, const BBox& view, const SvgStyle& style) {
    std::string s;
    s.reserve(64 + c.curves.size() * 64);
    s += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    s += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"";
    append_svg_number(s, view.width());
    s += "\" height=\"";
    append_svg_number(s, view.height());
    s += "\" viewBox=\"";
    append_svg_number(s, view.xmin);
    s += " ";
    append_svg_number(s, view.ymin);
    s += " ";
    append_svg_number(s, view.width());
    s += " ";
    append_svg_number(s, view.height());
    s += "\">\n";
    if (style.background) s += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    s += "<g fill=\"none\" stroke=\"black\" stroke-width=\"";
    append_svg_number(s, style.stroke_width);
    s += "\" stroke-linecap=\"round\" stroke-linejoin=\"round\">\n";
    for (const auto& cv : c.curves) {
        if (cv.points.size() < 2) continue;
        s += cv.closed ? "<polygon points=\"" : "<polyline points=\"";
        bool first = true;
        for (const auto& p : cv.points) {
            if (!first) s += ' ';
            first = false;
            append_svg_number(s, p.x);
            s += ',';
            append_svg_number(s, p.y);
        }
        s += "\"/>\n";
    }
    s += "</g>\n</svg>\n";
    return s;
}

namespace {

// Writes text to filename atomically (a temporary file, then renamed); errors name op.
void write_atomically(const std::string& text, const std::string& filename, const char* op) {
    const std::string tmp = filename + ".tmp";
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        if (!out) throw Error(op, "'" + filename + "': cannot write the file");
        out << text;
        out.flush();
        if (!out) {
            std::remove(tmp.c_str());
            throw Error(op, "'" + filename + "': write failed");
        }
    }
    if (std::rename(tmp.c_str(), filename.c_str()) != 0) {
        std::remove(tmp.c_str());
        throw Error(op, "'" + filename + "': cannot replace the file");
    }
}

}  // namespace

void ExportSVG(const Curves& c, double size, const std::string& filename, const SvgStyle& style) {
    if (!(size > 0) || !std::isfinite(size)) {
        std::ostringstream m;
        m << "size " << size << " is not a positive number";
        throw Error("ExportSVG", m.str());
    }
    write_atomically(ToSVG(c, size, style), filename, "ExportSVG");
}

Curves ExportSVG(const Arrangement& a, double size, const std::string& filename, const SvgStyle& style) {
    if (!(size > 0) || !std::isfinite(size)) {
        std::ostringstream m;
        m << "size " << size << " is not a positive number";
        throw Error("ExportSVG", m.str());
    }
    Curves c = a(Region::rectangle(0, 0, size, size));
    ExportSVG(c, size, filename, style);
    return c;
}

Curves ExportSVGinDomain(const Arrangement& a, const Curves& frame, const std::string& filename,
                         double margin, const SvgStyle& style) {
    if (!(margin >= 0) || !std::isfinite(margin)) {
        std::ostringstream m;
        m << "margin " << margin << " is not a number >= 0";
        throw Error("ExportSVGinDomain", m.str());
    }
    Curves c = EvaluateInDomain(a, frame);
    const BBox b = FrameRegion(frame, "ExportSVGinDomain").bbox();
    BBox view;
    view.add(Point{b.xmin - margin, b.ymin - margin});
    view.add(Point{b.xmax + margin, b.ymax + margin});
    write_atomically(ToSVG(c, view, style), filename, "ExportSVGinDomain");
    return c;
}

}  // namespace tex
