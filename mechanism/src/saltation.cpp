#include "mechanism/saltation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "mechanism/error.hpp"

namespace mechanism {

namespace {

// The cubic Hermite interpolant of a step (as Rk4::interpolate) at s = (t - t0) / h.
template <class A, class B, class C, class D>
auto hermite(double s, double h, const A& x0, const B& x1, const C& f0, const D& f1) {
  const double s2 = s * s, s3 = s2 * s;
  return ((2.0 * s3 - 3.0 * s2 + 1.0) * x0 + (3.0 * s2 - 2.0 * s3) * x1 + (h * (s3 - 2.0 * s2 + s)) * f0 +
          (h * (s3 - s2)) * f1)
      .eval();
}

}  // namespace

std::string saltation_unsupported(const Scene& scene) {
  if (scene.integrator.method != IntegratorMethod::rk4)
    return "the saltation method follows RK4's fixed steps (integrator.method = \"rk4\"): an adaptive stepper's step "
           "sequence depends on the state";
  bool lugre = false;
  auto look = [&](JointKind kind, const FrictionLawParameters& f) {
    if (kind != JointKind::clearance) return;
    lugre = lugre || f.law == FrictionLaw::lugre_absolute || f.law == FrictionLaw::lugre_normalised;
  };
  look(scene.slider_guide.kind, scene.slider_guide.friction);
  look(scene.crank_ground.kind, scene.crank_ground.friction);
  look(scene.crank_conrod.kind, scene.crank_conrod.friction);
  look(scene.conrod_slider.kind, scene.conrod_slider.friction);
  if (lugre && scene.integrator.bristles == BristleUpdate::exponential)
    return "the exponential bristle update rewrites the deflections at every step's end, a map the saltation method "
           "does not differentiate (integrator.bristles = \"integrated\", or --method benettin)";
  return {};
}

SaltationTangents::SaltationTangents(const SliderCrank& system, Eigen::VectorXd state_scale)
    : probe_(system), scale_(std::move(state_scale)), n_state_(system.state_size()), sites_(system.site_count()) {
  if (scale_.size() != n_state_)
    throw InvalidParameter("state_scale", std::to_string(scale_.size()) + " values",
                           "must have one entry per state row (" + std::to_string(n_state_) + ")");
  for (Eigen::Index i = 0; i < scale_.size(); ++i)
    if (!(scale_[i] > 0.0)) throw InvalidParameter("state_scale", std::to_string(scale_[i]), "every entry must be > 0");
}

double SaltationTangents::step_along(const Eigen::Ref<const Eigen::VectorXd>& v,
                                     const std::vector<ContactMemory>& memory) const {
  double largest = 0.0;
  for (Eigen::Index i = 0; i < n_state_; ++i) largest = std::max(largest, std::abs(v[i]) / scale_[i]);
  for (std::size_t i = 0; i < sites_ && v.size() > n_state_; ++i)
    if (memory[i].touching) {
      const double p = std::max(std::abs(memory[i].impact_velocity), 1e-9);
      largest = std::max(largest, std::abs(v[n_state_ + static_cast<Eigen::Index>(i)]) / p);
    }
  return largest > 0.0 ? jacobian_step / largest : 0.0;
}

void SaltationTangents::jacobian_product(double t, const State& x, const std::vector<ContactMemory>& memory,
                                         const Eigen::Ref<const Eigen::VectorXd>& v, Eigen::Ref<Eigen::VectorXd> out) {
  const double eta = step_along(v, memory);
  if (!(eta > 0.0)) {
    out.setZero();
    return;
  }
  // Both the state and the latched impact velocities move along v: a touching site's force
  // depends on its latched velocity for the whole contact.
  for (int sign : {1, -1}) {
    shifted_ = memory;
    if (v.size() > n_state_)
      for (std::size_t i = 0; i < sites_; ++i)
        if (memory[i].touching) shifted_[i].impact_velocity += sign * eta * v[n_state_ + static_cast<Eigen::Index>(i)];
    probe_.set_memory(shifted_);
    xs_ = x + (sign * eta) * v.head(n_state_);
    probe_.rhs(t, xs_, sign > 0 ? fp_ : fm_);
  }
  out = (fp_ - fm_) / (2.0 * eta);
}

void SaltationTangents::rk4_step(double t0, double h, const State& x0, const std::vector<ContactMemory>& memory,
                                 Eigen::MatrixXd& y, Eigen::MatrixXd* dF0) {
  // The reference's stages, as Rk4::step forms them.
  const double half = 0.5 * h;
  State stage[4];
  probe_.set_memory(memory);
  stage[0] = x0;
  probe_.rhs(t0, stage[0], k_[0]);
  stage[1] = x0 + half * k_[0];
  probe_.rhs(t0 + half, stage[1], k_[1]);
  stage[2] = x0 + half * k_[1];
  probe_.rhs(t0 + half, stage[2], k_[2]);
  stage[3] = x0 + h * k_[2];
  const double tstage[4] = {t0, t0 + half, t0 + half, t0 + h};
  const double advance[4] = {0.0, half, half, h};
  if (dF0) dF0->resize(n_state_, y.cols());
  Eigen::VectorXd v(rows()), d[4];
  for (auto& di : d) di.resize(n_state_);
  for (Eigen::Index j = 0; j < y.cols(); ++j) {
    for (int s = 0; s < 4; ++s) {
      v = y.col(j);
      if (s > 0) v.head(n_state_) += advance[s] * d[s - 1];
      jacobian_product(tstage[s], stage[s], memory, v, d[s]);
    }
    if (dF0) dF0->col(j) = d[0];
    y.col(j).head(n_state_) += (h / 6.0) * (d[0] + 2.0 * d[1] + 2.0 * d[2] + d[3]);
  }
}

SaltationTangents::SiteDerivatives SaltationTangents::site_derivatives(double t, const State& x, std::size_t site,
                                                                      const Eigen::Ref<const Eigen::VectorXd>& dx) {
  double largest = 0.0;
  for (Eigen::Index i = 0; i < n_state_; ++i) largest = std::max(largest, std::abs(dx[i]) / scale_[i]);
  if (!(largest > 0.0)) return {};
  const double eta = jacobian_step / largest;
  xs_ = x + eta * dx;
  probe_.evaluate(t, xs_, ev_);
  const SiteEvaluation plus = ev_.sites[site];  // nine doubles: a copy before the next evaluate()
  xs_ = x - eta * dx;
  probe_.evaluate(t, xs_, ev_);
  const SiteEvaluation& minus = ev_.sites[site];
  return {(plus.penetration - minus.penetration) / (2.0 * eta),
          (plus.penetration_rate - minus.penetration_rate) / (2.0 * eta),
          (plus.sliding_velocity - minus.sliding_velocity) / (2.0 * eta)};
}

void SaltationTangents::commit(const StepRecord& step, const Eigen::MatrixXd& y0, const Eigen::MatrixXd& dF0,
                               Eigen::MatrixXd& y) {
  const Evaluation& end = *step.at_end;
  const std::vector<ContactMemory>& memory = *step.memory;
  const State& x0 = *step.x0;
  const State& x1 = *step.x1;
  const double h = step.t1 - step.t0;
  const auto k = y.cols();
  // The latched velocities' new rows, from the tangents before this commit changes any row.
  std::vector<std::pair<std::size_t, Eigen::VectorXd>> latched;
  State f0, f1;
  Eigen::MatrixXd dF1;
  for (std::size_t i = 0; i < sites_; ++i) {
    if (!(end.sites[i].penetration > 0.0) || memory[i].touching) continue;
    Eigen::VectorXd row(k);
    const double tc = (*step.onset_time)[i];
    if (!std::isfinite(tc)) {
      // commit() latches the step end's rate: dp = grad(g') dx there.
      for (Eigen::Index j = 0; j < k; ++j) row[j] = site_derivatives(step.t1, x1, i, y.col(j).head(n_state_)).penetration_rate;
      latched.emplace_back(i, std::move(row));
      continue;
    }
    if (f0.size() == 0) {
      // The step's dense output and its tangent: Hermite through (x0, f0), (x1, f1) and through
      // (y0, J y0), (y, J y), all with the step's memory.
      probe_.set_memory(memory);
      probe_.rhs(step.t0, x0, f0);
      probe_.rhs(step.t1, x1, f1);
      dF1.resize(n_state_, k);
      for (Eigen::Index j = 0; j < k; ++j) {
        Eigen::VectorXd out(n_state_);
        jacobian_product(step.t1, x1, memory, y.col(j), out);
        dF1.col(j) = out;
      }
    }
    probe_.set_memory(memory);
    const double s = (tc - step.t0) / h;
    const State xc = hermite(s, h, x0, x1, f0, f1);
    // g' and g'' along the dense output, by central differences in time around t_c.
    const double tau = 1e-3 * h;
    const double ds = tau / h;
    probe_.evaluate(tc + tau, hermite(s + ds, h, x0, x1, f0, f1), ev_);
    const double g_plus = ev_.sites[i].penetration, r_plus = ev_.sites[i].penetration_rate;
    probe_.evaluate(tc - tau, hermite(s - ds, h, x0, x1, f0, f1), ev_);
    const double g_rate = (g_plus - ev_.sites[i].penetration) / (2.0 * tau);
    const double g_accel = (r_plus - ev_.sites[i].penetration_rate) / (2.0 * tau);
    for (Eigen::Index j = 0; j < k; ++j) {
      const Eigen::VectorXd dxc =
          hermite(s, h, y0.col(j).head(n_state_), y.col(j).head(n_state_), dF0.col(j), dF1.col(j));
      const SiteDerivatives d = site_derivatives(tc, xc, i, dxc);
      // Müller's correction: the onset time moves by -dg / g', and the latched rate with it.
      row[j] = d.penetration_rate - (g_accel / g_rate) * d.penetration;
    }
    latched.emplace_back(i, std::move(row));
  }
  for (auto& [i, row] : latched) y.row(n_state_ + static_cast<Eigen::Index>(i)) = row.transpose();
  for (std::size_t i = 0; i < sites_; ++i) {
    if (end.sites[i].penetration > 0.0) continue;
    // Released or still open: commit() forgets the latched velocity and unloads the bristles.
    y.row(n_state_ + static_cast<Eigen::Index>(i)).setZero();
    if (const int b = probe_.bristle_index(i); b >= 0) y.row(b).setZero();
  }
  if (step.reversal >= 0) reverse(step, y);
}

void SaltationTangents::reverse(const StepRecord& step, Eigen::MatrixXd& y) {
  // The step ended where site i's sliding velocity v crosses zero, and the force it holds flips
  // from f- to f+ there. A neighbour reaches v = 0 later by dt = -grad(v) dx / v', with v' the rate
  // along f-; it spends dt under f- while the reference is under f+, so dx+ = dx + (f+ - f-)
  // grad(v) dx / v' (Müller 1995 with h = v and no reset).
  const auto i = static_cast<std::size_t>(step.reversal);
  const State& x1 = *step.x1;
  const double t1 = step.t1;
  std::vector<ContactMemory> memory = *step.memory;
  probe_.set_memory(memory);
  State f_minus, f_plus;
  probe_.rhs(t1, x1, f_minus);
  const double tau = 1e-3 * probe_.scene().integrator.step;
  probe_.evaluate(t1 + tau, x1 + tau * f_minus, ev_);
  const double v_plus = ev_.sites[i].sliding_velocity;
  probe_.evaluate(t1 - tau, x1 - tau * f_minus, ev_);
  const double rate = (v_plus - ev_.sites[i].sliding_velocity) / (2.0 * tau);
  memory[i].sliding_direction = -memory[i].sliding_direction;
  probe_.set_memory(memory);
  probe_.rhs(t1, x1, f_plus);
  probe_.set_memory(*step.memory);
  if (!(std::abs(rate) > 0.0)) return;  // a tangential graze: no transversal crossing to correct
  const Eigen::VectorXd jump = (f_plus - f_minus) / rate;
  for (Eigen::Index j = 0; j < y.cols(); ++j) {
    const double dv = site_derivatives(t1, x1, i, y.col(j).head(n_state_)).sliding_velocity;
    y.col(j).head(n_state_) += dv * jump;
  }
}

void SaltationTangents::start(double t, const State& x, const std::vector<ContactMemory>& memory, Eigen::MatrixXd& y) {
  probe_.set_memory(memory);
  probe_.evaluate(t, x, ev_);
  std::vector<std::size_t> onsets;
  for (std::size_t i = 0; i < sites_; ++i)
    if (ev_.sites[i].penetration > 0.0 && !memory[i].touching) onsets.push_back(i);
  for (std::size_t i : onsets)
    for (Eigen::Index j = 0; j < y.cols(); ++j)
      y(n_state_ + static_cast<Eigen::Index>(i), j) = site_derivatives(t, x, i, y.col(j).head(n_state_)).penetration_rate;
}

void SaltationTangents::step(const StepRecord& step, Eigen::MatrixXd& y) {
  y0_ = y;
  rk4_step(step.t0, step.t1 - step.t0, *step.x0, *step.memory, y, &df0_);
  commit(step, y0_, df0_, y);
}

}  // namespace mechanism
