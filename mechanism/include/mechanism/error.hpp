#pragma once
// The one exception type the mechanism library throws for bad input: a scene key, a parameter of a
// contact or friction law, or an integrator setting outside its domain. The message names the key,
// the value and the rule. A simulation that cannot continue (step-size underflow, a non-finite
// state) is not an exception: it is a status in the result.

#include <stdexcept>
#include <string>

namespace mechanism {

class InvalidParameter : public std::invalid_argument {
 public:
  // key: the scene key or parameter name ("joint.slider.clearance"); value: as the user wrote it;
  // rule: what it must satisfy ("must be > 0").
  InvalidParameter(std::string key, std::string value, std::string rule)
      : std::invalid_argument(key + " = " + value + ": " + rule),
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
