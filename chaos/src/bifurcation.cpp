#include "chaos/bifurcation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "chaos/error.hpp"
#include "chaos/poincare.hpp"
#include "numeric.hpp"

namespace chaos {

using detail::format_number;

void MapBifurcationOptions::validate() const {
  if (keep == 0) throw InvalidInput(ErrorCode::invalid_parameter, "map bifurcation: keep must be >= 1 iterate");
  if (!std::isfinite(initial)) throw InvalidInput(ErrorCode::non_finite, "map bifurcation: the initial x must be finite");
}

BifurcationDiagram map_bifurcation(const MapFamily& f, std::span<const double> parameters, const MapBifurcationOptions& o) {
  o.validate();
  if (!f) throw InvalidInput(ErrorCode::invalid_parameter, "map bifurcation: no map given");
  if (parameters.empty()) throw InvalidInput(ErrorCode::empty, "map bifurcation: no parameter values");
  BifurcationDiagram out;
  for (double r : parameters) {
    if (!std::isfinite(r)) throw InvalidInput(ErrorCode::non_finite, "map bifurcation: a non-finite parameter value");
    double x = o.initial;
    std::vector<double> kept;
    kept.reserve(o.keep);
    for (std::size_t i = 0; i < o.transient + o.keep; ++i) {
      x = f(r, x);
      if (!std::isfinite(x)) {
        throw InvalidInput(ErrorCode::non_finite, "map bifurcation: the orbit at parameter " + format_number(r) + " from x0 = " +
                                                      format_number(o.initial) + " left the finite numbers at iterate " + std::to_string(i + 1));
      }
      if (i >= o.transient) kept.push_back(x);
    }
    out.parameters.push_back(r);
    out.points.push_back(std::move(kept));
  }
  return out;
}

void DensityMapOptions::validate() const {
  if (bins == 0) throw InvalidInput(ErrorCode::invalid_parameter, "density map: bins must be >= 1 (got 0)");
  if (bins > max_density_bins)
    throw InvalidInput(ErrorCode::invalid_parameter, "density map: bins must be at most " + std::to_string(max_density_bins) +
                                                         " (got " + std::to_string(bins) + ")");
  if (low.has_value() != high.has_value()) throw InvalidInput(ErrorCode::invalid_parameter, "density map: give both ends of the range or neither");
  if (low && (!std::isfinite(*low) || !std::isfinite(*high) || !(*low < *high))) {
    throw InvalidInput(ErrorCode::invalid_parameter, "density map: the range [" + format_number(*low) + ", " + format_number(*high) +
                                                         "] must be finite with low < high");
  }
  if (!(padding >= 0.0) || !std::isfinite(padding)) {
    throw InvalidInput(ErrorCode::invalid_parameter, "density map: padding (" + format_number(padding) + ") must be finite and >= 0");
  }
  if (bandwidth && (!(*bandwidth > 0.0) || !std::isfinite(*bandwidth))) {
    throw InvalidInput(ErrorCode::invalid_parameter, "density map: the bandwidth (" + format_number(*bandwidth) + ") must be finite and > 0");
  }
}

double quantile(std::span<const double> values, double q) {
  if (values.empty()) throw InvalidInput(ErrorCode::empty, "quantile: no values");
  if (!(q >= 0.0 && q <= 1.0)) throw InvalidInput(ErrorCode::invalid_parameter, "quantile: q = " + format_number(q) + " must lie in [0, 1]");
  std::vector<double> v(values.begin(), values.end());
  std::sort(v.begin(), v.end());
  const double h = static_cast<double>(v.size() - 1) * q;
  const auto i = static_cast<std::size_t>(std::floor(h));
  if (i + 1 >= v.size()) return v.back();
  return v[i] + (h - static_cast<double>(i)) * (v[i + 1] - v[i]);
}

double silverman_bandwidth(std::span<const double> values) {
  const std::size_t n = values.size();
  if (n < 2) return 0.0;
  double mean = 0.0;
  for (double v : values) mean += v;
  mean /= static_cast<double>(n);
  double ss = 0.0;
  for (double v : values) ss += (v - mean) * (v - mean);
  const double s = std::sqrt(ss / static_cast<double>(n - 1));
  const double iqr = quantile(values, 0.75) - quantile(values, 0.25);
  double spread = std::min(s, iqr / 1.34);
  if (!(spread > 0.0)) spread = s;  // IQR = 0 with s > 0 (most values equal): the robust scale says nothing
  return 0.9 * spread * std::pow(static_cast<double>(n), -0.2);
}

namespace {

void check_samples(std::span<const double> parameters, const std::vector<std::vector<double>>& samples) {
  if (parameters.empty()) throw InvalidInput(ErrorCode::empty, "density map: no parameter values");
  if (parameters.size() != samples.size()) {
    throw InvalidInput(ErrorCode::invalid_parameter, "density map: " + std::to_string(parameters.size()) + " parameter values but " +
                                                         std::to_string(samples.size()) + " sample sets");
  }
  for (std::size_t p = 0; p < parameters.size(); ++p) {
    if (!std::isfinite(parameters[p])) throw InvalidInput(ErrorCode::non_finite, "density map: parameter value " + std::to_string(p) + " is not finite");
    if (samples[p].empty()) {
      throw InvalidInput(ErrorCode::empty, "density map: no samples at parameter " + format_number(parameters[p]) + " (set " + std::to_string(p) + ")");
    }
    for (double v : samples[p]) {
      if (!std::isfinite(v)) throw InvalidInput(ErrorCode::non_finite, "density map: a non-finite sample at parameter " + format_number(parameters[p]));
    }
  }
}

double normal_cdf(double z) { return 0.5 * std::erfc(-z / std::numbers::sqrt2); }

}  // namespace

DensityMap density_map(std::span<const double> parameters, const std::vector<std::vector<double>>& samples, const DensityMapOptions& o) {
  o.validate();
  check_samples(parameters, samples);
  std::vector<double> pooled;
  for (const auto& s : samples) pooled.insert(pooled.end(), s.begin(), s.end());

  double low, high;
  if (o.low) {
    low = *o.low;
    high = *o.high;
  } else {
    const auto [lo, hi] = std::minmax_element(pooled.begin(), pooled.end());
    const double span = *hi - *lo;
    if (span > 0.0) {
      low = *lo - o.padding * span;
      high = *hi + o.padding * span;
    } else {  // constant: no span to pad, a unit-scale window around the value
      const double half = 0.5 * std::max(std::abs(*lo), 1.0);
      low = *lo - half;
      high = *lo + half;
    }
  }

  DensityMap out;
  std::size_t bins = o.bins;
  if (o.bin_rule == BinRule::freedman_diaconis) {
    const double iqr = quantile(pooled, 0.75) - quantile(pooled, 0.25);
    if (iqr > 0.0) {
      const double width = 2.0 * iqr / std::cbrt(static_cast<double>(pooled.size()));
      const double count = std::ceil((high - low) / width);
      out.rule_bins = count >= 1e15 ? static_cast<std::size_t>(1e15) : static_cast<std::size_t>(std::max(count, 1.0));
      bins = std::min(*out.rule_bins, o.bins);
    }
  }

  const double width = (high - low) / static_cast<double>(bins);
  for (std::size_t b = 0; b <= bins; ++b) out.edges.push_back(low + width * static_cast<double>(b));
  out.edges.back() = high;
  for (std::size_t b = 0; b < bins; ++b) out.centres.push_back(0.5 * (out.edges[b] + out.edges[b + 1]));
  out.parameters.assign(parameters.begin(), parameters.end());

  for (std::size_t p = 0; p < parameters.size(); ++p) {
    const auto& x = samples[p];
    std::size_t inside = 0;
    for (double v : x) inside += v >= low && v <= high;
    if (inside == 0) {
      throw InvalidInput(ErrorCode::invalid_parameter, "density map: none of the " + std::to_string(x.size()) + " samples at parameter " +
                                                           format_number(parameters[p]) + " lies in the range [" + format_number(low) + ", " +
                                                           format_number(high) + "]");
    }
    out.in_range.push_back(inside);
    if (o.estimator == DensityEstimator::histogram) {
      out.density.push_back(probability_density(x, bins, low, high).density);
      continue;
    }
    // Kernel estimate averaged over each bin: the Gaussian's mass in the bin is a difference of
    // normal CDFs, so a bandwidth narrower than a bin is not lost between grid points, and the
    // bins sum to the estimate's mass inside the range (renormalised to 1, the loss reported).
    double h = o.bandwidth ? *o.bandwidth : silverman_bandwidth(x);
    if (!(h > 0.0)) h = width;  // a constant sample: one bin width
    std::vector<double> mass(bins, 0.0);
    for (double v : x) {
      const double reach = 10.0 * h;  // Phi(-10) ~ 8e-24: nothing beyond
      const auto first = static_cast<std::size_t>(std::clamp(std::floor((v - reach - low) / width), 0.0, static_cast<double>(bins)));
      const auto last = static_cast<std::size_t>(std::clamp(std::ceil((v + reach - low) / width), 0.0, static_cast<double>(bins)));
      double previous = normal_cdf((out.edges[first] - v) / h);
      for (std::size_t e = first + 1; e <= last; ++e) {
        const double next = normal_cdf((out.edges[e] - v) / h);
        mass[e - 1] += next - previous;
        previous = next;
      }
    }
    double total = 0.0;
    for (double m : mass) total += m;
    total /= static_cast<double>(x.size());
    if (!(total > 0.0)) {
      throw InvalidInput(ErrorCode::invalid_parameter, "density map: the kernel estimate at parameter " + format_number(parameters[p]) +
                                                           " has no mass in the range [" + format_number(low) + ", " + format_number(high) + "]");
    }
    std::vector<double> d(bins);
    for (std::size_t b = 0; b < bins; ++b) d[b] = mass[b] / (static_cast<double>(x.size()) * total * width);
    out.density.push_back(std::move(d));
    out.bandwidths.push_back(h);
    out.kernel_mass.push_back(total);
  }
  return out;
}

}  // namespace chaos
