// finite_difference_lyapunov: Benettin's renormalisation on k + 1 trajectories. Expected values:
// a linear map with known stretching (analytic), the Henon map (lambda_1 = 0.41922 per iteration,
// Sprott, Chaos and Time-Series Analysis (OUP 2003); lambda_1 + lambda_2 = ln b exactly, because
// det J = -b everywhere), a map that annihilates one direction (a reset: -inf, reported as
// collapsed), and the options' rules.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "mechanism/error.hpp"
#include "mechanism/finite_difference_lyapunov.hpp"

namespace {

// x -> A x with A = R diag(2, 1/3) R^T, R a rotation by 0.3 rad: exponents ln 2 and -ln 3. The
// reference sits at the fixed point 0, so every separation is exactly A applied to the last one.
struct LinearMap {
  Eigen::Vector2d x = Eigen::Vector2d::Zero();
  Eigen::VectorXd phase_point() const { return x; }
  void set_phase_point(const Eigen::VectorXd& p) { x = p; }
  bool advance() {
    const double c = std::cos(0.3), s = std::sin(0.3);
    Eigen::Matrix2d r;
    r << c, -s, s, c;
    x = r * Eigen::Vector2d(2.0, 1.0 / 3.0).asDiagonal() * r.transpose() * x;
    return true;
  }
};

struct Henon {
  Eigen::Vector2d x{0.1, 0.1};
  Eigen::VectorXd phase_point() const { return x; }
  void set_phase_point(const Eigen::VectorXd& p) { x = p; }
  bool advance() {
    x = Eigen::Vector2d(1.0 - 1.4 * x[0] * x[0] + x[1], 0.3 * x[0]);
    return std::isfinite(x[0]) && std::isfinite(x[1]);
  }
};

// (x, y) -> (f(x), 0): y is reset every iteration, like a bristle deflection at contact release.
struct ResetMap {
  Eigen::Vector2d x{0.3, 0.5};
  Eigen::VectorXd phase_point() const { return x; }
  void set_phase_point(const Eigen::VectorXd& p) { x = p; }
  bool advance() {
    x = Eigen::Vector2d(4.0 * x[0] * (1.0 - x[0]), 0.0);
    if (x[0] <= 0.0 || x[0] >= 1.0) x[0] = 0.3;  // keep the logistic orbit off its fixed points
    return true;
  }
};

TEST(FiniteDifferenceLyapunov, RecoversTheStretchingOfALinearMap) {
  LinearMap map;
  mechanism::FiniteDifferenceOptions o;
  o.exponents = 2;
  o.iterations = 200;
  const auto r = mechanism::finite_difference_lyapunov(map, o);
  ASSERT_EQ(r.status, mechanism::FiniteDifferenceLyapunov::Status::completed);
  EXPECT_NEAR(r.exponents[0], std::log(2.0), 1e-9);
  EXPECT_NEAR(r.exponents[1], -std::log(3.0), 1e-9);
  EXPECT_EQ(r.iterations, 200u);
  EXPECT_EQ(r.running.size(), 400u);
  EXPECT_NEAR(r.largest_growth, 2.0, 1e-9);  // one iteration stretches a unit separation at most 2x
}

TEST(FiniteDifferenceLyapunov, HenonMatchesSprottAndTheDeterminantIdentity) {
  Henon map;
  mechanism::FiniteDifferenceOptions o;
  o.exponents = 2;
  o.transient = 100;
  o.iterations = 200'000;
  const auto r = mechanism::finite_difference_lyapunov(map, o);
  ASSERT_EQ(r.status, mechanism::FiniteDifferenceLyapunov::Status::completed);
  EXPECT_NEAR(r.exponents[0], 0.41922, 0.005);  // Sprott; 2e5 iterations give about +-0.002
  // det J = -0.3 at every point: the finite differences carry it to their O(delta) error.
  EXPECT_NEAR(r.exponents[0] + r.exponents[1], std::log(0.3), 1e-6);
  EXPECT_GT(r.standard_error[0], 0.0);
  EXPECT_LT(r.standard_error[0], 0.005);
}

TEST(FiniteDifferenceLyapunov, AnAnnihilatedDirectionIsReportedAsCollapsed) {
  ResetMap map;
  mechanism::FiniteDifferenceOptions o;
  o.exponents = 2;
  o.iterations = 1000;
  const auto r = mechanism::finite_difference_lyapunov(map, o);
  ASSERT_EQ(r.status, mechanism::FiniteDifferenceLyapunov::Status::completed);
  EXPECT_NEAR(r.exponents[0], std::log(2.0), 0.05);  // the logistic map at r = 4: ln 2
  EXPECT_EQ(r.exponents[1], -std::numeric_limits<double>::infinity());
  EXPECT_EQ(r.collapsed[0], 0u);
  EXPECT_EQ(r.collapsed[1], 1000u);
}

TEST(FiniteDifferenceLyapunov, RefusesImpossibleOptions) {
  Henon map;
  mechanism::FiniteDifferenceOptions o;
  o.exponents = 3;  // the phase space has 2 dimensions
  EXPECT_THROW(mechanism::finite_difference_lyapunov(map, o), mechanism::InvalidParameter);
  o.exponents = 1;
  o.perturbation = 0.0;
  EXPECT_THROW(mechanism::finite_difference_lyapunov(map, o), mechanism::InvalidParameter);
  o.perturbation = 1e-8;
  o.scale = Eigen::VectorXd::Constant(2, -1.0);
  EXPECT_THROW(mechanism::finite_difference_lyapunov(map, o), mechanism::InvalidParameter);
  o.scale = Eigen::VectorXd::Ones(3);
  EXPECT_THROW(mechanism::finite_difference_lyapunov(map, o), mechanism::InvalidParameter);
  o.scale.resize(0);
  o.blocks = 0;
  EXPECT_THROW(mechanism::finite_difference_lyapunov(map, o), mechanism::InvalidParameter);
}

// A trajectory that stops (a failed integration) ends the run with a status, not an exception.
struct Failing {
  int left = 5;
  Eigen::VectorXd phase_point() const { return Eigen::VectorXd::Zero(1); }
  void set_phase_point(const Eigen::VectorXd&) {}
  bool advance() { return --left > 0; }
};

TEST(FiniteDifferenceLyapunov, AFailedTrajectoryEndsTheRunWithAStatus) {
  Failing f;
  mechanism::FiniteDifferenceOptions o;
  o.transient = 0;
  o.iterations = 100;
  const auto r = mechanism::finite_difference_lyapunov(f, o);
  EXPECT_EQ(r.status, mechanism::FiniteDifferenceLyapunov::Status::trajectory_failed);
  EXPECT_NE(r.message.find("reference"), std::string::npos) << r.message;
}

}  // namespace
