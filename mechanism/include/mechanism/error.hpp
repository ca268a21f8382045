#pragma once
// The one exception type the mechanism library throws for bad input: a scene key, a parameter of a
// contact or friction law, or an integrator setting outside its domain. The message names the key,
// the value and the rule. A simulation that cannot continue (step-size underflow, a non-finite
// state) is not an exception: it is a status in the result.

#include <cstdio>
#include <stdexcept>
#include <string>

namespace mechanism {

namespace detail {

// The text with every control byte (below 0x20, and 0x7F) written as \xHH: a key or value read
// from a file may hold a NUL, which would end the message where it stands (a key "\u0000x" gave
// the message ""), or a line break or escape sequence that garbles the terminal.
inline std::string escape_control_bytes(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7F) {
      char hex[5];
      std::snprintf(hex, sizeof hex, "\\x%02x", static_cast<unsigned>(u));
      out += hex;
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace detail

class InvalidParameter : public std::invalid_argument {
 public:
  // key: the scene key or parameter name ("joint.slider.clearance"); value: as the user wrote it;
  // rule: what it must satisfy ("must be > 0"). The message escapes control bytes
  // (detail::escape_control_bytes); key(), value() and rule() keep the text as given.
  InvalidParameter(std::string key, std::string value, std::string rule)
      : std::invalid_argument(detail::escape_control_bytes(key + " = " + value + ": " + rule)),
        key_(std::move(key)),
        value_(std::move(value)),
        rule_(std::move(rule)) {}
  const std::string& key() const noexcept { return key_; }
  const std::string& value() const noexcept { return value_; }
  const std::string& rule() const noexcept { return rule_; }

 private:
  std::string key_, value_, rule_;
};

}  // namespace mechanism
