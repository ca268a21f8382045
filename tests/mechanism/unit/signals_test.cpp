// The output columns: one value per named signal for every scene shape, unique names, and the
// values taken from the evaluation they claim to show (property of the table itself).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "mechanism/scene.hpp"
#include "mechanism/signals.hpp"

namespace mechanism {
namespace {

TEST(Signals, OneValuePerNamedColumnForEverySceneShape) {
  const std::vector<std::vector<std::string>> scenes = {
      {},
      {"joint.slider.type=ideal"},
      {"joint.slider.model=corners"},
      {"joint.crank_ground.type=clearance", "joint.crank_conrod.type=clearance", "joint.conrod_slider.type=clearance"}};
  for (const auto& overrides : scenes) {
    const SliderCrank sys(read_scene("", overrides));
    const SignalTable table = signal_table(sys);
    EXPECT_EQ(table.names.size(), table.units.size());
    EXPECT_EQ(std::set<std::string>(table.names.begin(), table.names.end()).size(), table.names.size());
    Evaluation ev;
    const State x = sys.initial_state();
    sys.evaluate(0.0, x, ev);
    std::vector<double> values;
    signal_values(sys, 0.0, x, ev, values);
    ASSERT_EQ(values.size(), table.names.size()) << (overrides.empty() ? "seed" : overrides.front());
    for (double v : values) EXPECT_TRUE(std::isfinite(v));
  }
}

TEST(Signals, ValuesComeFromTheEvaluation) {
  const SliderCrank sys(read_scene("", {"joint.crank_conrod.type=clearance"}));
  const SignalTable table = signal_table(sys);
  State x = sys.initial_state();
  x[0] += 0.6e-3;  // the conrod's pin 0.1 mm into its bearing (clearance 0.5 mm)
  Evaluation ev;
  sys.evaluate(0.001, x, ev);
  std::vector<double> values;
  signal_values(sys, 0.001, x, ev, values);
  auto column = [&](const std::string& name) {
    const auto it = std::find(table.names.begin(), table.names.end(), name);
    EXPECT_NE(it, table.names.end()) << name;
    return values[static_cast<std::size_t>(it - table.names.begin())];
  };
  EXPECT_EQ(column("t"), 0.001);
  EXPECT_EQ(column("slider_y"), ev.slider_pose[1]);
  EXPECT_EQ(column("driving_torque"), ev.driving_torque);
  EXPECT_EQ(column("crank_conrod_ecc_x"), ev.eccentricity[0][0]);
  EXPECT_GT(column("crank_conrod_penetration"), 0.0);
  EXPECT_GT(column("crank_conrod_normal"), 0.0);
}

}  // namespace
}  // namespace mechanism
