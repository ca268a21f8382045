#pragma once
// The exceptions of the study layer: a refused request, naming what was refused, the value and
// the rule (as mechanism::InvalidParameter and chaos::InvalidInput do for their libraries), and
// its kind for a result that could not be written (exit 4 in docs/reference/study.md, not 3).

#include <stdexcept>
#include <string>

namespace study {

class StudyError : public std::invalid_argument {
 public:
  StudyError(const std::string& what, const std::string& value, const std::string& rule)
      : std::invalid_argument(what + " = " + value + ": " + rule) {}
  // A message that names the option and the value itself (cli_support's output checks).
  explicit StudyError(const std::string& message) : std::invalid_argument(message) {}
};

class StudyIoError : public StudyError {
 public:
  using StudyError::StudyError;
};

}  // namespace study
