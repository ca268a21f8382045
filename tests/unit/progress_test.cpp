// The progress callbacks of the long estimators (the commands draw them): every
// report is a fraction in [0, 1] that never goes back, some are made, and the result is the one
// computed without a callback. Expected values are the same calls without `progress`.

#include <gtest/gtest.h>

#include <functional>
#include <vector>

#include "chaos/cao.hpp"
#include "chaos/fnn.hpp"
#include "chaos/models/generate.hpp"
#include "chaos/lyapunov.hpp"
#include "chaos/nonlinearity_test.hpp"
#include "chaos/surrogates.hpp"

namespace {

// Records the fractions reported.
struct Reports {
  std::vector<double> fractions;
  std::function<void(double)> callback() {
    return [this](double f) { fractions.push_back(f); };
  }
  void expect_sane() const {
    ASSERT_FALSE(fractions.empty());
    for (std::size_t k = 0; k < fractions.size(); ++k) {
      EXPECT_GE(fractions[k], 0.0);
      EXPECT_LE(fractions[k], 1.0);
      if (k > 0) {
        EXPECT_GE(fractions[k], fractions[k - 1]) << "report " << k;
      }
    }
  }
};

std::vector<double> henon(std::size_t n) {
  return chaos::generate({chaos::SystemKind::henon, n, {}, 1}).components[0];
}

TEST(Progress, CaoAndFnn) {
  const auto x = henon(20000);
  chaos::CaoOptions c;
  c.max_dimension = 4;
  Reports cao_reports;
  chaos::CaoOptions with = c;
  with.progress = cao_reports.callback();
  EXPECT_EQ(chaos::cao(x, with).E1, chaos::cao(x, c).E1);
  cao_reports.expect_sane();
  chaos::FnnOptions f;
  f.max_dimension = 4;
  Reports fnn_reports;
  chaos::FnnOptions fwith = f;
  fwith.progress = fnn_reports.callback();
  EXPECT_EQ(chaos::false_nearest_neighbors(x, fwith).false_fraction, chaos::false_nearest_neighbors(x, f).false_fraction);
  fnn_reports.expect_sane();
}

TEST(Progress, LyapunovOnTwoThreads) {
  const auto x = henon(20000);
  for (const auto method : {chaos::LyapunovMethod::rosenstein, chaos::LyapunovMethod::kantz}) {
    chaos::LyapunovOptions l;
    l.method = method;
    l.threads = 2;
    Reports reports;
    chaos::LyapunovOptions with = l;
    with.progress = reports.callback();
    EXPECT_EQ(chaos::divergence_curve(x, with).divergence, chaos::divergence_curve(x, l).divergence);
    reports.expect_sane();
  }
}

TEST(Progress, SurrogatesAndTheNonlinearityTest) {
  const auto x = henon(2048);
  chaos::SurrogateOptions s;
  Reports reports;
  chaos::SurrogateOptions with = s;
  with.progress = reports.callback();
  const auto a = chaos::surrogates(x, 3, 7, with), b = chaos::surrogates(x, 3, 7, s);
  for (std::size_t k = 0; k < 3; ++k) EXPECT_EQ(a[k].values, b[k].values);
  reports.expect_sane();
  EXPECT_EQ(reports.fractions.back(), 1.0);
  chaos::NonlinearityTestOptions t;
  t.surrogates = 5;
  Reports test_reports;
  chaos::NonlinearityTestOptions twith = t;
  twith.progress = test_reports.callback();
  EXPECT_EQ(chaos::nonlinearity_test(x, twith).surrogate_statistics, chaos::nonlinearity_test(x, t).surrogate_statistics);
  test_reports.expect_sane();
  EXPECT_EQ(test_reports.fractions.back(), 1.0);
}

}  // namespace
