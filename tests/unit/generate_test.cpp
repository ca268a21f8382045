// The system registry: every system is reachable by name, defaults match the parameter structs of
// systems.hpp, overrides reach the generator, and unknown names are refused with the valid ones.

#include <gtest/gtest.h>

#include "chaos/error.hpp"
#include "chaos/models/generate.hpp"

namespace {

TEST(Generate, EveryNameRoundTripsAndProducesTheLength) {
  for (const auto kind : chaos::all_systems()) {
    const auto name = chaos::to_string(kind);
    ASSERT_EQ(chaos::system_from_name(name), kind) << name;
    chaos::GenerateRequest request;
    request.system = kind;
    request.length = 257;
    const auto t = chaos::generate(request);
    ASSERT_FALSE(t.components.empty()) << name;
    EXPECT_EQ(t.size(), 257u) << name;
    EXPECT_EQ(t.names.size(), t.components.size()) << name;
  }
  EXPECT_FALSE(chaos::system_from_name("lorenz63").has_value());
}

TEST(Generate, OverridesReachTheGenerator) {
  // Henon with b = 0 is the 1-D map x' = 1 - a x^2: compare with the direct function.
  chaos::GenerateRequest request;
  request.system = chaos::SystemKind::henon;
  request.length = 100;
  request.parameters = {{"a", 1.2}, {"b", 0.1}};
  const auto via_registry = chaos::generate(request);
  const auto direct = chaos::henon(100, {1.2, 0.1});
  EXPECT_EQ(via_registry.components[0], direct.components[0]);
}

TEST(Generate, UnknownParameterListsTheValidOnes) {
  chaos::GenerateRequest request;
  request.system = chaos::SystemKind::lorenz;
  request.parameters = {{"rh", 28.0}};
  try {
    chaos::generate(request);
    FAIL();
  } catch (const chaos::InvalidInput& e) {
    EXPECT_EQ(e.code(), chaos::ErrorCode::invalid_parameter);
    EXPECT_NE(std::string(e.what()).find("rho"), std::string::npos) << e.what();
  }
}

TEST(Generate, WholeNumberParametersRefuseFractions) {
  chaos::GenerateRequest request;
  request.system = chaos::SystemKind::henon;
  request.parameters = {{"transient", 10.5}};
  EXPECT_THROW(chaos::generate(request), chaos::InvalidInput);
}

}  // namespace
