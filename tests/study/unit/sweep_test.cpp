// The sweep protocol on short runs of the seed scene: which revolutions are kept, that the result
// files do not depend on the thread count, that a resumed sweep recomputes only missing points and
// gives the same files, and that continuation starts a point from its predecessor's final state.
// Expected values come from the protocol (study/sweep.hpp) and from direct mechanism runs.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "mechanism/error.hpp"
#include "mechanism/scene_lyapunov.hpp"
#include "mechanism/simulate.hpp"
#include "study/error.hpp"
#include "study/point.hpp"
#include "study/result_store.hpp"
#include "study/run_sweep.hpp"

namespace fs = std::filesystem;

namespace {

study::SweepSpec short_spec() {
  study::SweepSpec spec;
  spec.overrides = {"joint.slider.friction.sigma1_velocity=1e-3", "integrator.method=\"dopri5\"",
                    "integrator.relative_tolerance=1e-5"};
  spec.grid = study::Grid({study::parse_axis("joint.slider.clearance=2e-4:5e-4:3")});
  spec.periods = 6;
  spec.keep = 3;
  return spec;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("study_test_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  return dir;
}

// slider_y at revolutions 4..6 of point p's scene run directly by the mechanism library, from
// its initial state or from `start`: what the study must reproduce exactly.
std::vector<double> direct_samples(const study::SweepSpec& spec, std::size_t p, const mechanism::State* start = nullptr) {
  mechanism::Scene scene = study::point_scene(spec, p);
  scene.run.transient = 3 * scene.driver.period();
  scene.run.duration = 3 * scene.driver.period();
  scene.run.output_interval = 0;
  mechanism::SliderCrank system(scene);
  std::vector<double> ys;
  mechanism::SimulationObserver obs;
  obs.stroboscopic = [&](std::size_t rev, double, const mechanism::State&, const mechanism::Evaluation& ev) {
    if (rev > 3) ys.push_back(ev.slider_pose[1]);
  };
  if (start) {
    mechanism::simulate(system, *start, obs);
  } else {
    mechanism::simulate(system, obs);
  }
  return ys;
}

TEST(Sweep, KeepsTheLastRevolutions) {
  const study::SweepSpec spec = short_spec();
  const study::PointResult r = study::run_point(spec, 1);
  ASSERT_EQ(r.summary.status, mechanism::SimulationStatus::completed);
  ASSERT_EQ(r.samples.size(), 3u);
  const double period = 60.0 / 5000.0;
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(r.samples[k][0], static_cast<double>(4 + k));  // revolutions 4, 5, 6 of 6
    EXPECT_NEAR(r.samples[k][1], static_cast<double>(4 + k) * period, 1e-12);
    EXPECT_LE(std::abs(r.samples[k][2]), 5e-4 + 1e-3);  // slider_y within clearance + penetration
  }
  EXPECT_DOUBLE_EQ(r.coordinates[0], 3.5e-4);
}

TEST(Sweep, PointEqualsADirectSimulation) {
  // The study adds nothing to the physics: its kept sample equals the mechanism's own
  // stroboscopic sample of the same scene.
  const study::SweepSpec spec = short_spec();
  const study::PointResult r = study::run_point(spec, 0);
  const std::vector<double> ys = direct_samples(spec, 0);
  ASSERT_EQ(ys.size(), r.samples.size());
  for (std::size_t k = 0; k < ys.size(); ++k) EXPECT_EQ(ys[k], r.samples[k][2]);
}

TEST(Sweep, SameFilesOnOneAndTwoThreads) {
  const study::SweepSpec spec = short_spec();
  const fs::path a = scratch("threads1"), b = scratch("threads2");
  for (auto [dir, threads] : {std::pair{a, 1}, std::pair{b, 2}}) {
    study::ResultStore store(dir, spec, false);
    study::SweepExecution exec;
    exec.threads = static_cast<std::size_t>(threads);
    EXPECT_EQ(study::run_sweep(spec, store, exec).done, 3u);
    store.assemble();
  }
  for (const char* f : {"samples.tsv", "points.tsv", "spec.txt"}) EXPECT_EQ(slurp(a / f), slurp(b / f)) << f;
  fs::remove_all(a);
  fs::remove_all(b);
}

TEST(Sweep, LyapunovExponentsFromThePointsFinalState) {
  // --lyapunov: each point's exponents are mechanism::scene_lyapunov of its scene started from its
  // final state (the same numbers, bit for bit), written to lyapunov.tsv, the same on 1 and 2
  // threads, and the spec (hence a resume) records the Lyapunov settings.
  study::SweepSpec spec = short_spec();
  spec.lyapunov = true;
  spec.lyapunov_options.periods = 10;
  spec.lyapunov_options.transient_periods = 2;
  spec.lyapunov_options.exponents = 3;
  spec.lyapunov_options.intervals_per_period = 10;
  const study::PointResult r = study::run_point(spec, 1);
  ASSERT_TRUE(r.lyapunov);
  mechanism::Scene scene = study::point_scene(spec, 1);
  scene.run.transient = 0.0;
  mechanism::SceneLyapunovOptions o;
  o.periods = 10;
  o.transient_periods = 2;
  o.exponents = 3;
  o.intervals_per_period = 10;
  o.start.assign(r.summary.final_state.data(), r.summary.final_state.data() + r.summary.final_state.size());
  const mechanism::SceneLyapunov direct = mechanism::scene_lyapunov(scene, o);
  ASSERT_EQ(r.lyapunov->exponents.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) EXPECT_EQ(r.lyapunov->exponents[k], direct.exponents[k]);
  EXPECT_EQ(r.lyapunov->status, direct.status);

  const fs::path a = scratch("lyap1"), b = scratch("lyap2");
  for (auto [dir, threads] : {std::pair{a, 1}, std::pair{b, 2}}) {
    study::ResultStore store(dir, spec, false);
    study::SweepExecution exec;
    exec.threads = static_cast<std::size_t>(threads);
    EXPECT_EQ(study::run_sweep(spec, store, exec).done, 3u);
    store.assemble();
  }
  const std::string table = slurp(a / "lyapunov.tsv");
  EXPECT_EQ(table, slurp(b / "lyapunov.tsv"));
  EXPECT_NE(table.find("\tlambda_1\tlambda_2\tlambda_3\tse_1"), std::string::npos);
  std::size_t rows = 0;
  std::istringstream in(table);
  for (std::string line; std::getline(in, line);) rows += !line.empty() && line[0] != '#';
  EXPECT_EQ(rows, 3u);
  EXPECT_NE(slurp(a / "spec.txt").find("lyapunov.periods = 10"), std::string::npos);
  fs::remove_all(a);
  fs::remove_all(b);
  spec.lyapunov_options.periods = 5;
  EXPECT_THROW(spec.validate(), study::StudyError);
}

TEST(Sweep, RanksSplitThePointsAndAgree) {
  // Two ranks simulated in one process: each runs its share into the same directory.
  const study::SweepSpec spec = short_spec();
  const fs::path one = scratch("rank1"), two = scratch("rank2");
  {
    study::ResultStore store(one, spec, false);
    study::run_sweep(spec, store, {});
    store.assemble();
  }
  study::ResultStore store(two, spec, false);
  study::SweepExecution r0, r1;
  r0.ranks = r1.ranks = 2;
  r1.rank = 1;
  EXPECT_EQ(study::run_sweep(spec, store, r0).done, 2u);  // points 0 and 2
  EXPECT_THROW(store.assemble(), study::StudyError);       // point 1 is missing yet
  EXPECT_EQ(study::run_sweep(spec, store, r1).done, 1u);
  store.assemble();
  EXPECT_EQ(slurp(one / "samples.tsv"), slurp(two / "samples.tsv"));
  fs::remove_all(one);
  fs::remove_all(two);
}

TEST(Sweep, ResumeRecomputesOnlyMissingPoints) {
  const study::SweepSpec spec = short_spec();
  const fs::path dir = scratch("resume");
  {
    study::ResultStore store(dir, spec, false);
    study::run_sweep(spec, store, {});
    store.assemble();
  }
  const std::string before = slurp(dir / "samples.tsv");
  fs::remove(dir / "points" / "000001.tsv");  // as if killed before point 1 was written
  // Without --resume an existing sweep is refused; with it only point 1 runs again.
  EXPECT_THROW(study::ResultStore(dir, spec, false), study::StudyError);
  study::ResultStore store(dir, spec, true);
  const study::SweepProgress p = study::run_sweep(spec, store, {});
  EXPECT_EQ(p.done, 1u);
  EXPECT_EQ(p.skipped, 2u);
  store.assemble();
  EXPECT_EQ(slurp(dir / "samples.tsv"), before);
  // A different sweep cannot resume this directory.
  study::SweepSpec other = spec;
  other.keep = 2;
  EXPECT_THROW(study::ResultStore(dir, other, true), study::StudyError);
  fs::remove_all(dir);
}

// A directory whose points were analysed under older series-analysis rules (the delay search
// changed) was resumed silently: old and new points mixed two rules. The spec records
// the rules' revision; a resume that differs only there is refused with that reason, and a spec
// from before the revision was recorded reads as revision 1. No point is computed: the spec alone
// decides.
TEST(Sweep, ResumeRefusesPointsAnalysedUnderOtherRules) {
  study::SweepSpec spec = short_spec();
  spec.analyse = true;
  const std::string rules = "analysis.rules = " + std::to_string(study::analysis_rules_revision) + "\n";
  ASSERT_NE(spec.describe().find("\n" + rules), std::string::npos);
  const fs::path dir = scratch("rules");
  { study::ResultStore store(dir, spec, false); }
  const auto resume_error = [&](const std::string& rules_line) {
    std::string text = spec.describe();
    text.replace(text.find(rules), rules.size(), rules_line);
    std::ofstream(dir / "spec.txt") << text;
    try {
      study::ResultStore store(dir, spec, true);
    } catch (const study::StudyError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string old = resume_error("");
  EXPECT_NE(old.find("revision 1 (a spec without an analysis.rules line"), std::string::npos) << old;
  EXPECT_NE(old.find("this build uses revision " + std::to_string(study::analysis_rules_revision)), std::string::npos) << old;
  const std::string other = resume_error("analysis.rules = 1\n");
  EXPECT_NE(other.find("analysed under revision 1 of the series-analysis rules"), std::string::npos) << other;
  // The same rules resume; another difference is still reported as another sweep.
  EXPECT_EQ(resume_error(rules), "no error");
  study::SweepSpec more = spec;
  more.keep = 2;
  try {
    study::ResultStore store(dir, more, true);
    ADD_FAILURE() << "a different sweep resumed the directory";
  } catch (const study::StudyError& e) {
    EXPECT_NE(std::string(e.what()).find("holds another sweep"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

// Two sweeps writing one directory at once mixed their points. The directory's
// lock refuses the second, naming the holder's process; it is free again once the first closes.
TEST(Sweep, ASecondSweepIntoAHeldDirectoryIsRefused) {
  const study::SweepSpec spec = short_spec();
  const fs::path dir = scratch("lock");
  {
    study::ResultStore first(dir, spec, false);
    try {
      study::ResultStore second(dir, spec, true);
      ADD_FAILURE() << "a second store of a held directory was opened";
    } catch (const study::StudyError& e) {
      EXPECT_NE(std::string(e.what()).find("in use by another sweep (process " + std::to_string(::getpid())),
                std::string::npos)
          << e.what();
    }
  }
  EXPECT_NO_THROW(study::ResultStore(dir, spec, true));
  fs::remove_all(dir);
}

// A point file cut short was kept on resume (2 of 50 rows, one cut in half).
// Every point file is checked on resume (end line, spec hash, sample count): a bad one is deleted
// and recomputed, and the tables equal an uninterrupted run's.
TEST(Sweep, ResumeRecomputesADamagedPointFile) {
  const study::SweepSpec spec = short_spec();
  const fs::path dir = scratch("damaged");
  {
    study::ResultStore store(dir, spec, false);
    study::run_sweep(spec, store, {});
    store.assemble();
  }
  const std::string before = slurp(dir / "samples.tsv");
  const auto rewrite = [&](const char* name, const std::string& text) {
    std::ofstream(dir / "points" / name, std::ios::binary | std::ios::trunc) << text;
  };
  const std::string whole = slurp(dir / "points" / "000001.tsv");
  rewrite("000001.tsv", whole.substr(0, whole.size() / 2));  // truncated
  std::string other_spec = slurp(dir / "points" / "000002.tsv");
  const auto at = other_spec.find("spec\t") + 5;
  other_spec[at] = other_spec[at] == '0' ? '1' : '0';  // another spec's hash
  rewrite("000002.tsv", other_spec);
  {
    study::ResultStore store(dir, spec, true);
    ASSERT_EQ(store.discarded().size(), 2u);
    EXPECT_NE(store.discarded()[0].find("point 1"), std::string::npos);
    EXPECT_NE(store.discarded()[0].find("incomplete"), std::string::npos) << store.discarded()[0];
    EXPECT_NE(store.discarded()[1].find("another spec"), std::string::npos) << store.discarded()[1];
    const study::SweepProgress p = study::run_sweep(spec, store, {});
    EXPECT_EQ(p.done, 2u);
    EXPECT_EQ(p.skipped, 1u);
    store.assemble();
  }
  EXPECT_EQ(slurp(dir / "samples.tsv"), before);
  // A sample row dropped from a file that still ends properly, and (corrupt-file tier) a
  // field edited in place, which was assembled as it stood (a final_state of "x" made a resumed
  // continuation chain exit with an internal error), are caught by the check line.
  const std::string again = slurp(dir / "points" / "000000.tsv");
  const auto row = again.find("\nsample\t") + 1;
  rewrite("000000.tsv", again.substr(0, row) + again.substr(again.find('\n', row) + 1));
  std::string edited = slurp(dir / "points" / "000001.tsv");
  edited.replace(edited.find("final_state\t") + 12, 1, "x");
  rewrite("000001.tsv", edited);
  {
    study::ResultStore store(dir, spec, true);
    ASSERT_EQ(store.discarded().size(), 2u);
    for (const auto& why : store.discarded())
      EXPECT_NE(why.find("is damaged (its contents do not match its check line)"), std::string::npos) << why;
    study::run_sweep(spec, store, {});
    store.assemble();
  }
  EXPECT_EQ(slurp(dir / "samples.tsv"), before);
  fs::remove_all(dir);
}

// A result that cannot be written is an input/output error (exit 4 in
// docs/reference/study.md), not a refused request (3), and leaves no temporary file.
TEST(Sweep, AnUnwritableResultIsAnIoError) {
  const fs::path dir = scratch("unwritable");
  try {
    study::write_atomically(dir / "missing" / "samples.tsv", "text");
    ADD_FAILURE() << "an unwritable result was accepted";
  } catch (const study::StudyError& e) {
    EXPECT_EQ(e.kind(), study::StudyError::Kind::io) << e.what();
  }
  fs::remove_all(dir);
}

TEST(Sweep, ContinuationStartsFromThePreviousFinalState) {
  study::SweepSpec spec = short_spec();
  spec.initial = study::InitialConditions::continuation;
  const study::PointResult first = study::run_point(spec, 0);
  const study::PointResult continued = study::run_point(spec, 1, &first.summary.final_state);
  const study::PointResult fresh = study::run_point(spec, 1);
  // Starting from a state of the previous clearance changes the trajectory; a direct run from
  // that state reproduces the continued point exactly.
  EXPECT_NE(continued.samples[0][2], fresh.samples[0][2]);
  const std::vector<double> ys = direct_samples(spec, 1, &first.summary.final_state);
  ASSERT_EQ(ys.size(), continued.samples.size());
  for (std::size_t k = 0; k < ys.size(); ++k) EXPECT_EQ(ys[k], continued.samples[k][2]);

  // A resumed chain picks up the stored final state: the same files as an uninterrupted chain.
  const fs::path a = scratch("chain_a"), b = scratch("chain_b");
  {
    study::ResultStore store(a, spec, false);
    study::run_sweep(spec, store, {});
    store.assemble();
  }
  {
    {
      // Closed before the resume, as a killed run's lock is released: two stores of one
      // directory at once are refused (the lock of result_store.hpp).
      study::ResultStore store(b, spec, false);
      study::run_sweep(spec, store, {});
    }
    fs::remove(b / "points" / "000002.tsv");
    study::ResultStore again(b, spec, true);
    EXPECT_EQ(study::run_sweep(spec, again, {}).done, 1u);
    again.assemble();
  }
  EXPECT_EQ(slurp(a / "samples.tsv"), slurp(b / "samples.tsv"));
  fs::remove_all(a);
  fs::remove_all(b);
}

TEST(Sweep, ResumedChainDoesNotContinueFromAFailedPoint) {
  // Point 0 stops at its step limit (integrator.max_steps = 10 on the chain's axis), so a live
  // chain starts point 1 fresh (run_sweep.cpp). A resume used to start it from point 0's stored
  // final state, a mid-run state, and wrote other samples than the uninterrupted sweep.
  study::SweepSpec spec = short_spec();
  spec.grid = study::Grid({study::parse_axis("integrator.max_steps=10,1e9")});
  spec.initial = study::InitialConditions::continuation;
  const fs::path a = scratch("failed_chain_a"), b = scratch("failed_chain_b");
  {
    study::ResultStore store(a, spec, false);
    EXPECT_EQ(study::run_sweep(spec, store, {}).failed, 1u);
    store.assemble();
  }
  {
    {
      study::ResultStore store(b, spec, false);
      study::run_sweep(spec, store, {});
    }
    fs::remove(b / "points" / "000001.tsv");
    study::ResultStore again(b, spec, true);
    EXPECT_FALSE(again.final_state(0).has_value());  // point 0 is kept, its state is not used
    EXPECT_EQ(study::run_sweep(spec, again, {}).done, 1u);
    again.assemble();
  }
  // The test can fail: point 1 from point 0's final state differs from point 1 fresh.
  const study::PointResult first = study::run_point(spec, 0);
  ASSERT_EQ(first.summary.status, mechanism::SimulationStatus::step_limit);
  EXPECT_NE(study::run_point(spec, 1, &first.summary.final_state).samples, study::run_point(spec, 1).samples);
  EXPECT_EQ(slurp(a / "samples.tsv"), slurp(b / "samples.tsv"));
  fs::remove_all(a);
  fs::remove_all(b);
}

TEST(Sweep, RefusesImpossibleSpecs) {
  study::SweepSpec spec = short_spec();
  spec.keep = 7;
  EXPECT_THROW(spec.validate(), study::StudyError);
  spec = short_spec();
  spec.signals = {"slider_height"};
  EXPECT_THROW(spec.validate(), study::StudyError);
  spec = short_spec();
  spec.grid = study::Grid({study::parse_axis("joint.slider.clearance=-1e-4,1e-4")});
  EXPECT_THROW(spec.validate(), mechanism::InvalidParameter);  // the scene's own rule: clearance > 0
  spec = short_spec();
  spec.grid = study::Grid({study::parse_axis("joint.slider.no_such_key=1,2")});
  EXPECT_THROW(spec.validate(), mechanism::InvalidParameter);
  spec = short_spec();
  spec.analyse = true;
  spec.analysis.periods = 10;
  EXPECT_THROW(spec.validate(), study::StudyError);
  // A free crank has no revolution to sample at.
  spec = short_spec();
  spec.overrides.push_back("driver.free=true");
  EXPECT_THROW(spec.validate(), study::StudyError);
  // A Lyapunov perturbation below 1e3 machine epsilon: no scene resolves it.
  spec = short_spec();
  spec.lyapunov = true;
  spec.lyapunov_options.perturbation = 1e-16;
  EXPECT_THROW(spec.validate(), study::StudyError);
}

TEST(Sweep, AnalysisDimensionRange) {
  // 2 .. 33: 2 log10(1e8 samples, the mechanism's row limit) = 16 is the largest dimension any
  // analysed series resolves (Eckmann-Ruelle), 2 * 16 + 1 = 33 embeds it (Takens); a
  // --max-dimension 1000 ran and failed every point's analysis.
  EXPECT_EQ(study::largest_analysis_dimension(), 33u);
  study::SweepSpec spec = short_spec();
  spec.analyse = true;
  spec.analysis.periods = 2;
  for (const std::size_t m : {2, 12, 33}) {
    spec.analysis.max_dimension = m;
    EXPECT_NO_THROW(spec.validate()) << m;
  }
  for (const std::size_t m : {1, 34, 1000}) {
    spec.analysis.max_dimension = m;
    try {
      spec.validate();
      ADD_FAILURE() << "--max-dimension " << m << " accepted";
    } catch (const study::StudyError& e) {
      EXPECT_NE(std::string(e.what()).find("--max-dimension = " + std::to_string(m) + ": must be 2 .. 33"),
                std::string::npos)
          << e.what();
    }
  }
}

TEST(Sweep, RefusesAStartStateOfTheWrongSize) {
  const study::SweepSpec spec = short_spec();
  const mechanism::State wrong = mechanism::State::Zero(3);
  const study::PointResult r = study::run_point(spec, 0, &wrong);
  EXPECT_NE(r.summary.message.find("started fresh"), std::string::npos);
  EXPECT_EQ(r.samples, study::run_point(spec, 0).samples);
}

}  // namespace
