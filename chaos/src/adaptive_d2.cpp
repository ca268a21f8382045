#include "chaos/adaptive_d2.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include "chaos/automatic_analysis.hpp"
#include "chaos/error.hpp"

namespace chaos {

void AdaptiveD2Options::validate() const {
  if (!(target > 0.0) || !std::isfinite(target))
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "the fast D2's target agreement must be positive and finite (got " + std::to_string(target) + ")");
  if (!(confidence > 0.0) || !std::isfinite(confidence))
    throw InvalidInput(ErrorCode::invalid_parameter, "the fast D2's confidence factor must be positive and finite (got " +
                                                         std::to_string(confidence) + ")");
  if (initial_reference_points < 2)
    throw InvalidInput(ErrorCode::invalid_parameter, "the fast D2 needs at least 2 initial reference points (got " +
                                                         std::to_string(initial_reference_points) + ")");
}

namespace {

using Table = std::vector<std::vector<std::uint64_t>>;

void add(Table& into, const Table& from) {
  for (std::size_t d = 0; d < into.size(); ++d)
    for (std::size_t k = 0; k < into[d].size(); ++k) into[d][k] += from[d][k];
}

// C = pairs / examined again after the counts changed (0 where nothing was examined, as in
// correlation_sum).
void recompute_correlation_sum(CorrelationSumResult& sums) {
  for (std::size_t d = 0; d < sums.pairs.size(); ++d)
    for (std::size_t k = 0; k < sums.pairs[d].size(); ++k)
      sums.correlation_sum[d][k] = sums.examined[d][k] > 0 ? static_cast<double>(sums.pairs[d][k]) /
                                                                 static_cast<double>(sums.examined[d][k])
                                                           : 0.0;
}

// The counts of two disjoint, equally large reference sets added up. Their jackknife groups are
// equally large too; adjacent ones are joined so the merged counts keep the same number of groups.
CorrelationSumResult merge(CorrelationSumResult a, const CorrelationSumResult& b) {
  add(a.pairs, b.pairs);
  add(a.examined, b.examined);
  std::vector<Table> pairs = a.group_pairs, examined = a.group_examined;
  pairs.insert(pairs.end(), b.group_pairs.begin(), b.group_pairs.end());
  examined.insert(examined.end(), b.group_examined.begin(), b.group_examined.end());
  a.group_pairs.clear();
  a.group_examined.clear();
  for (std::size_t g = 0; g + 1 < pairs.size(); g += 2) {
    add(pairs[g], pairs[g + 1]);
    add(examined[g], examined[g + 1]);
    a.group_pairs.push_back(std::move(pairs[g]));
    a.group_examined.push_back(std::move(examined[g]));
  }
  recompute_correlation_sum(a);
  a.points += b.points;
  return a;
}

bool overlap(const std::optional<Interval>& a, const std::optional<Interval>& b) {
  return a && b && std::max(a->low, b->low) <= std::min(a->high, b->high);
}

// How far apart two scaling regions lie, in steps of the radius grid: the larger of the two ends'
// distances (a region's ends are radii of the grid).
std::size_t region_distance(const std::vector<double>& radius, const Interval& a, const Interval& b) {
  const auto index = [&](double r) {
    return static_cast<std::ptrdiff_t>(std::lower_bound(radius.begin(), radius.end(), r) - radius.begin());
  };
  return static_cast<std::size_t>(
      std::max(std::abs(index(a.low) - index(b.low)), std::abs(index(a.high) - index(b.high))));
}

// The counts with jackknife group g left out (no groups of their own).
CorrelationSumResult without_group(const CorrelationSumResult& sums, std::size_t g) {
  CorrelationSumResult out = sums;
  out.group_pairs.clear();
  out.group_examined.clear();
  for (std::size_t d = 0; d < out.pairs.size(); ++d)
    for (std::size_t k = 0; k < out.pairs[d].size(); ++k) {
      out.pairs[d][k] -= sums.group_pairs[g][d][k];
      out.examined[d][k] -= sums.group_examined[g][d][k];
    }
  recompute_correlation_sum(out);
  return out;
}

// Whether the plateau choice survives leaving out each group of reference points in turn: every
// leave-out saturates on a plateau overlapping the full one, within half the target of its D2.
// Where several plateaus are nearly tied in support (Henon's lacunar local slopes), a few reference
// points decide which wins, and a D2 that hinges on them is not an estimate of the exact one.
bool stable_choice(const CorrelationSumResult& sums, const CorrelationDimensionResult& d2,
                   const CorrelationDimensionOptions& dimension, double target) {
  if (!d2.d2) return false;
  for (std::size_t g = 0; g < sums.group_pairs.size(); ++g) {
    const CorrelationDimensionResult left = correlation_dimension(without_group(sums, g), dimension);
    if (!left.d2 || !overlap(left.scaling_region, d2.scaling_region) || std::abs(*left.d2 - *d2.d2) > target / 2.0)
      return false;
  }
  return true;
}

// Another admissible plateau of the saturating dimensions (CorrelationDimensionResult::
// other_plateaus) whose slope differs from D2 by more than the target: the counts support two
// readings at this precision, and which one wins is a near-tie in support, not the attractor.
std::optional<double> competing_plateau(const CorrelationDimensionResult& d2, double target) {
  if (!d2.d2) return std::nullopt;
  for (const D2Plateau& other : d2.other_plateaus)
    if (std::abs(other.slope - *d2.d2) > target) return other.slope;
  return std::nullopt;
}

}  // namespace

