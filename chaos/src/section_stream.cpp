#include "chaos/section_stream.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "chaos/error.hpp"
#include "lagrange.hpp"
#include "numeric.hpp"

namespace chaos {

using detail::format_number;

namespace {

// A section time this close to a sample (as a fraction of the step) is that sample: a whole number
// of steps per period accumulates rounding of a few ulps, not 1e-9 of a step.
constexpr double snap = 1e-9;

// The nodes of the interval [lo, lo + 1] of the window in units of that interval: the cubic uses
// all four samples (lo = 1), the linear form the interval's two ends.
std::size_t nodes(const detail::SampleWindow& w, std::size_t lo, bool cubic, double u[4]) {
  const double h = w.times[lo + 1] - w.times[lo];
  if (!cubic) {
    u[0] = 0.0;
    u[1] = 1.0;
    return 2;
  }
  for (std::size_t k = 0; k < 4; ++k) u[k] = (w.times[k] - w.times[lo]) / h;
  u[lo] = 0.0;
  u[lo + 1] = 1.0;
  return 4;
}

std::vector<double> interpolate(const detail::SampleWindow& w, std::size_t first_node, std::size_t n, const double* u, double s) {
  double weight[4];
  detail::lagrange_weights(u, n, s, weight);
  std::vector<double> point(w.dimension, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    for (std::size_t c = 0; c < w.dimension; ++c) point[c] += weight[k] * w.values[(first_node + k) * w.dimension + c];
  }
  return point;
}

std::vector<double> sample(const detail::SampleWindow& w, std::size_t j) {
  return {w.values.begin() + static_cast<std::ptrdiff_t>(j * w.dimension),
          w.values.begin() + static_cast<std::ptrdiff_t>((j + 1) * w.dimension)};
}

}  // namespace

void detail::SampleWindow::push(double time, std::span<const double> point, const char* who) {
  if (point.size() != dimension) {
    throw InvalidInput(ErrorCode::invalid_parameter, std::string(who) + ": a point of " + std::to_string(point.size()) +
                                                         " components, expected " + std::to_string(dimension));
  }
  if (!std::isfinite(time)) throw InvalidInput(ErrorCode::non_finite, std::string(who) + ": a non-finite time at sample " + std::to_string(count));
  for (double v : point) {
    if (!std::isfinite(v)) throw InvalidInput(ErrorCode::non_finite, std::string(who) + ": a non-finite value at sample " + std::to_string(count) +
                                                                          " (t = " + format_number(time) + ")");
  }
  if (size > 0 && !(time > times[size - 1])) {
    throw InvalidInput(ErrorCode::invalid_parameter, std::string(who) + ": times must increase (sample " + std::to_string(count) + " at t = " +
                                                         format_number(time) + " after t = " + format_number(times[size - 1]) + ")");
  }
  if (size == 4) {
    std::rotate(times.begin(), times.begin() + 1, times.end());
    std::rotate(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(dimension), values.end());
    --size;
  }
  times[size] = time;
  std::copy(point.begin(), point.end(), values.begin() + static_cast<std::ptrdiff_t>(size * dimension));
  ++size;
  ++count;
}

HyperplaneCrossingDetector::HyperplaneCrossingDetector(std::size_t dimension, const HyperplaneOptions& options) : options_(options) {
  if (dimension == 0) throw InvalidInput(ErrorCode::invalid_parameter, "hyperplane crossing detector: the dimension must be >= 1");
  if (options.component >= dimension) {
    throw InvalidInput(ErrorCode::invalid_parameter, "hyperplane crossing detector: component " + std::to_string(options.component) +
                                                         " does not exist (dimension " + std::to_string(dimension) + ")");
  }
  if (!std::isfinite(options.level)) throw InvalidInput(ErrorCode::invalid_parameter, "hyperplane crossing detector: the level must be finite");
  window_.dimension = dimension;
  window_.values.resize(4 * dimension);
}

std::optional<SectionPoint> HyperplaneCrossingDetector::push(double time, std::span<const double> point) {
  if (finished_) throw InvalidInput(ErrorCode::invalid_parameter, "hyperplane crossing detector: a sample pushed after finish()");
  window_.push(time, point, "hyperplane crossing detector");
  // Interval [count-3, count-2] is complete now: cubic when a sample precedes it, linear at the start.
  if (window_.count < 3) return std::nullopt;
  return window_.size == 4 ? examine(1, true) : examine(0, false);
}

std::optional<SectionPoint> HyperplaneCrossingDetector::finish() {
  if (finished_) return std::nullopt;
  finished_ = true;
  if (window_.size < 2) return std::nullopt;
  return examine(window_.size - 2, false);
}

std::optional<SectionPoint> HyperplaneCrossingDetector::examine(std::size_t lo, bool cubic) {
  const auto& w = window_;
  const std::size_t d = w.dimension, k = options_.component;
  const double level = options_.level;
  const double a = w.values[lo * d + k] - level, b = w.values[(lo + 1) * d + k] - level;
  if (!detail::crosses(a, b, options_.direction)) return std::nullopt;
  double u[4];
  const std::size_t n = nodes(w, lo, cubic, u);
  const std::size_t first_node = cubic ? 0 : lo;
  double s;
  if (cubic) {
    // Bisection on the cubic: it passes through the two samples of opposite sign, so [0, 1] brackets a root.
    auto f = [&](double t) {
      double weight[4];
      detail::lagrange_weights(u, 4, t, weight);
      double v = 0.0;
      for (std::size_t j = 0; j < 4; ++j) v += weight[j] * w.values[j * d + k];
      return v - level;
    };
    s = detail::bisect_unit_interval(f, a);
  } else {
    s = a / (a - b);
  }
  SectionPoint out;
  out.time = w.times[lo] + s * (w.times[lo + 1] - w.times[lo]);
  out.point = interpolate(w, first_node, n, u, s);
  out.point[k] = level;  // on the plane by construction
  if (last_crossing_) out.return_time = out.time - *last_crossing_;
  last_crossing_ = out.time;
  return out;
}

StroboscopicSampler::StroboscopicSampler(std::size_t dimension, double period, double phase) : period_(period), phase_(phase) {
  if (dimension == 0) throw InvalidInput(ErrorCode::invalid_parameter, "stroboscopic sampler: the dimension must be >= 1");
  if (!(period > 0.0) || !std::isfinite(period)) {
    throw InvalidInput(ErrorCode::invalid_parameter, "stroboscopic sampler: the period (" + format_number(period) + ") must be finite and > 0");
  }
  if (!std::isfinite(phase)) throw InvalidInput(ErrorCode::invalid_parameter, "stroboscopic sampler: the phase must be finite");
  window_.dimension = dimension;
  window_.values.resize(4 * dimension);
}

std::vector<SectionPoint> StroboscopicSampler::push(double time, std::span<const double> point) {
  if (finished_) throw InvalidInput(ErrorCode::invalid_parameter, "stroboscopic sampler: a sample pushed after finish()");
  window_.push(time, point, "stroboscopic sampler");
  if (window_.count == 1) next_ = static_cast<long long>(std::ceil((time - phase_) / period_ - snap));
  if (window_.count < 3) return {};
  return window_.size == 4 ? examine(1, true, false) : examine(0, false, false);
}

std::vector<SectionPoint> StroboscopicSampler::finish() {
  if (finished_) return {};
  finished_ = true;
  if (window_.size == 1) {  // a single sample: a section point only if it lies on a section time
    const double t = phase_ + static_cast<double>(next_) * period_;
    if (std::abs(t - window_.times[0]) <= snap * period_) return {SectionPoint{t, sample(window_, 0), std::nullopt}};
    return {};
  }
  if (window_.size < 2) return {};
  return examine(window_.size - 2, false, true);
}

std::vector<SectionPoint> StroboscopicSampler::examine(std::size_t lo, bool cubic, bool include_end) {
  const auto& w = window_;
  const double t_low = w.times[lo], h = w.times[lo + 1] - t_low;
  double u[4];
  const std::size_t n = nodes(w, lo, cubic, u);
  const std::size_t first_node = cubic ? 0 : lo;
  std::vector<SectionPoint> out;
  for (;;) {
    const double t = phase_ + static_cast<double>(next_) * period_;  // by multiplication: no drift over a long run
    const double s = (t - t_low) / h;
    if (!(s < 1.0 || (include_end && s <= 1.0 + snap))) break;
    SectionPoint p;
    p.time = t;
    if (std::abs(s) <= snap) p.point = sample(w, lo);
    else if (std::abs(1.0 - s) <= snap) p.point = sample(w, lo + 1);
    else p.point = interpolate(w, first_node, n, u, s);
    out.push_back(std::move(p));
    ++next_;
  }
  return out;
}

}  // namespace chaos
