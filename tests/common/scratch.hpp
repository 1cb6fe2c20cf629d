// A scratch folder for the files one test process writes. It is made on first use with a
// fresh name (mkdtemp), so tests that ctest runs side by side, or two runs of the suite on
// one machine, never share a file; it is removed with its contents when the process exits.
#pragma once

#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>

namespace rh_test {

inline const std::filesystem::path& scratch_dir() {
    struct Folder {
        std::filesystem::path path;
        Folder() {
            std::string name = (std::filesystem::temp_directory_path() / "rockhatch-test-XXXXXX").string();
            if (!::mkdtemp(name.data())) throw std::runtime_error("cannot make a scratch folder in " + name);
            path = name;
        }
        ~Folder() {
            std::error_code ignored;
            std::filesystem::remove_all(path, ignored);
        }
    };
    static const Folder folder;
    return folder.path;
}

// A path in the scratch folder (its parent folders are made).
inline std::string scratch(const std::string& name) {
    const std::filesystem::path p = scratch_dir() / name;
    std::filesystem::create_directories(p.parent_path());
    return p.string();
}

// An empty folder of that name in the scratch folder (made again if a test made it before).
inline std::filesystem::path fresh_dir(const std::string& name) {
    const std::filesystem::path dir = scratch_dir() / name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

// A file's bytes.
inline std::string file_bytes(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace rh_test
