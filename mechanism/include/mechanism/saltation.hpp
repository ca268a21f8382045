#pragma once
// Tangent vectors carried along a simulation of the slider-crank: the variational equations of the
// map that simulate() integrates, with the jumps of the hybrid state at every commit (contact
// onsets that latch an impact velocity, releases that reset the LuGre bristles). This is Müller's
// construction (P. C. Müller, "Calculation of Lyapunov exponents for dynamic systems with
// discontinuities", Chaos, Solitons & Fractals 5(9), 1671-1681 (1995)) for our event functions; the
// derivation is in docs/reference/mechanism/saltation.md.
//
// A tangent is a column of state_size() + site_count() rows: the variation of the state x, then per
// contact site the variation of the impact velocity latched at its onset (ContactMemory), which
// the normal force of a touching site depends on for as long as the contact lasts.
//
// Between commits the tangents follow the variational equation Y' = J(t, x) Y with the step's own
// RK4 stages (so a tangent step is the derivative of the RK4 step), and J Y is a central
// difference of the right-hand side (jacobian_product). At a commit:
//   onset at site i, located at t_c inside the step:  dp_i = grad(g_i') dx_c - (g_i'' / g_i') grad(g_i) dx_c,
//     g_i the penetration, dx_c the tangent at t_c (the step's Hermite dense output), g_i'' along it;
//     the state's rows jump by nothing (the force is zero at zero penetration on either side);
//   onset where the located rate was not positive (commit() latches the end's rate): dp_i = grad(g_i') dx;
//   a site open at the step's end: its bristle row is zeroed (commit() resets z to 0), dp_i = 0;
//   a Coulomb site whose held sliding direction reverses at the step's end (the step ended on that
//     zero of its sliding velocity v, StepRecord::reversal): dx+ = dx + (f+ - f-) grad(v) dx / v',
//     f- and f+ the right-hand sides with the old and the new direction, v' along f-.
// Only RK4 runs with integrated bristles are handled (saltation_unsupported). A Coulomb contact
// that sticks (SimulationSummary::unlocated_reversals) has no saltation matrix: scene_lyapunov
// stops the saltation method there.

#include <Eigen/Core>

#include <string>
#include <vector>

#include "mechanism/simulate.hpp"
#include "mechanism/slider_crank.hpp"

namespace mechanism {

// Empty when the saltation method applies to the scene, else why not (a sentence).
std::string saltation_unsupported(const Scene& scene);

class SaltationTangents {
 public:
  // `system`: copied, as a probe whose memory is set for every evaluation; `state_scale`: one entry per
  // state row, the size of that coordinate (the central differences' step is relative to it).
  SaltationTangents(const SliderCrank& system, Eigen::VectorXd state_scale);

  Eigen::Index rows() const { return n_state_ + static_cast<Eigen::Index>(sites_); }
  Eigen::Index state_size() const { return n_state_; }

  // J(t, x) v for a tangent v (rows()): the derivative of the right-hand side along v's state rows
  // and, for touching sites, along v's impact-velocity rows; out gets state_size() rows. A central
  // difference with a step of jacobian_step times each coordinate's scale at most.
  void jacobian_product(double t, const State& x, const std::vector<ContactMemory>& memory,
                        const Eigen::Ref<const Eigen::VectorXd>& v, Eigen::Ref<Eigen::VectorXd> out);

  // One RK4 step of the variational equations from (t0, x0) over h for every column of y, with the
  // memory the step ran with. dF0 (if given) gets J(t0, x0) y at the step's start.
  void rk4_step(double t0, double h, const State& x0, const std::vector<ContactMemory>& memory, Eigen::MatrixXd& y,
                Eigen::MatrixXd* dF0 = nullptr);

  // The jumps of commit() for every column of y (at the step's end), given the tangents y0 and
  // their derivatives dF0 at the step's start (for the dense output at an onset).
  void commit(const StepRecord& step, const Eigen::MatrixXd& y0, const Eigen::MatrixXd& dF0, Eigen::MatrixXd& y);

  // What simulate() does at a run's start: a site already penetrating that memory says is not
  // touching latches its current rate.
  void start(double t, const State& x, const std::vector<ContactMemory>& memory, Eigen::MatrixXd& y);

  // rk4_step then commit: the body of SimulationObserver::step.
  void step(const StepRecord& step, Eigen::MatrixXd& y);

  // The central differences' step relative to each coordinate's scale.
  static constexpr double jacobian_step = 1e-6;

 private:
  // The derivatives along dx of a site's penetration, penetration rate and sliding velocity at
  // (t, x): evaluate() by central differences, all zero for dx = 0.
  struct SiteDerivatives {
    double penetration = 0.0, penetration_rate = 0.0, sliding_velocity = 0.0;
  };
  SiteDerivatives site_derivatives(double t, const State& x, std::size_t site,
                                   const Eigen::Ref<const Eigen::VectorXd>& dx);
  // The jump at a held sliding direction's reversal (StepRecord::reversal), after commit's.
  void reverse(const StepRecord& step, Eigen::MatrixXd& y);
  double step_along(const Eigen::Ref<const Eigen::VectorXd>& v, const std::vector<ContactMemory>& memory) const;

  SliderCrank probe_;
  Eigen::VectorXd scale_;
  Eigen::Index n_state_ = 0;
  std::size_t sites_ = 0;
  std::vector<ContactMemory> shifted_;
  State xs_, fp_, fm_, k_[4];
  Eigen::MatrixXd y0_, df0_;
  Evaluation ev_;
};

}  // namespace mechanism
