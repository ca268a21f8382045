// Hostile input the estimators must take in their stride: heavily tied (quantised) series, whose
// neighbour searches must cost about what untied data of the same length cost and whose results
// say that most pairs tie; and series far from magnitude 1, whose estimates must be those of the
// rescaled copy.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include "chaos/cao.hpp"
#include "chaos/choose.hpp"
#include "chaos/correlation_dimension.hpp"
#include "chaos/correlation_sum.hpp"
#include "chaos/embedding.hpp"
#include "chaos/fnn.hpp"
#include "chaos/lyapunov.hpp"
#include "chaos/models/systems.hpp"
#include "chaos/neighbors.hpp"
#include "chaos/nonlinearity_test.hpp"
#include "chaos/series.hpp"
#include "chaos/surrogates.hpp"

namespace {

std::vector<double> lorenz_x(std::size_t n) { return chaos::lorenz(n).components[0]; }

// floor(levels (x - min) / (max - min)), the top value folded into the last level: a series that
// takes only `levels` values, as a coarse converter would give.
std::vector<double> quantised(const std::vector<double>& x, int levels) {
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  std::vector<double> q(x.size());
  for (std::size_t i = 0; i < x.size(); ++i)
    q[i] = std::min<double>(levels - 1, std::floor(levels * (x[i] - *lo) / (*hi - *lo)));
  return q;
}

std::vector<double> times(std::vector<double> x, double f) {
  for (double& v : x) v *= f;
  return x;
}

void expect_relative(double expected, double actual, double tolerance, const std::string& what) {
  EXPECT_LE(std::fabs(actual - expected), tolerance * std::fabs(expected)) << what << ": " << actual << " vs " << expected;
}

// --- ties -------------------------------------------------------------------------------------

// Analytic: 0, 0, 1, 1 has 6 pairs, 2 at distance 0 and 4 at distance 1, each at least 1% of the
// pairs. 0..199 has 19900 pairs, 200 - k of them at distance k: only k = 1 reaches 1% (199 pairs),
// so 199 / 19900 = 1% tie. A smooth series has no repeated distance.
TEST(Ties, FractionOfTiedPairs) {
  const chaos::ValueTies two = chaos::value_ties(std::vector<double>{0, 1, 0, 1});
  EXPECT_EQ(two.distinct, 2u);
  EXPECT_DOUBLE_EQ(two.tied_pairs, 1.0);
  EXPECT_TRUE(two.most_pairs_tie());
  std::vector<double> ramp(200);
  std::iota(ramp.begin(), ramp.end(), 0.0);
  const chaos::ValueTies r = chaos::value_ties(ramp);
  EXPECT_EQ(r.distinct, 200u);
  EXPECT_DOUBLE_EQ(r.tied_pairs, 199.0 / 19900.0);
  EXPECT_FALSE(r.most_pairs_tie());
  const chaos::ValueTies smooth = chaos::value_ties(lorenz_x(3000));
  EXPECT_EQ(smooth.distinct, 3000u);
  EXPECT_EQ(smooth.tied_pairs, 0.0);
  EXPECT_TRUE(chaos::ties_note(smooth).empty());
  const chaos::ValueTies three = chaos::value_ties(quantised(lorenz_x(3000), 3));
  EXPECT_EQ(three.distinct, 3u);
  EXPECT_DOUBLE_EQ(three.tied_pairs, 1.0);
  EXPECT_NE(chaos::ties_note(three).find("takes 3 distinct values"), std::string::npos);
}

// Kantz's neighbourhoods on three-level data: a radius just above the level spacing takes most of
// the series at one distance. The work (pairs followed) must stay within 3 times that of the untied
// series: each tie group is represented by max_tied_neighbours members, while without the thinning
// every member is followed (the count measured here as the control). Without a neighbour cap, as
// chaos analyze runs it.
TEST(Ties, KantzNeighbourhoodsCostWhatUntiedOnesCost) {
  const std::vector<double> x = lorenz_x(5000);
  chaos::LyapunovOptions o;
  o.method = chaos::LyapunovMethod::kantz;
  o.dimension = 3;
  o.delay = 10;
  o.theiler = 10;
  o.steps = 30;
  const chaos::DivergenceCurve untied = chaos::divergence_curve(x, o);
  ASSERT_GT(untied.references_used, 0u);
  EXPECT_EQ(untied.tied_neighbourhoods, 0u);
  const chaos::DivergenceCurve tied = chaos::divergence_curve(quantised(x, 3), o);
  ASSERT_GT(tied.references_used, 0u);
  EXPECT_GT(tied.tied_neighbourhoods, tied.references_used / 2);
  EXPECT_LE(tied.pairs_followed, 3 * untied.pairs_followed)
      << "tied " << tied.pairs_followed << " pairs, untied " << untied.pairs_followed;
  chaos::LyapunovOptions all = o;
  all.max_tied_neighbours = 0;
  const chaos::DivergenceCurve control = chaos::divergence_curve(quantised(x, 3), all);
  EXPECT_GT(control.pairs_followed, 10 * untied.pairs_followed);  // what the thinning saves
  EXPECT_EQ(control.tied_neighbourhoods, 0u);
  // The thinned mean represents the whole neighbourhood: the ln of a mean of 8 draws is biased by
  // about CV^2 / (2 * 8), below 0.07 for a coefficient of variation CV <= 1, and its noise averages
  // out over the ~5000 reference points, so the curves agree within 0.1.
  for (std::size_t k = 0; k <= o.steps; ++k) {
    ASSERT_TRUE(tied.divergence[k] && control.divergence[k]);
    EXPECT_NEAR(*tied.divergence[k], *control.divergence[k], 0.1) << "step " << k;
  }
}

// Property: untied data never have a tie group, so the thinning leaves every curve bit for bit as
// it was (the same values summed in the same order), whatever the cap and the neighbourhood size.
TEST(Ties, ThinningLeavesUntiedCurvesUnchanged) {
  const std::vector<double> x = chaos::henon(3000).components[0];
  for (const std::optional<double> radius : {std::optional<double>(), std::optional<double>(0.5)}) {
    chaos::LyapunovOptions o;
    o.method = chaos::LyapunovMethod::kantz;
    o.dimension = 2;
    o.steps = 10;
    o.radius = radius;
    chaos::LyapunovOptions plain = o;
    plain.max_tied_neighbours = 0;
    const chaos::DivergenceCurve a = chaos::divergence_curve(x, o), b = chaos::divergence_curve(x, plain);
    EXPECT_EQ(a.divergence, b.divergence);
    EXPECT_EQ(a.pairs_followed, b.pairs_followed);
    EXPECT_EQ(a.tied_neighbourhoods, 0u);
  }
}

// The result says so: the Lyapunov and D2 explanations carry the ties note on quantised data and
// not on the untied series.
TEST(Ties, ExplanationsSayMostPairsTie) {
  const std::vector<double> x = lorenz_x(4000);
  chaos::LyapunovOptions o;
  o.dimension = 3;
  o.delay = 10;
  o.theiler = 10;
  o.steps = 30;
  chaos::LyapunovFitOptions fit;
  fit.dimensions = 1;
  const std::string note = "most pairs of samples tie";
  EXPECT_NE(chaos::largest_lyapunov(quantised(x, 3), o, fit).fit.explanation.find(note), std::string::npos);
  EXPECT_EQ(chaos::largest_lyapunov(x, o, fit).fit.explanation.find(note), std::string::npos);
  chaos::CorrelationSumOptions s;
  s.delay = 10;
  s.theiler = 10;
  s.max_dimension = 4;
  s.radii = chaos::log_radii(0.05, 1.5, 12);
  EXPECT_NE(chaos::correlation_dimension(chaos::correlation_sum(quantised(x, 3), s)).explanation.find(note),
            std::string::npos);
  s.radii = chaos::log_radii(0.5, 15.0, 12);
  EXPECT_EQ(chaos::correlation_dimension(chaos::correlation_sum(x, s)).explanation.find(note), std::string::npos);
}

// ... and so do Cao's method, FNN and the surrogate test, whose neighbours are chosen among the same
// ties (a property: the note is ties_note's sentence exactly where most pairs tie).
TEST(Ties, CaoFnnAndTheSurrogateTestSayMostPairsTie) {
  const std::vector<double> x = lorenz_x(3000), q = quantised(x, 3);
  ASSERT_TRUE(chaos::value_ties(q).most_pairs_tie());
  ASSERT_FALSE(chaos::value_ties(x).most_pairs_tie());
  const std::string note = chaos::ties_note(chaos::value_ties(q));
  chaos::CaoOptions c;
  c.delay = 10;
  c.theiler = 10;
  c.max_dimension = 4;
  EXPECT_EQ(chaos::cao(q, c).value_ties, note);
  EXPECT_EQ(chaos::cao(x, c).value_ties, "");
  chaos::FnnOptions f;
  f.delay = 10;
  f.theiler = 10;
  f.max_dimension = 4;
  EXPECT_EQ(chaos::false_nearest_neighbors(q, f).value_ties, note);
  EXPECT_EQ(chaos::false_nearest_neighbors(x, f).value_ties, "");
  chaos::NonlinearityTestOptions t;
  t.surrogates = 3;
  t.statistic = chaos::NonlinearityStatistic::time_reversal_asymmetry;
  EXPECT_EQ(chaos::nonlinearity_test(q, t).value_ties, note);
  EXPECT_EQ(chaos::nonlinearity_test(x, t).value_ties, "");
}

// Brute force: the locally constant predictor written out with k_nearest_brute_force, whose
// neighbours come in (distance, index) order, the order the kd-tree path sums them in.
double prediction_error_brute_force(const std::vector<double>& x, const chaos::PredictionErrorOptions& o) {
  const std::size_t ahead = (o.dimension - 1) * o.delay + o.horizon, p = x.size() - ahead;
  const chaos::DelayEmbedding points(x, o.dimension, o.delay, p);
  double sum = 0.0;
  for (std::size_t i = 0; i < p; ++i) {
    const auto found = chaos::k_nearest_brute_force(points, i, o.neighbours, o.norm, {o.theiler, false});
    double prediction = 0.0;
    for (const auto& nb : found) prediction += x[nb.index + ahead];
    const double e = prediction / static_cast<double>(found.size()) - x[i + ahead];
    sum += e * e;
  }
  double mean = 0.0, ss = 0.0;
  for (const double v : x) mean += v;
  mean /= static_cast<double>(x.size());
  for (const double v : x) ss += (v - mean) * (v - mean);
  return std::sqrt(sum / static_cast<double>(p)) / std::sqrt(ss / static_cast<double>(x.size()));
}

// The prediction error on three-level data (every first coordinate shared by a third of the
// points) takes the kd-tree, and gives the brute-force value exactly.
TEST(Ties, PredictionErrorOnQuantisedDataEqualsBruteForce) {
  const std::vector<double> q = quantised(lorenz_x(1500), 3);
  for (const chaos::Norm norm : {chaos::Norm::max, chaos::Norm::euclidean}) {
    chaos::PredictionErrorOptions o;
    o.dimension = 4;
    o.delay = 5;
    o.neighbours = 7;
    o.theiler = 3;
    o.norm = norm;
    EXPECT_EQ(chaos::prediction_error(q, o), prediction_error_brute_force(q, o));
  }
}

// within() orders a large answer through a bitmap: it must still be brute force's list.
TEST(Ties, LargeNeighbourhoodsEqualBruteForce) {
  const std::vector<double> q = quantised(lorenz_x(2000), 3);
  const chaos::DelayEmbedding points(q, 3, 8);
  const chaos::KdTree tree(points, chaos::Norm::max);
  std::vector<std::size_t> out;
  for (const double radius : {0.5, 1.5, 2.5})
    for (const std::size_t i : {0u, 517u, 1900u}) {
      tree.within(i, radius, out, {10, true});
      EXPECT_EQ(out, chaos::within_brute_force(points, i, radius, chaos::Norm::max, {10, true}))
          << "radius " << radius << ", point " << i;
    }
}

// --- scale ------------------------------------------------------------------------------------

// Lorenz x times 1e-150 and 1e150 (and 1e+-300): Cao's E1 and E2, D2, the prediction error, the
// time-reversal asymmetry and the end-matched segment are those of the unscaled series to 1e-6
// relative (the rescaled copies differ from x by one rounding per value); a surrogate is the
// unscaled one times the factor, and an IAAFT surrogate holds the scaled data's own values.
TEST(Scale, EstimatesOfARescaledCopy) {
  const std::vector<double> x = lorenz_x(5000);
  chaos::CaoOptions cao_options;
  cao_options.delay = 10;
  cao_options.max_dimension = 6;
  const chaos::CaoResult cao = chaos::cao(x, cao_options);
  // chaos d2's automatic choices for this series (delay 17, Theiler window 33).
  const chaos::CorrelationSumOptions s = chaos::choose_correlation_sum_options(x, 17, 33, 10, 40);
  const chaos::CorrelationDimensionResult d2 = chaos::correlation_dimension(chaos::correlation_sum(x, s));
  ASSERT_TRUE(d2.d2) << d2.explanation;
  chaos::PredictionErrorOptions p;
  p.delay = 10;
  p.theiler = 10;
  const double error = chaos::prediction_error(x, p);
  const double asymmetry = chaos::time_reversal_asymmetry(x, 5);
  const chaos::EndMatch match = chaos::end_match(x);
  chaos::SurrogateOptions iaaft;
  iaaft.max_iterations = 20;
  const chaos::Surrogate reference = chaos::surrogates(x, 1, 7, iaaft).front();
  chaos::SurrogateOptions fourier;
  fourier.method = chaos::SurrogateMethod::fourier;
  const chaos::Surrogate reference_ft = chaos::surrogates(x, 1, 7, fourier).front();
  for (const double f : {1e-150, 1e150, 1e-300, 1e300}) {
    const std::string at = "x " + std::to_string(f);
    const std::vector<double> y = times(x, f);
    const chaos::CaoResult c = chaos::cao(y, cao_options);
    ASSERT_EQ(c.E1.size(), cao.E1.size());
    for (std::size_t k = 0; k < cao.E1.size(); ++k) {
      expect_relative(cao.E1[k], c.E1[k], 1e-6, at + " E1");
      expect_relative(cao.E2[k], c.E2[k], 1e-6, at + " E2");
    }
    chaos::CorrelationSumOptions sy = s;
    for (double& r : sy.radii) r *= f;
    const chaos::CorrelationDimensionResult dy = chaos::correlation_dimension(chaos::correlation_sum(y, sy));
    ASSERT_TRUE(dy.d2) << at << ": " << dy.explanation;
    expect_relative(*d2.d2, *dy.d2, 1e-6, at + " D2");
    expect_relative(error, chaos::prediction_error(y, p), 1e-6, at + " prediction error");
    expect_relative(asymmetry, chaos::time_reversal_asymmetry(y, 5), 1e-6, at + " time-reversal asymmetry");
    const chaos::EndMatch m = chaos::end_match(y);
    EXPECT_EQ(m.offset, match.offset) << at;
    EXPECT_EQ(m.length, match.length) << at;
    expect_relative(match.mismatch, m.mismatch, 1e-6, at + " end mismatch");
    const chaos::Surrogate sur = chaos::surrogates(y, 1, 7, iaaft).front();
    std::vector<double> sorted_y(y), sorted_s(sur.values);
    std::sort(sorted_y.begin(), sorted_y.end());
    std::sort(sorted_s.begin(), sorted_s.end());
    EXPECT_EQ(sorted_s, sorted_y) << at << ": an IAAFT surrogate is a permutation of the data";
    expect_relative(reference.spectral_deviation, sur.spectral_deviation, 1e-6, at + " spectral deviation");
    const chaos::Surrogate ft = chaos::surrogates(y, 1, 7, fourier).front();
    for (std::size_t t = 0; t < x.size(); t += 97)
      EXPECT_NEAR(ft.values[t], reference_ft.values[t] * f, 1e-6 * std::fabs(f) * 20.0) << at << ", t = " << t;
  }
}

// Times a power of two the rescaling is exact, so the results are equal bit for bit.
TEST(Scale, PowersOfTwoGiveTheSameBits) {
  const std::vector<double> x = lorenz_x(2000);
  chaos::PredictionErrorOptions p;
  p.delay = 10;
  const double error = chaos::prediction_error(x, p);
  const chaos::EndMatch match = chaos::end_match(x);
  for (const int e : {-900, -500, 500, 900}) {
    std::vector<double> y(x);
    for (double& v : y) v = std::ldexp(v, e);
    EXPECT_EQ(chaos::prediction_error(y, p), error) << "2^" << e;
    EXPECT_EQ(chaos::end_match(y).mismatch, match.mismatch) << "2^" << e;
  }
}

}  // namespace
