#include "chaos/correlation_dimension.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>

#include "chaos/error.hpp"

namespace chaos {

const char* to_string(D2Status status) noexcept {
  switch (status) {
    case D2Status::saturated: return "saturated";
    case D2Status::not_saturated: return "not_saturated";
    case D2Status::no_scaling_region: return "no_scaling_region";
    case D2Status::scale_dependent: return "scale_dependent";
    case D2Status::not_reproduced: return "not_reproduced";
    case D2Status::noise_limited: return "noise_limited";
  }
  return "unknown";
}

void CorrelationDimensionOptions::validate() const {
  region.validate();
  if (!(max_region_fraction > 0.0))
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "the largest scaling-region radius, as a fraction of the range, must be positive (got " +
                           std::to_string(max_region_fraction) + ")");
  if (!(pair_counting_error >= 0.0) || !std::isfinite(pair_counting_error))
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "the counting error of a local slope times sqrt(pairs) must be finite and not negative (got " +
                           std::to_string(pair_counting_error) + ")");
  if (!(slope_error_fraction > 0.0))
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "the largest local-slope error, as a fraction of the tolerance band, must be positive (got " +
                           std::to_string(slope_error_fraction) + ")");
  if (saturation_dimensions < 1)
    throw InvalidInput(ErrorCode::invalid_parameter, "saturation needs at least 1 dimension (got 0)");
  if (!(min_plateau_ratio >= 1.0) || !std::isfinite(min_plateau_ratio))
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "the plateau's smallest extent, a factor in eps, must be finite and at least 1 (got " +
                           std::to_string(min_plateau_ratio) + ")");
  if (!(projection_tolerance >= 0.0))
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "the projection check's tolerance, a fraction of the plateau's slope, must be at least 0 (got " +
                           std::to_string(projection_tolerance) + ")");
  if (!(noise_fill_fraction > 0.0))
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "the noise check's fraction of the way from the plateau's slope to m must be positive (got " +
                           std::to_string(noise_fill_fraction) + "; inf turns the check off)");
  if (!(delay_tolerance >= 0.0))
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "the delay check's tolerance, an absolute difference of D2, must be at least 0 (got " +
                           std::to_string(delay_tolerance) + ")");
}

std::optional<std::pair<double, double>> takens_theiler(const std::vector<double>& radius,
                                                        const std::vector<double>& c, std::uint64_t pairs_at_k,
                                                        std::size_t k) {
  if (k >= radius.size() || k >= c.size() || !(c[k] > 0.0)) return std::nullopt;
  std::size_t first = 0;
  while (first < k && !(c[first] > 0.0)) ++first;
  // Below the first populated radius C is extended as a power law with the next interval's exponent.
  const std::size_t next = first + 1 <= k ? first + 1 : first;
  if (next == first) return std::nullopt;  // one populated radius: no exponent to extend with
  const double s0 = std::log(c[next] / c[first]) / std::log(radius[next] / radius[first]);
  if (!(s0 > 0.0)) return std::nullopt;
  double integral = c[first] / s0;
  for (std::size_t j = first; j < k; ++j) {
    const double ratio = std::log(radius[j + 1] / radius[j]);
    const double s = std::log(c[j + 1] / c[j]) / ratio;
    integral += s > 1e-12 ? (c[j + 1] - c[j]) / s : c[j] * ratio;  // C flat over the interval
  }
  const double d = c[k] / integral;
  return std::make_pair(d, d / std::sqrt(static_cast<double>(std::max<std::uint64_t>(pairs_at_k, 1))));
}

