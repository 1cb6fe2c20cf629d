// An output written atomically: to a temporary name next to the target, renamed over it at
// the end, removed on any failure (internal to carto).
#pragma once

#include <filesystem>
#include <string>

#include "carto/error.hpp"

namespace carto {

// Temporary name next to the target, removed on any failure.
struct TempFile {
    std::string path;
    bool keep = false;
    explicit TempFile(const std::string& target, const std::string& ext)
        : path(target + ".part" + ext) {
        std::error_code ec;
        std::filesystem::remove(path, ec);
    }
    void commit(const std::string& target) {
        std::error_code ec;
        std::filesystem::rename(path, target, ec);
        if (ec) throw Error(Code::OutputExists, "-o '" + target + "': cannot move the result in place (" + ec.message() + ")");
        keep = true;
    }
    ~TempFile() {
        if (!keep) {
            std::error_code ec;
            std::filesystem::remove(path, ec);
        }
    }
};

}  // namespace carto
