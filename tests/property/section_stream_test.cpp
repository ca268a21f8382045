// Properties of the streaming sections that must hold for any input: on uniformly sampled data the
// detector gives the crossings of the whole-series hyperplane_section (same count, times and
// points to rounding) and the stroboscopic sampler on a whole number of samples per period gives
// stroboscopic_section's samples exactly, for random series, levels, directions and steps.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "chaos/poincare.hpp"
#include "chaos/random.hpp"
#include "chaos/section_stream.hpp"

namespace chaos {
namespace {

TEST(SectionStreamProperty, DetectorEqualsWholeSeriesOnRandomWalks) {
  Random rng(2024);
  for (int trial = 0; trial < 50; ++trial) {
    const std::size_t n = 2 + rng.below(400), dimension = 1 + rng.below(3);
    std::vector<std::vector<double>> c(dimension, std::vector<double>(n));
    for (auto& v : c) {
      double x = rng.gaussian();
      for (auto& e : v) e = x += rng.gaussian();
    }
    const double dt = 0.001 + rng.uniform();
    HyperplaneOptions o;
    o.component = rng.below(dimension);
    o.level = c[o.component][rng.below(n)] + 0.1 * rng.gaussian();
    o.direction = static_cast<CrossingDirection>(rng.below(3));
    const HyperplaneSection whole = hyperplane_section(c, dt, o);
    HyperplaneCrossingDetector detector(dimension, o);
    std::vector<SectionPoint> streamed;
    std::vector<double> point(dimension);
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t k = 0; k < dimension; ++k) point[k] = c[k][i];
      if (auto s = detector.push(static_cast<double>(i) * dt, point)) streamed.push_back(*s);
    }
    if (auto s = detector.finish()) streamed.push_back(*s);
    ASSERT_EQ(streamed.size(), whole.times.size()) << "trial " << trial;
    for (std::size_t j = 0; j < streamed.size(); ++j) {
      EXPECT_NEAR(streamed[j].time, whole.times[j], 1e-9 * (1.0 + whole.times[j])) << "trial " << trial;
      for (std::size_t k = 0; k < dimension; ++k) {
        EXPECT_NEAR(streamed[j].point[k], whole.points[j][k], 1e-8 * (1.0 + std::abs(whole.points[j][k]))) << "trial " << trial;
      }
    }
  }
}

TEST(SectionStreamProperty, SamplerOnWholeStepsEqualsStroboscopicSection) {
  Random rng(7);
  for (int trial = 0; trial < 50; ++trial) {
    const std::size_t period = 1 + rng.below(50), phase = rng.below(period), n = phase + 1 + rng.below(2000);
    const double dt = 0.001 + rng.uniform();
    std::vector<double> x(n);
    for (auto& v : x) v = rng.gaussian();
    StroboscopicSampler sampler(1, static_cast<double>(period) * dt, static_cast<double>(phase) * dt);
    std::vector<double> got;
    for (std::size_t i = 0; i < n; ++i) {
      for (auto& s : sampler.push(static_cast<double>(i) * dt, std::span<const double>(&x[i], 1))) got.push_back(s.point[0]);
    }
    for (auto& s : sampler.finish()) got.push_back(s.point[0]);
    EXPECT_EQ(got, stroboscopic_section(x, period, phase)) << "trial " << trial << ": period " << period << " phase " << phase << " n " << n;
  }
}

}  // namespace
}  // namespace chaos
