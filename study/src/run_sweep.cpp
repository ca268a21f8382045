#include "study/run_sweep.hpp"

#include <algorithm>
#include <exception>
#include <fstream>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <string>

#include "chaos/detail/parallel.hpp"
#include "study/error.hpp"

namespace study {

SweepProgress run_sweep(const SweepSpec& spec, const ResultStore& store, const SweepExecution& exec) {
  if (exec.threads == 0) throw StudyError("--threads", "0", "at least one thread");
  if (exec.ranks == 0 || exec.rank >= exec.ranks)
    throw StudyError("rank", std::to_string(exec.rank), "must be below the number of ranks");
  const Grid& grid = spec.grid;
  const bool chains = spec.initial == InitialConditions::continuation;
  const std::size_t unit_length = chains ? grid.chain_length() : 1;
  const std::size_t units = grid.size() / unit_length;

  // This rank's units that still have unfinished points.
  std::vector<std::size_t> mine;
  SweepProgress progress;
  for (std::size_t u = exec.rank; u < units; u += exec.ranks) {
    std::size_t unfinished = 0;
    for (std::size_t k = 0; k < unit_length; ++k) unfinished += store.finished(u * unit_length + k) ? 0 : 1;
    progress.skipped += unit_length - unfinished;
    progress.to_do += unfinished;
    if (unfinished) mine.push_back(u);
  }

  std::mutex mutex;  // guards progress
  // An exception stops the other threads after their current unit and is rethrown here.
  const std::size_t n = std::min(exec.threads, std::max<std::size_t>(1, mine.size()));
  chaos::detail::parallel_tasks(n, mine.size(), [&](std::size_t i, std::size_t) {
    const std::size_t first = mine[i] * unit_length;
    std::optional<mechanism::State> state;
    for (std::size_t k = 0; k < unit_length; ++k) {
      const std::size_t p = first + k;
      if (store.finished(p)) {
        // A resumed chain continues from the stored final state of its last finished point.
        if (chains) {
          const auto x = store.final_state(p);
          if (x) state = Eigen::Map<const mechanism::State>(x->data(), static_cast<Eigen::Index>(x->size()));
        }
        continue;
      }
      PointResult r;
      try {
        r = run_point(spec, p, state ? &*state : nullptr);
      } catch (const std::exception& e) {
        // Name the point, so the failure can be rerun alone (study sweep --set for each axis).
        std::string where = "point " + std::to_string(p);
        for (const std::string& o : grid.overrides(p)) where += " " + o;
        throw std::runtime_error(where + ": " + e.what());
      }
      store.write(r);
      if (chains) {
        if (r.summary.status == mechanism::SimulationStatus::completed) {
          state = r.summary.final_state;
        } else {
          state.reset();  // a failed point's state is no place to continue from
        }
      }
      std::lock_guard<std::mutex> lock(mutex);
      ++progress.done;
      if (r.summary.status != mechanism::SimulationStatus::completed) ++progress.failed;
      if (exec.progress) exec.progress(progress);
    }
  });
  return progress;
}

SweepSummary summarise_sweep(const SweepSpec& spec, const ResultStore& store, std::size_t computed,
                             std::size_t resumed) {
  // The status column of an assembled table: after the point index and one column per axis.
  const auto statuses = [&](const char* table) {
    std::vector<std::string> out;
    std::ifstream in(store.dir() / table);
    const std::size_t status_column = 1 + spec.grid.axes().size();
    for (std::string line; std::getline(in, line);) {
      if (line.empty() || line[0] == '#') continue;
      std::istringstream f(line);
      std::string field;
      for (std::size_t k = 0; k <= status_column; ++k) std::getline(f, field, '\t');
      out.push_back(field);
    }
    return out;
  };
  SweepSummary s;
  s.points = spec.grid.size();
  s.computed = computed;
  s.resumed_from_disk = resumed;
  std::size_t point = 0;
  for (const std::string& status : statuses("points.tsv")) {
    if (status != "completed" && s.failed++ == 0) {
      s.first_failed = point;
      s.first_failed_status = status;
    }
    ++point;
  }
  if (spec.analyse)
    for (const std::string& status : statuses("analysis.tsv")) {
      if (status.rfind("not analysed", 0) == 0) continue;
      ++s.analysed;
      if (status.rfind("stopped at", 0) == 0 || status.rfind("series too short", 0) == 0) {
        if (s.analysis_failed++ == 0) s.first_analysis_failure = status;
      }
    }
  if (spec.lyapunov)
    for (const std::string& status : statuses("lyapunov.tsv"))
      s.lyapunov_failed += status == "trajectory_failed" || status == "refused";
  return s;
}

nlohmann::json summary_json(const SweepSummary& s, const std::string& directory, std::size_t threads,
                            std::size_t ranks, double wall_seconds) {
  return {{"directory", directory},
          {"points", s.points},
          {"computed", s.computed},
          {"resumed_from_disk", s.resumed_from_disk},
          {"failed", s.failed},
          {"analysis_failed", s.analysis_failed},
          {"lyapunov_failed", s.lyapunov_failed},
          {"threads", threads},
          {"ranks", ranks},
          {"wall_seconds", wall_seconds}};
}

}  // namespace study
