// The rockhatch command line: one option table shared by the C++ program and the Python
// entry point (`python3 -m rockhatch`, style scripts run on their own), so both accept the
// same options with the same messages.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "carto/plan.hpp"
#include "carto/styles.hpp"

namespace carto {

struct CommandLine {
    Options options;
    std::string script;  // --script: a Python style script (run by the Python module)
    bool quiet = false;
    bool list_styles = false;
    bool help = false;
};

// Parses the arguments (without the program name). Throws Error(Usage) naming the option.
CommandLine parse_command_line(const std::vector<std::string>& args);

// The --help text, and the style list of --list-styles.
std::string help_text();
// The option table as --help prints it (name, argument or "" for a flag, help), for the
// man page and the shell completion (apps/make_docs.cpp).
struct OptionHelp {
    std::string name, arg, help;
};
std::vector<OptionHelp> option_table();
// The exit codes' lines of --help.
std::string exit_codes_text();

// A command-line number: the whole of `v`, finite; else Error(Usage) "OPT: 'V' is not a number".
double parse_double(const std::string& opt, const std::string& v);
std::string styles_text();
// One line per parameter, as --list-styles prints them: "name = default unit  help", each
// line indented by `indent` spaces (the style scripts' headers are made from it).
std::string params_text(const std::vector<StyleParam>& params, int indent = 6);

// `rockhatch update`: the command's options (the plan of the run that wrote the files) and
// its own, --reset and --face ID (carto/update.hpp).
struct UpdateCommandLine {
    CommandLine command;
    bool reset = false;
    std::vector<std::int64_t> faces;
};
UpdateCommandLine parse_update_command_line(const std::vector<std::string>& args);
// update's own options (--reset, --face) as --help prints them, and its help text.
std::vector<OptionHelp> update_option_table();
std::string update_help_text();

}  // namespace carto
