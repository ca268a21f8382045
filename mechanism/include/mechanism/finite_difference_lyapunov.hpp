#pragma once
// Lyapunov exponents of a map by finite differences: Benettin et al.'s renormalisation (Meccanica
// 15, 9 (1980)) carried by k + 1 trajectories instead of variational equations. A reference
// trajectory and k companions, each started delta away along one of k orthonormal directions, are
// advanced through one iteration of the map; the companions' separations from the reference,
// divided by delta, are orthonormalised (modified Gram-Schmidt, i.e. a QR factorisation), and
// lambda_j is the mean of ln R_jj over the iterations. The companions then restart delta away from
// the reference along the new directions, so a separation never grows beyond delta times one
// iteration's stretch.
//
// Why finite differences: a non-smooth system (contact onsets and releases, latched impact
// velocities, bristles reset at release) has no variational equation without saltation matrices
// at every event. The companions go through the same events as the reference, so the jumps are in
// the difference quotients wherever the separation stays smaller than the scale on which the events
// move; `largest_growth` says how far each separation grew in one iteration, which is how a caller
// checks that.
//
// The trajectory type carries its discrete memory with it (a copy is a companion with the
// reference's memory) and exposes its continuous state as a phase point:
//   T(const T&)                      copy: the companion starts with the reference's memory
//   Eigen::VectorXd phase_point()    the coordinates the exponents are about
//   void set_phase_point(v)          move the trajectory there (memory unchanged)
//   bool advance()                   one iteration of the map; false when it cannot continue
//   (optional) failure()             why the last advance() failed, quoted in the message
// Coordinates of different units are compared through `scale`: a separation dx counts as
// dx ./ scale, so delta is relative to each coordinate's typical size.

#include <Eigen/Core>

#include <cmath>
#include <concepts>
#include <cstdio>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "mechanism/error.hpp"

namespace mechanism {

template <class T>
concept PerturbableTrajectory = std::copy_constructible<T> && std::is_copy_assignable_v<T> &&
                                requires(T& t, const T& ct, const Eigen::VectorXd& v) {
                                  { ct.phase_point() } -> std::convertible_to<Eigen::VectorXd>;
                                  t.set_phase_point(v);
                                  { t.advance() } -> std::same_as<bool>;
                                };

struct FiniteDifferenceOptions {
  int exponents = 1;                   // k: the k leading exponents (1 <= k <= dimension)
  double perturbation = 1e-8;          // delta, in scaled coordinates
  std::size_t transient = 20;          // iterations that align the directions, not averaged
  std::size_t iterations = 1000;       // iterations averaged
  std::size_t blocks = 10;             // the average is also split into this many blocks (error)
  std::uint64_t seed = 1;              // the initial directions (random, then orthonormalised)
  Eigen::VectorXd scale;               // per coordinate; empty: all 1
  std::function<void(double fraction)> progress;  // optional, about every percent
  void validate(Eigen::Index dimension) const;    // throws InvalidParameter naming the option
};

struct FiniteDifferenceLyapunov {
  enum class Status { completed, trajectory_failed };
  Status status = Status::completed;
  std::string message;                 // why a run stopped early
  std::vector<double> exponents;       // per iteration, in QR order (descending for a long run)
  // The standard error of each mean from its block means (their standard deviation / sqrt(blocks)).
  std::vector<double> standard_error;
  // The running means after each averaged iteration (iterations x k, row-major).
  std::vector<double> running;
  std::size_t iterations = 0;          // iterations averaged
  double largest_growth = 0.0;         // max over iterations and companions of |separation| / delta
  // Per exponent: iterations in which its direction collapsed to zero (a non-invertible step such
  // as a reset state); its mean is then -inf.
  std::vector<std::size_t> collapsed;
};

namespace detail {
[[noreturn]] inline void throw_invalid_option(const char* key, double value, const std::string& rule) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", value);
  throw InvalidParameter(key, buf, rule);
}
}  // namespace detail

