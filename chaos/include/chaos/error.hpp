#pragma once
// The one exception type the library throws for bad input. A legitimate "no answer" (no
// mutual-information minimum, no saturation) is never an exception: it is a status in the result.

#include <stdexcept>
#include <string>

namespace chaos {

enum class ErrorCode {
  io,                 // file missing or unreadable
  parse,              // a token that is not a number, a column that does not exist
  empty,              // no data at all
  non_finite,         // NaN or infinity in the input
  too_short,          // too few samples for the requested dimension, delay or window
  constant,           // zero variance: no dynamics to analyse
  invalid_parameter,  // a parameter outside its domain (m = 0, tau = 0, negative radius, ...)
  scale,              // values too large or too finely spread for the sums of squares in double
};

// Returns a stable lower-case name for messages and JSON ("too_short", ...).
const char* to_string(ErrorCode code) noexcept;

class InvalidInput : public std::invalid_argument {
 public:
  InvalidInput(ErrorCode code, const std::string& message)
      : std::invalid_argument(message), code_(code) {}
  ErrorCode code() const noexcept { return code_; }

 private:
  ErrorCode code_;
};

// Throws InvalidInput with ErrorCode::invalid_parameter: a parameter outside its domain.
[[noreturn]] inline void refuse_parameter(const std::string& message) {
  throw InvalidInput(ErrorCode::invalid_parameter, message);
}

}  // namespace chaos
