// A sweep point's analysis is `chaos analyze`'s pipeline on a slider-crank series: on the same series
// it must report the same delay, Theiler window, embedding dimension and D2 (the property under test
// is equality; tests/study/unit/series_analysis_test.cpp checks it on Lorenz x). The series is what
// the point analyses, slider_y of the seed scene with the study tests' fast integrator settings,
// sampled 100 times a revolution over the last 40 of 50 revolutions, taken here from a direct run of
// the mechanism library. The reference is chaos::analyse_series with `chaos analyze`'s defaults and
// the study's switches (no stationarity rule, no Lyapunov exponents, Cao up to the study's largest m).
// In the reference tier (label study-reference: the Release build only), with the other tests that
// run the mechanism for many revolutions; 0.8 s optimised.
#include <gtest/gtest.h>

#include <optional>
#include <vector>

#include "chaos/automatic_analysis.hpp"
#include "mechanism/simulate.hpp"
#include "mechanism/slider_crank.hpp"
#include "study/point.hpp"
#include "study/same_as_analyze.hpp"

namespace {

TEST(StudyAnalysis, ReportsWhatChaosAnalyzeReportsOnASliderCrankSeries) {
  study::SweepSpec spec;
  spec.overrides = {"joint.slider.friction.sigma1_velocity=1e-3", "integrator.method=\"dopri5\"",
                    "integrator.relative_tolerance=1e-5"};
  spec.grid = study::Grid({study::parse_axis("joint.slider.clearance=2e-4,3e-4")});
  spec.periods = 50;
  spec.keep = 1;
  spec.analyse = true;
  spec.analysis.periods = 40;
  spec.analysis.samples_per_period = 100;
  const study::PointResult point = study::run_point(spec, 0);
  ASSERT_TRUE(point.analysis);
  const study::SeriesAnalysis& a = *point.analysis;

  // The same series from the mechanism library directly: slider_y at every output sample of the last
  // 40 revolutions.
  const mechanism::Scene scene = study::point_run_scene(spec, 0);
  const double period = scene.driver.period();
  const double start = static_cast<double>(spec.periods - spec.analysis.periods) * period;
  mechanism::SliderCrank system(scene);
  std::vector<double> series;
  mechanism::SimulationObserver observer;
  observer.sample = [&](double t, const mechanism::State&, const mechanism::Evaluation& ev) {
    if (t >= start - 1e-9 * period) series.push_back(ev.slider_pose[1]);
  };
  ASSERT_EQ(mechanism::simulate(system, observer).status, mechanism::SimulationStatus::completed);
  ASSERT_EQ(series.size(), a.samples);

  chaos::AutomaticAnalysisOptions o;
  o.check_stationarity = false;
  o.rosenstein = o.kantz = o.local_maps = false;
  o.max_dimension = spec.analysis.max_dimension;
  const chaos::AutomaticAnalysis reference = chaos::analyse_series(series, std::nullopt, o);
  // Not a vacuous equality: the pipeline gets as far as D2 on this series.
  ASSERT_TRUE(reference.delay && reference.dimension && reference.d2) << reference.stopped;

  expect_same_as_analyze(a, reference);
}

}  // namespace
