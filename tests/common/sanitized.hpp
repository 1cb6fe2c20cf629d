// Whether the tests run under the sanitizers (scripts/sanitize.sh sets RH_SANITIZED=1): there
// the slowest tests check their property on fewer repetitions or a smaller input, and the
// normal pass keeps the full versions. Each cut version must still be able to fail.
#pragma once

#include <cstdlib>
#include <cstring>

namespace rh_test {

inline bool sanitized() {
    const char* v = std::getenv("RH_SANITIZED");
    return v && std::strcmp(v, "1") == 0;
}

}  // namespace rh_test
