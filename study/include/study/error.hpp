#pragma once
// The one exception of the study layer: a refused request, naming what was refused, the value and
// the rule (as mechanism::InvalidParameter and chaos::InvalidInput do for their libraries).

#include <stdexcept>
#include <string>

namespace study {

class StudyError : public std::invalid_argument {
 public:
  StudyError(const std::string& what, const std::string& value, const std::string& rule)
      : std::invalid_argument(what + " = " + value + ": " + rule) {}
};

}  // namespace study