namespace {

// The delete-a-group jackknife standard error of an estimate from its G leave-one-group-out values
// (Efron & Tibshirani 1993, Eq. 11.5): sqrt((G - 1) / G * sum (v_g - mean)^2).
double jackknife_error(const std::vector<double>& leave_out) {
  const double g = static_cast<double>(leave_out.size());
  double mean = 0.0;
  for (const double v : leave_out) mean += v;
  mean /= g;
  double sum = 0.0;
  for (const double v : leave_out) sum += (v - mean) * (v - mean);
  return std::sqrt((g - 1.0) / g * sum);
}

// ln C and the local slopes with each group of reference points left out in turn
// ([group][m index][radius index]); empty for exact counts (no groups). A radius is defined in a
// leave-out curve where it is in the full curve and the remaining groups still have pairs there.
struct JackknifeCurves {
  std::vector<std::vector<std::vector<std::optional<double>>>> log_c, local_slope;
};

JackknifeCurves jackknife_curves(const CorrelationSumResult& sums, const std::vector<double>& log_r,
                                 const std::vector<std::vector<std::optional<double>>>& log_c, std::size_t half_width) {
  JackknifeCurves out;
  const std::size_t groups = sums.group_pairs.size();
  if (groups < 2 || sums.group_examined.size() != groups) return out;
  for (std::size_t b = 0; b < groups; ++b) {
    std::vector<std::vector<std::optional<double>>> group_log_c(log_c.size());
    std::vector<std::vector<std::optional<double>>> group_slopes;
    for (std::size_t d = 0; d < log_c.size(); ++d) {
      group_log_c[d].resize(log_c[d].size());
      for (std::size_t k = 0; k < log_c[d].size(); ++k) {
        const std::uint64_t pairs = sums.pairs[d][k] - sums.group_pairs[b][d][k];
        const std::uint64_t examined = sums.examined[d][k] - sums.group_examined[b][d][k];
        if (log_c[d][k] && pairs > 0 && examined > 0)
          group_log_c[d][k] = std::log(static_cast<double>(pairs) / static_cast<double>(examined));
      }
      group_slopes.push_back(local_slopes(log_r, group_log_c[d], half_width));
    }
    out.log_c.push_back(std::move(group_log_c));
    out.local_slope.push_back(std::move(group_slopes));
  }
  return out;
}

}  // namespace

