#pragma once
// The parameter grid of a sweep: one or two axes, each a scene key and its values, and the
// cartesian product of them as numbered points. Point p has coordinate index p % n0 on the first
// axis and p / n0 on the second, so the first axis varies fastest: a continuation chain (the same
// second-axis value, the first axis in order) is a run of consecutive points.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace study {

struct Axis {
  std::string key;             // a scene key, e.g. joint.slider.clearance
  std::vector<double> values;  // in sweep order
};

// "key=from:to:count" (count values equally spaced, both ends included; count = 1 gives from) or
// "key=v1,v2,...". Refuses a missing '=', non-numeric or non-finite values, count = 0 and
// count > 1 with from = to.
Axis parse_axis(std::string_view text);

class Grid {
 public:
  Grid() = default;
  // At most two axes; no axis gives a single point (the scene as it is).
  explicit Grid(std::vector<Axis> axes);

  const std::vector<Axis>& axes() const { return axes_; }
  std::size_t size() const;
  // The index on each axis of point p.
  std::vector<std::size_t> indices(std::size_t point) const;
  std::vector<double> coordinates(std::size_t point) const;
  // The scene overrides "key=value" that make point p (values printed exactly, %.17g).
  std::vector<std::string> overrides(std::size_t point) const;
  // Points sharing every axis index but the first: the chains of a continuation, in order.
  std::size_t chain_length() const { return axes_.empty() ? 1 : axes_[0].values.size(); }
  std::size_t chain_count() const { return size() / chain_length(); }

 private:
  std::vector<Axis> axes_;
};

// A double printed so that reading it back gives the same double (%.17g).
std::string exact(double v);

}  // namespace study
