// neighbors: the neighbour-search benchmark, its checks against brute force and the JSON
// (commands.hpp; conventions in docs/reference/neighbors.md).

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include "chaos/box_grid.hpp"
#include "chaos/embedding.hpp"
#include "chaos/error.hpp"
#include "chaos/neighbors.hpp"
#include "commands.hpp"
// nanoflann, the outside reference, where it is built (CHAOS_WITH_NANOFLANN, on by default): the
// test-support adaptor tests/support/nanoflann_search.hpp. Without it its rows say so.
#if CHAOS_WITH_NANOFLANN
#include "nanoflann_search.hpp"
#endif

namespace chaos::cli {

namespace {

using Clock = std::chrono::steady_clock;
constexpr std::size_t no_slot = std::numeric_limits<std::size_t>::max();
constexpr std::size_t kd_leaf_size = 8;         // the library's default
constexpr std::size_t nanoflann_leaf_size = 10;  // nanoflann's default
constexpr bool nanoflann_built = CHAOS_WITH_NANOFLANN;
constexpr double grid_points_per_box = 4.0;     // BoxGrid::box_for's default, for k nearest

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// The query points compared with brute force: every point, or K evenly spaced ones (floor(c P / K),
// c = 0..K-1), each with its slot in the answers kept.
struct Checks {
  std::vector<std::size_t> points;
  std::vector<std::size_t> slot;  // per query point: its slot, or no_slot
};

Checks make_checks(std::size_t points, bool brute, std::optional<std::size_t> check_points) {
  Checks c;
  if (!brute) return c;
  const std::size_t k = std::min(check_points.value_or(points), points);
  c.slot.assign(points, no_slot);
  for (std::size_t s = 0; s < k; ++s) {
    const auto i = static_cast<std::size_t>(static_cast<long double>(s) * points / k);
    c.points.push_back(i);
    c.slot[i] = s;
  }
  return c;
}

// Progress over the whole run: `jobs` (size, query kind, structure) of equal weight.
struct Ticker {
  const std::function<void(double)>& progress;
  std::size_t jobs, done = 0;
  void operator()(double fraction) const {
    if (progress) progress((static_cast<double>(done) + fraction) / static_cast<double>(jobs));
  }
};

// Times ask(i, slot) over every query point (all P, or only the check points for brute force).
template <class Ask>
double time_queries(std::size_t points, const Checks& checks, bool only_checks, const Ticker& tick, Ask&& ask) {
  const std::size_t total = only_checks ? checks.points.size() : points;
  const std::size_t stride = only_checks ? 16 : 4096;
  const auto t0 = Clock::now();
  for (std::size_t q = 0; q < total; ++q) {
    const std::size_t i = only_checks ? checks.points[q] : q;
    ask(i, only_checks ? q : (checks.slot.empty() ? no_slot : checks.slot[i]));
    if (q % stride == stride - 1) tick(static_cast<double>(q + 1) / static_cast<double>(total));
  }
  return seconds_since(t0);
}

// Fills a row's check columns from the number of mismatching check points.
void judge(NeighborsRow& row, const Checks& checks, std::size_t mismatches) {
  if (checks.points.empty()) {
    row.equal = "unchecked";
    return;
  }
  row.checked = checks.points.size();
  row.mismatches = mismatches;
  row.equal = mismatches == 0 ? "yes" : "no";
}

struct Setting {
  std::size_t n, theiler;
  Norm norm;
};

NeighborsRow row_for(const Setting& s, const DelayEmbedding& points, const std::string& structure,
                     const std::string& query) {
  NeighborsRow row;
  row.n = s.n;
  row.points = points.size();
  row.structure = structure;
  row.query = query;
  return row;
}

NeighborsRow nanoflann_skipped(const Setting& s, const DelayEmbedding& points, const std::string& query) {
  NeighborsRow row = row_for(s, points, "nanoflann", query);
  row.ran = false;
  row.equal = "skipped";
  row.note = nanoflann_built
                 ? "nanoflann has no maximum norm (its pruning bound is Euclidean): --norm euclidean runs it"
                 : "this chaos was built without nanoflann (-DCHAOS_WITH_NANOFLANN=OFF)";
  return row;
}

// Fixed-radius counts from every point, per structure; brute force (at the check points) first.
void measure_counts(const Setting& s, const DelayEmbedding& points, double radius, const Checks& checks, Ticker& tick,
                    std::vector<NeighborsRow>& rows) {
  const NeighborQuery query{s.theiler, false};
  const std::size_t slots = checks.points.size();
  std::vector<std::size_t> expected(slots), got(slots);
  const auto keep = [&](std::size_t slot, std::size_t count) {
    if (slot != no_slot) got[slot] = count;
  };
  const auto mismatches = [&] {
    std::size_t bad = 0;
    for (std::size_t c = 0; c < slots; ++c) bad += got[c] != expected[c];
    return bad;
  };
  if (slots > 0) {
    NeighborsRow row = row_for(s, points, "brute_force", "count");
    row.query_seconds = time_queries(points.size(), checks, true, tick, [&](std::size_t i, std::size_t slot) {
      expected[slot] = count_within_brute_force(points, i, radius, s.norm, query);
    });
    row.queries = slots;
    row.checked = slots;
    row.equal = "reference";
    row.note = "the definition: every pair";
    rows.push_back(row);
    ++tick.done;
  }
  {
    NeighborsRow row = row_for(s, points, "kd_tree", "count");
    const auto t0 = Clock::now();
    const KdTree tree(points, s.norm, kd_leaf_size);
    row.build_seconds = seconds_since(t0);
    row.query_seconds = time_queries(points.size(), checks, false, tick, [&](std::size_t i, std::size_t slot) {
      keep(slot, tree.count_within(i, radius, query));
    });
    row.queries = points.size();
    row.memory_bytes = tree.memory_bytes();
    row.note = "leaf size " + std::to_string(kd_leaf_size);
    judge(row, checks, mismatches());
    rows.push_back(row);
    ++tick.done;
  }
  {
    NeighborsRow row = row_for(s, points, "box_grid", "count");
    const auto t0 = Clock::now();
    const BoxGrid grid(points, s.norm, radius);  // box = radius, as TISEAN
    row.build_seconds = seconds_since(t0);
    row.query_seconds = time_queries(points.size(), checks, false, tick, [&](std::size_t i, std::size_t slot) {
      keep(slot, grid.count_within(i, radius, query));
    });
    row.queries = points.size();
    row.memory_bytes = grid.memory_bytes();
    row.note = "box " + number(grid.box()) + ", " + std::to_string(grid.boxes()) + " boxes";
    judge(row, checks, mismatches());
    rows.push_back(row);
    ++tick.done;
  }
  if (s.norm != Norm::euclidean || !nanoflann_built) {
    rows.push_back(nanoflann_skipped(s, points, "count"));
    ++tick.done;
    return;
  }
#if CHAOS_WITH_NANOFLANN
  NeighborsRow row = row_for(s, points, "nanoflann", "count");
  const auto t0 = Clock::now();
  const NanoflannSearch nano(points, nanoflann_leaf_size);
  row.build_seconds = seconds_since(t0);
  row.query_seconds = time_queries(points.size(), checks, false, tick, [&](std::size_t i, std::size_t slot) {
    keep(slot, nano.count_within(i, radius, s.theiler));
  });
  row.queries = points.size();
  row.memory_bytes = nano.memory_bytes();
  row.note = "leaf size " + std::to_string(nanoflann_leaf_size);
  judge(row, checks, mismatches());
  rows.push_back(row);
  ++tick.done;
#endif
}

// The k nearest of every point, per structure; brute force (at the check points) first. Ours must
// equal brute force exactly (indices and distances, rank by rank); nanoflann in distances rank by
// rank, with every index admissible and at the distance it claims (other indices at tied distances
// are counted as tie swaps, not mismatches).
void measure_nearest(const Setting& s, const DelayEmbedding& points, std::size_t k, const Checks& checks, Ticker& tick,
                     std::vector<NeighborsRow>& rows) {
  const NeighborQuery query{s.theiler, false};
  const std::size_t slots = checks.points.size();
  std::vector<Neighbor> expected(slots * k), got(slots * k);
  std::vector<Neighbor> out;
  const auto keep = [&](std::size_t slot, const std::vector<Neighbor>& found) {
    if (slot == no_slot) return;
    // The length rule (P >= k + 2w + 1) gives every point k admissible neighbours.
    std::copy_n(found.begin(), std::min(found.size(), k), got.begin() + static_cast<std::ptrdiff_t>(slot * k));
  };
  const auto exact_mismatches = [&] {
    std::size_t bad = 0;
    for (std::size_t c = 0; c < slots; ++c)
      for (std::size_t r = 0; r < k; ++r) {
        const Neighbor &a = got[c * k + r], &b = expected[c * k + r];
        if (a.index != b.index || a.distance != b.distance) {
          ++bad;
          break;
        }
      }
    return bad;
  };
  if (slots > 0) {
    NeighborsRow row = row_for(s, points, "brute_force", "knn");
    row.query_seconds = time_queries(points.size(), checks, true, tick, [&](std::size_t i, std::size_t slot) {
      const auto found = k_nearest_brute_force(points, i, k, s.norm, query);
      std::copy_n(found.begin(), std::min(found.size(), k), expected.begin() + static_cast<std::ptrdiff_t>(slot * k));
    });
    row.queries = slots;
    row.checked = slots;
    row.equal = "reference";
    row.note = "the definition: every pair";
    rows.push_back(row);
    ++tick.done;
  }
  {
    NeighborsRow row = row_for(s, points, "kd_tree", "knn");
    const auto t0 = Clock::now();
    const KdTree tree(points, s.norm, kd_leaf_size);
    row.build_seconds = seconds_since(t0);
    row.query_seconds = time_queries(points.size(), checks, false, tick, [&](std::size_t i, std::size_t slot) {
      if (k == 1) {  // the library's nearest(), the query Cao, FNN and Lyapunov make
        const auto one = tree.nearest(i, query);
        out.assign(one ? 1 : 0, one.value_or(Neighbor{0, 0.0}));
      } else {
        tree.k_nearest(i, k, out, query);
      }
      keep(slot, out);
    });
    row.queries = points.size();
    row.memory_bytes = tree.memory_bytes();
    row.note = "leaf size " + std::to_string(kd_leaf_size) + (k == 1 ? ", nearest()" : ", k_nearest()");
    judge(row, checks, exact_mismatches());
    rows.push_back(row);
    ++tick.done;
  }
  {
    NeighborsRow row = row_for(s, points, "box_grid", "knn");
    const auto t0 = Clock::now();
    const BoxGrid grid(points, s.norm, BoxGrid::box_for(points, grid_points_per_box));
    row.build_seconds = seconds_since(t0);
    row.query_seconds = time_queries(points.size(), checks, false, tick, [&](std::size_t i, std::size_t slot) {
      grid.k_nearest(i, k, out, query);
      keep(slot, out);
    });
    row.queries = points.size();
    row.memory_bytes = grid.memory_bytes();
    row.note = "box " + number(grid.box()) + ", " + std::to_string(grid.boxes()) + " boxes";
    judge(row, checks, exact_mismatches());
    rows.push_back(row);
    ++tick.done;
  }
  if (s.norm != Norm::euclidean || !nanoflann_built) {
    rows.push_back(nanoflann_skipped(s, points, "knn"));
    ++tick.done;
    return;
  }
#if CHAOS_WITH_NANOFLANN
  NeighborsRow row = row_for(s, points, "nanoflann", "knn");
  const auto t0 = Clock::now();
  const NanoflannSearch nano(points, nanoflann_leaf_size);
  row.build_seconds = seconds_since(t0);
  row.query_seconds = time_queries(points.size(), checks, false, tick, [&](std::size_t i, std::size_t slot) {
    nano.k_nearest(i, k, out, s.theiler);
    keep(slot, out);
  });
  row.queries = points.size();
  row.memory_bytes = nano.memory_bytes();
  row.note = "leaf size " + std::to_string(nanoflann_leaf_size) + "; ties compared by distance";
  std::size_t bad = 0, swaps = 0;
  for (std::size_t c = 0; c < slots; ++c) {
    const std::size_t i = checks.points[c];
    bool wrong = false, swapped = false;
    for (std::size_t r = 0; r < k; ++r) {
      const Neighbor &a = got[c * k + r], &b = expected[c * k + r];
      const std::size_t gap = a.index > i ? a.index - i : i - a.index;
      if (a.index >= points.size() || gap <= s.theiler || a.distance != b.distance ||
          a.distance != points.distance(i, a.index, s.norm))
        wrong = true;
      else if (a.index != b.index)
        swapped = true;
    }
    bad += wrong;
    swaps += !wrong && swapped;
  }
  judge(row, checks, bad);
  row.tie_swaps = swaps;
  rows.push_back(row);
  ++tick.done;
#endif
}

// Each point needs k admissible candidates: P - (2w + 1) >= k, P = n - (m - 1) tau (P >= 2w + 2
// for counts, as k = 1).
void check_length(std::size_t n, std::size_t m, std::size_t tau, std::size_t w, std::size_t k) {
  const bool fits = n > 0 && m - 1 <= (n - 1) / tau;
  const std::size_t points = fits ? n - (m - 1) * tau : 0;
  const double needed = static_cast<double>(k) + 2.0 * static_cast<double>(w) + 1.0;
  if (static_cast<double>(points) >= needed) return;
  throw InvalidInput(ErrorCode::too_short,
                     "too short: N = " + std::to_string(n) + " samples give " + std::to_string(points) +
                         " embedded points (m = " + std::to_string(m) + ", tau = " + std::to_string(tau) +
                         "), and every point needs k = " + std::to_string(k) +
                         " admissible neighbours outside its Theiler window w = " + std::to_string(w) +
                         ", which takes at least k + 2w + 1 = " + number(needed) + " points");
}

std::string join(const std::vector<std::size_t>& v) {
  std::string s;
  for (std::size_t c = 0; c < v.size(); ++c) {
    if (c) s += ',';
    s += std::to_string(v[c]);
  }
  return s;
}

}  // namespace

void check_neighbors_params(const NeighborsParams& params) {
  if (params.k && *params.k == 0)
    throw InvalidInput(ErrorCode::invalid_parameter, "k = 0: the number of nearest neighbours must be at least 1");
  if (params.radius && !(*params.radius > 0.0 && std::isfinite(*params.radius)))
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "radius r = " + number(*params.radius) + ": it must be positive and finite");
  if (params.dimension == 0)
    throw InvalidInput(ErrorCode::invalid_parameter, "embedding dimension m = 0: it must be at least 1");
  if (params.delay == 0) throw InvalidInput(ErrorCode::invalid_parameter, "delay tau = 0: it must be at least 1");
  if (params.check_points && *params.check_points == 0)
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "--check-points 0: at least 1 point must be checked by brute force (--no-brute checks none)");
  if (params.check_points && !params.brute)
    throw InvalidInput(ErrorCode::invalid_parameter, "--check-points and --no-brute exclude each other");
  for (const std::size_t n : params.sizes)
    if (n == 0) throw InvalidInput(ErrorCode::invalid_parameter, "--sizes 0: every size must be at least 1 sample");
}

