// rh_make_docs VERSION MAN_PAGE COMPLETION: writes the rockhatch(1) man page and the bash
// completion from the command's own option table (carto::option_table, the one --help
// prints) and the partition subcommand's usage, so neither can drift from the program.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "carto/cli.hpp"
#include "carto/styles.hpp"

const char* partition_usage();  // apps/partition_cmd.cpp

namespace {

// Text for roff: backslashes escaped, no line read as a request.
std::string roff(const std::string& s) {
    std::string out;
    for (char c : s) out += c == '\\' ? std::string("\\e") : std::string(1, c);
    std::string lines, line;
    std::istringstream in(out);
    while (std::getline(in, line)) {
        if (!line.empty() && (line[0] == '.' || line[0] == '\'')) line = "\\&" + line;
        lines += line + "\n";
    }
    return lines;
}

// An option name or argument in roff: minus signs, not hyphens.
std::string dashes(const std::string& s) {
    std::string out;
    for (char c : s) out += c == '-' ? std::string("\\-") : std::string(1, c);
    return out;
}

// The option names of a usage text: the first word of the lines indented "  -".
std::vector<std::string> usage_options(const std::string& usage) {
    std::vector<std::string> names;
    std::istringstream in(usage);
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("  -", 0) == 0) names.push_back(line.substr(2, line.find(' ', 2) - 2));
    return names;
}

std::string man_page(const std::string& version) {
    std::ostringstream m;
    m << ".TH ROCKHATCH 1 \"\" \"rockhatch " << version << "\" \"User Commands\"\n"
      << ".SH NAME\nrockhatch \\- rock drawing for maps from a DEM and a partition of the rock areas\n"
      << ".SH SYNOPSIS\n.B rockhatch\n\\-\\-dem \\fIDEM\\fR \\-\\-partition \\fIFACES\\fR|auto [\\fIoptions\\fR] "
         "\\-o \\fIOUT\\fR.gpkg|.svg|.png\n.br\n"
      << ".B rockhatch partition\n\\-\\-dem \\fIDEM\\fR \\-o \\fIFACES\\fR.gpkg [\\fIoptions\\fR]\n.br\n"
      << ".B rockhatch tiles\n[\\fIthe options above\\fR] \\-\\-tile\\-size \\fIM\\fR [\\-\\-scheduler \\fIADDRESS\\fR] "
         "\\-o \\fIOUT\\fR.gpkg\n.br\n"
      << ".B rockhatch serve\n\\fIDIR\\fR [\\-\\-port \\fIN\\fR] [\\-\\-dem \\fIDEM\\fR]\n.br\n"
      << ".B rockhatch update\n[\\-\\-reset] [\\-\\-face \\fIID\\fR]... [\\fIthe options of the run\\fR] "
         "\\-o \\fIOUT\\fR.gpkg\n"
      << ".SH DESCRIPTION\n"
      << roff("Draws rock hatching from a DEM and a partition of the rock areas whose borders are labelled ridge, "
              "valley, cliff or other (the partition can be extracted from the DEM with --partition auto or "
              "rockhatch partition). The drawing is a program of libtex operators over each face, steered by "
              "control fields made from the DEM, its slope and its roughness. Outputs are GeoPackage layers, "
              "an SVG at true scale, a PNG preview. The same inputs and seed give the same bytes whatever the "
              "thread count or the tiling. rockhatch tiles runs the same drawing tile by tile on Dask "
              "distributed (see rockhatch tiles --help); rockhatch serve shows the drawing's vector tiles "
              "(MBTiles) on a web map page (see rockhatch serve --help). rockhatch update redraws, in the "
              "GeoPackage a run wrote, only the faces whose inputs changed since, keeping every other feature "
              "(see ROCKHATCH UPDATE).")
      << ".SH OPTIONS\n";
    for (const auto& o : carto::option_table()) {
        m << ".TP\n.B " << dashes(o.name);
        if (!o.arg.empty()) m << " \\fI" << dashes(o.arg) << "\\fR";
        m << "\n" << roff(o.help);
    }
    m << ".SH STYLES\n"
      << roff("Style parameters are millimetres on paper at the map scale, metres on the ground, ratios or "
              "degrees; set them with --param NAME=VALUE.")
      << ".PP\n.nf\n" << roff(carto::styles_text()) << ".fi\n"
      << ".SH \"ROCKHATCH PARTITION\"\n.nf\n" << roff(partition_usage()) << ".fi\n"
      << ".SH \"ROCKHATCH UPDATE\"\n.nf\n" << roff(carto::update_help_text()) << ".fi\n"
      << ".SH \"EXIT STATUS\"\n" << roff(carto::exit_codes_text())
      << ".SH FILES\n.TP\n.I share/rockhatch/data/sample_montblanc\n"
         "a DEM and a hand-drawn partition to try the command on\n"
         ".TP\n.I share/rockhatch/styles\nthe built-in styles as Python style scripts (\\-\\-script)\n"
         ".TP\n.I share/rockhatch/qgis_plugin\nthe QGIS Processing provider and install_qgis_plugin.sh\n"
         ".TP\n.I share/rockhatch/web\nthe web map page of rockhatch serve, with MapLibre GL JS\n"
      << ".SH \"SEE ALSO\"\n.BR gdalinfo (1),\n.BR qgis (1)\n";
    return m.str();
}

