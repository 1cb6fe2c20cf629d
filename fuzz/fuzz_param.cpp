// libFuzzer target: --param values. The first line of the input is a style name (or empty:
// every built-in style), the second a map scale, each further line the value of one
// `--param NAME=VALUE`. They go through the command line parser, then through the style
// table's parameter validation (carto::resolve_params), which must either accept them
// (finite values in ground units) or refuse them with carto::Error (Usage, UnknownStyle).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "carto/cli.hpp"
#include "carto/error.hpp"
#include "carto/styles.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::vector<std::string> lines(1);
    for (std::size_t i = 0; i < size; ++i) {
        if (data[i] == '\n') lines.emplace_back();
        else if (data[i] != 0) lines.back() += char(data[i]);  // argv strings hold no NUL
    }
    while (lines.size() < 2) lines.emplace_back();
    std::vector<std::string> args;
    if (!lines[0].empty()) args.insert(args.end(), {"--style", lines[0]});
    if (!lines[1].empty()) args.push_back("--scale=" + lines[1]);
    for (std::size_t i = 2; i < lines.size(); ++i)
        if (!lines[i].empty()) args.insert(args.end(), {"--param", lines[i]});
    carto::CommandLine cl;
    try {
        cl = carto::parse_command_line(args);
    } catch (const carto::Error& e) {
        if (e.code() != carto::Code::Usage) std::abort();
        return 0;
    }
    // carto::validate checks the scale before the parameters.
    if (!(cl.options.scale > 0) || !std::isfinite(cl.options.scale)) return 0;
    std::vector<const carto::StyleInfo*> which;
    try {
        if (cl.options.style.empty())
            for (const auto& s : carto::styles()) which.push_back(&s);
        else
            which.push_back(&carto::find_style(cl.options.style));
    } catch (const carto::Error& e) {
        if (e.code() != carto::Code::UnknownStyle) std::abort();
        return 0;
    }
    for (const carto::StyleInfo* s : which) {
        try {
            const carto::ParamValues v = carto::resolve_params(*s, cl.options.params, cl.options.scale);
            for (const auto& [name, x] : v)
                if (!std::isfinite(x)) std::abort();  // accepted values reach the styles finite
        } catch (const carto::Error& e) {
            if (e.code() != carto::Code::Usage && e.code() != carto::Code::UnknownStyle) std::abort();
        }
    }
    return 0;
}
