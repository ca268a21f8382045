// The zoo's checkpoint (chaos/commands/zoo_checkpoint.hpp). Expectations are properties of the
// file: a stored result reads back bit for bit; a resumed run's report equals an uninterrupted
// run's; a cut last line is dropped; a file written by another build or with other options, or not
// by `chaos zoo` at all, is refused and left as it was.
#include "zoo_checkpoint.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>

#include "chaos/error.hpp"
#include "commands.hpp"

namespace {

using chaos::ZooCaseResult;
using chaos::ZooEstimate;
using chaos::ZooRow;
using chaos::ZooVerdict;
using chaos::cli::ZooCheckpoint;

std::filesystem::path fresh_path(const std::string& name) {
  const auto path = std::filesystem::temp_directory_path() /
                    (name + "_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + ".jsonl");
  std::filesystem::remove(path);
  return path;
}

std::string contents(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

void expect_same(const ZooEstimate& a, const ZooEstimate& b) {
  ASSERT_EQ(a.value.has_value(), b.value.has_value());
  if (a.value) {
    EXPECT_TRUE(same_bits(*a.value, *b.value) || (std::isnan(*a.value) && std::isnan(*b.value)));
  }
  ASSERT_EQ(a.interval.has_value(), b.interval.has_value());
  if (a.interval) {
    EXPECT_TRUE(same_bits(a.interval->low, b.interval->low));
    EXPECT_TRUE(same_bits(a.interval->high, b.interval->high));
  }
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.verdict, b.verdict);
  EXPECT_EQ(a.dimension, b.dimension);
}

// Awkward values: doubles whose shortest text needs 17 digits, a subnormal, infinities, NaN,
// estimates with and without value, interval and dimension, and a note with quotes and a newline.
ZooCaseResult awkward_result() {
  ZooCaseResult r;
  r.case_index = 7;
  r.seconds = 0.1 + 0.2;
  r.error = "";
  ZooRow a;
  a.n = 100000;
  a.theiler_factor = 2.0 / 3.0;
  a.theiler = 63;
  a.delay = 17;
  a.dimension = 5;
  a.automatic = true;
  a.d2 = {2.0499999999999998, chaos::Interval{1.9 + 1e-15, std::numeric_limits<double>::infinity()}, "saturated",
          ZooVerdict::in_band, std::nullopt};
  a.rosenstein = {std::nullopt, std::nullopt, "no_linear_region", ZooVerdict::unsure, std::nullopt};
  a.kantz = {4.9406564584124654e-324, chaos::Interval{-std::numeric_limits<double>::infinity(), 1e308},
             "linear_region", ZooVerdict::wrong, std::nullopt};
  a.local_maps = {0.88851234567890123, chaos::Interval{0.8, 0.9}, "consistent", ZooVerdict::in_band, std::size_t{4}};
  a.note = "stopped: \"no MI minimum\"\nsecond line, ünïcode";
  ZooRow b = a;
  b.automatic = false;
  b.theiler_factor = 3.0;
  b.local_maps.value = std::numeric_limits<double>::quiet_NaN();
  r.rows = {a, b};
  return r;
}

TEST(ZooCheckpoint, ResultRoundTripIsExact) {
  const ZooCaseResult r = awkward_result();
  const std::string text = chaos::cli::zoo_result_to_json(r).dump();
  const ZooCaseResult back = chaos::cli::zoo_result_from_json(nlohmann::ordered_json::parse(text));
  EXPECT_EQ(back.case_index, r.case_index);
  EXPECT_TRUE(same_bits(back.seconds, r.seconds));
  EXPECT_EQ(back.error, r.error);
  ASSERT_EQ(back.rows.size(), r.rows.size());
  for (std::size_t k = 0; k < r.rows.size(); ++k) {
    const ZooRow &x = r.rows[k], &y = back.rows[k];
    EXPECT_EQ(x.n, y.n);
    EXPECT_TRUE(same_bits(x.theiler_factor, y.theiler_factor));
    EXPECT_EQ(x.theiler, y.theiler);
    EXPECT_EQ(x.delay, y.delay);
    EXPECT_EQ(x.dimension, y.dimension);
    EXPECT_EQ(x.automatic, y.automatic);
    expect_same(x.d2, y.d2);
    expect_same(x.rosenstein, y.rosenstein);
    expect_same(x.kantz, y.kantz);
    expect_same(x.local_maps, y.local_maps);
    EXPECT_EQ(x.note, y.note);
  }
}

// Every double, not only the hand-picked ones: 5000 random bit patterns (seed 5) read back exactly.
TEST(ZooCheckpoint, RandomDoublesReadBackExactly) {
  std::mt19937_64 bits(5);
  ZooCaseResult r;
  r.rows.resize(1);
  for (int k = 0; k < 5000; ++k) {
    const double v = std::bit_cast<double>(bits());
    r.seconds = v;
    const ZooCaseResult back = chaos::cli::zoo_result_from_json(nlohmann::ordered_json::parse(chaos::cli::zoo_result_to_json(r).dump()));
    ASSERT_TRUE(same_bits(back.seconds, v) || (std::isnan(v) && std::isnan(back.seconds))) << std::hexfloat << v;
  }
}

TEST(ZooCheckpoint, CutLastLineIsDroppedAndOthersKept) {
  const auto path = fresh_path("zoo_checkpoint_cut");
  {
    ZooCheckpoint c(path.string(), true, 0);
    c.append("first", awkward_result());
  }
  const std::string whole = contents(path);
  {
    std::ofstream out(path, std::ios::binary | std::ios::app);
    out << R"({"case": "second", "result": {"case_index": 3, "ro)";  // a run killed while writing
  }
  ZooCheckpoint c(path.string(), true, 0);
  ASSERT_EQ(c.results().size(), 1u);
  EXPECT_EQ(c.results().begin()->first, "first");
  EXPECT_EQ(contents(path), whole);  // the cut line is gone, so the next append starts a line
  c.append("second", ZooCaseResult{});
  EXPECT_EQ(ZooCheckpoint(path.string(), true, 0).results().size(), 2u);
  std::filesystem::remove(path);
}

TEST(ZooCheckpoint, OtherOptionsOrForeignFilesAreRefusedAndLeftAlone) {
  const auto path = fresh_path("zoo_checkpoint_refuse");
  { ZooCheckpoint(path.string(), true, 0).append("first", awkward_result()); }
  const std::string whole = contents(path);
  try {
    ZooCheckpoint(path.string(), false, 0);
    FAIL() << "a checkpoint of --fast was accepted by a full run";
  } catch (const chaos::InvalidInput& e) {
    EXPECT_EQ(e.code(), chaos::ErrorCode::invalid_parameter);
    EXPECT_NE(std::string(e.what()).find("another build or with other options"), std::string::npos) << e.what();
  }
  EXPECT_EQ(contents(path), whole);
  EXPECT_THROW(ZooCheckpoint(path.string(), true, 2), chaos::InvalidInput);  // another grid sample
  EXPECT_EQ(contents(path), whole);

  // A different build: the same first line with another fingerprint.
  std::string other = whole;
  const std::string fingerprint = chaos::cli::zoo_build_fingerprint();
  ASSERT_EQ(fingerprint.size(), 16u);
  other.replace(other.find(fingerprint), 16, std::string(16, fingerprint[0] == '0' ? '1' : '0'));
  { std::ofstream(path, std::ios::binary) << other; }
  EXPECT_THROW(ZooCheckpoint(path.string(), true, 0), chaos::InvalidInput);
  EXPECT_EQ(contents(path), other);

  // Not a checkpoint: a text file of one line without a newline is not mistaken for a cut line.
  { std::ofstream(path, std::ios::binary) << "1.0 2.0 3.0"; }
  EXPECT_THROW(ZooCheckpoint(path.string(), true, 0), chaos::InvalidInput);
  EXPECT_EQ(contents(path), "1.0 2.0 3.0");
  std::filesystem::remove(path);
}

// A run stopped after some cases and resumed gives the report of an uninterrupted run, and the
// resumed run reads those cases instead of running them. Two quick controls of the CI subset.
TEST(ZooCheckpoint, ResumedRunEqualsUninterruptedRun) {
  chaos::cli::ZooParams params;
  params.fast = true;
  params.grid = false;
  params.only = {"white_noise", "random_walk"};
  const chaos::cli::ZooRun whole = chaos::cli::run_zoo(params);

  const auto path = fresh_path("zoo_checkpoint_resume");
  params.checkpoint = path.string();
  params.only = {"random_walk"};  // the first session
  const chaos::cli::ZooRun first = chaos::cli::run_zoo(params);
  EXPECT_EQ(first.resumed, 0u);
  params.only = {"white_noise", "random_walk"};  // the second
  std::size_t ran = 0;
  const chaos::cli::ZooRun resumed = chaos::cli::run_zoo(params, [&](std::size_t done, std::size_t total, const chaos::ZooCase& c,
                                                                      const ZooCaseResult&) {
    ++ran;
    EXPECT_EQ(c.name, "white_noise");
    EXPECT_EQ(done, 2u);
    EXPECT_EQ(total, 2u);
  });
  EXPECT_EQ(ran, 1u);
  EXPECT_EQ(resumed.resumed, 1u);
  // Rows are the same data; the per-case seconds differ between runs, so they are set aside.
  auto rows = [](nlohmann::ordered_json j) {
    for (auto& r : j["rows"]) r.erase("seconds");
    return j["rows"];
  };
  EXPECT_EQ(rows(resumed.json), rows(whole.json));
  EXPECT_EQ(resumed.wrong, whole.wrong);
  EXPECT_NE(resumed.markdown.find("the other 1 were read from a checkpoint"), std::string::npos);
  // The read case carries the time it took when it ran.
  const ZooCheckpoint stored(path.string(), true, 0);
  EXPECT_TRUE(same_bits(stored.results().at("random_walk").seconds, first.results.front().seconds));
  std::filesystem::remove(path);
}

}  // namespace
