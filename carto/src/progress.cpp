#include "carto/progress.hpp"

#include <cstdio>

namespace carto {

bool ProgressBar::operator()(double fraction, const std::string& stage) {
    if (!on_) return true;
    const int pct = int(fraction * 100 + 0.5);
    if (pct == last_ && stage == stage_) return true;
    last_ = pct;
    stage_ = stage;
    open_ = true;
    std::fprintf(stderr, "\r%s[%-25s] %3d%% %-24s", prefix_.c_str(), std::string(std::size_t(pct / 4), '#').c_str(), pct,
                 stage.c_str());
    if (pct >= 100) finish();
    std::fflush(stderr);
    return true;
}

void ProgressBar::finish() {
    if (open_) std::fprintf(stderr, "\n");
    open_ = false;
    std::fflush(stderr);
}

}  // namespace carto
