// The simulator's finite-difference Lyapunov method (mechanism/finite_difference_lyapunov.hpp)
// against the chaos library's variational spectrum (chaos::zoo_spectrum, QR on the tangent
// equations) on the forced oscillators of the zoo, Duffing and Ueda: the same equations
// (chaos::zoo_flow_system), integrated here with the simulator's RK4 over one forcing period per
// iteration. The stroboscopic map's exponents per period divided by the period are the flow's
// nonzero exponents (the phase adds the flow's zero). The bar: agreement to 1e-3. The sum
// has an exact value, -damping (the divergence of the field), for both.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "chaos/models/zoo.hpp"
#include "mechanism/finite_difference_lyapunov.hpp"
#include "mechanism/rk4.hpp"

namespace {

struct Field {
  const chaos::FlowSystem* flow;
  void rhs(double, const mechanism::State& x, mechanism::State& dxdt) const {
    flow->field(std::span<const double>(x.data(), 3), std::span<double>(dxdt.data(), 3));
  }
};

// One forcing period of a forced oscillator (x, v, phase) as a map of (x, v).
struct ForcedPeriod {
  const chaos::FlowSystem* flow;
  double period = 0.0;
  int steps = 200;
  mechanism::State x = mechanism::State::Zero(3);
  Eigen::VectorXd phase_point() const { return x.head(2); }
  void set_phase_point(const Eigen::VectorXd& p) { x.head(2) = p; }
  bool advance() {
    mechanism::Rk4 rk4;
    const Field f{flow};
    x[2] = 0.0;  // every iteration starts at forcing phase 0
    double t = 0.0;
    for (int i = 0; i < steps; ++i) rk4.step(f, t, x, period / steps);
    return x.allFinite();
  }
};

void compare(const std::string& name, double damping) {
  const chaos::ZooEntry& entry = chaos::zoo_system(name);
  const chaos::LyapunovSpectrum reference = chaos::zoo_spectrum(entry);  // its converged settings
  const chaos::FlowSystem flow = chaos::zoo_flow_system(entry);
  const std::vector<double> p = chaos::zoo_parameters(entry);
  const double omega = p.back();  // both entries list the forcing frequency last
  ForcedPeriod map{&flow, 2.0 * M_PI / omega};
  map.x << entry.initial_state[0], entry.initial_state[1], 0.0;
  for (int i = 0; i < 50; ++i) map.advance();  // onto the attractor

  mechanism::FiniteDifferenceOptions o;
  o.exponents = 2;
  o.transient = 100;
  o.iterations = static_cast<std::size_t>(40'000.0 / map.period);  // the reference's length, 40 000
  const auto r = mechanism::finite_difference_lyapunov(map, o);
  ASSERT_EQ(r.status, mechanism::FiniteDifferenceLyapunov::Status::completed);
  const double l1 = r.exponents[0] / map.period, l2 = r.exponents[1] / map.period;
  SCOPED_TRACE(name + ": finite differences " + std::to_string(l1) + ", " + std::to_string(l2) +
               "; variational " + std::to_string(reference.exponents[0]) + ", " +
               std::to_string(reference.exponents[2]));
  std::printf("[ measured ] %s: finite differences %.6f %.6f, variational %.6f %.6f\n", name.c_str(), l1, l2,
              reference.exponents[0], reference.exponents[2]);
  EXPECT_NEAR(l1, reference.exponents[0], 1e-3);
  EXPECT_NEAR(l2, reference.exponents[2], 1e-3);
  EXPECT_NEAR(l1 + l2, -damping, 1e-6);  // det of the period map = exp(-damping T), exactly
}

TEST(FiniteDifferenceLyapunov, DuffingAgreesWithTheVariationalSpectrum) { compare("duffing", 0.1); }

TEST(FiniteDifferenceLyapunov, UedaAgreesWithTheVariationalSpectrum) { compare("ueda", 0.05); }

}  // namespace
