#pragma once
// Private to the library: the checks the law modules share, each refusing with the key, the value
// as the user would write it, and the rule. Written so that NaN and infinities fail.

#include <array>
#include <charconv>
#include <cmath>
#include <string>

#include "mechanism/error.hpp"

namespace mechanism::detail {

// Shortest round-trip text of a value, for the message of InvalidParameter.
inline std::string text(double v) {
  std::array<char, 32> buf{};
  const auto res = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  return std::string(buf.data(), res.ptr);
}

inline void require_positive(const char* key, double v) {
  if (!(std::isfinite(v) && v > 0.0)) throw InvalidParameter(key, text(v), "must be finite and > 0");
}

inline void require_non_negative(const char* key, double v) {
  if (!(std::isfinite(v) && v >= 0.0)) throw InvalidParameter(key, text(v), "must be finite and >= 0");
}

}  // namespace mechanism::detail