inline void FiniteDifferenceOptions::validate(Eigen::Index dimension) const {
  if (exponents < 1 || exponents > dimension)
    detail::throw_invalid_option("exponents", exponents,
                                 "must be between 1 and the phase-space dimension " + std::to_string(dimension));
  if (!(perturbation > 0.0 && perturbation < 1.0))
    detail::throw_invalid_option("perturbation", perturbation, "must be in (0, 1) (scaled coordinates)");
  if (iterations < 1) detail::throw_invalid_option("iterations", 0.0, "must be >= 1");
  if (blocks < 1 || blocks > iterations)
    detail::throw_invalid_option("blocks", static_cast<double>(blocks), "must be between 1 and the iterations");
  if (scale.size() != 0) {
    if (scale.size() != dimension)
      detail::throw_invalid_option("scale", static_cast<double>(scale.size()),
                                   "must have one entry per coordinate (" + std::to_string(dimension) + ")");
    for (Eigen::Index i = 0; i < scale.size(); ++i)
      if (!(scale[i] > 0.0 && std::isfinite(scale[i])))
        detail::throw_invalid_option("scale", scale[i], "every entry must be finite and > 0");
  }
}

namespace detail {

// Modified Gram-Schmidt on the columns of y (a QR factorisation): r_diag gets R's diagonal. The
// same column operations are applied to `along` when given (a variational method measures only some
// rows of its tangents, and carries the others with them). A column that collapsed to zero
// (dead) restarts along a fresh random direction orthogonal to those before it; its `along`
// column is then zero, for the caller to rebuild from y.
template <class Rng>
void orthonormalise_columns(Eigen::MatrixXd& y, Eigen::MatrixXd* along, Eigen::VectorXd& r_diag, std::vector<bool>& dead,
                            Rng& rng, std::normal_distribution<double>& normal) {
  const Eigen::Index k = y.cols();
  for (Eigen::Index j = 0; j < k; ++j) {
    for (Eigen::Index i = 0; i < j; ++i) {
      const double c = y.col(i).dot(y.col(j));
      y.col(j) -= c * y.col(i);
      if (along) along->col(j) -= c * along->col(i);
    }
    r_diag[j] = y.col(j).norm();
    const auto js = static_cast<std::size_t>(j);
    dead[js] = !(r_diag[j] > 0.0);
    if (dead[js]) {
      for (Eigen::Index i = 0; i < y.rows(); ++i) y(i, j) = normal(rng);
      for (Eigen::Index i = 0; i < j; ++i) y.col(j) -= y.col(i).dot(y.col(j)) * y.col(i);
      if (along) along->col(j).setZero();
      y.col(j) /= y.col(j).norm();
    } else {
      y.col(j) /= r_diag[j];
      if (along) along->col(j) /= r_diag[j];
    }
  }
}

// The averages of Benettin's method: ln R_jj per iteration after the transient, their running
// means, block means (the standard error) and the collapse counts, written into `out`.
class BenettinAverages {
 public:
  BenettinAverages(int k, const FiniteDifferenceOptions& options, FiniteDifferenceLyapunov& out)
      : k_(static_cast<std::size_t>(k)), options_(options), out_(out), sums_(k_, 0.0), block_sums_(k_, 0.0),
        block_means_(k_) {
    out_.exponents.assign(k_, 0.0);
    out_.collapsed.assign(k_, 0);
    block_length_ = options.iterations / options.blocks;
    out_.running.reserve(options.iterations * k_);
  }
  std::size_t total() const { return options_.transient + options_.iterations; }
  // After the renormalisation of iteration `it` (0-based, transient included: those are not averaged).
  void add(std::size_t it, const Eigen::VectorXd& r_diag, const std::vector<bool>& dead) {
    if (it < options_.transient) return;
    {
      const std::size_t n = it - options_.transient + 1;
      for (std::size_t j = 0; j < k_; ++j) {
        const double log_r = dead[j] ? -std::numeric_limits<double>::infinity()
                                     : std::log(r_diag[static_cast<Eigen::Index>(j)]);
        if (dead[j]) ++out_.collapsed[j];
        sums_[j] += log_r;
        block_sums_[j] += log_r;
        out_.running.push_back(sums_[j] / static_cast<double>(n));
        if (n % block_length_ == 0 && block_means_[j].size() < options_.blocks) {
          block_means_[j].push_back(block_sums_[j] / static_cast<double>(block_length_));
          block_sums_[j] = 0.0;
        }
      }
      out_.iterations = n;
    }
    if (options_.progress) {
      const double f = static_cast<double>(it + 1) / static_cast<double>(total());
      if (f - last_progress_ >= 0.01 || it + 1 == total()) {
        options_.progress(f);
        last_progress_ = f;
      }
    }
  }
  // The means and their standard errors (NaN with fewer than two blocks).
  void finish() {
    out_.standard_error.assign(k_, std::numeric_limits<double>::quiet_NaN());
    for (std::size_t j = 0; j < k_; ++j) {
      out_.exponents[j] = out_.iterations ? sums_[j] / static_cast<double>(out_.iterations)
                                          : std::numeric_limits<double>::quiet_NaN();
      const auto& b = block_means_[j];
      if (b.size() >= 2) {
        double mean = 0.0, ss = 0.0;
        for (double v : b) mean += v;
        mean /= static_cast<double>(b.size());
        for (double v : b) ss += (v - mean) * (v - mean);
        out_.standard_error[j] = std::sqrt(ss / static_cast<double>(b.size() - 1) / static_cast<double>(b.size()));
      }
    }
  }

