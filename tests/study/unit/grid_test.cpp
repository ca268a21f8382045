// The sweep grid: axis parsing, point numbering (first axis fastest) and the scene overrides.
// Expected values are the definitions in study/grid.hpp.
#include <gtest/gtest.h>

#include "study/error.hpp"
#include "study/grid.hpp"

namespace {

TEST(Grid, RangeIncludesBothEnds) {
  const study::Axis a = study::parse_axis("joint.slider.clearance=1e-5:6e-4:120");
  EXPECT_EQ(a.key, "joint.slider.clearance");
  ASSERT_EQ(a.values.size(), 120u);
  EXPECT_DOUBLE_EQ(a.values.front(), 1e-5);
  EXPECT_DOUBLE_EQ(a.values.back(), 6e-4);
  EXPECT_NEAR(a.values[1] - a.values[0], (6e-4 - 1e-5) / 119, 1e-18);
}

TEST(Grid, ListAndSingleValue) {
  EXPECT_EQ(study::parse_axis("driver.speed_rpm=500,1000,5000").values, (std::vector<double>{500, 1000, 5000}));
  EXPECT_EQ(study::parse_axis("driver.speed_rpm=700:700:1").values, (std::vector<double>{700}));
}

TEST(Grid, RefusesMalformedAxes) {
  for (const char* bad : {"no_equals", "=1:2:3", "k=1:2", "k=1:2:0", "k=1:2:2.5", "k=1:1:3", "k=a,b", "k=1,,2",
                          "k=inf,1", "k=nan:1:2"})
    EXPECT_THROW(study::parse_axis(bad), study::StudyError) << bad;
}

TEST(Grid, FirstAxisVariesFastest) {
  study::Grid g({study::parse_axis("a=1,2,3"), study::parse_axis("b=10,20")});
  ASSERT_EQ(g.size(), 6u);
  EXPECT_EQ(g.chain_length(), 3u);
  EXPECT_EQ(g.chain_count(), 2u);
  EXPECT_EQ(g.coordinates(4), (std::vector<double>{2, 20}));
  EXPECT_EQ(g.overrides(4), (std::vector<std::string>{"a=2", "b=20"}));
}

TEST(Grid, NoAxisIsOnePoint) {
  study::Grid g;
  EXPECT_EQ(g.size(), 1u);
  EXPECT_TRUE(g.overrides(0).empty());
}

TEST(Grid, RefusesThreeAxesAndARepeatedKey) {
  EXPECT_THROW(study::Grid({study::parse_axis("a=1"), study::parse_axis("b=1"), study::parse_axis("c=1")}), study::StudyError);
  EXPECT_THROW(study::Grid({study::parse_axis("a=1"), study::parse_axis("a=2")}), study::StudyError);
}

TEST(Grid, ExactPrintingRoundTrips) {
  for (double v : {0.1, 1e-5 + (6e-4 - 1e-5) / 119, 5000.0, 1e-300})
    EXPECT_EQ(std::stod(study::exact(v)), v);
}

}  // namespace