std::string join(const std::vector<std::string>& v) {
    std::string s;
    for (const auto& x : v) s += (s.empty() ? "" : " ") + x;
    return s;
}

std::string completion() {
    std::vector<std::string> all, files, styles;
    for (const auto& o : carto::option_table()) {
        all.push_back(o.name);
        if (o.arg.find("PATH") != std::string::npos || o.arg.find(".svg") != std::string::npos) files.push_back(o.name);
    }
    for (const auto& s : carto::styles()) styles.push_back(s.name);
    const std::vector<std::string> part = usage_options(partition_usage());
    std::vector<std::string> update;
    for (const auto& o : carto::update_option_table()) update.push_back(o.name);
    std::string file_case;
    for (const auto& f : files) file_case += (file_case.empty() ? "" : "|") + f;
    std::ostringstream c;
    c << "# bash completion for rockhatch, made from its option table (rh_make_docs)\n"
      << "_rockhatch() {\n"
      << "  local cur=\"${COMP_WORDS[COMP_CWORD]}\" prev=\"${COMP_WORDS[COMP_CWORD-1]}\"\n"
      << "  case \"$prev\" in\n"
      << "    --style) COMPREPLY=($(compgen -W \"" << join(styles) << "\" -- \"$cur\")); return ;;\n"
      << "    " << file_case << "|--png) COMPREPLY=($(compgen -f -- \"$cur\")); return ;;\n"
      << "  esac\n"
      << "  if [ \"${COMP_WORDS[1]}\" = partition ]; then\n"
      << "    COMPREPLY=($(compgen -W \"" << join(part) << "\" -- \"$cur\"))\n"
      << "  elif [ \"$COMP_CWORD\" -eq 1 ]; then\n"
      << "    COMPREPLY=($(compgen -W \"partition tiles serve update " << join(all) << "\" -- \"$cur\"))\n"
      << "  elif [ \"${COMP_WORDS[1]}\" = update ]; then\n"
      << "    COMPREPLY=($(compgen -W \"" << join(update) << " " << join(all) << "\" -- \"$cur\"))\n"
      << "  else\n"
      << "    COMPREPLY=($(compgen -W \"" << join(all) << "\" -- \"$cur\"))\n"
      << "  fi\n"
      << "}\n"
      << "complete -o filenames -o bashdefault -F _rockhatch rockhatch\n";
    return c.str();
}

bool write(const std::string& path, const std::string& text) {
    std::ofstream f(path, std::ios::binary);
    f << text;
    return bool(f.flush());
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: rh_make_docs VERSION MAN_PAGE COMPLETION\n");
        return 2;
    }
    for (const auto& [path, text] : {std::pair{std::string(argv[2]), man_page(argv[1])},
                                     std::pair{std::string(argv[3]), completion()}}) {
        std::error_code ec;
        std::filesystem::create_directories(std::filesystem::path(path).parent_path(), ec);
        if (!write(path, text)) {
            std::fprintf(stderr, "rh_make_docs: cannot write %s\n", path.c_str());
            return 1;
        }
    }
    return 0;
}
