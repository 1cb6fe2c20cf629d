// carto errors: each names the input at fault and maps to a distinct exit code of the
// rockhatch command (caught only at the boundaries: CLI, Python, QGIS).
#pragma once

#include <stdexcept>
#include <string>

namespace carto {

enum class Code : int {
    Failure = 1,        // anything else
    Usage = 2,          // bad command line / option value
    InputMissing = 3,   // missing or unreadable file
    NoCrs = 4,          // raster or layer without a CRS
    NoOverlap = 5,      // partition does not overlap the DEM
    BadLayer = 6,       // missing layer or attribute, bad attribute value
    UnknownStyle = 7,   // unknown style or style parameter
    BadGeometry = 8,    // invalid geometry that cannot be repaired
    OutputExists = 9,   // output exists (no --overwrite) or cannot be written
    Cancelled = 10,     // progress callback asked to stop
};

class Error : public std::runtime_error {
public:
    Error(Code code, const std::string& what) : std::runtime_error(what), code_(code) {}
    Code code() const { return code_; }
    int exit_code() const { return int(code_); }

private:
    Code code_;
};

}  // namespace carto