AdaptiveD2Result adaptive_correlation_dimension(std::span<const double> x, CorrelationSumOptions sums,
                                                const CorrelationDimensionOptions& dimension,
                                                const AdaptiveD2Options& options) {
  options.validate();
  sums.validate();
  if (sums.reference_points != 0 || sums.reference_offset != 0 || sums.pairs_per_radius != 0)
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "the fast D2 chooses its own reference subset: reference_points, reference_offset and "
                       "pairs_per_radius must be 0 (got " + std::to_string(sums.reference_points) + ", " +
                           std::to_string(sums.reference_offset) + ", " + std::to_string(sums.pairs_per_radius) + ")");
  sums.progress = nullptr;  // many short counts: a progress line would restart at each
  const std::size_t span = (sums.max_dimension - 1) * sums.delay;
  const std::size_t points = x.size() > span ? x.size() - span : 0;

  AdaptiveD2Result out;
  std::ostringstream why;
  const auto exact = [&] {
    CorrelationSumOptions all = sums;
    all.reference_points = 0;
    out.sums = correlation_sum(x, all);
    out.d2 = correlation_dimension(out.sums, dimension);
    out.reference_points = 0;
    out.exact = true;
  };
  std::size_t counted = options.initial_reference_points;  // T: points behind `total`
  // (counted > points / 16, not 16 * counted > points: a huge --fast-start must not wrap around)
  if (counted > points / 16) {  // the first round would already count more than an eighth of the points
    exact();
    why << "exact counts: one round needs 2 x " << counted << " reference points, more than an eighth of the "
        << points;
    out.explanation = why.str();
    return out;
  }
  // One search structure for every round's subsets: the whole record's, or one per half.
  std::optional<CorrelationSumSubsets> whole, first, second;
  bool halves = options.halves;
  if (halves) {
    const auto [x1, x2] = record_halves(x);
    try {
      first.emplace(x1, sums);
      second.emplace(x2, sums);
    } catch (const InvalidInput&) {
      // A half too short to embed (or constant): the subsets come from the whole record, and
      // out.halves stays false, so a caller's halves check (check_record_halves) says why.
      halves = false;
    }
  }
  if (!halves) whole.emplace(x, sums);
  // Subset a: the first T reference points of the whole record, or of the first half; b: the next T
  // of the whole record, or the first T of the second half.
  CorrelationSumResult a = halves ? first->count(0, counted) : whole->count(0, counted);
  CorrelationSumResult b = halves ? second->count(0, counted) : whole->count(counted, counted);
  CorrelationDimensionResult a_d2 = correlation_dimension(a, dimension);
  for (;;) {
    const CorrelationDimensionResult b_d2 = correlation_dimension(b, dimension);
    CorrelationSumResult merged = merge(a, b);
    CorrelationDimensionResult merged_d2 = correlation_dimension(merged, dimension);
    AdaptiveD2Round round;
    round.reference_points = counted;
    round.status_a = a_d2.status;
    round.status_b = b_d2.status;
    round.status_merged = merged_d2.status;
    round.d2_a = a_d2.d2;
    round.d2_b = b_d2.d2;
    round.d2_merged = merged_d2.d2;
    round.region_a = a_d2.scaling_region;
    round.region_b = b_d2.scaling_region;
    round.region_merged = merged_d2.scaling_region;
    round.standard_error = merged_d2.d2_standard_error;
    round.agreed = a_d2.d2 && b_d2.d2 && merged_d2.d2 && std::abs(*a_d2.d2 - *b_d2.d2) <= options.target &&
                   overlap(merged_d2.scaling_region, a_d2.scaling_region) &&
                   overlap(merged_d2.scaling_region, b_d2.scaling_region);
    if (round.agreed) {
      const Interval& region = *merged_d2.scaling_region;
      round.region_shift = std::max(region_distance(merged.radius, region, *a_d2.scaling_region),
                                    region_distance(merged.radius, region, *b_d2.scaling_region));
    }
    round.same_region = round.agreed && *round.region_shift <= options.region_slack;
    round.precise = round.standard_error && options.confidence * *round.standard_error <= options.target;
    round.stable = round.same_region && round.precise && stable_choice(merged, merged_d2, dimension, options.target);
    if (round.stable) {
      round.competing = competing_plateau(merged_d2, options.target);
      round.stable = !round.competing;
    }
    out.rounds.push_back(round);
    // Another round would count 4T in all: more than an eighth of the points, or beyond the budget
    // (T > points / 32, not 32 T > points: no wrap-around).
    const bool eighth = counted > points / 32, over_budget = options.budget != 0 && counted > options.budget / 4;
    if (round.stable || eighth || over_budget) {
      out.settled = round.stable;
      out.reference_points = 2 * counted;
      if (halves) {
        out.halves = true;
        if (merged_d2.status == D2Status::saturated)
          require_reproduced_by_halves(merged_d2, a_d2, b_d2, dimension);
      }
      out.sums = std::move(merged);
      out.d2 = std::move(merged_d2);
      const char* const source = halves ? " reference points, one subset from each half of the record,"
                                        : " reference points";
      if (round.stable)
        why << "two disjoint subsets of " << counted << source << " agree (D2 " << *round.d2_a << " and "
            << *round.d2_b << ", within " << options.target << ", on scaling regions within " << options.region_slack
            << (options.region_slack == 1 ? " radius" : " radii")
            << " of the merged one at both ends), the merged D2's standard error " << *round.standard_error
            << " is at most " << options.target << " / " << options.confidence
            << ", leaving out any group of them keeps the plateau, and no other plateau reads another D2; D2 from all "
            << 2 * counted << " of them";
      else  // unsettled: the counts so far answer, rough, with what their subsets read (subsets_answer)
        why << "two disjoint subsets of up to " << counted << source << " did not agree within " << options.target
            << " on one unambiguous plateau and scaling region, precisely enough, that leaving out any group of "
            << "reference points keeps (another round would count "
            << (eighth ? "more than an eighth of the " + std::to_string(points) + " points"
                       : std::to_string(4 * counted) + " reference points, beyond the budget of " +
                             std::to_string(options.budget))
            << "); D2 from all " << 2 * counted
            << " of them, rough (a larger --fast-budget, or exact counts without --fast)";
      break;
    }
    // The next round: a and b twice as large, both halves growing, or the merged counts against the
    // next 2T points of the whole record.
    if (halves) {
      a = merge(std::move(a), first->count(counted, counted));
      b = merge(std::move(b), second->count(counted, counted));
      a_d2 = correlation_dimension(a, dimension);
    } else {
      a = std::move(merged);
      a_d2 = std::move(merged_d2);
      b = whole->count(2 * counted, 2 * counted);
    }
    counted *= 2;
  }
  out.explanation = why.str();
  return out;
}