NeighborsRun run_neighbors(const SeriesInput& in, NeighborsParams params, const OutputOptions& output) {
  check_neighbors_params(params);
  const Norm norm = parse_norm(params.norm);
  if (!params.radius && !params.k) params.k = 1;
  std::vector<std::size_t> sizes = params.sizes;
  if (sizes.empty()) sizes.push_back(in.values.size());
  std::sort(sizes.begin(), sizes.end());
  sizes.erase(std::unique(sizes.begin(), sizes.end()), sizes.end());
  if (sizes.back() > in.values.size())
    throw InvalidInput(ErrorCode::too_short, "--sizes " + std::to_string(sizes.back()) +
                                                 " asks for more samples than the series has (N = " +
                                                 std::to_string(in.values.size()) + ")");
  // The smallest size decides (the counts need one admissible neighbour, k nearest k).
  check_length(sizes.front(), params.dimension, params.delay, params.theiler, params.k.value_or(1));

  Report report("neighbors", output);
  report.parameter("file", in.file).parameter("column", in.column).parameter("N", in.values.size())
      .parameter("dt", in.dt).parameter("dimension", params.dimension).parameter("delay", params.delay)
      .parameter("theiler", params.theiler).parameter("norm", params.norm).parameter("radius", params.radius)
      .parameter("k", params.k).parameter("sizes", join(sizes))
      .parameter("brute_force", std::string(!params.brute          ? "none (--no-brute): nothing is checked"
                                            : params.check_points ? "at the check points only"
                                                                  : "every point"))
      .parameter("check_points", params.check_points)
      .parameter("kd_tree_leaf_size", kd_leaf_size).parameter("nanoflann_leaf_size", nanoflann_leaf_size)
      .parameter("grid_points_per_box", grid_points_per_box).parameter("threads", std::size_t{1});

  const std::size_t kinds = (params.radius ? 1 : 0) + (params.k ? 1 : 0);
  Ticker tick{params.progress, sizes.size() * kinds * (params.brute ? 4 : 3)};
  std::vector<NeighborsRow> rows;
  for (const std::size_t n : sizes) {
    const DelayEmbedding points(in.values.first(n), params.dimension, params.delay);
    const Checks checks = make_checks(points.size(), params.brute, params.check_points);
    const Setting setting{n, params.theiler, norm};
    if (params.radius) measure_counts(setting, points, *params.radius, checks, tick, rows);
    if (params.k) measure_nearest(setting, points, *params.k, checks, tick, rows);
  }

  NeighborsRun run{std::move(rows), true, std::move(report)};
  auto& rows_json = run.report.json()["rows"];
  rows_json = nlohmann::ordered_json::array();
  for (const auto& r : run.rows) {
    run.all_equal = run.all_equal && r.equal != "no";
    rows_json.push_back({{"N", r.n},
                         {"points", r.points},
                         {"structure", r.structure},
                         {"query", r.query},
                         {"ran", r.ran},
                         {"build_seconds", r.build_seconds},
                         {"query_seconds", r.query_seconds},
                         {"queries", r.queries},
                         {"memory_bytes", r.memory_bytes},
                         {"checked", r.checked},
                         {"mismatches", r.mismatches},
                         {"tie_swaps", r.tie_swaps},
                         {"equal", r.equal},
                         {"note", r.note}});
  }
  run.report.json()["all_equal"] = run.all_equal;
  return run;
}

}  // namespace chaos::cli
