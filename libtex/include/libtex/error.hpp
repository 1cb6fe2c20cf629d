// The one exception type of libtex: it names the operator and the offending value.
#pragma once

#include <stdexcept>
#include <string>

namespace tex {

class Error : public std::runtime_error {
public:
    Error(std::string op, const std::string& what)
        : std::runtime_error(op + ": " + what), op_(std::move(op)) {}
    const std::string& op() const { return op_; }

private:
    std::string op_;
};

}  // namespace tex
