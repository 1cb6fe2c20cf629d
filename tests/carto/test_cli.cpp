// The rockhatch option parser and the --param validation: regressions of the checks of
// issue 17 (fuzz/fuzz_cli, fuzz/fuzz_param).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "carto/cli.hpp"
#include "carto/error.hpp"
#include "carto/styles.hpp"

using namespace carto;

namespace {

Code usage_code(const std::vector<std::string>& args) {
    try {
        parse_command_line(args);
    } catch (const Error& e) {
        return e.code();
    }
    return Code::Failure;  // accepted
}

}  // namespace

TEST(CommandLine, IntegersTooLargeForTheirOptionAreRefusedNotWrapped) {
    // unsigned(4294967296) was 0, "all cores"; int(4294967312) was 16, a valid PNG size.
    EXPECT_EQ(usage_code({"--threads", "4294967296"}), Code::Usage);
    EXPECT_EQ(usage_code({"--png-size=4294967312"}), Code::Usage);
    EXPECT_EQ(usage_code({"--seed", "18446744073709551616"}), Code::Usage);
    EXPECT_EQ(parse_command_line({"--threads", "4294967295"}).options.threads, 4294967295u);
    EXPECT_EQ(parse_command_line({"--seed", "18446744073709551615"}).options.seed, 18446744073709551615ull);
    EXPECT_EQ(parse_command_line({"--png-size", "2147483647"}).options.png_pixels, 2147483647);
}

// fuzz/fuzz_param: a --param value valid on paper became +inf (1e308 mm at 1:10000) or 0
// (1e-300 mm at 1:1e-30) in ground units, and reached the styles as an infinite or zero
// spacing. Both are refused with a usage error naming the parameter.
TEST(Params, ValuesThatOverflowOrVanishInGroundUnitsAreRefused) {
    const StyleInfo& noisy = find_style("noisy");
    for (const auto& [value, scale] : std::vector<std::pair<double, double>>{{1e308, 10000}, {1e-300, 1e-30}}) {
        try {
            const ParamValues v = resolve_params(noisy, {{"spacing_min", value}}, scale);
            ADD_FAILURE() << "accepted: spacing_min = " << v.at("spacing_min") << " ground units";
        } catch (const Error& e) {
            EXPECT_EQ(e.code(), Code::Usage);
            EXPECT_NE(std::string(e.what()).find("spacing_min"), std::string::npos) << e.what();
        }
    }
    // Every accepted value is finite, and spacings positive.
    const ParamValues v = resolve_params(noisy, {{"spacing_min", 1e-3}}, 1e-3);
    for (const auto& [name, x] : v) EXPECT_TRUE(std::isfinite(x)) << name;
    EXPECT_GT(v.at("spacing_min"), 0);
}
