// The zoo of chaotic systems: the registry, the dual-number Jacobians against central finite
// differences, the delegation to the reference generators, the exact identities of the spectrum
// sum, boundedness and a positive lambda1 from short runs, and the refusals. The converged
// spectra (two lengths, two steps) are the slow test tests/slow/zoo_spectra_test.cpp.

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <regex>
#include <set>

#include "chaos/error.hpp"
#include "chaos/models/generate.hpp"
#include "chaos/models/lyapunov_spectrum.hpp"
#include "chaos/random.hpp"
#include "chaos/models/zoo.hpp"
#include "chaos/models/zoo_suite.hpp"

namespace {

using chaos::ZooEntry;
using chaos::ZooKind;

bool has_equations(const ZooEntry& e) { return !e.delay; }

// Short spectrum settings: a twentieth of the entry's averaging length.
chaos::ZooSpectrumOptions short_run(const ZooEntry& e) {
  chaos::ZooSpectrumOptions o;
  auto f = e.flow_spectrum;
  f.time = std::max(1.0, std::round(f.time / 20.0 / f.renormalisation_interval)) * f.renormalisation_interval;
  o.flow = f;
  auto m = e.map_spectrum;
  m.iterations = m.iterations / 20;
  o.map = m;
  return o;
}

TEST(Zoo, RegistryHasEnoughFlowsAndMapsWithConsistentMetadata) {
  const auto& all = chaos::zoo_systems();
  std::size_t flows = 0, maps = 0;
  std::set<std::string> names;
  const std::regex snake("[a-z][a-z0-9_]*");
  for (const auto& e : all) {
    SCOPED_TRACE(e.name);
    EXPECT_TRUE(std::regex_match(e.name, snake));
    EXPECT_TRUE(names.insert(e.name).second) << "duplicate name";
    (e.kind == ZooKind::flow ? flows : maps)++;
    EXPECT_EQ(e.variables.size(), e.dimension);
    if (e.name != "logistic" && !e.delay) {
      EXPECT_EQ(e.initial_state.size(), e.dimension);
    }
    EXPECT_LT(e.component, e.dimension);
    EXPECT_FALSE(e.citation.empty());
    EXPECT_FALSE(e.equations.empty());
    for (const auto& p : e.parameters) EXPECT_TRUE(std::isfinite(p.value)) << p.name;
    if (e.kind == ZooKind::flow) {
      EXPECT_NO_THROW(e.flow_spectrum.validate());
    }
    if (e.forced) {
      EXPECT_EQ(e.variables.back(), "phi");
    }
    if (!e.dysts_name.empty()) {
      EXPECT_FALSE(e.dysts.exponents.empty()) << "dysts row without values";
    }
    EXPECT_EQ(chaos::find_zoo_system(e.name), &e);
  }
  // The task's floor: at least 28 flows and 12 maps.
  EXPECT_GE(flows, 28u);
  EXPECT_GE(maps, 12u);
  // The five chaotic reference systems and Mackey-Glass are in the one list.
  for (const char* n : {"lorenz", "rossler", "henon", "logistic", "ikeda", "mackey_glass"})
    EXPECT_NE(chaos::find_zoo_system(n), nullptr) << n;
  EXPECT_EQ(chaos::find_zoo_system("no_such_system"), nullptr);
}

TEST(Zoo, LiteratureRowsAreParsedFromTheTable) {
  // The values are those of references/zoo.tsv, quoted from Sprott's table (see its source column).
  const auto& lorenz = chaos::zoo_system("lorenz");
  ASSERT_EQ(lorenz.literature.exponents.size(), 3u);
  EXPECT_DOUBLE_EQ(lorenz.literature.lambda1(), 0.9056);
  EXPECT_DOUBLE_EQ(lorenz.literature.kaplan_yorke, 2.06215);
  EXPECT_FALSE(lorenz.literature.source.empty());
  EXPECT_EQ(lorenz.dysts_name, "Lorenz");
  EXPECT_TRUE(chaos::zoo_system("lozi").literature.empty());
}

// Central differences with a relative step of 1e-6: truncation O(eps^2) and rounding O(1e-16 /
// eps) give an absolute error of order 1e-9 times the size of the terms.
std::vector<double> finite_difference(const std::function<void(std::span<const double>, std::span<double>)>& g,
                                      std::vector<double> x) {
  const std::size_t d = x.size();
  std::vector<double> j(d * d), plus(d), minus(d);
  for (std::size_t k = 0; k < d; ++k) {
    const double x0 = x[k], h = 1e-6 * std::max(1.0, std::abs(x0));
    x[k] = x0 + h;
    g(x, plus);
    x[k] = x0 - h;
    g(x, minus);
    x[k] = x0;
    for (std::size_t i = 0; i < d; ++i) j[i * d + k] = (plus[i] - minus[i]) / (2.0 * h);
  }
  return j;
}

TEST(Zoo, DualJacobianMatchesCentralDifferencesForEverySystem) {
  chaos::Random rng(7);
  for (const auto& e : chaos::zoo_systems()) {
    if (!has_equations(e)) continue;
    SCOPED_TRACE(e.name);
    // States on the attractor (samples of the default trajectory) moved by a random 1 %.
    const chaos::Trajectory t = chaos::zoo_trajectory(e, 8);
    std::function<void(std::span<const double>, std::span<double>)> g, jac;
    if (e.kind == ZooKind::flow) {
      const auto s = chaos::zoo_flow_system(e);
      g = s.field;
      jac = s.jacobian;
    } else {
      const auto s = chaos::zoo_map_system(e);
      g = s.map;
      jac = s.jacobian;
    }
    for (std::size_t n = 0; n < t.size(); ++n) {
      std::vector<double> x(e.dimension);
      for (std::size_t c = 0; c < e.dimension; ++c)
        x[c] = t.components[c][n] * (1.0 + 0.01 * (rng.uniform() - 0.5)) + 0.01 * (rng.uniform() - 0.5);
      std::vector<double> exact(e.dimension * e.dimension);
      jac(x, exact);
      const auto fd = finite_difference(g, x);
      for (std::size_t i = 0; i < exact.size(); ++i)
        EXPECT_NEAR(exact[i], fd[i], 1e-6 * std::max(1.0, std::abs(exact[i]))) << "entry " << i << " at sample " << n;
    }
  }
}

TEST(Zoo, ConstantDivergenceIsTheTraceOrLogDeterminantEverywhere) {
  // The closed forms recorded in the entries (e.g. Lorenz -(sigma + 1 + beta), Henon ln b) against
  // the dual Jacobian at random states.
  chaos::Random rng(11);
  for (const auto& e : chaos::zoo_systems()) {
    if (!e.constant_divergence || !has_equations(e)) continue;
    SCOPED_TRACE(e.name);
    std::vector<double> x(e.dimension), j(e.dimension * e.dimension);
    for (int trial = 0; trial < 5; ++trial) {
      for (auto& v : x) v = 2.0 * rng.uniform() - 1.0;
      if (e.kind == ZooKind::flow) {
        chaos::zoo_flow_system(e).jacobian(x, j);
        double trace = 0.0;
        for (std::size_t i = 0; i < e.dimension; ++i) trace += j[i * e.dimension + i];
        EXPECT_NEAR(trace, e.divergence, 1e-12);
      } else {
        chaos::zoo_map_system(e).jacobian(x, j);
        double det = 0.0;
        if (e.dimension == 2) det = j[0] * j[3] - j[1] * j[2];
        if (e.dimension == 3)
          det = j[0] * (j[4] * j[8] - j[5] * j[7]) - j[1] * (j[3] * j[8] - j[5] * j[6]) + j[2] * (j[3] * j[7] - j[4] * j[6]);
        EXPECT_NEAR(std::log(std::abs(det)), e.divergence, 1e-12);
      }
    }
  }
}

TEST(Zoo, DelegatesReproduceTheReferenceGeneratorsExactly) {
  for (const char* name : {"lorenz", "rossler", "henon", "logistic", "ikeda", "mackey_glass"}) {
    SCOPED_TRACE(name);
    chaos::GenerateRequest r;
    r.system = *chaos::system_from_name(name);
    r.length = 200;
    const auto expected = chaos::generate(r);
    const auto got = chaos::zoo_trajectory(chaos::zoo_system(name), 200);
    EXPECT_EQ(got.components, expected.components);
    EXPECT_EQ(got.dt, expected.dt);
  }
  chaos::MapSpectrumOptions o;
  o.iterations = 20'000;
  chaos::ZooSpectrumOptions zo;
  zo.map = o;
  EXPECT_EQ(chaos::zoo_spectrum(chaos::zoo_system("henon"), {}, zo).exponents, chaos::henon_spectrum({}, o).exponents);
}

TEST(Zoo, GenericEquationsOfDelegatesAgreeWithTheHandWrittenSpectra) {
  // The dual-number Jacobian of the zoo's Lorenz equations drives flow_spectrum along the same
  // orbit as lorenz_spectrum's hand-written Jacobian: over 10 time units (where rounding
  // differences grow at most by e^(0.9 * 10)) the exponents agree to 1e-8.
  chaos::FlowSpectrumOptions o;
  o.time = 10.0;
  o.transient = 0.0;
  const auto generic = chaos::flow_spectrum(chaos::zoo_flow_system(chaos::zoo_system("lorenz")), std::vector<double>{1, 1, 1}, o);
  const auto reference = chaos::lorenz_spectrum({}, o);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR(generic.exponents[i], reference.exponents[i], 1e-8);
}

TEST(Zoo, DelaySchemeIsTheGeneratorsScheme) {
  // The delay spectrum linearises detail::delay_orbit; it must be chaos::mackey_glass bit for bit.
  for (double tau : {17.0, 30.0}) {
    const std::size_t m = tau == 17.0 ? 170 : 300;  // h = tau / m = 0.1 for both
    const auto expected = chaos::mackey_glass(300, {0.2, 0.1, 10.0, tau}, 1.0, m, 100.0);
    const auto got = chaos::detail::delay_orbit({0.2, 0.1, 10.0, tau}, m, 1000, 10, 300);
    EXPECT_EQ(got, expected.components[0]) << "tau = " << tau;
  }
}

// Under AddressSanitizer the two whole-catalogue integrations below run about 20 times slower than in
// Release (124 s and 116 s of CI's sanitizer tier): that build checks every fourth system, the
// Release build every one.
#ifdef __SANITIZE_ADDRESS__
constexpr std::size_t catalogue_stride = 4;
#else
constexpr std::size_t catalogue_stride = 1;
#endif

TEST(Zoo, EverySystemIsBoundedAndChaoticAtItsDefaults) {
  const auto& systems = chaos::zoo_systems();
  for (std::size_t i = 0; i < systems.size(); i += catalogue_stride) {
    const auto& e = systems[i];
    SCOPED_TRACE(e.name);
    chaos::Trajectory t;
    ASSERT_NO_THROW(t = chaos::zoo_trajectory(e, 2000));  // refuses an escaping orbit
    for (const auto& c : t.components)
      for (const double v : c) ASSERT_TRUE(std::isfinite(v));
    const auto s = chaos::zoo_spectrum(e, {}, short_run(e));
    EXPECT_GT(s.exponents.front(), 0.0) << "lambda1 = " << s.exponents.front();
    if (e.hyperchaotic && !e.delay) {
      EXPECT_GT(s.exponents[1], 0.0) << "lambda2 = " << s.exponents[1];
    }
  }
}

TEST(Zoo, SumOfExponentsObeysTheExactIdentities) {
  // Maps: sum = mean ln|det J| exactly (the QR factors multiply to the Jacobian product); flows:
  // sum = time average of trace J up to the RK4 error (the tangent map is the RK4 step's Jacobian).
  const auto& systems = chaos::zoo_systems();
  for (std::size_t i = 0; i < systems.size(); i += catalogue_stride) {
    const auto& e = systems[i];
    if (e.delay || e.name == "logistic") continue;
    SCOPED_TRACE(e.name);
    const auto o = short_run(e);
    const auto s = chaos::zoo_spectrum(e, {}, o);
    const double target = e.constant_divergence ? e.divergence : chaos::zoo_mean_divergence(e, {}, o);
    const double tolerance = e.kind == ZooKind::map ? 1e-9 : 1e-4 * std::max(1.0, std::abs(target));
    EXPECT_NEAR(s.sum, target, tolerance);
  }
}

TEST(Zoo, ParametersAndSamplingAreOverriddenByName) {
  const auto& e = chaos::zoo_system("lozi");
  const auto a = chaos::zoo_trajectory(e, 50, {{"b", 0.3}});
  const auto s = chaos::zoo_spectrum(e, {{"b", 0.3}}, short_run(e));
  EXPECT_NEAR(s.sum, std::log(0.3), 1e-9);  // sum = ln b for any b
  EXPECT_EQ(chaos::zoo_parameters(e, {{"a", 1.5}}), (std::vector<double>{1.5, 0.5}));
  const auto flow = chaos::zoo_trajectory(chaos::zoo_system("thomas"), 10, {{"dt", 0.4}});
  EXPECT_DOUBLE_EQ(flow.dt, 0.4);
}

void expect_invalid(const std::function<void()>& f, const std::string& fragment) {
  try {
    f();
    ADD_FAILURE() << "no exception; expected one mentioning '" << fragment << "'";
  } catch (const chaos::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

// The sampled grid (chaos zoo --grid-points): properties of the rule, no stored expectation.
TEST(ZooGrid, ShortRecordsRunTheWholeGridAndLongOnesASampleThatCoversItOverTheZoo) {
  // N = 10^4, or a sample of 12: all 12 points, each (window, extra) once.
  for (const std::size_t sample : {1u, 2u, 12u}) {
    const auto points = chaos::zoo_grid_points(10000, "lorenz", sample);
    ASSERT_EQ(points.size(), 12u);
    std::set<std::pair<std::size_t, std::size_t>> distinct;
    for (const auto& p : points) {
      EXPECT_LT(p.window, 3u);
      EXPECT_LT(p.extra, 4u);
      distinct.insert({p.window, p.extra});
    }
    EXPECT_EQ(distinct.size(), 12u);
  }
  EXPECT_EQ(chaos::zoo_grid_points(100000, "lorenz", 12).size(), 12u);
  // N = 10^5: `sample` distinct points, the same for a name whatever else is run; over the zoo's
  // systems two points each cover every point of the grid.
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> runs;
  for (const ZooEntry& e : chaos::zoo_systems()) {
    for (const std::size_t sample : {1u, 2u, 3u, 5u}) {
      const auto points = chaos::zoo_grid_points(100000, e.name, sample);
      std::set<std::pair<std::size_t, std::size_t>> distinct;
      for (const auto& p : points) distinct.insert({p.window, p.extra});
      EXPECT_EQ(distinct.size(), sample) << e.name;
    }
    const auto two = chaos::zoo_grid_points(100000, e.name, 2);
    const auto again = chaos::zoo_grid_points(100000, e.name, 2);
    ASSERT_EQ(two.size(), again.size());
    for (std::size_t k = 0; k < two.size(); ++k) {
      EXPECT_EQ(two[k].window, again[k].window);
      EXPECT_EQ(two[k].extra, again[k].extra);
      ++runs[{two[k].window, two[k].extra}];
    }
  }
  EXPECT_EQ(runs.size(), 12u) << "some grid point is run by no system";
}

TEST(Zoo, BadInputIsRefusedWithTheRuleAndTheNumbers) {
  expect_invalid([] { chaos::zoo_system("lorenz85"); }, "valid: lorenz, rossler");
  const auto& e = chaos::zoo_system("chen");
  expect_invalid([&] { chaos::zoo_trajectory(e, 10, {{"q", 1.0}}); }, "no model parameter 'q' (valid: a, b, c)");
  expect_invalid([&] { chaos::zoo_trajectory(e, 10, {{"a", std::nan("")}}); }, "must be finite");
  expect_invalid([&] { chaos::zoo_trajectory(e, 0); }, "at least 1");
  expect_invalid([&] { chaos::zoo_trajectory(e, 10, {{"dt", 0.0015}}); }, "whole multiple");
  expect_invalid([&] { chaos::zoo_spectrum(e, {{"dt", 0.1}}); }, "sampling setting");
  expect_invalid([&] { chaos::zoo_trajectory(e, 10, {{"a", -35.0}}); }, "left every bounded region");
  expect_invalid([] { chaos::zoo_flow_system(chaos::zoo_system("henon")); }, "not an ordinary differential equation");
  chaos::ZooSpectrumOptions o;
  o.delay_exponents = 9;
  expect_invalid([&] { chaos::zoo_spectrum(chaos::zoo_system("mackey_glass"), {}, o); }, "1..8");
}

}  // namespace
