// The tangents of the saltation method (saltation.hpp) on the built-in scene, each against an
// independent computation:
//  - J v: its position rows against the equation q' = q_dot (exact: they are v's rate rows), its
//    other rows against central differences of the right-hand side with steps 100 times larger and
//    smaller (the same derivative, with truncation and rounding errors far apart), and the
//    latched-velocity rows against a difference of rhs() with the memory changed by hand;
//  - the tangents carried through a run that contains contact onsets and releases against central
//    differences of simulate() itself (the flow across the events, to second order in the
//    perturbation), with the slider's rotation free and locked; the same tangents without the
//    onset's latched-velocity rows, without Müller's correction for the moving onset time, or with
//    the latched variations dropped every T/50 as Benettin's companions drop them, miss the
//    differences by far more;
//  - the scenes the method refuses, with the reason.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "mechanism/error.hpp"
#include "mechanism/saltation.hpp"
#include "mechanism/scene.hpp"
#include "mechanism/simulate.hpp"
#include "mechanism/slider_crank.hpp"

namespace mechanism {
namespace {

// The built-in scene on the fixed grid that scene_lyapunov integrates (no located switches).
Scene grid_scene(double duration, const std::string& rotation = "free", std::vector<std::string> keys = {}) {
  keys.push_back("integrator.locate_switches=false");
  keys.push_back("joint.slider.rotation=" + rotation);
  Scene s = read_scene("", keys);
  s.run.transient = 0.0;
  s.run.duration = duration;
  s.run.output_interval = duration;
  return s;
}

// Scales for the central differences: each state row's typical size in this scene.
Eigen::VectorXd scales(const SliderCrank& sys) {
  Eigen::VectorXd s = Eigen::VectorXd::Constant(sys.state_size(), std::numeric_limits<double>::infinity());
  Eigen::VectorXd phase(sys.phase_dimension());
  const int n = sys.coordinate_count();
  for (int i = 0; i < n; ++i) phase[i] = 1e-3, phase[n + i] = 1.0;  // rad (or m), rad/s
  for (Eigen::Index i = 2 * n; i < phase.size(); ++i) phase[i] = 1e-6;  // bristle deflections, m
  sys.set_phase_point(s, phase);
  return s;
}

// A state in contact: the built-in scene after 0.02 s (about 1.7 crank periods), with its memory.
struct InContact {
  SliderCrank sys;
  State x;
  explicit InContact(const Scene& scene) : sys(scene) {
    const SimulationSummary r = simulate(sys);
    x = r.final_state;
  }
};

TEST(SaltationTangents, JacobianProductMatchesTheEquationsAndCentralDifferencesOfOtherSteps) {
  InContact c(grid_scene(0.02));
  const SliderCrank& sys = c.sys;
  bool touching = false;
  for (const auto& m : sys.memory()) touching = touching || m.touching;
  ASSERT_TRUE(touching) << "the state should be in contact for the test to reach the contact forces";
  SaltationTangents tg(sys, scales(sys));
  const int n = sys.coordinate_count();
  const double t = 0.02;
  // A direction along every phase coordinate, in proportion to its scale.
  Eigen::VectorXd v = Eigen::VectorXd::Zero(tg.rows());
  const Eigen::VectorXd sc = scales(sys);
  for (Eigen::Index i = 0; i < tg.state_size(); ++i)
    if (std::isfinite(sc[i])) v[i] = sc[i] * std::sin(1.0 + 3.0 * static_cast<double>(i));
  Eigen::VectorXd jv(tg.state_size());
  tg.jacobian_product(t, c.x, sys.memory(), v, jv);
  // q' = q_dot: the position rows of J v are v's rate rows (to the rounding of q_dot, about 500 rad/s,
  // over the step: 1e-7 relative).
  for (int i = 0; i < n; ++i) EXPECT_NEAR(jv[i], v[n + i], 1e-6 * std::abs(v[n + i])) << "row " << i;
  // The other rows against central differences with steps 1e-4 and 1e-8 of the scale.
  SliderCrank probe = sys;
  for (double step : {1e-4, 1e-8}) {
    State xp = c.x + step * v.head(tg.state_size()), xm = c.x - step * v.head(tg.state_size()), fp, fm;
    probe.rhs(t, xp, fp);
    probe.rhs(t, xm, fm);
    const Eigen::VectorXd fd = (fp - fm) / (2.0 * step);
    for (Eigen::Index i = n; i < 2 * n; ++i)
      EXPECT_NEAR(jv[i], fd[i], 1e-5 * jv.segment(n, n).cwiseAbs().maxCoeff()) << "row " << i << ", step " << step;
  }
  // The latched velocities: a direction along those of the touching sites only.
  Eigen::VectorXd u = Eigen::VectorXd::Zero(tg.rows());
  std::vector<ContactMemory> up = sys.memory(), down = sys.memory();
  for (std::size_t i = 0; i < sys.site_count(); ++i)
    if (sys.memory()[i].touching) {
      const double dp = 1e-3 * sys.memory()[i].impact_velocity;
      u[tg.state_size() + static_cast<Eigen::Index>(i)] = dp;
      up[i].impact_velocity += 1e-3 * dp;
      down[i].impact_velocity -= 1e-3 * dp;
    }
  tg.jacobian_product(t, c.x, sys.memory(), u, jv);
  State fp, fm;
  probe.set_memory(up);
  probe.rhs(t, c.x, fp);
  probe.set_memory(down);
  probe.rhs(t, c.x, fm);
  const Eigen::VectorXd fd = (fp - fm) / 2e-3;
  ASSERT_GT(fd.segment(n, n).norm(), 0.0) << "the latched velocity should move the accelerations";
  EXPECT_LT((jv - fd).segment(n, n).norm(), 1e-5 * fd.segment(n, n).norm());
}

// The tangents carried along simulate() from t = 0 (on the built-in scene's first contacts),
// against central differences of simulate() over the same run.
struct CarriedTangents {
  Eigen::MatrixXd tangent, difference;
  std::size_t onsets = 0, releases = 0, reversals = 0;
};

// variant 0: the saltation method; 1-3: wrong on purpose (below); 4: the jump at a Coulomb reversal
// left out.
CarriedTangents carry(double duration, int variant, double eps = 1e-6, const std::string& rotation = "free",
                      const std::vector<std::string>& keys = {}, int start_periods = 2) {
  const Scene scene = grid_scene(duration, rotation, keys);
  // The start: whole crank periods after Eq. 29 (two by default; the crank is back at its initial
  // angle), with the contact memory of that moment; Eq. 29's level slider would put every
  // perturbation of the slider's angle on the kink of the deepest corner.
  SliderCrank sys(grid_scene(start_periods * scene.driver.period(), rotation, keys));
  const State x0 = simulate(sys).final_state;
  const std::vector<ContactMemory> memory0 = sys.memory();
  const Eigen::VectorXd sc = scales(sys);
  SaltationTangents tg(SliderCrank(scene), sc);
  const int d = sys.phase_dimension();
  const int n = sys.coordinate_count();
  const int cols = 2 * n;  // along each mechanical phase coordinate
  Eigen::MatrixXd y = Eigen::MatrixXd::Zero(tg.rows(), cols);
  for (int j = 0; j < cols; ++j) {
    Eigen::VectorXd p = Eigen::VectorXd::Zero(d);
    p[j] = 1.0;
    State col = State::Zero(sys.state_size());
    sys.set_phase_point(col, p.cwiseProduct(sys.phase_point(sc)));
    y.col(j).head(sys.state_size()) = col;
  }
  CarriedTangents out;
  SimulationObserver obs;
  Eigen::MatrixXd y0, df0;
  std::size_t steps = 0;
  obs.step = [&](const StepRecord& step) {
    for (std::size_t i = 0; i < sys.site_count(); ++i) {
      const bool now = step.at_end->sites[i].penetration > 0.0;
      if (now && !(*step.memory)[i].touching) ++out.onsets;
      if (!now && (*step.memory)[i].touching) ++out.releases;
    }
    if (step.reversal >= 0) ++out.reversals;
    y0 = y;
    tg.rk4_step(step.t0, step.t1 - step.t0, *step.x0, *step.memory, y, &df0);
    if (variant == 4) {
      StepRecord s = step;
      s.reversal = -1;
      tg.commit(s, y0, df0, y);
    } else if (variant == 3) {
      // Benettin's product: the latched variations dropped every T/50, where its companions restart.
      tg.commit(step, y0, df0, y);
      if (++steps % 240 == 0) y.bottomRows(tg.rows() - tg.state_size()).setZero();
    } else if (variant == 0) {
      tg.commit(step, y0, df0, y);
    } else {
      // Wrong on purpose: the onset's latched variation left at zero (variant 1) or its time
      // correction dropped (variant 2: the commit of a step whose onset times are unknown).
      std::vector<double> none(sys.site_count(), std::numeric_limits<double>::quiet_NaN());
      StepRecord s = step;
      if (variant == 2) s.onset_time = &none;
      tg.commit(s, y0, df0, y);
      if (variant == 1)
        for (std::size_t i = 0; i < sys.site_count(); ++i)
          if (step.at_end->sites[i].penetration > 0.0 && !(*step.memory)[i].touching)
            y.row(tg.state_size() + static_cast<Eigen::Index>(i)).setZero();
    }
  };
  SliderCrank run(scene);
  run.set_memory(memory0);
  tg.start(0.0, x0, memory0, y);
  const SimulationSummary r = simulate(run, x0, obs);
  EXPECT_EQ(r.status, SimulationStatus::completed) << r.message;
  out.tangent.resize(d, cols);
  for (int j = 0; j < cols; ++j) out.tangent.col(j) = sys.phase_point(y.col(j).head(sys.state_size()));
  out.difference.resize(d, cols);
  for (int j = 0; j < cols; ++j) {
    State col = State::Zero(sys.state_size());
    Eigen::VectorXd p = Eigen::VectorXd::Zero(d);
    p[j] = 1.0;
    sys.set_phase_point(col, p.cwiseProduct(sys.phase_point(sc)));
    SliderCrank a(scene), b(scene);
    a.set_memory(memory0);
    b.set_memory(memory0);
    const State xp = simulate(a, x0 + eps * col).final_state, xm = simulate(b, x0 - eps * col).final_state;
    out.difference.col(j) = (sys.phase_point(xp) - sys.phase_point(xm)) / (2.0 * eps);
  }
  return out;
}

TEST(SaltationTangents, CarriedThroughContactEventsTheyMatchCentralDifferencesOfTheFlow) {
  // 0.01 s from Eq. 29: the slider falls onto the guide and the first contacts open and close.
  const CarriedTangents c = carry(0.01, 0);
  ASSERT_GT(c.onsets, 0u);
  ASSERT_GT(c.releases, 0u);
  const double scale = c.difference.norm();
  const double error = (c.tangent - c.difference).norm() / scale;
  // Measured 7.5e-6, the central differences' own error: steps of 1e-5 and 1e-7 of the scale give 1.5e-4
  // and 1.7e-5 (truncation and rounding), 1e-6 is their best.
  EXPECT_LT(error, 1e-4) << "relative Frobenius error over " << c.onsets << " onsets, " << c.releases << " releases";
  // Without the latched velocity's variation, or without Müller's onset-time term, the tangents
  // miss the flow's derivative by far more than that (measured: 0.25 and 0.31); and so does the
  // product Benettin's finite differences compute, whose companions restart every T/50 with the
  // reference's memory, dropping the latched variations there (variant 3, measured: 0.15).
  for (int variant : {1, 2, 3}) {
    const CarriedTangents w = carry(0.01, variant);
    std::printf("variant %d: relative error %.3g (the saltation tangents' %.3g)\n", variant,
                (w.tangent - w.difference).norm() / w.difference.norm(), error);
    EXPECT_GT((w.tangent - w.difference).norm() / w.difference.norm(), 100.0 * std::max(error, 1e-6)) << "variant " << variant;
  }
}

TEST(SaltationTangents, WithTheRotationLockedTheyMatchCentralDifferencesOfTheFlow) {
  // The slider level (one coordinate fewer), 0.01 s with 8 onsets. Here the flow is less linear at
  // the central differences' scale: steps of 1e-5, 1e-6 and 1e-7 of the scale give relative errors
  // of 2.7, 2.4e-3 and 4.2e-5 (measured), so the comparison uses the smallest.
  const CarriedTangents c = carry(0.01, 0, 1e-7, "locked");
  ASSERT_GT(c.onsets, 0u);
  EXPECT_LT((c.tangent - c.difference).norm() / c.difference.norm(), 1e-3) << c.onsets << " onsets";
}

TEST(SaltationTangents, OnTheSeedsPrintedReadingBenettinsProductMissesTheFlowsDerivative) {
  // The seed as printed (face model, exponent 1.5, absolute LuGre with constant sigma1; lambda_1 about
  // 7400 1/s, so central differences of the flow stay linear only over a few intervals): 4 intervals
  // of T/50 with 4 onsets. Measured: the saltation tangents 1.1e-4 from the differences at steps of
  // 1e-6, 1e-7 and 1e-8 of the scale alike; dropping the latched variations at each interval's end
  // 1.7e-3.
  const std::vector<std::string> printed = {"joint.slider.model=face", "joint.slider.contact.exponent=1.5",
                                            "joint.slider.friction.law=lugre_absolute",
                                            "joint.slider.friction.sigma1_velocity=0"};
  const CarriedTangents c = carry(0.00096, 0, 1e-7, "free", printed);
  const CarriedTangents b = carry(0.00096, 3, 1e-7, "free", printed);
  ASSERT_GT(c.onsets, 0u);
  const double error = (c.tangent - c.difference).norm() / c.difference.norm();
  EXPECT_LT(error, 4e-4);
  EXPECT_GT((b.tangent - b.difference).norm() / b.difference.norm(), 4.0 * error);
}

// Coulomb's law on the RK4 grid holds each contact's sliding direction and ends the step where
// the sliding velocity reverses (SliderCrank::holds_sliding_direction). The built-in scene with
// Coulomb friction reverses first at t = 0.10187 s (slider site 0, 8.49 crank periods; found with an
// observer on StepRecord::reversal): the run starts 8 periods in and crosses it.
TEST(SaltationTangents, CarriedThroughACoulombReversalTheyMatchCentralDifferencesOfTheFlow) {
  const std::vector<std::string> coulomb = {"joint.slider.friction.law=\"coulomb\""};
  const CarriedTangents c = carry(0.006, 0, 1e-6, "free", coulomb, 8);
  ASSERT_GT(c.reversals, 0u);
  const double error = (c.tangent - c.difference).norm() / c.difference.norm();
  EXPECT_LT(error, 1e-4) << c.reversals << " reversals, " << c.onsets << " onsets";
  // Without the jump at the reversal the tangents miss the flow's derivative by far more.
  const CarriedTangents w = carry(0.006, 4, 1e-6, "free", coulomb, 8);
  std::printf("Coulomb reversal: relative error %.3g, without its jump %.3g\n", error,
              (w.tangent - w.difference).norm() / w.difference.norm());
  EXPECT_GT((w.tangent - w.difference).norm() / w.difference.norm(), 100.0 * std::max(error, 1e-6));
}

TEST(SaltationTangents, RefusesScenesItDoesNotDifferentiate) {
  EXPECT_TRUE(saltation_unsupported(read_scene("")).empty());
  EXPECT_NE(saltation_unsupported(read_scene("", {"integrator.method=\"dopri5\""})).find("rk4"), std::string::npos);
  // Coulomb's law on the RK4 grid is differentiated at its located reversals (the test above).
  EXPECT_TRUE(saltation_unsupported(read_scene("", {"joint.slider.friction.law=\"coulomb\""})).empty());
  EXPECT_NE(saltation_unsupported(read_scene("", {"integrator.bristles=\"exponential\""})).find("exponential"),
            std::string::npos);
}

}  // namespace
}  // namespace mechanism
