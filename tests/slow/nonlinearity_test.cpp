// The size of the surrogate test. On a linear Gaussian process the null hypothesis is true, so a
// test at the nominal 5% level (two-sided, K = 39) must reject in about 5% of independent trials
// (Theiler et al. 1992, Physica D 58:77). Data: 200 seeded realisations of the Gaussian AR(1)
// process x_t = 0.9 x_{t-1} + e_t (chaos::ar1's default phi), N = 1024. If the size is exactly
// 5%, the number of rejections is Binomial(200, 0.05): mean 10, standard deviation 3.1; the issue's
// band 3-8% is 6 to 16 rejections, which holds for 91% of seed sets (the seeds are fixed, so the
// outcome here is deterministic).
//
// The two configurations are the ones whose size theory or practice makes exact:
//   - the default test (IAAFT surrogates, zeroth-order prediction error) on the sub-series with
//     the best end-to-end match, as TISEAN advises (Schreiber & Schmitz 2000, Physica D 142:346,
//     Sec. 4.3; end_match with any length). Measured on 1000 other seeds: 5.0%. Untrimmed it
//     rejects in 7.1% (the wrap-around jump adds high-frequency power that the surrogates spread
//     over their whole length, making the data look more predictable), trimmed to lengths 2^a 3^b
//     5^c in 6.0% (docs/reference/nonlinearity_test.md);
//   - time-reversal asymmetry with FT surrogates, which realise the null of a Gaussian linear
//     process exactly (Theiler et al. 1992). Measured on 2000 other seeds: 5.1%. With IAAFT (AAFT)
//     surrogates the same statistic is conservative: 3.75% (3.3%): over 400 other seeds the RMS of
//     Q is 0.075 for the data, 0.077 for FT, 0.083 for AAFT and 0.085 for IAAFT surrogates, so the
//     data's value is too rarely the most extreme.
// About 40 s on one core of the (shared) development machine.
#include "chaos/nonlinearity_test.hpp"

#include <gtest/gtest.h>

#include <span>
#include <string>
#include <vector>

#include "chaos/surrogates.hpp"
#include "chaos/models/systems.hpp"

namespace {

void expect_nominal_size(const chaos::NonlinearityTestOptions& base, bool trim) {
  constexpr int trials = 200;
  chaos::NonlinearityTestOptions o = base;
  int rejected = 0, lowest = 0, highest = 0;
  double rank_sum = 0.0;
  for (int trial = 0; trial < trials; ++trial) {
    const auto x = chaos::ar1(1024, 0.9, 1000 + static_cast<std::uint64_t>(trial)).components[0];
    std::span<const double> series(x);
    if (trim) {
      chaos::EndMatchOptions e;
      e.smooth_lengths = false;
      const auto m = chaos::end_match(x, e);
      series = series.subspan(m.offset, m.length);
    }
    o.seed = 5000 + static_cast<std::uint64_t>(trial);
    const auto r = chaos::nonlinearity_test(series, o);
    rejected += r.test.rejected ? 1 : 0;
    lowest += r.test.rank == 1 ? 1 : 0;
    highest += r.test.rank == o.surrogates + 1 ? 1 : 0;
    rank_sum += static_cast<double>(r.test.rank);
  }
  const std::string summary = std::string(chaos::to_string(o.statistic)) + " with " +
                              chaos::to_string(o.surrogate.method) + " surrogates: " + std::to_string(rejected) +
                              " of 200 rejected (" + std::to_string(lowest) + " lowest, " + std::to_string(highest) +
                              " highest); mean rank " + std::to_string(rank_sum / trials) +
                              " (20.5 if the data are exchangeable with the surrogates)";
  EXPECT_GE(rejected, 6) << summary;
  EXPECT_LE(rejected, 16) << summary;
  ::testing::Test::RecordProperty("summary", summary);
}

TEST(NonlinearityTestSize, DefaultTestOnEndMatchedGaussianAr1) {
  expect_nominal_size(chaos::NonlinearityTestOptions{}, true);
}

TEST(NonlinearityTestSize, TimeReversalWithFourierSurrogatesOnGaussianAr1) {
  chaos::NonlinearityTestOptions o;
  o.statistic = chaos::NonlinearityStatistic::time_reversal_asymmetry;
  o.surrogate.method = chaos::SurrogateMethod::fourier;
  expect_nominal_size(o, false);
}

}  // namespace
