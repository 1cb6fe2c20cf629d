// rh_gallery: writes the Appendix A examples as SVG files.
//
//   rh_gallery [--out DIR] [--only NAME[,NAME...]] [--threads N] [--seed N]
//              [--elements DIR] [--list]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "gallery.hpp"

namespace {

int usage(const char* msg) {
    if (msg) std::cerr << "rh_gallery: " << msg << "\n";
    std::cerr << "usage: rh_gallery [--out DIR] [--only NAME[,NAME...]] [--threads N] [--seed N]\n"
                 "                  [--elements DIR] [--list]\n";
    return 2;
}

bool parse_uint(const std::string& s, unsigned long long& out) {
    if (s.empty() || s.find_first_not_of("0123456789") != std::string::npos) return false;
    out = std::strtoull(s.c_str(), nullptr, 10);
    return true;
}

}  // namespace

int main(int argc, char** argv) {
    std::string out = "gallery_out", only, elements = gallery::default_elements_dir();
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&](const char* opt) -> std::string {
            if (i + 1 >= argc) {
                std::exit(usage((std::string(opt) + " needs a value").c_str()));
            }
            return argv[++i];
        };
        unsigned long long n = 0;
        if (a == "--out") out = value("--out");
        else if (a == "--only") only = value("--only");
        else if (a == "--elements") elements = value("--elements");
        else if (a == "--threads") {
            const std::string v = value("--threads");
            if (!parse_uint(v, n)) return usage(("--threads: '" + v + "' is not a non-negative integer").c_str());
            tex::SetThreads(unsigned(n));
        } else if (a == "--seed") {
            const std::string v = value("--seed");
            if (!parse_uint(v, n)) return usage(("--seed: '" + v + "' is not a non-negative integer").c_str());
            tex::SetSeed(n);
        } else if (a == "--list") {
            for (const auto& e : gallery::examples()) std::cout << e.name << "\t" << e.title << "\n";
            return 0;
        } else if (a == "-h" || a == "--help") {
            usage(nullptr);
            return 0;
        } else {
            return usage(("unknown option '" + a + "'").c_str());
        }
    }
    std::vector<const gallery::Example*> todo;
    try {
        if (only.empty()) {
            for (const auto& e : gallery::examples()) todo.push_back(&e);
        } else {
            std::stringstream ss(only);
            std::string name;
            while (std::getline(ss, name, ',')) todo.push_back(&gallery::find(name));
        }
        std::filesystem::create_directories(out);
        for (const auto* e : todo) {
            const auto t0 = std::chrono::steady_clock::now();
            const tex::Curves c = tex::ExportSVG(e->build(elements), gallery::kSize, out + "/" + e->name + ".svg");
            const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            std::printf("%-10s %7zu curves  %8.3f s  -> %s/%s.svg\n", e->name.c_str(), c.curves.size(), s,
                        out.c_str(), e->name.c_str());
        }
    } catch (const std::exception& ex) {
        std::cerr << "rh_gallery: " << ex.what() << "\n";
        return 1;
    }
    return 0;
}
