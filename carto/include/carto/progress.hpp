// Progress of a long call, and the progress bar every front end shows it with (the command,
// `rockhatch partition`, the Python command and `rockhatch tiles`).
#pragma once

#include <functional>
#include <string>

namespace carto {

// Progress: fraction in [0, 1] and a stage name; return false to cancel.
using Progress = std::function<bool(double, const std::string&)>;

// A one-line bar on standard error, "\r<prefix>[#####    ]  21% stage", redrawn when the
// percentage or the stage changes; off, it prints nothing. As a Progress it never cancels.
class ProgressBar {
public:
    explicit ProgressBar(bool on = false, std::string prefix = "") : on_(on), prefix_(std::move(prefix)) {}
    bool operator()(double fraction, const std::string& stage);
    // Ends an unfinished bar line, so that a following message starts on its own line.
    void finish();

private:
    bool on_;
    std::string prefix_;
    bool open_ = false;
    int last_ = -1;
    std::string stage_;
};

}  // namespace carto
