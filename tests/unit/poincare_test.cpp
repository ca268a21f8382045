// Poincaré sections, branch counting and the section PDF. Expected values: the logistic map's
// period doubling (period 2 at r = 3.2, period 4 at r = 3.5, no short period at r = 3.9: May 1976,
// Feigenbaum 1978), a sine's stroboscopic section (analytic), the Lorenz z = 27 section located
// from a coarse sampling against the same trajectory sampled ten times finer (brute force), and a
// histogram's normalisation (a property).

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "chaos/error.hpp"
#include "chaos/poincare.hpp"
#include "chaos/models/systems.hpp"

namespace chaos {
namespace {

TEST(Poincare, LogisticPeriodDoubling) {
  auto branches = [](double r) {
    const Trajectory t = logistic(2000, {r}, 5000);
    return distinct_values(stroboscopic_section(t.components[0], 1), 1e-6);
  };
  EXPECT_EQ(branches(3.2), 2u);
  EXPECT_EQ(branches(3.5), 4u);
  EXPECT_GT(branches(3.9), 100u);
}

TEST(Poincare, StroboscopicSectionOfASineIsOnePoint) {
  // sin(2 pi t) sampled 100 times per period: every 100th sample from phase 25 is sin(pi / 2) = 1.
  const Trajectory t = sine(10'000, 1.0, 0.01);
  const auto section = stroboscopic_section(t.components[0], 100, 25);
  ASSERT_EQ(section.size(), 100u);
  for (double v : section) EXPECT_NEAR(v, section.front(), 1e-9);
  EXPECT_EQ(distinct_values(section, 1e-9), 1u);
}

TEST(Poincare, LorenzSectionMatchesAFinerSampling) {
  FlowSampling coarse;  // dt = 0.01 from RK4 at 0.001: the fine run samples the same trajectory
  FlowSampling fine = coarse;
  fine.dt = 0.001;
  const Trajectory a = lorenz(20'000, {}, coarse), b = lorenz(200'000, {}, fine);
  HyperplaneOptions o;
  o.component = 2;
  o.level = 27.0;
  const HyperplaneSection sa = hyperplane_section(a.components, a.dt, o);
  const HyperplaneSection sb = hyperplane_section(b.components, b.dt, o);
  ASSERT_GT(sa.times.size(), 100u);
  ASSERT_EQ(sa.times.size(), sb.times.size());
  double worst_time = 0, worst_x = 0;
  for (std::size_t j = 0; j < sa.times.size(); ++j) {
    worst_time = std::max(worst_time, std::abs(sa.times[j] - sb.times[j]));
    worst_x = std::max(worst_x, std::abs(sa.points[j][0] - sb.points[j][0]));
    EXPECT_EQ(sa.points[j][2], 27.0);
  }
  // Cubic interpolation on the coarse samples errs by about (dt^4 / 24) 0.56 max|x''''|: with
  // dt = 0.01 and |x''''| up to about 20 x 15^4 (x ~ 20, angular frequencies ~ 15 on the
  // attractor) that is 2e-4 in x, and that over |z'| ~ 100 in time. Linear interpolation would err
  // by dt^2 / 8 |x''| ~ 0.06.
  EXPECT_LT(worst_time, 1e-5);
  EXPECT_LT(worst_x, 5e-4);
  // Upward crossings only, and the return times add up to the span of the crossings.
  double total = 0;
  for (double r : sa.return_times) {
    EXPECT_GT(r, 0.0);
    total += r;
  }
  EXPECT_NEAR(total, sa.times.back() - sa.times.front(), 1e-9);
  // Both directions: the crossings alternate, about twice as many.
  o.direction = CrossingDirection::both;
  const auto both = hyperplane_section(a.components, a.dt, o);
  EXPECT_NEAR(static_cast<double>(both.times.size()), 2.0 * static_cast<double>(sa.times.size()), 1.0);
}

TEST(Poincare, HistogramIsANormalisedDensity) {
  const Trajectory u = uniform_noise(100'000, 3);
  const Histogram h = probability_density(u.components[0], 10, 0.0, 1.0);
  double integral = 0;
  for (std::size_t b = 0; b < 10; ++b) integral += h.density[b] * (h.edges[b + 1] - h.edges[b]);
  EXPECT_NEAR(integral, 1.0, 1e-12);
  // Uniform on [0, 1): density 1 per bin within a few standard errors (sqrt(10 / 1e5) ~ 0.01).
  for (double d : h.density) EXPECT_NEAR(d, 1.0, 0.05);
  EXPECT_EQ(h.in_range + h.out_of_range, 100'000u);
}

TEST(Poincare, RefusesBadInput) {
  const std::vector<double> x = {0.0, 1.0, 2.0};
  EXPECT_THROW(stroboscopic_section(x, 0), InvalidInput);
  EXPECT_THROW(stroboscopic_section(x, 1, 3), InvalidInput);
  EXPECT_THROW(hyperplane_section({{0.0, 1.0}, {0.0}}, 0.1), InvalidInput);
  EXPECT_THROW(hyperplane_section({{0.0, 1.0}}, 0.0), InvalidInput);
  HyperplaneOptions o;
  o.component = 3;
  EXPECT_THROW(hyperplane_section({{0.0, 1.0}}, 0.1, o), InvalidInput);
  EXPECT_THROW(hyperplane_section({{0.0, NAN}}, 0.1), InvalidInput);
  EXPECT_THROW(probability_density(x, 0, 0.0, 1.0), InvalidInput);
  EXPECT_THROW(probability_density(x, 4, 1.0, 1.0), InvalidInput);
  EXPECT_THROW(probability_density(std::vector<double>{}, 4, 0.0, 1.0), InvalidInput);
  // A constant series has one branch, not an error.
  EXPECT_EQ(distinct_values(std::vector<double>(10, 0.5), 0.0), 1u);
}

}  // namespace
}  // namespace chaos