CorrelationDimensionResult correlation_dimension(const CorrelationSumResult& sums,
                                                 const CorrelationDimensionOptions& options) {
  options.validate();
  CorrelationDimensionResult out;
  out.dimension = sums.dimension;
  out.radius = sums.radius;
  const std::size_t dims = sums.dimension.size();
  const std::size_t radii = sums.radius.size();
  if (dims == 0 || radii < 2)
    throw InvalidInput(ErrorCode::invalid_parameter, "the correlation dimension needs at least 2 radii and 1 dimension (got " +
                                                         std::to_string(radii) + " radii, " + std::to_string(dims) + " dimensions)");
  std::vector<double> log_r(radii);
  for (std::size_t k = 0; k < radii; ++k) log_r[k] = std::log(sums.radius[k]);

  // The evidence behind a region: the e-folds of pairs that enter across it.
  std::vector<std::vector<double>> support(dims, std::vector<double>(radii));
  for (std::size_t d = 0; d < dims; ++d)
    for (std::size_t k = 0; k < radii; ++k)
      support[d][k] = std::log(std::max(1.0, static_cast<double>(sums.pairs[d][k])));

  // Regions stay at radii small against the diameter; the slopes above are reported, not searched.
  std::size_t searched = radii;
  if (std::isfinite(options.max_region_fraction) && sums.range > 0.0 &&
      std::isfinite(options.max_region_fraction * sums.range)) {
    out.max_region_radius = options.max_region_fraction * sums.range;
    searched = static_cast<std::size_t>(
        std::upper_bound(sums.radius.begin(), sums.radius.end(), *out.max_region_radius) - sums.radius.begin());
  }
  const auto searchable = [&](const std::vector<std::optional<double>>& slopes) {
    std::vector<std::optional<double>> s = slopes;
    for (std::size_t k = searched; k < s.size(); ++k) s[k].reset();
    return s;
  };

  // Steps 1-2: local slopes and a region per dimension.
  std::vector<std::vector<std::optional<double>>> log_c(dims, std::vector<std::optional<double>>(radii));
  for (std::size_t d = 0; d < dims; ++d) {
    for (std::size_t k = 0; k < radii; ++k)
      // Left out: too few pairs for a meaningful ratio, and radii where every examined pair is
      // already closer than eps (C = 1 says nothing about the scaling, only that eps exceeds the
      // attractor).
      if (sums.pairs[d][k] >= options.min_pairs && sums.correlation_sum[d][k] > 0.0 &&
          sums.pairs[d][k] < sums.examined[d][k])
        log_c[d][k] = std::log(sums.correlation_sum[d][k]);
    out.local_slope.push_back(local_slopes(log_r, log_c[d], options.region.half_width));
  }
  // The slopes a region may use: without the statistically unsupported ones (reference subsets).
  std::vector<std::vector<std::optional<double>>> usable = out.local_slope;
  const JackknifeCurves jackknife = jackknife_curves(sums, log_r, log_c, options.region.half_width);
  if (!jackknife.log_c.empty()) {
    out.local_slope_error.assign(dims, std::vector<std::optional<double>>(radii));
    for (std::size_t d = 0; d < dims; ++d)
      for (std::size_t k = 0; k < radii; ++k) {
        if (!out.local_slope[d][k]) continue;
        std::vector<double> leave_out;
        for (const auto& slopes : jackknife.local_slope)
          if (slopes[d][k]) leave_out.push_back(*slopes[d][k]);
        if (leave_out.size() == jackknife.local_slope.size()) out.local_slope_error[d][k] = jackknife_error(leave_out);
        const double allowed = options.slope_error_fraction * options.region.tolerance * std::abs(*out.local_slope[d][k]);
        if (!out.local_slope_error[d][k] || !(*out.local_slope_error[d][k] <= allowed)) {
          usable[d][k].reset();
          if (k < searched) ++out.slopes_too_uncertain;
        }
      }
  }
  // Finite-set structure: counts that stop changing over a run of radii in the highest dimension.
  {
    const auto& p = sums.pairs[dims - 1];
    for (std::size_t k = 0; k + 2 < radii; ++k) {
      std::size_t end = k;
      while (end + 1 < radii && p[end + 1] == p[k]) ++end;
      // (A run at C = 1, every pair already inside eps, is the attractor's size, not a finite set.)
      if (p[k] > 0 && p[k] < sums.examined[dims - 1][k] && end >= k + 2) out.finite_set_below = sums.radius[end];
      k = end;
    }
  }
  for (std::size_t d = 0; d < dims; ++d) {
    const auto region = find_scaling_region(log_r, {searchable(usable[d])}, options.region, support[d]);
    if (region) {
      out.d2_by_dimension.push_back(fit_slope(log_r, log_c[d], region->first, region->last));
      out.d2_by_dimension_interval.push_back(Interval{region->slope_min, region->slope_max});
      out.region_by_dimension.push_back(Interval{sums.radius[region->first], sums.radius[region->last]});
    } else {
      out.d2_by_dimension.push_back(std::nullopt);
      out.d2_by_dimension_interval.push_back(std::nullopt);
      out.region_by_dimension.push_back(std::nullopt);
    }
  }
  out.eckmann_ruelle_limit = 2.0 * std::log10(static_cast<double>(std::max<std::size_t>(sums.points, 1)));

  // Step 3: the highest dimensions that have an estimate must share one plateau.
  std::vector<std::size_t> top;
  for (std::size_t d = dims; d-- > 0 && top.size() < options.saturation_dimensions;)
    if (out.d2_by_dimension[d]) top.insert(top.begin(), d);
  // The fewest close pairs of the saturating dimensions over radii first..last: a stretch's slopes are
  // read from at least that many (d2_answer weighs a reading below the plateau by its counting error).
  const auto fewest_pairs = [&](std::size_t first, std::size_t last) {
    std::uint64_t fewest = std::numeric_limits<std::uint64_t>::max();
    for (const auto d : top)
      for (std::size_t k = first; k <= last; ++k) fewest = std::min(fewest, sums.pairs[d][k]);
    return fewest;
  };
  std::ostringstream why;
  const auto list_d2 = [&] {
    std::ostringstream s;
    for (std::size_t d = 0; d < dims; ++d)
      if (out.d2_by_dimension[d]) s << (s.tellp() > 0 ? ", " : "") << "m=" << out.dimension[d] << ": " << *out.d2_by_dimension[d];
    return s.str();
  };
  if (top.empty()) {
    out.status = D2Status::no_scaling_region;
    why << "no dimension has a range of at least " << options.region.min_points << " radii with local slopes within "
        << options.region.tolerance * 100 << "% of their mean";
    if (out.max_region_radius)
      why << " at radii up to " << *out.max_region_radius << " (" << options.max_region_fraction
          << " of the range: larger scales show the attractor's shape, not its dimension)";
  } else if (top.size() < options.saturation_dimensions) {
    out.status = D2Status::not_saturated;
    why << "only " << top.size() << " dimension(s) have a scaling region, " << options.saturation_dimensions
        << " are needed to judge saturation (" << list_d2() << ")";
  } else {
    std::vector<std::vector<std::optional<double>>> curves;
    for (const auto d : top) curves.push_back(searchable(usable[d]));
    // The highest dimension has the fewest pairs: its count is the shared region's support. The
    // plateau must also span min_plateau_ratio in eps: a shorter flat stretch may be the crest of
    // a hump (docs/reference/correlation_dimension.md, step 3).
    ScalingRegionOptions plateau_options = options.region;
    plateau_options.min_width = std::log(options.min_plateau_ratio);
    const auto shared = find_scaling_region(log_r, curves, plateau_options, support[top.back()]);
    // Step 4 (small-scale limit): a second plateau at smaller radii, searched below the first.
    std::optional<ScalingRegion> below, lacunar_below;
    if (shared && shared->first >= options.region.min_points) {
      const std::size_t n = shared->first;
      std::vector<std::vector<std::optional<double>>> lower;
      for (const auto& curve : curves) lower.emplace_back(curve.begin(), curve.begin() + static_cast<std::ptrdiff_t>(n));
      below = find_scaling_region(std::span<const double>(log_r).first(n), lower, options.region,
                                  std::span<const double>(support[top.back()]).first(n));
      // Disagreement means the two plateaus' allowances (mean +- tolerance * |mean|) do not overlap,
      // i.e. the means are more than about twice the tolerance apart. Closer plateaus are one scaling
      // seen through the oscillation of the local slopes in scale (lacunarity: at N = 10^5 Henon's
      // slopes average 1.13 over eps in [0.006, 0.014] and 1.23 over [0.019, 0.053], around its D2 of
      // 1.22).
      if (below && std::abs(below->slope - shared->slope) <=
                       options.region.tolerance * (std::abs(below->slope) + std::abs(shared->slope))) {
        lacunar_below = below;
        below.reset();
      }
    }
    const auto plateau = [&](const ScalingRegion& r) {
      return D2Plateau{Interval{sums.radius[r.first], sums.radius[r.last]}, r.slope, Interval{r.slope_min, r.slope_max},
                       fewest_pairs(r.first, r.last)};
    };
    // Other readings of a saturated D2, reported, not judged: the plateau below that step 4 took for
    // the same scaling (within the allowances), and the best one above the region, before the slopes
    // fall towards 0 at the attractor's size. Henon, N = 10^5: 1.23 is chosen, 1.13 lies below and
    // 1.19 above; which one wins is a near-tie in support (docs/reference/correlation_dimension.md, step 7).
    if (shared && !below) {
      if (lacunar_below) out.other_plateaus.push_back(plateau(*lacunar_below));
      const std::size_t begin = shared->last + 1;
      if (searched > begin && searched - begin >= options.region.min_points) {
        std::vector<std::vector<std::optional<double>>> upper;
        for (const auto& curve : curves)
          upper.emplace_back(curve.begin() + static_cast<std::ptrdiff_t>(begin), curve.begin() + static_cast<std::ptrdiff_t>(searched));
        if (const auto above = find_scaling_region(std::span<const double>(log_r).subspan(begin, searched - begin), upper,
                                                   plateau_options,
                                                   std::span<const double>(support[top.back()]).subspan(begin, searched - begin))) {
          ScalingRegion shifted = *above;
          shifted.first += begin;
          shifted.last += begin;
          out.other_plateaus.push_back(plateau(shifted));
        }
      }
    }
    // Step 5: the dimensions below the saturating ones, over the shared plateau's radii, from
    // m >= 2 D2 + 1 up (Takens' bound with d = D2): in lower dimensions the delay map folds the set
    // onto itself, and pairs across the fold raise the local slopes at finite scales (25 circles
    // in m = 2 read 1.44 where m = 4..6 agree on 1.02), which says nothing about the set's D2.
    if (shared) {
      const std::size_t count = shared->last - shared->first + 1;
      const double lowest = 2.0 * shared->slope + 1.0;
      for (std::size_t d = 0; d < top.front(); ++d) {
        if (static_cast<double>(out.dimension[d]) < lowest) continue;
        double sum = 0.0;
        std::size_t n = 0;
        for (std::size_t k = shared->first; k <= shared->last; ++k)
          if (usable[d][k]) {
            sum += *usable[d][k];
            ++n;
          }
        if (2 * n < count || n == 0) continue;
        const double mean = sum / static_cast<double>(n);
        if (!out.steepest_lower_slope || mean > *out.steepest_lower_slope) {
          out.steepest_lower_dimension = out.dimension[d];
          out.steepest_lower_slope = mean;
        }
      }
    }
    const bool projection_contradicts =
        shared && out.steepest_lower_slope &&
        *out.steepest_lower_slope > shared->slope + options.projection_tolerance * std::abs(shared->slope);
    // Steps 6 and 7 read runs of radii as long as a plateau's local slopes need: min_points less the
    // half-width on each side.
    const std::size_t hw = options.region.half_width;
    const std::size_t needed = options.region.min_points > 2 * hw ? options.region.min_points - 2 * hw : 1;
    // Step 6: noise below the plateau. At a radius where every saturating dimension m reads a usable
    // local slope more than noise_fill_fraction of the way from the plateau's slope to m, and not
    // above m (1 + tolerance), the dimensions fill their space as noise does; pairs entering in
    // bursts (the quasi-lattice of a torus sampled at small scales) read slopes above m and do not
    // count. The regime must hold over consecutive radii whose local slopes span min_points radii,
    // the evidence a plateau needs. noise_floor: the largest radius at which such a run is long enough.
    if (shared && std::isfinite(options.noise_fill_fraction)) {
      std::size_t run = 0;
      for (std::size_t k = 0; k < shared->first; ++k) {
        std::vector<double> slopes;
        for (const auto d : top) {
          const auto& s = usable[d][k];
          const double m = static_cast<double>(out.dimension[d]);
          if (!s || !(*s > shared->slope + options.noise_fill_fraction * (m - shared->slope)) ||
              *s > m * (1.0 + options.region.tolerance))
            break;
          slopes.push_back(*s);
        }
        run = slopes.size() == top.size() ? run + 1 : 0;
        if (run >= needed) {
          out.noise_floor = sums.radius[k];
          out.noise_floor_slopes = std::move(slopes);
        }
      }
    }
    // Step 7 (reported; d2_answer judges it): the smallest scales the counts resolve well, below the
    // plateau. From the lowest radius above any finite-set structure where every saturating dimension
    // has a usable local slope from at least small_scale_min_pairs pairs, as many radii as a plateau's
    // local slopes need, each of them so counted (else nothing is reported); their slopes say whether
    // the slope still moves towards the small-scale limit.
    if (shared && options.small_scale_min_pairs > 0) {
      const auto well_counted = [&](std::size_t k) {
        // (Where the data are a finite set of points no dimension can be read.)
        if (out.finite_set_below && sums.radius[k] <= *out.finite_set_below) return false;
        for (const auto d : top)
          if (!usable[d][k] || sums.pairs[d][k] < options.small_scale_min_pairs) return false;
        return true;
      };
      std::size_t first = 0;
      while (first < shared->first && !well_counted(first)) ++first;
      if (first + needed <= shared->first) {
        bool run = true;
        for (std::size_t k = first; k < first + needed; ++k) run = run && well_counted(k);
        if (run) {
          double sum = 0.0, lo = std::numeric_limits<double>::infinity(), hi = -lo;
          for (std::size_t k = first; k < first + needed; ++k)
            for (const auto d : top) {
              sum += *usable[d][k];
              lo = std::min(lo, *usable[d][k]);
              hi = std::max(hi, *usable[d][k]);
            }
          out.smallest_scales = D2Plateau{Interval{sums.radius[first], sums.radius[first + needed - 1]},
                                          sum / static_cast<double>(needed * top.size()), Interval{lo, hi},
                                          fewest_pairs(first, first + needed - 1)};
        }
      }
    }
    if (!shared) {
      out.status = D2Status::not_saturated;
      why << "the highest dimensions share no plateau";
      if (const auto narrow = find_scaling_region(log_r, curves, options.region, support[top.back()]))
        why << " spanning a factor of " << options.min_plateau_ratio << " in eps (their local slopes agree on "
            << narrow->slope << " only for eps in [" << sums.radius[narrow->first] << ", " << sums.radius[narrow->last]
            << "], a factor of " << sums.radius[narrow->last] / sums.radius[narrow->first]
            << ": too short to tell a plateau from the crest of a hump)";
      why << "; D2(m) by dimension: " << list_d2();
    } else if (below) {
      out.status = D2Status::scale_dependent;
      out.plateaus = {plateau(*shared), plateau(*below)};
      out.saturation_dimensions_used.clear();
      for (const auto d : top) out.saturation_dimensions_used.push_back(out.dimension[d]);
      why << "local slopes of m = " << out.dimension[top.front()] << ".." << out.dimension[top.back()] << " agree on "
          << shared->slope << " for eps in [" << out.plateaus[0].radii.low << ", " << out.plateaus[0].radii.high
          << "] but on " << below->slope << " at smaller scales, eps in [" << out.plateaus[1].radii.low << ", "
          << out.plateaus[1].radii.high << "]: the slope still changes with scale, so neither plateau is the "
          << "small-scale limit D2 (a longer record reaches smaller scales)";
    } else if (projection_contradicts) {
      out.status = D2Status::not_saturated;
      out.plateaus = {plateau(*shared)};
      why << "local slopes of m = " << out.dimension[top.front()] << ".." << out.dimension[top.back()] << " agree on "
          << shared->slope << " for eps in [" << out.plateaus[0].radii.low << ", " << out.plateaus[0].radii.high
          << "], but m = " << *out.steepest_lower_dimension << " reads " << *out.steepest_lower_slope
          << " there, more than " << options.projection_tolerance * 100
          << "% higher: a projection cannot have a larger correlation dimension than the set it projects, so "
          << "this plateau is not the saturated D2 (uneven density along a curve at these scales reads like this)";
    } else if (out.noise_floor) {
      out.status = D2Status::noise_limited;
      out.plateaus = {plateau(*shared)};
      why << "local slopes of m = " << out.dimension[top.front()] << ".." << out.dimension[top.back()] << " agree on "
          << shared->slope << " for eps in [" << out.plateaus[0].radii.low << ", " << out.plateaus[0].radii.high
          << "], but at eps = " << *out.noise_floor << " below it they read";
      for (std::size_t i = 0; i < top.size(); ++i) why << (i > 0 ? ", " : " ") << out.noise_floor_slopes[i];
      why << " (m = " << out.dimension[top.front()] << ".." << out.dimension[top.back()] << "), more than "
          << options.noise_fill_fraction * 100 << "% of the way from " << shared->slope
          << " to m over consecutive radii down to there: the embedding dimensions fill their "
          << "space there as measurement noise does, so the smaller scales where D2 is defined cannot be read "
          << "and this plateau is not the attractor's D2 (reduce the noise, or read it as a large-scale "
          << "exponent only)";
    } else {
      out.plateaus = {plateau(*shared)};
      out.status = D2Status::saturated;
      double sum = 0.0, lo = shared->slope_min, hi = shared->slope_max;
      for (const auto d : top) {
        const double fit = fit_slope(log_r, log_c[d], shared->first, shared->last).value_or(shared->slope);
        sum += fit;
        lo = std::min(lo, fit);
        hi = std::max(hi, fit);
      }
      out.d2 = sum / static_cast<double>(top.size());
      out.d2_interval = Interval{lo, hi};
      if (!jackknife.log_c.empty()) {
        // D2 with each group left out, over the same region and dimensions.
        std::vector<double> leave_out;
        for (const auto& group_log_c : jackknife.log_c) {
          double group_sum = 0.0;
          std::size_t fitted = 0;
          for (const auto d : top)
            if (const auto fit = fit_slope(log_r, group_log_c[d], shared->first, shared->last)) {
              group_sum += *fit;
              ++fitted;
            }
          if (fitted == top.size()) leave_out.push_back(group_sum / static_cast<double>(fitted));
        }
        if (leave_out.size() == jackknife.log_c.size()) out.d2_standard_error = jackknife_error(leave_out);
      }
      out.scaling_region = Interval{sums.radius[shared->first], sums.radius[shared->last]};
      out.saturation_dimensions_used.clear();
      for (const auto d : top) out.saturation_dimensions_used.push_back(out.dimension[d]);
      const std::size_t d_top = top.back();
      if (const auto tt = takens_theiler(sums.radius, sums.correlation_sum[d_top], sums.pairs[d_top][shared->last],
                                         shared->last)) {
        out.takens_theiler = tt->first;
        out.takens_theiler_error = tt->second;
      }
      why << "local slopes of m = " << out.dimension[top.front()] << ".." << out.dimension[top.back()]
          << " agree within " << options.region.tolerance * 100 << "% for eps in [" << out.scaling_region->low << ", "
          << out.scaling_region->high << "]";
    }
  }
  if (out.slopes_too_uncertain > 0)
    why << "; " << out.slopes_too_uncertain << " local slope(s) left out of the search: their jackknife error over "
        << sums.group_pairs.size() << " groups of reference points exceeds " << options.slope_error_fraction
        << " of the tolerance band (more reference points make them usable)";
  if (out.finite_set_below)
    why << "; below eps = " << *out.finite_set_below << " the pair counts stop changing over consecutive radii: at "
        << "those scales the data are a finite set of points (periodic with a rational period, or quantised), "
        << "and no dimension can be read there";
  double largest = out.d2.value_or(0.0);
  for (const auto& v : out.d2_by_dimension)
    if (v) largest = std::max(largest, *v);
  out.exceeds_eckmann_ruelle = largest > out.eckmann_ruelle_limit;
  if (out.exceeds_eckmann_ruelle)
    why << "; an estimate exceeds the Eckmann-Ruelle limit 2 log10(N) = " << out.eckmann_ruelle_limit
        << " and cannot be trusted";
  if (const std::string ties = ties_note(sums.ties); !ties.empty()) why << "; " << ties;
  out.explanation = why.str();
  return out;
}

