// Image input for the discrete operators: a grey PGM file as a grid of samples (a field).
#include <cctype>
#include <fstream>
#include <iterator>

#include "libtex/discrete.hpp"
#include "libtex/error.hpp"

namespace tex::disc {

namespace {

// Next header number of a PGM file, skipping blanks and # comments.
long read_header_number(const std::string& s, std::size_t& at, const std::string& file) {
    for (;;) {
        while (at < s.size() && std::isspace(static_cast<unsigned char>(s[at]))) ++at;
        if (at < s.size() && s[at] == '#') {
            while (at < s.size() && s[at] != '\n') ++at;
            continue;
        }
        break;
    }
    const std::size_t start = at;
    while (at < s.size() && std::isdigit(static_cast<unsigned char>(s[at]))) ++at;
    if (at == start || at - start > 9) throw Error("ReadPGM", file + ": malformed header");
    return std::stol(s.substr(start, at - start));
}

}  // namespace

GridSamples ReadPGM(const std::string& filename) {
    std::ifstream in(filename, std::ios::binary);
    if (!in) throw Error("ReadPGM", filename + ": cannot open the file");
    return ParsePGM(
        std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>()),
        filename);
}

GridSamples ParsePGM(const std::string& s, const std::string& filename) {
    if (s.size() < 2 || s[0] != 'P' || (s[1] != '5' && s[1] != '2'))
        throw Error("ReadPGM", filename + ": not a PGM file (P2 or P5)");
    const bool binary = s[1] == '5';
    std::size_t at = 2;
    const long w = read_header_number(s, at, filename), h = read_header_number(s, at, filename),
               maxval = read_header_number(s, at, filename);
    if (w < 1 || h < 1 || w > 100000 || h > 100000 || w * h > 400000000L)
        throw Error("ReadPGM",
                    filename + ": bad size " + std::to_string(w) + " x " + std::to_string(h));
    if (maxval < 1 || maxval > 65535) throw Error("ReadPGM", filename + ": bad maximum value");
    const std::size_t n = std::size_t(w * h);
    const std::size_t bytes = maxval > 255 ? 2 : 1;
    if (binary) ++at;  // the single blank after maxval
    // Enough bytes for every pixel (a text value takes a digit and a blank at least),
    // checked before the pixels are allocated: a short file cannot claim a huge image.
    if (s.size() < at || s.size() - at < (binary ? n * bytes : 2 * n - 1))
        throw Error("ReadPGM", filename + ": truncated pixel data");
    auto values = std::make_shared<std::vector<float>>(n);
    if (binary) {
        for (std::size_t i = 0; i < values->size(); ++i) {
            const auto* p = reinterpret_cast<const unsigned char*>(s.data() + at + i * bytes);
            const unsigned v = bytes == 2 ? (unsigned(p[0]) << 8 | p[1]) : p[0];
            (*values)[i] = float(double(v) / maxval);
        }
    } else {
        for (std::size_t i = 0; i < values->size(); ++i) {
            const long v = read_header_number(s, at, filename);
            if (v > maxval) throw Error("ReadPGM", filename + ": a value exceeds the maximum");
            (*values)[i] = float(double(v) / maxval);
        }
    }
    GridSamples g;
    g.width = int(w);
    g.height = int(h);
    g.transform = {0, 1, 0, double(h), 0, -1};  // one unit per pixel, y up, row 0 at the top
    g.values = std::move(values);
    return g;
}

Region Image(const GridSamples& grid) {
    if (grid.width < 1 || grid.height < 1) throw Error("Image", "the grid is empty");
    BBox b;
    for (double c : {0.0, double(grid.width)})
        for (double r : {0.0, double(grid.height)}) {
            const auto& t = grid.transform;
            b.add(Point{t[0] + c * t[1] + r * t[2], t[3] + c * t[4] + r * t[5]});
        }
    return Region::rectangle(b.xmin, b.ymin, b.xmax, b.ymax);
}

}  // namespace tex::disc
