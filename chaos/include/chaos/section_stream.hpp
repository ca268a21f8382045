#pragma once
// Poincaré sections of a trajectory that arrives one sample at a time, as from a simulation's
// observer callback (odeint's obs(x, t), the mechanism's sample sink): nothing is stored but the
// last four samples, so a long run costs no memory.
//
//   HyperplaneCrossingDetector  the crossings of x_k = level, located and interpolated as
//                               hyperplane_section (poincare.hpp) does for a whole series: on the
//                               cubic through the four samples around the crossing (linear in the
//                               first and last interval); the sample times need not be uniform;
//   StroboscopicSampler         the state at t = phase + j period (j = 0, 1, ...): the sample itself
//                               when one falls on that time (a whole number of steps per period),
//                               else the same cubic interpolation in time.
//
// A cubic through samples i-1 .. i+2 needs the sample after the interval, so each result comes
// out one push late; finish() flushes the last interval. Both refuse a point of the wrong size, a
// non-finite value and a time that does not increase.

#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include "chaos/poincare.hpp"

namespace chaos {

struct SectionPoint {
  double time = 0.0;
  std::vector<double> point;          // every component there
  std::optional<double> return_time;  // time since the previous crossing (hyperplane only; none for the first)
};

namespace detail {
// The last (up to) four samples, oldest first.
struct SampleWindow {
  std::size_t dimension = 0;
  std::size_t size = 0;             // samples held, at most 4
  std::size_t count = 0;            // samples pushed in all
  std::array<double, 4> times{};
  std::vector<double> values;       // 4 x dimension, row j = sample j of the window
  void push(double time, std::span<const double> point, const char* who);
};
}  // namespace detail

class HyperplaneCrossingDetector {
 public:
  HyperplaneCrossingDetector(std::size_t dimension, const HyperplaneOptions& options = {});
  // Takes the next sample; returns the crossing in the interval before the previous sample, if any.
  std::optional<SectionPoint> push(double time, std::span<const double> point);
  // Returns the crossing in the last interval, if any; no push is accepted afterwards.
  std::optional<SectionPoint> finish();
  std::size_t samples() const noexcept { return window_.count; }

 private:
  std::optional<SectionPoint> examine(std::size_t first, bool cubic);
  HyperplaneOptions options_;
  detail::SampleWindow window_;
  std::optional<double> last_crossing_;
  bool finished_ = false;
};

class StroboscopicSampler {
 public:
  // Section times phase + j period for j >= 0 with phase + j period >= the first sample's time.
  // period > 0, phase finite.
  StroboscopicSampler(std::size_t dimension, double period, double phase = 0.0);
  // Takes the next sample; returns the section points in the interval before the previous sample
  // (more than one when the sampling is coarser than the period).
  std::vector<SectionPoint> push(double time, std::span<const double> point);
  // Returns the section points in the last interval, its end included.
  std::vector<SectionPoint> finish();

 private:
  std::vector<SectionPoint> examine(std::size_t first, bool cubic, bool include_end);
  double period_, phase_;
  detail::SampleWindow window_;
  long long next_ = 0;  // index j of the next section time
  bool finished_ = false;
};

}  // namespace chaos
