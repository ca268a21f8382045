// The delay-embedding view: coordinates by the definition x[i + k tau] (seed Eq. 30), point counts
// N - (m-1) tau, distances by hand, and refusals of m = 0, tau = 0 and too short a series.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "chaos/embedding.hpp"
#include "chaos/error.hpp"

namespace {

TEST(DelayEmbedding, CoordinatesAndSize) {
  const std::vector<double> x{0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
  const chaos::DelayEmbedding e(x, 3, 2);
  EXPECT_EQ(e.size(), 10u - 2u * 2u);
  EXPECT_EQ(e(0, 0), 0);
  EXPECT_EQ(e(0, 2), 4);
  EXPECT_EQ(e(5, 2), 9);  // last point reaches the last sample
  EXPECT_EQ(e.series().data(), x.data());  // a view, not a copy
}

TEST(DelayEmbedding, PointLimit) {
  const std::vector<double> x{0, 1, 2, 3, 4, 5};
  EXPECT_EQ(chaos::DelayEmbedding(x, 2, 1, 3).size(), 3u);
  EXPECT_THROW(chaos::DelayEmbedding(x, 2, 1, 6), chaos::InvalidInput);
}

TEST(DelayEmbedding, DistancesByHand) {
  const std::vector<double> x{0, 3, 1, 5};
  const chaos::DelayEmbedding e(x, 2, 1);  // points (0,3), (3,1), (1,5)
  EXPECT_DOUBLE_EQ(e.distance(0, 1, chaos::Norm::max), 3.0);
  EXPECT_DOUBLE_EQ(e.distance(0, 1, chaos::Norm::euclidean), std::sqrt(9.0 + 4.0));
  EXPECT_DOUBLE_EQ(e.distance(0, 2, chaos::Norm::max), 2.0);
  EXPECT_DOUBLE_EQ(e.distance(1, 1, chaos::Norm::euclidean), 0.0);
}

TEST(DelayEmbedding, Refusals) {
  const std::vector<double> x(10, 1.0);
  try {
    chaos::DelayEmbedding(x, 0, 1);
    FAIL();
  } catch (const chaos::InvalidInput& e) {
    EXPECT_EQ(e.code(), chaos::ErrorCode::invalid_parameter);
  }
  try {
    chaos::DelayEmbedding(x, 2, 0);
    FAIL();
  } catch (const chaos::InvalidInput& e) {
    EXPECT_EQ(e.code(), chaos::ErrorCode::invalid_parameter);
  }
  try {
    chaos::DelayEmbedding(x, 4, 3);  // needs N > 10
    FAIL();
  } catch (const chaos::InvalidInput& e) {
    EXPECT_EQ(e.code(), chaos::ErrorCode::too_short);
    EXPECT_NE(std::string(e.what()).find("N = 10"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("m = 4"), std::string::npos) << e.what();
  }
  EXPECT_EQ(chaos::DelayEmbedding::points_for(5, 3, 3), 0u);
}

}  // namespace
