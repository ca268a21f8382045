// The reference-table parser: the shipped table parses, its rows are well formed, and malformed
// tables are refused with the line number.

#include <gtest/gtest.h>

#include <set>

#include "chaos/error.hpp"
#include "chaos/models/generate.hpp"
#include "chaos/models/validation.hpp"

namespace {

const std::string kHeader = "id\tsystem\tparameters\tcomponent\tquantity\tvalue\tlow\thigh\tconditions\tsource\tkind\tnote\n";

TEST(ReferenceTable, ShippedTableIsWellFormed) {
  const auto& table = chaos::reference_table();
  ASSERT_FALSE(table.empty());
  for (const auto& r : table) {
    EXPECT_TRUE(chaos::system_from_name(r.system).has_value()) << r.id;
    EXPECT_LE(r.low, r.high) << r.id;
    if (r.value) {
      EXPECT_TRUE(*r.value >= r.low && *r.value <= r.high) << r.id << ": the source's own value lies outside the band";
    }
    EXPECT_FALSE(r.source.empty()) << r.id;
    // Estimates from a series state their N; spectra from the equations state how long they average.
    if (r.quantity.rfind("lyapunov_spectrum.", 0) == 0)
      EXPECT_TRUE(r.conditions.count("time") || r.conditions.count("iterations")) << r.id << ": states no averaging length";
    else
      EXPECT_TRUE(r.conditions.count("N")) << r.id << ": every estimate states its N";
  }
}

TEST(ReferenceTable, ParsesARow) {
  const auto table = chaos::parse_reference_table(
      kHeader + "# comment\nh.x.q\thenon\ta=1.4;b=0.3\tx\tcao.embedding_dimension\t2\t2\t2\tN=100;tau=1\tsrc\tanalytic\tnote\n", "t");
  ASSERT_EQ(table.size(), 1u);
  EXPECT_EQ(table[0].parameters.at("a"), 1.4);
  EXPECT_EQ(table[0].conditions.at("tau"), "1");
  EXPECT_EQ(table[0].value, 2.0);
}

TEST(ReferenceTable, RefusesMalformedRows) {
  const auto refuse = [](const std::string& text, const char* fragment) {
    try {
      chaos::parse_reference_table(text, "t");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const chaos::InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  refuse("id\tsystem\n", "t:1: header");
  refuse(kHeader + "a\thenon\t-\tx\tq\t1\t2\n", "t:2: expected 12");
  refuse(kHeader + "a\thenon\t-\tx\tq\tone\t0\t2\tN=1\ts\tanalytic\tn\n", "'one' is not a number");
  refuse(kHeader + "a\thenon\t-\tx\tq\t1\t3\t2\tN=1\ts\tanalytic\tn\n", "low > high");
  refuse(kHeader + "a\thenon\t-\tx\tq\t1\t0\t2\tN=1\ts\tguess\tn\n", "kind");
  refuse(kHeader + "a\thenon\tb\tx\tq\t1\t0\t2\tN=1\ts\tanalytic\tn\n", "key=value");
}

}  // namespace