Estimate subsets_answer(const AdaptiveD2Result& fast, const CorrelationDimensionResult& d2,
                        const CorrelationDimensionOptions& dimension) {
  // The floor goes last: an unsettled answer turns rough below, and takes the rough floor.
  Estimate e = d2_reading(d2, dimension);
  if (fast.exact || fast.rounds.empty()) return with_d2_floor(std::move(e));
  const AdaptiveD2Round& last = fast.rounds.back();
  for (const auto& v : {last.d2_a, last.d2_b})
    if (v && e.value) e.include(*v);
  if (!fast.settled) {
    // Unsettled, the exact counts may choose another of the plateaus the merged ones show (Henon's
    // lacunarity: 1.13 at small scales, 1.23 above): the interval spans them all.
    if (e.value)
      for (const auto* list : {&d2.plateaus, &d2.other_plateaus})
        for (const auto& p : *list) {
          e.include(p.slopes.low);
          e.include(p.slopes.high);
        }
    if (e.value && last.standard_error) {
      e.include(*e.value - 2.0 * *last.standard_error);
      e.include(*e.value + 2.0 * *last.standard_error);
    }
    e.downgrade("from " + std::to_string(fast.reference_points) +
                " reference points whose subsets did not settle (more of them: --fast-budget; exact counts: without "
                "--fast)");
  }
  return with_d2_floor(std::move(e));
}

}  // namespace chaos
