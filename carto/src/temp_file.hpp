// Outputs written atomically: to a temporary name next to the target, renamed over it at
// the end, removed on any failure (internal to carto).
#pragma once

#include <atomic>
#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

#include "carto/error.hpp"

namespace carto {

// Temporary name next to the target, removed on any failure. The name is one that does not
// exist yet (target.part-<pid>-<n><ext>): a file of the user's that happens to carry a
// temporary-looking name is never removed or written over.
struct TempFile {
    std::string path;
    bool keep = false;
    explicit TempFile(const std::string& target, const std::string& ext) {
        static std::atomic<unsigned long> counter{0};
        std::error_code ec;
        do {
            path = target + ".part-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + ext;
        } while (std::filesystem::exists(std::filesystem::symlink_status(path, ec)));
    }
    void commit(const std::string& target) {
        std::error_code ec;
        std::filesystem::rename(path, target, ec);
        if (ec)
            throw Error(Code::OutputExists,
                        "-o '" + target + "': cannot move the result in place (" + ec.message() + ")");
        keep = true;
    }
    ~TempFile() {
        if (!keep) {
            std::error_code ec;
            std::filesystem::remove(path, ec);
        }
    }
};

// Writes 8-bit pixels (`bands` interleaved per pixel, 1 grey or 3 RGB) as a PNG, atomically,
// through GDAL's in-memory and PNG drivers; `what` names the output in error messages.
void write_png_pixels(const std::vector<unsigned char>& pixels, int w, int h, int bands, const std::string& path,
                      const std::string& what);

}  // namespace carto
