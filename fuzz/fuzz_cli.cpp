// libFuzzer target: the rockhatch option parser (carto::parse_command_line, all that main
// does before running the pipeline). The bytes are the arguments, separated by NUL bytes.
// The only expected failure is carto::Error(Usage); the pipeline never runs.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "carto/cli.hpp"
#include "carto/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::vector<std::string> args(1);
    for (std::size_t i = 0; i < size; ++i) {
        if (data[i] == 0) args.emplace_back();
        else args.back() += char(data[i]);
    }
    if (args.size() == 1 && args[0].empty()) args.clear();
    try {
        const carto::CommandLine cl = carto::parse_command_line(args);
        if (cl.help) (void)carto::help_text();
    } catch (const carto::Error& e) {
        if (e.code() != carto::Code::Usage) std::abort();
    }
    return 0;
}
