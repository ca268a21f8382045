#include "chaos/format.hpp"

#include <charconv>
#include <cstdio>

namespace chaos {

std::string format_number(double value, Precision precision) {
  char buffer[64];
  if (precision == Precision::shortest) {
    const auto end = std::to_chars(buffer, buffer + sizeof buffer, value).ptr;
    return std::string(buffer, end);
  }
  const int digits = precision == Precision::round_trip ? 17
                     : precision == Precision::table    ? 12
                     : precision == Precision::result   ? 10
                     : precision == Precision::message  ? 6
                     : precision == Precision::title    ? 4
                                                        : 3;
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  return buffer;
}

}  // namespace chaos
