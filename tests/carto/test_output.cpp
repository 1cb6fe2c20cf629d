// Outputs (issue 17): no output onto an input or onto another output, however spelt.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <unistd.h>

#include "carto/error.hpp"
#include "carto/output.hpp"

using namespace carto;
namespace fs = std::filesystem;

namespace {

fs::path fresh_dir(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("rh_test_output_" + std::to_string(::getpid())) / name;
    fs::remove_all(dir);
    fs::create_directories(dir / "sub");
    return dir;
}

std::string bytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// The message of the OutputExists error check_outputs throws (nullopt when it accepts).
std::optional<std::string> refusal(const std::vector<FileArg>& in, const std::vector<FileArg>& out) {
    try {
        check_outputs(in, out, true);
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), Code::OutputExists) << e.what();
        return std::string(e.what());
    }
    return std::nullopt;
}

}  // namespace

TEST(CheckOutputs, RefusesAnInputHoweverItIsSpelt) {
    const fs::path dir = fresh_dir("spelt");
    const fs::path input = dir / "faces.gpkg";
    std::ofstream(input) << "the user's partition";
    fs::create_symlink(input, dir / "link.gpkg");
    fs::create_hard_link(input, dir / "hard.gpkg");
    const std::string in = input.string();
    for (const std::string out : {in, (dir / "." / "faces.gpkg").string(), (dir / "sub" / ".." / "faces.gpkg").string(),
                                  (dir / "link.gpkg").string(), (dir / "hard.gpkg").string()}) {
        const auto msg = refusal({{"--dem", (dir / "none.tif").string()}, {"--partition", in}}, {{"-o", out}});
        ASSERT_TRUE(msg) << out;
        EXPECT_NE(msg->find("-o '" + out + "'"), std::string::npos) << *msg;
        EXPECT_NE(msg->find("--partition '" + in + "'"), std::string::npos) << *msg;
        EXPECT_EQ(msg->find('\n'), std::string::npos);
    }
    // A relative spelling, from the folder of the input.
    const fs::path cwd = fs::current_path();
    fs::current_path(dir / "sub");
    EXPECT_TRUE(refusal({{"--script", "../faces.gpkg"}}, {{"-o", "./../sub/../faces.gpkg"}}));
    fs::current_path(cwd);
    EXPECT_EQ(bytes(input), "the user's partition");
}

TEST(CheckOutputs, RefusesTwoOutputsThatAreOneFile) {
    const fs::path dir = fresh_dir("twice");
    const std::string a = (dir / "out.svg").string(), b = (dir / "sub" / ".." / "out.svg").string();
    const auto msg = refusal({}, {{"-o", a}, {"-o", b}});
    ASSERT_TRUE(msg);
    EXPECT_NE(msg->find(a), std::string::npos);
    EXPECT_NE(msg->find(b), std::string::npos);
    // An existing output and a link to it.
    std::ofstream(a) << "old";
    fs::create_symlink(a, dir / "link.svg");
    EXPECT_TRUE(refusal({}, {{"-o", a}, {"--png", (dir / "link.svg").string()}}));
}

TEST(CheckOutputs, AcceptsOtherFilesAndLeavesMissingInputsToTheirReader) {
    const fs::path dir = fresh_dir("other");
    std::ofstream(dir / "dem.tif") << "dem";
    const std::string dem = (dir / "dem.tif").string();
    EXPECT_FALSE(refusal({{"--dem", dem}, {"--slope", ""}, {"--partition", (dir / "missing.gpkg").string()}},
                         {{"-o", (dir / "missing.gpkg").string()}, {"-o", (dir / "out.svg").string()}, {"--png", ""}}));
    // Without --overwrite an existing output is still refused, named by its option.
    try {
        check_outputs({}, {{"--png", dem}}, false);
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()).rfind("--png '" + dem + "': the file exists", 0), 0u) << e.what();
    }
}