namespace {

// A saturated plateau that a reproducibility check refuses: the status becomes not_reproduced, the
// value and what was read off the plateau are withdrawn (the plateau stays in `plateaus`), and the
// explanation leads with `why`, keeping the earlier one under `label`.
void withdraw_as_not_reproduced(CorrelationDimensionResult& d2, const std::string& why, const char* label) {
  d2.status = D2Status::not_reproduced;
  d2.d2.reset();
  d2.d2_interval.reset();
  d2.scaling_region.reset();
  d2.takens_theiler.reset();
  d2.takens_theiler_error.reset();
  d2.d2_standard_error.reset();  // the error of a value no longer reported
  d2.explanation = why + (d2.explanation.empty() ? "" : std::string(" [") + label + ": " + d2.explanation + "]");
}

}  // namespace

void require_reproduced_by_halves(CorrelationDimensionResult& full, const CorrelationDimensionResult& first,
                                  const CorrelationDimensionResult& second, const CorrelationDimensionOptions& options) {
  options.validate();
  full.first_half_status = first.status;
  full.second_half_status = second.status;
  full.first_half_d2 = first.d2;
  full.second_half_d2 = second.d2;
  if (full.status != D2Status::saturated) return;
  std::ostringstream why;
  const auto text = [](const CorrelationDimensionResult& h) {
    return h.d2 ? std::to_string(*h.d2) : std::string(to_string(h.status));
  };
  if (!first.d2 || !second.d2) {
    why << "the halves of the record do not both saturate (first half: " << text(first) << ", second half: "
        << text(second) << ")";
  } else if (std::abs(*first.d2 - *second.d2) >
             options.region.tolerance * (std::abs(*first.d2) + std::abs(*second.d2))) {
    why << "the halves of the record disagree (" << *first.d2 << " and " << *second.d2 << ", more than "
        << 2 * options.region.tolerance * 100 << "% apart)";
  } else {
    return;  // reproduced
  }
  why << "; the full record's plateau (" << *full.d2 << " for eps in [" << full.scaling_region->low << ", "
      << full.scaling_region->high << "]) is not reproduced by its two halves, so it is not reported as D2 "
      << "(a longer record may settle it)";
  withdraw_as_not_reproduced(full, why.str(), "full record");
}

void require_reproduced_at_delay(CorrelationDimensionResult& d2, const CorrelationDimensionResult& variant,
                                 std::size_t variant_delay, const CorrelationDimensionOptions& options) {
  options.validate();
  d2.variant_delay = variant_delay;
  d2.variant_delay_status = variant.status;
  d2.variant_delay_d2 = variant.d2;
  if (d2.status != D2Status::saturated) return;
  std::ostringstream why;
  if (!variant.d2) {
    why << "at delay " << variant_delay << " the same sums do not saturate (" << to_string(variant.status) << ")";
  } else if (std::abs(*variant.d2 - *d2.d2) > options.delay_tolerance) {
    why << "at delay " << variant_delay << " the same sums read " << *variant.d2 << ", more than "
        << options.delay_tolerance << " from " << *d2.d2;
  } else {
    return;  // reproduced
  }
  why << "; the plateau (" << *d2.d2 << " for eps in [" << d2.scaling_region->low << ", " << d2.scaling_region->high
      << "]) depends on the embedding, so it is not reported as D2 (D2 belongs to the attractor; smaller "
      << "scales, i.e. a longer record, may settle it)";
  withdraw_as_not_reproduced(d2, why.str(), "chosen delay");
}

}  // namespace chaos
