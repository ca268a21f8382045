// The streaming sections (section_stream.hpp). Expected values: the whole-series functions of
// poincare.hpp on the same samples (an independent implementation of the same cubic, on uniform
// nodes), the zeros of sin t (analytic) under non-uniform steps with the cubic's error bound, a
// sine's stroboscopic values (analytic), and the refusals the header documents.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "chaos/error.hpp"
#include "chaos/poincare.hpp"
#include "chaos/section_stream.hpp"
#include "chaos/models/systems.hpp"

namespace chaos {
namespace {

constexpr double two_pi = 2.0 * std::numbers::pi;

// Feeds every sample of a trajectory to the detector, as an observer callback would.
std::vector<SectionPoint> stream(const Trajectory& t, const HyperplaneOptions& o) {
  HyperplaneCrossingDetector detector(t.components.size(), o);
  std::vector<SectionPoint> out;
  std::vector<double> point(t.components.size());
  for (std::size_t n = 0; n < t.size(); ++n) {
    for (std::size_t k = 0; k < point.size(); ++k) point[k] = t.components[k][n];
    if (auto c = detector.push(static_cast<double>(n) * t.dt, point)) out.push_back(*c);
  }
  if (auto c = detector.finish()) out.push_back(*c);
  return out;
}

TEST(SectionStream, DetectorMatchesTheWholeSeriesSectionOnLorenz) {
  const Trajectory t = lorenz(20'000);
  for (auto direction : {CrossingDirection::upward, CrossingDirection::downward, CrossingDirection::both}) {
    HyperplaneOptions o;
    o.component = 2;
    o.level = 27.0;
    o.direction = direction;
    const HyperplaneSection whole = hyperplane_section(t.components, t.dt, o);
    const auto streamed = stream(t, o);
    ASSERT_GT(whole.times.size(), 100u);
    ASSERT_EQ(streamed.size(), whole.times.size());
    EXPECT_FALSE(streamed.front().return_time.has_value());
    for (std::size_t j = 0; j < streamed.size(); ++j) {
      // Same cubic on nodes -1, 0, 1, 2 (here from the times, there by construction): rounding only.
      EXPECT_NEAR(streamed[j].time, whole.times[j], 1e-9);
      for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(streamed[j].point[k], whole.points[j][k], 1e-9);
      if (j > 0) {
        EXPECT_NEAR(*streamed[j].return_time, whole.return_times[j - 1], 1e-9);
      }
    }
  }
}

TEST(SectionStream, DetectorLocatesZerosOfASineUnderNonUniformSteps) {
  // x = sin t, y = cos t with steps alternating 0.05 and 0.08: upward zeros of x at t = 2 pi k
  // (analytic), where y = 1. Cubic interpolation errs by at most max|f''''| / 24 x 0.5625 h^4
  // (the node polynomial's maximum on the middle interval) ~ 1e-6 for h = 0.08.
  HyperplaneOptions o;
  o.component = 0;
  HyperplaneCrossingDetector detector(2, o);
  std::vector<SectionPoint> found;
  double t = 0.01;
  for (int n = 0; t < 40.0; ++n) {
    const std::vector<double> p = {std::sin(t), std::cos(t)};
    if (auto c = detector.push(t, p)) found.push_back(*c);
    t += n % 2 == 0 ? 0.05 : 0.08;
  }
  if (auto c = detector.finish()) found.push_back(*c);
  ASSERT_EQ(found.size(), 6u);  // 2 pi k for k = 1 .. 6 below 40
  for (std::size_t j = 0; j < found.size(); ++j) {
    EXPECT_NEAR(found[j].time, two_pi * static_cast<double>(j + 1), 2e-6);
    EXPECT_NEAR(found[j].point[1], 1.0, 2e-6);
    EXPECT_EQ(found[j].point[0], 0.0);
    if (j > 0) {
      EXPECT_NEAR(*found[j].return_time, two_pi, 4e-6);
    }
  }
}

TEST(SectionStream, DetectorIsLinearInTheFirstAndLastInterval) {
  // Two samples (0, -1) and (1, 3): the straight line crosses 0 at t = 1/4 (no cubic possible).
  HyperplaneCrossingDetector detector(1);
  EXPECT_FALSE(detector.push(0.0, std::vector<double>{-1.0}));
  EXPECT_FALSE(detector.push(1.0, std::vector<double>{3.0}));
  const auto c = detector.finish();
  ASSERT_TRUE(c);
  EXPECT_DOUBLE_EQ(c->time, 0.25);
  EXPECT_EQ(detector.samples(), 2u);
  EXPECT_FALSE(detector.finish());  // flushed once
}

TEST(SectionStream, StroboscopicSamplerOnWholeStepsIsEveryKthSample) {
  // sin(2 pi t) every 0.01: 100 samples per period, phase 0.25 = sample 25. The sampler must give
  // the samples themselves, bit for bit, as stroboscopic_section(series, 100, 25) does.
  const Trajectory s = sine(10'000, 1.0, 0.01);
  StroboscopicSampler sampler(1, 1.0, 0.25);
  std::vector<SectionPoint> got;
  for (std::size_t n = 0; n < s.size(); ++n) {
    for (auto& p : sampler.push(static_cast<double>(n) * 0.01, std::span<const double>(&s.components[0][n], 1))) got.push_back(p);
  }
  for (auto& p : sampler.finish()) got.push_back(p);
  const auto expected = stroboscopic_section(s.components[0], 100, 25);
  ASSERT_EQ(got.size(), expected.size());
  for (std::size_t j = 0; j < got.size(); ++j) {
    EXPECT_EQ(got[j].point[0], expected[j]);
    EXPECT_DOUBLE_EQ(got[j].time, 0.25 + static_cast<double>(j));
  }
}

TEST(SectionStream, StroboscopicSamplerInterpolatesBetweenSamples) {
  // sin(2 pi t) every 0.03 (no sample on t = 0.25 + j after the first few): the section value is
  // sin(pi / 2) = 1, up to the cubic's error (2 pi)^4 / 24 x 0.5625 x 0.03^4 ~ 3e-5.
  StroboscopicSampler sampler(1, 1.0, 0.25);
  std::vector<SectionPoint> got;
  const std::size_t n = 1000;  // t up to 29.97: section times 0.25 .. 29.25
  for (std::size_t i = 0; i < n; ++i) {
    const double t = 0.03 * static_cast<double>(i), x = std::sin(two_pi * t);
    for (auto& p : sampler.push(t, std::span<const double>(&x, 1))) got.push_back(p);
  }
  for (auto& p : sampler.finish()) got.push_back(p);
  ASSERT_EQ(got.size(), 30u);
  for (const auto& p : got) EXPECT_NEAR(p.point[0], 1.0, 5e-5);
}

TEST(SectionStream, CoarseSamplingGivesSeveralSectionPointsPerSample) {
  // x = t sampled every 2.5 with period 1: every section time is met, and x = t there exactly (the
  // cubic reproduces a straight line).
  StroboscopicSampler sampler(1, 1.0);
  std::vector<SectionPoint> got;
  for (int i = 0; i <= 4; ++i) {
    const double t = 2.5 * i;
    for (auto& p : sampler.push(t, std::span<const double>(&t, 1))) got.push_back(p);
  }
  for (auto& p : sampler.finish()) got.push_back(p);
  ASSERT_EQ(got.size(), 11u);  // t = 0 .. 10
  for (std::size_t j = 0; j < got.size(); ++j) EXPECT_NEAR(got[j].point[0], static_cast<double>(j), 1e-12);
}

TEST(SectionStream, RefusesBadInput) {
  HyperplaneOptions o;
  o.component = 2;
  EXPECT_THROW(HyperplaneCrossingDetector(2, o), InvalidInput);
  EXPECT_THROW(HyperplaneCrossingDetector(0), InvalidInput);
  HyperplaneCrossingDetector d(2);
  EXPECT_THROW(d.push(0.0, std::vector<double>{1.0}), InvalidInput);          // wrong size
  EXPECT_THROW(d.push(0.0, std::vector<double>{1.0, NAN}), InvalidInput);     // non-finite
  d.push(1.0, std::vector<double>{1.0, 2.0});
  EXPECT_THROW(d.push(1.0, std::vector<double>{1.0, 2.0}), InvalidInput);     // time does not increase
  d.finish();
  EXPECT_THROW(d.push(2.0, std::vector<double>{1.0, 2.0}), InvalidInput);     // after finish
  EXPECT_THROW(StroboscopicSampler(1, 0.0), InvalidInput);
  EXPECT_THROW(StroboscopicSampler(1, 1.0, INFINITY), InvalidInput);
  try {
    StroboscopicSampler s(1, 1.0);
    s.push(2.0, std::vector<double>{0.0});
    s.push(1.5, std::vector<double>{0.0});
    FAIL() << "a decreasing time was accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("times must increase"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace chaos
