#include "chaos/error.hpp"
#include "chaos/norm.hpp"

namespace chaos {

const char* to_string(ErrorCode code) noexcept {
  switch (code) {
    case ErrorCode::io: return "io";
    case ErrorCode::parse: return "parse";
    case ErrorCode::empty: return "empty";
    case ErrorCode::non_finite: return "non_finite";
    case ErrorCode::too_short: return "too_short";
    case ErrorCode::constant: return "constant";
    case ErrorCode::invalid_parameter: return "invalid_parameter";
    case ErrorCode::scale: return "scale";
  }
  return "unknown";
}

const char* to_string(Norm norm) noexcept { return norm == Norm::max ? "max" : "euclidean"; }

}  // namespace chaos
