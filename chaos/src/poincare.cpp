#include "chaos/poincare.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "chaos/error.hpp"
#include "lagrange.hpp"
#include "numeric.hpp"

namespace chaos {

namespace {

// Lagrange weights of the cubic through nodes -1, 0, 1, 2 at parameter s in [0, 1].
void cubic_weights(double s, double w[4]) {
  w[0] = -s * (s - 1) * (s - 2) / 6.0;
  w[1] = (s + 1) * (s - 1) * (s - 2) / 2.0;
  w[2] = -(s + 1) * s * (s - 2) / 2.0;
  w[3] = (s + 1) * s * (s - 1) / 6.0;
}

}  // namespace

std::vector<double> stroboscopic_section(std::span<const double> series, std::size_t period, std::size_t phase) {
  if (period == 0) throw InvalidInput(ErrorCode::invalid_parameter, "stroboscopic section: the period must be >= 1 sample");
  if (phase >= series.size()) {
    throw InvalidInput(ErrorCode::too_short, "stroboscopic section: the phase (" + std::to_string(phase) +
                                                 ") must be below the series length (" + std::to_string(series.size()) + ")");
  }
  std::vector<double> out;
  for (std::size_t i = phase; i < series.size(); i += period) out.push_back(series[i]);
  return out;
}

HyperplaneSection hyperplane_section(const std::vector<std::vector<double>>& components, double dt,
                                     const HyperplaneOptions& o) {
  if (!(dt > 0.0) || !std::isfinite(dt)) throw InvalidInput(ErrorCode::invalid_parameter, "hyperplane section: dt = " + detail::format_number(dt) + " must be > 0");
  if (o.component >= components.size()) {
    throw InvalidInput(ErrorCode::invalid_parameter, "hyperplane section: component " + std::to_string(o.component) +
                                                         " does not exist (" + std::to_string(components.size()) + " given)");
  }
  if (!std::isfinite(o.level)) throw InvalidInput(ErrorCode::invalid_parameter, "hyperplane section: the level must be finite");
  const std::size_t n = components.front().size();
  for (const auto& c : components) {
    if (c.size() != n) throw InvalidInput(ErrorCode::invalid_parameter, "hyperplane section: components of different lengths");
    for (double v : c) {
      if (!std::isfinite(v)) throw InvalidInput(ErrorCode::non_finite, "hyperplane section: a non-finite sample");
    }
  }
  if (n < 2) throw InvalidInput(ErrorCode::too_short, "hyperplane section: at least 2 samples are needed (got " + std::to_string(n) + ")");

  const auto& g = components[o.component];
  HyperplaneSection out;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double a = g[i] - o.level, b = g[i + 1] - o.level;
    if (!detail::crosses(a, b, o.direction)) continue;
    double s;  // crossing at sample i + s
    std::vector<double> point(components.size());
    if (i >= 1 && i + 2 < n) {
      // Bisection on the cubic through samples i-1 .. i+2, which brackets the root on [0, 1]
      // because it passes through the two samples of opposite sign.
      auto f = [&](double t) {
        double w[4];
        cubic_weights(t, w);
        return w[0] * g[i - 1] + w[1] * g[i] + w[2] * g[i + 1] + w[3] * g[i + 2] - o.level;
      };
      s = detail::bisect_unit_interval(f, a);
      double w[4];
      cubic_weights(s, w);
      for (std::size_t k = 0; k < components.size(); ++k) {
        const auto& c = components[k];
        point[k] = w[0] * c[i - 1] + w[1] * c[i] + w[2] * c[i + 1] + w[3] * c[i + 2];
      }
    } else {
      s = a / (a - b);
      for (std::size_t k = 0; k < components.size(); ++k) point[k] = components[k][i] + s * (components[k][i + 1] - components[k][i]);
    }
    point[o.component] = o.level;  // on the plane by construction (the root's residual is below 1 ulp of the bracket)
    out.times.push_back((static_cast<double>(i) + s) * dt);
    out.points.push_back(std::move(point));
  }
  for (std::size_t j = 1; j < out.times.size(); ++j) out.return_times.push_back(out.times[j] - out.times[j - 1]);
  return out;
}

std::size_t distinct_values(std::span<const double> values, double tolerance) {
  if (!(tolerance >= 0.0)) throw InvalidInput(ErrorCode::invalid_parameter, "distinct values: the tolerance must be >= 0");
  if (values.empty()) return 0;
  std::vector<double> v(values.begin(), values.end());
  for (double x : v) {
    if (!std::isfinite(x)) throw InvalidInput(ErrorCode::non_finite, "distinct values: a non-finite value");
  }
  std::sort(v.begin(), v.end());
  std::size_t groups = 1;
  for (std::size_t i = 1; i < v.size(); ++i) groups += v[i] - v[i - 1] > tolerance;
  return groups;
}

Histogram probability_density(std::span<const double> values, std::size_t bins, double low, double high) {
  if (bins == 0) throw InvalidInput(ErrorCode::invalid_parameter, "probability density: bins must be >= 1");
  if (!(low < high) || !std::isfinite(low) || !std::isfinite(high)) {
    throw InvalidInput(ErrorCode::invalid_parameter, "probability density: the range [" + detail::format_number(low) + ", " + detail::format_number(high) +
                                                         "] must be finite with low < high");
  }
  if (values.empty()) throw InvalidInput(ErrorCode::empty, "probability density: no values");
  Histogram h;
  const double width = (high - low) / static_cast<double>(bins);
  for (std::size_t b = 0; b <= bins; ++b) h.edges.push_back(low + width * static_cast<double>(b));
  h.edges.back() = high;
  std::vector<std::size_t> counts(bins, 0);
  for (double v : values) {
    if (!std::isfinite(v)) throw InvalidInput(ErrorCode::non_finite, "probability density: a non-finite value");
    if (v < low || v > high) {
      ++h.out_of_range;
      continue;
    }
    const auto b = std::min(bins - 1, static_cast<std::size_t>((v - low) / width));
    ++counts[b];
    ++h.in_range;
  }
  h.density.resize(bins, 0.0);
  if (h.in_range > 0) {
    for (std::size_t b = 0; b < bins; ++b) {
      h.density[b] = static_cast<double>(counts[b]) / (static_cast<double>(h.in_range) * width);
    }
  }
  return h;
}

}  // namespace chaos
