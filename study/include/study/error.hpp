#pragma once
// The exception of the study layer: a refused request, naming what was refused, the value and
// the rule (as mechanism::InvalidParameter and chaos::InvalidInput do for their libraries), or a
// result that could not be written (exit 4 in docs/reference/study.md, not 3).

#include <stdexcept>
#include <string>

namespace study {

// The one exception type of the study layer; its kind tells a refused request (exit 3) from a
// result that could not be written (exit 4).
class StudyError : public std::invalid_argument {
 public:
  enum class Kind { refused, io };
  StudyError(const std::string& what, const std::string& value, const std::string& rule, Kind kind = Kind::refused)
      : std::invalid_argument(what + " = " + value + ": " + rule), kind_(kind) {}
  // A message that names the option and the value itself (cli_support's output checks).
  explicit StudyError(const std::string& message, Kind kind = Kind::refused)
      : std::invalid_argument(message), kind_(kind) {}
  Kind kind() const noexcept { return kind_; }

 private:
  Kind kind_;
};

}  // namespace study