 private:
  std::size_t k_;
  const FiniteDifferenceOptions& options_;
  FiniteDifferenceLyapunov& out_;
  std::vector<double> sums_, block_sums_;
  std::vector<std::vector<double>> block_means_;
  std::size_t block_length_ = 1;
  double last_progress_ = -1.0;
};

// The initial directions: seeded Gaussian vectors, orthonormalised (no coordinate is singled out).
// `normal` goes on drawing the restarts of collapsed directions.
template <class Rng>
Eigen::MatrixXd initial_directions(Eigen::Index d, int k, Rng& rng, std::normal_distribution<double>& normal) {
  Eigen::MatrixXd q(d, k);
  for (Eigen::Index i = 0; i < q.size(); ++i) q.data()[i] = normal(rng);
  Eigen::VectorXd r_diag(k);
  std::vector<bool> dead(static_cast<std::size_t>(k));
  orthonormalise_columns(q, nullptr, r_diag, dead, rng, normal);
  return q;
}

}  // namespace detail

// Runs the method from `reference` (advanced in place: it ends where the run ended).
template <PerturbableTrajectory T>
FiniteDifferenceLyapunov finite_difference_lyapunov(T& reference, const FiniteDifferenceOptions& options) {
  const Eigen::VectorXd start = reference.phase_point();
  const Eigen::Index d = start.size();
  options.validate(d);
  const int k = options.exponents;
  const Eigen::VectorXd scale = options.scale.size() ? options.scale : Eigen::VectorXd::Ones(d);
  const double delta = options.perturbation;

  std::mt19937_64 rng(options.seed);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd q = detail::initial_directions(d, k, rng, normal);
  Eigen::VectorXd r_diag(k);
  std::vector<bool> dead(static_cast<std::size_t>(k));

  FiniteDifferenceLyapunov out;
  detail::BenettinAverages averages(k, options, out);
  std::vector<T> companions(static_cast<std::size_t>(k), reference);
  Eigen::MatrixXd y(d, k);
  for (std::size_t it = 0; it < averages.total(); ++it) {
    const Eigen::VectorXd x0 = reference.phase_point();
    for (int j = 0; j < k; ++j) {
      T& c = companions[static_cast<std::size_t>(j)];
      c = reference;  // the reference's memory
      c.set_phase_point(x0 + delta * scale.cwiseProduct(q.col(j)));
    }
    // A trajectory type that says why it stopped (a member failure()) has its reason quoted.
    auto fail = [&](const std::string& who, const T& t) {
      out.status = FiniteDifferenceLyapunov::Status::trajectory_failed;
      out.message = "the " + who + " could not be advanced at iteration " + std::to_string(it);
      if constexpr (requires { std::string(t.failure()); }) out.message += ": " + std::string(t.failure());
    };
    if (!reference.advance()) {
      fail("reference trajectory", reference);
      break;
    }
    int stopped = -1;
    for (int j = 0; j < k && stopped < 0; ++j)
      if (!companions[static_cast<std::size_t>(j)].advance()) stopped = j;
    if (stopped >= 0) {
      fail("companion trajectory " + std::to_string(stopped + 1), companions[static_cast<std::size_t>(stopped)]);
      break;
    }
    const Eigen::VectorXd x1 = reference.phase_point();
    for (int j = 0; j < k; ++j)
      y.col(j) = (companions[static_cast<std::size_t>(j)].phase_point() - x1).cwiseQuotient(scale) / delta;
    for (int j = 0; j < k; ++j) out.largest_growth = std::max(out.largest_growth, y.col(j).norm());
    detail::orthonormalise_columns(y, nullptr, r_diag, dead, rng, normal);
    q = y;
    averages.add(it, r_diag, dead);
  }
  averages.finish();
  return out;
}

}  // namespace mechanism
