// Fitting a straight stretch to divergence curves (fit_divergence): the strict linear region, and
// where there is none the looser stretch that still gives a rough value.

#include "chaos/lyapunov.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "chaos/error.hpp"
#include "chaos/scaling_region.hpp"
#include "numeric.hpp"

namespace chaos {

void LyapunovFitOptions::validate() const {
  if (!(tolerance > 0.0) || !std::isfinite(tolerance))
    refuse_parameter("Lyapunov fit: tolerance must be positive and finite (got " + detail::format_number(tolerance) + ")");
  if (min_steps == 1) refuse_parameter("Lyapunov fit: a linear region needs at least 2 steps (got min_steps = 1)");
  if (dimensions < 1) refuse_parameter("Lyapunov fit: at least 1 embedding dimension must be fitted (got dimensions = 0)");
  if (!(min_rise >= 0.0) || !std::isfinite(min_rise))
    refuse_parameter("Lyapunov fit: the minimum rise must be finite and >= 0 (got " + detail::format_number(min_rise) + ")");
}

LyapunovFit fit_divergence(const DivergenceCurve& curve, const LyapunovFitOptions& options) {
  return fit_divergence(std::vector<DivergenceCurve>{curve}, options);
}

LyapunovFit fit_divergence(const std::vector<DivergenceCurve>& curves, const LyapunovFitOptions& options) {
  options.validate();
  if (curves.empty()) refuse_parameter("Lyapunov fit: no divergence curve to fit");
  for (const auto& c : curves)
    if (c.step != curves.front().step) refuse_parameter("Lyapunov fit: the curves of one fit must cover the same steps");
  LyapunovFit fit;
  const DivergenceCurve& curve = curves.front();
  const std::size_t last = curve.step.empty() ? 0 : curve.step.back();
  // Each local slope spans at least one whole oscillation period, so a rotating flow's periodic
  // modulation of the divergence averages out instead of breaking the tolerance.
  const bool secants = options.period > 1 && options.half_width == 0;
  fit.half_width = options.half_width != 0 ? options.half_width
                   : secants               ? (options.period + 1) / 2
                                           : std::max<std::size_t>(2, last / 25);
  fit.min_steps = options.min_steps != 0 ? options.min_steps : std::max(3 * fit.half_width + 1, options.period + 1);
  const ScalingRegionOptions region_options{options.tolerance, true, fit.min_steps, fit.half_width};
  std::vector<double> x(curve.step.size());
  for (std::size_t k = 0; k < x.size(); ++k) x[k] = static_cast<double>(curve.step[k]);
  std::vector<std::vector<std::optional<double>>> slopes;
  for (const auto& c : curves) {
    if (secants) {
      // Over a whole period the periodic part of the curve returns to its value, so the secant
      // (y[k+after] - y[k-before]) / P with before + after = P (the mean of the short local slopes
      // over the period) cancels it exactly; a least-squares line over the same window would not.
      const std::size_t before = options.period / 2, after = options.period - before;
      std::vector<std::optional<double>> secant(x.size());
      for (std::size_t k = before; k + after < x.size(); ++k)
        if (c.divergence[k - before] && c.divergence[k + after])
          secant[k] = (*c.divergence[k + after] - *c.divergence[k - before]) / (x[k + after] - x[k - before]);
      slopes.push_back(std::move(secant));
    } else {
      slopes.push_back(local_slopes(x, c.divergence, fit.half_width));
    }
  }
  fit.local_slope = slopes.front();
  std::ostringstream why;
  for (const auto& c : curves)
    if (c.references_used == 0) {
      fit.status = LyapunovStatus::no_neighbours;
      why << "none of the " << c.reference_points << " reference points has a neighbour"
          << (c.method == LyapunovMethod::kantz ? " within eps" : "") << " outside the Theiler window";
      fit.explanation = why.str();
      fit.estimate.reason = fit.explanation;
      return fit;
    }
  // Only a rising curve carries a positive exponent, and these methods estimate nothing else: the
  // straight stretch is searched among steps with a positive local slope. (A saturated plateau
  // whose slopes were exactly 0 would otherwise count as perfectly straight.)
  std::vector<std::vector<std::optional<double>>> rising(slopes.size(), std::vector<std::optional<double>>(x.size()));
  bool rises = false;
  for (std::size_t c = 0; c < slopes.size(); ++c)
    for (std::size_t k = 0; k < x.size(); ++k)
      if (slopes[c][k] && *slopes[c][k] > 0.0) {
        rising[c][k] = slopes[c][k];
        rises = true;
      }
  if (!rises) {
    fit.status = LyapunovStatus::not_diverging;
    why << "no local slope of the divergence curve is positive: no exponential divergence";
    fit.explanation = why.str();
    fit.estimate.reason = fit.explanation;
    return fit;
  }
  // Among the straight stretches, the one across which the curve rises most wins, and it must rise
  // by min_rise: the growth of the separation is the evidence for an exponential divergence.
  std::vector<double> level(x.size(), 0.0);
  for (std::size_t k = 0; k < x.size(); ++k) {
    std::size_t n = 0;
    for (const auto& c : curves)
      if (c.divergence[k]) {
        level[k] += *c.divergence[k];
        ++n;
      }
    if (n > 0) level[k] /= static_cast<double>(n);
  }
  const auto search = [&](double tolerance, double min_rise) {
    ScalingRegionOptions o = region_options;
    o.tolerance = tolerance;
    o.min_support_gain = min_rise;
    return find_scaling_region(x, rising, o, level);
  };
  // The least-squares slope of each curve over steps [first, last] (indices into the curve).
  const auto slopes_over = [&](std::size_t from, std::size_t to, double fallback) {
    std::vector<double> out;
    for (const auto& c : curves) out.push_back(fit_slope(x, c.divergence, from, to).value_or(fallback));
    return out;
  };
  // The estimate from a stretch: the mean of the curves' slopes; the interval spans every curve's
  // slope over the stretch and over each half of it (where the curve bends, the halves differ).
  const auto estimate_over = [&](const ScalingRegion& r, EstimateStatus status, const std::string& reason) {
    Estimate e;
    const std::vector<double> whole = slopes_over(r.first, r.last, r.slope);
    double sum = 0.0;
    for (const double s : whole) sum += s;
    const double value = sum / static_cast<double>(whole.size());
    if (!(value > 0.0)) {
      e.reason = "the straightest rising stretch (steps " + std::to_string(curve.step[r.first]) + ".." +
                 std::to_string(curve.step[r.last]) + ") has a least-squares slope <= 0: no exponential divergence";
      return e;
    }
    e.value = value;
    for (const double s : whole) e.include(s);
    const std::size_t mid = r.first + (r.last - r.first) / 2;
    if (mid - r.first >= 2 && r.last - mid >= 2)
      for (const auto& part : {std::pair{r.first, mid}, std::pair{mid, r.last}})
        for (const double s : slopes_over(part.first, part.second, value)) e.include(s);
    e.status = status;
    e.reason = reason;
    if (status == EstimateStatus::confident && e.relative_half_width() > 0.1) {
      e.status = EstimateStatus::rough;
      e.reason += "; the slopes over the stretch, its halves and the embedding dimensions spread by more than 10%";
    }
    return e;
  };
  // Where the strict rule finds no linear region, the answer comes from the loosest rung that has one.
  const double loose_rise = std::min(1.0, options.min_rise);
  const auto loose_estimate = [&](const std::string& strict_verdict) {
    const struct {
      double tolerance;
      EstimateStatus status;
    } rungs[] = {{options.tolerance, EstimateStatus::confident},
                 {2 * options.tolerance, EstimateStatus::rough},
                 {3 * options.tolerance, EstimateStatus::rough}};
    for (const auto& rung : rungs)
      if (const auto r = search(rung.tolerance, loose_rise)) {
        std::ostringstream s;
        s << "local slopes within " << rung.tolerance * 100 << "% over steps " << curve.step[r->first] << ".."
          << curve.step[r->last] << ", rising by " << loose_rise << " e-fold or more (" << strict_verdict << ")";
        fit.estimate = estimate_over(*r, rung.status, s.str());
        if (fit.estimate.value) return;
      }
    fit.estimate = Estimate{};
    fit.estimate.reason = strict_verdict + "; no stretch rising by " + format_number(loose_rise, Precision::title) +
                          " e-fold has local slopes within " + format_number(300 * options.tolerance, Precision::title) +
                          "% of their mean either";
  };
  const auto region = search(options.tolerance, options.min_rise);
  if (!region) {
    fit.status = LyapunovStatus::no_linear_region;
    why << "no stretch of at least " << fit.min_steps << " steps rising by " << options.min_rise
        << " e-folds or more has positive local slopes within " << options.tolerance * 100 << "% of their mean";
    if (curves.size() > 1) why << " in all " << curves.size() << " embedding dimensions at once";
    why << ": the divergence curve has no linear region";
    if (curves.size() > 1) why << " that does not depend on m";
    fit.explanation = why.str();
    loose_estimate(std::string("strictly, ") + to_string(fit.status));
    return fit;
  }
  fit.first_step = curve.step[region->first];
  fit.last_step = curve.step[region->last];
  double sum = 0.0, lo = region->slope_min, hi = region->slope_max, low_fit = INFINITY, high_fit = -INFINITY;
  for (const double slope : slopes_over(region->first, region->last, region->slope)) {
    fit.lambda_by_curve.push_back(slope);
    sum += slope;
    low_fit = std::min(low_fit, slope);
    high_fit = std::max(high_fit, slope);
  }
  const double slope = sum / static_cast<double>(curves.size());
  if (!(low_fit > 0.0)) {  // local slopes all positive but a least-squares line is not: refuse to guess
    fit.status = LyapunovStatus::not_diverging;
    why << "the straightest stretch (steps " << *fit.first_step << ".." << *fit.last_step << ") has slope "
        << low_fit << " <= 0: no exponential divergence";
    fit.first_step.reset();
    fit.last_step.reset();
    fit.lambda_by_curve.clear();
    fit.explanation = why.str();
    fit.estimate.reason = fit.explanation;
    return fit;
  }
  if (high_fit - low_fit > options.tolerance * slope) {  // the dimensions disagree on the slope itself
    fit.status = LyapunovStatus::no_linear_region;
    why << "the embedding dimensions disagree on the slope over steps " << *fit.first_step << ".." << *fit.last_step
        << " (" << low_fit << " to " << high_fit << " per sample, more than " << options.tolerance * 100
        << "% apart)";
    fit.first_step.reset();
    fit.last_step.reset();
    fit.lambda_by_curve.clear();
    fit.explanation = why.str();
    fit.estimate = estimate_over(*region, EstimateStatus::rough, "strictly, no_linear_region: " + fit.explanation);
    return fit;
  }
  const double rise = slope * (x[region->last] - x[region->first]);
  if (rise < options.min_rise) {
    fit.status = LyapunovStatus::no_linear_region;
    why << "the straightest stretch (steps " << *fit.first_step << ".." << *fit.last_step << ", slope " << slope
        << " per sample) rises by only " << rise << " e-folds, fewer than the " << options.min_rise
        << " needed to identify an exponential divergence (follow the curve longer with more steps, or it is "
        << "a piece of the initial transient)";
    fit.first_step.reset();
    fit.last_step.reset();
    fit.lambda_by_curve.clear();
    fit.explanation = why.str();
    loose_estimate(std::string("strictly, ") + to_string(fit.status));
    return fit;
  }
  fit.status = LyapunovStatus::linear_region;
  fit.lambda = slope;
  fit.lambda_interval = Interval{std::min({lo, low_fit}), std::max({hi, high_fit})};
  why << "local slopes agree within " << options.tolerance * 100 << "% over steps " << *fit.first_step << ".."
      << *fit.last_step;
  if (curves.size() > 1) why << " in " << curves.size() << " embedding dimensions";
  if (options.period > 1) why << " (local slopes over " << 2 * fit.half_width + 1 << " steps: a whole oscillation period)";
  fit.explanation = why.str();
  fit.estimate = estimate_over(*region, EstimateStatus::confident, fit.explanation);
  return fit;
}

}  // namespace chaos
