// The largest Lyapunov exponent from data beyond the single rows of references/references.tsv:
// the same bands hold on other stretches of the orbit, other seeds and other embeddings, so the
// rows do not pass by a lucky choice. Values and bands:
//   Hénon (a = 1.4, b = 0.3): lambda1 = 0.41922 per iteration (Sprott 2003), band [0.39, 0.44];
//   logistic r = 4: lambda = ln 2 (analytic, conjugacy to the tent map), band [0.64, 0.74];
//   Lorenz (10, 28, 8/3): lambda1 = 0.9056 per time unit (Sprott 2003), band [0.82, 0.98];
//   Baier & Klein's generalised Henon map (a = 1.76, b = 0.1): lambda_1 from its equations
//     (chaos::zoo_spectrum), band 10% as in the zoo, for the local linear maps at two delays;
// as stated in each test. Each test takes well under a second on one core, but for the local maps'
// (3.4 s in Release, 36 s under the sanitizers: the reference tier keeps it out of that build).
#include "chaos/lyapunov.hpp"
#include "chaos/lyapunov_local_maps.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "chaos/models/systems.hpp"
#include "chaos/models/zoo.hpp"

namespace {

using chaos::LyapunovMethod;
using chaos::LyapunovOptions;

constexpr LyapunovMethod both[] = {LyapunovMethod::rosenstein, LyapunovMethod::kantz};

TEST(LyapunovFromDataReference, HenonOnFourStretchesOfTheOrbit) {
  // Four disjoint stretches of 10^4 iterations (transients 10^3, 1.1 10^4, ...): m = 2, tau = 1.
  for (std::size_t s = 0; s < 4; ++s) {
    const auto x = chaos::henon(10'000, {}, 1'000 + 10'000 * s).components[0];
    for (const auto method : both) {
      LyapunovOptions o;
      o.method = method;
      const auto r = chaos::largest_lyapunov(x, o);
      ASSERT_TRUE(r.fit.lambda.has_value()) << chaos::to_string(method) << " stretch " << s << ": " << r.fit.explanation;
      EXPECT_GE(*r.fit.lambda, 0.39) << chaos::to_string(method) << " stretch " << s;
      EXPECT_LE(*r.fit.lambda, 0.44) << chaos::to_string(method) << " stretch " << s;
      // The interval is the spread of the local slopes over the region: it brackets the fit.
      EXPECT_LE(r.fit.lambda_interval->low, *r.fit.lambda);
      EXPECT_GE(r.fit.lambda_interval->high, *r.fit.lambda);
    }
  }
}

TEST(LyapunovFromDataReference, LogisticOverSeedsAndDimensions) {
  // Five seeded initial conditions, m = 1 and m = 2 (the map is one-dimensional: any m >= 1 embeds it).
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const auto x = chaos::logistic(10'000, {4.0}, 1'000, seed).components[0];
    for (const std::size_t m : {1u, 2u})
      for (const auto method : both) {
        LyapunovOptions o;
        o.method = method;
        o.dimension = m;
        const auto r = chaos::largest_lyapunov(x, o);
        ASSERT_TRUE(r.fit.lambda.has_value()) << chaos::to_string(method) << " seed " << seed << " m " << m << ": "
                                              << r.fit.explanation;
        EXPECT_NEAR(*r.fit.lambda, std::log(2.0), 0.05) << chaos::to_string(method) << " seed " << seed << " m " << m;
      }
  }
}

TEST(LyapunovFromDataReference, LorenzWithAnotherEmbedding) {
  // tau = 10, m = 4, Euclidean norm, 2 10^4 evenly spaced reference points of N = 10^5 (the row
  // uses tau = 17, m = 3, the maximum norm and all points). Per time unit: per sample / 0.01.
  const auto x = chaos::lorenz(100'000).components[0];
  for (const auto method : both) {
    LyapunovOptions o;
    o.method = method;
    o.dimension = 4;
    o.delay = 10;
    o.theiler = 100;
    o.steps = 500;
    o.norm = chaos::Norm::euclidean;
    o.reference_points = 20'000;
    if (method == LyapunovMethod::kantz) o.radius = 0.1;
    const auto r = chaos::largest_lyapunov(x, o, {}, 0.01);
    ASSERT_TRUE(r.lambda_per_time.has_value()) << chaos::to_string(method) << ": " << r.fit.explanation;
    EXPECT_GE(*r.lambda_per_time, 0.82) << chaos::to_string(method);
    EXPECT_LE(*r.lambda_per_time, 0.98) << chaos::to_string(method);
    EXPECT_NEAR(*r.fit.lambda, *r.lambda_per_time * 0.01, 1e-15);
  }
}

// Delay vectors at any delay are smooth changes of coordinates of each other, so lambda_1 does not
// depend on the delay, but the fitted maps do. The generalised Henon map x' = a - y^2 - b z, y' = x,
// z' = y (a = 1.76, b = 0.1) at tau = 2 needs x_{j+1} = (a - x_{j+2}^2 - x_{j+4}) / b for the one-step
// map of its delay vectors: before the delay variants, every other variant agreed on 1.997 per
// sample at N = 5 10^4, nine times lambda_1, with status consistent (docs/reference/lyapunov-maps.md).
TEST(LocalMapsReference, EveryDelayIsRightOrUnsure) {
  const chaos::ZooEntry& entry = chaos::zoo_system("generalized_henon");
  const double expected = chaos::zoo_spectrum(entry).exponents.front();
  const auto x = chaos::zoo_trajectory(entry, 50000).components.front();
  for (const std::size_t tau : {1u, 2u}) {
    chaos::LocalMapOptions o;
    o.dimension = 3;
    o.delay = tau;
    o.theiler = 2;
    const auto r = chaos::largest_lyapunov_local_maps(x, o);
    if (r.status == chaos::LocalMapStatus::consistent) {
      EXPECT_NEAR(*r.lambda, expected, 0.1 * expected) << "tau = " << tau << ": " << r.explanation;
    }
    if (tau == 1) {
      EXPECT_EQ(r.status, chaos::LocalMapStatus::consistent) << r.explanation;  // the natural delay of a map
    }
    EXPECT_EQ(r.variants.size(), tau == 1 ? 9u : 11u) << "tau = " << tau;
  }
}

}  // namespace
