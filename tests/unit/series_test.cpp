// The series reader and the shared input checks. Expected values are the literal file contents;
// each refusal is checked for its error code and for naming the line and the rule.

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "chaos/error.hpp"
#include "chaos/series.hpp"

namespace {

using chaos::ErrorCode;
using chaos::InvalidInput;
using chaos::ReadOptions;

chaos::Series read(const std::string& text, ReadOptions options = {}) {
  std::istringstream in(text);
  return chaos::read_series(in, "input.dat", options);
}

// Runs `f`, expects InvalidInput with `code` and a message containing every fragment.
template <class F>
void expect_refusal(F f, ErrorCode code, std::initializer_list<const char*> fragments) {
  try {
    f();
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.code(), code) << e.what();
    for (const char* fragment : fragments) EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(ReadSeries, WhitespaceCommasCommentsAndColumns) {
  const std::string text = "# header\n1, 10\t100\n\n2 20 200  # trailing comment\n3,30,300\n";
  EXPECT_EQ(read(text).values, (std::vector<double>{1, 2, 3}));
  ReadOptions second;
  second.column = 3;
  EXPECT_EQ(read(text, second).values, (std::vector<double>{100, 200, 300}));
}

TEST(ReadSeries, SkipAndLengthCountDataRowsOnly) {
  ReadOptions options;
  options.skip = 1;
  options.length = 2;
  EXPECT_EQ(read("# c\n1\n# c\n2\n3\n4\n", options).values, (std::vector<double>{2, 3}));
}

TEST(ReadSeries, NumberFormats) {
  const auto values = read("+1.5\n-2e-3\n1E300\n4.9e-324\n").values;
  ASSERT_EQ(values.size(), 4u);
  EXPECT_EQ(values[0], 1.5);
  EXPECT_EQ(values[1], -2e-3);
  EXPECT_EQ(values[2], 1e300);
  EXPECT_EQ(values[3], 4.9e-324);  // the smallest subnormal survives parsing
}

// A spreadsheet's CSV ("time,value" header, often after a UTF-8 byte-order
// mark) failed with "'time' is not a number". The mark is skipped, a first data line with no
// number on it is a header, and a column can be named by it; -x and -l count the rows after it.
// pandas' to_csv of a series indexed by date-time writes "2020-01-01 00:00:00,1.5": split at the
// blank too, the row had three columns under a header of two, so `-c value` read "00:00:00" and was
// refused. A header of names with commas makes the file CSV: its lines split at commas only. The
// expected values are the file's literal numbers.
TEST(ReadSeries, CsvWithDateTimeColumnAndUnnamedIndex) {
  const std::string csv = "time,value\n2020-01-01 00:00:00,1.5\n2020-01-01 00:00:01, 2.5\n\n2020-01-01 00:00:02,3.5 # c\n";
  ReadOptions by_name;
  by_name.column_name = "value";
  const chaos::Series named = read(csv, by_name);
  EXPECT_EQ(named.values, (std::vector<double>{1.5, 2.5, 3.5}));
  EXPECT_EQ(named.column, 2u);
  ReadOptions second;
  second.column = 2;
  EXPECT_EQ(read(csv, second).values, (std::vector<double>{1.5, 2.5, 3.5}));
  // pandas' unnamed index: the header's first field is empty.
  const std::string indexed = ",value\n2020-01-01 00:00:00,4\n2020-01-02 00:00:00,5\n";
  EXPECT_EQ(read(indexed, by_name).values, (std::vector<double>{4, 5}));
  // The date-time column itself is still not a number, and an empty field says so.
  expect_refusal([&] { read(csv); }, ErrorCode::parse, {"input.dat:2", "'2020-01-01 00:00:00' is not a number"});
  expect_refusal([&] { read("a,b\n1,\n", second); }, ErrorCode::parse, {"input.dat:2", "column 2 is empty"});
  // Without a header the permissive split stays: blanks, tabs and commas mixed.
  EXPECT_EQ(read("1, 10\t100\n2 20,200\n", second).values, (std::vector<double>{10, 20}));
}

TEST(ReadSeries, HeaderRowByteOrderMarkAndColumnNames) {
  const std::string csv = "\xEF\xBB\xBFtime,value\n0,1.5\n1,2.5\n2,3.5\n";
  EXPECT_EQ(read(csv).values, (std::vector<double>{0, 1, 2}));
  // The mark also on a one-line file with no line end, and only at the start of the first line.
  EXPECT_EQ(read("\xEF\xBB\xBF" "1.5").values, (std::vector<double>{1.5}));
  ReadOptions by_name;
  by_name.column_name = "value";
  const chaos::Series named = read(csv, by_name);
  EXPECT_EQ(named.values, (std::vector<double>{1.5, 2.5, 3.5}));
  EXPECT_EQ(named.column, 2u);
  by_name.skip = 1;
  by_name.length = 1;
  EXPECT_EQ(read(csv, by_name).values, (std::vector<double>{2.5}));
  ReadOptions missing;
  missing.column_name = "valeur";
  expect_refusal([&] { read(csv, missing); }, ErrorCode::parse, {"input.dat:1", "no column named 'valeur'", "(time, value)"});
  expect_refusal([&] { read("1\n2\n", missing); }, ErrorCode::parse, {"input.dat:1", "not a header"});
  expect_refusal([] { read("time,value\n"); }, ErrorCode::empty, {"only a header row"});
  // A line with a number on it is data, so a bad token there is still refused.
  ReadOptions second;
  second.column = 2;
  expect_refusal([&] { read("1,three\n", second); }, ErrorCode::parse, {"'three' is not a number"});
}

// A refused token is cut to 60 bytes (a 1 MB token was echoed whole) and a byte-order mark
// inside the file, invisible in a terminal, is shown as <BOM> and named.
TEST(ReadSeries, RefusedTokensAreShownShortAndVisible) {
  try {
    read("1\n" + std::string(1'000'000, 'x') + "\n");
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_LT(std::string(e.what()).size(), 200u);
    EXPECT_NE(std::string(e.what()).find("... (1000000 bytes)"), std::string::npos) << e.what();
  }
  expect_refusal([] { read("1\n\xEF\xBB\xBF" "2\n"); }, ErrorCode::parse, {"'<BOM>2' is not a number", "byte-order mark"});
  expect_refusal([] { read("1\n2\x01\n"); }, ErrorCode::parse, {"'2\\x01' is not a number"});
  // Binary garbage is shown as \xHH too (it reached the terminal raw), UTF-8 text as it is.
  expect_refusal([] { read("1\n2\xE9\xFF\n"); }, ErrorCode::parse, {"'2\\xE9\\xFF' is not a number"});
  expect_refusal([] { read("1\n2\xC3\xA9\n"); }, ErrorCode::parse, {"'2\xC3\xA9' is not a number"});
  expect_refusal([] { read("nan\n1\n"); }, ErrorCode::non_finite, {"input.dat:1"});  // not a header
}

// Corrupt-file tier: a file with lone CR line ends (or CR, LF and CR LF mixed) was read
// as one line of many columns, so column 1 gave a one-sample series (or silently fewer samples);
// 1e400 was "not a number"; a line of NUL bytes passed for a header; a directory was "read error".
TEST(ReadSeries, LineEndsRangeAndBinary) {
  EXPECT_EQ(read("1\r2\r3\r").values, (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(read("1\r\n2\r3\n4").values, (std::vector<double>{1, 2, 3, 4}));
  ReadOptions second;
  second.column = 2;
  EXPECT_EQ(read("t,x\r0,5\r1,6\r", second).values, (std::vector<double>{5, 6}));
  expect_refusal([] { read("1\n1e400\n"); }, ErrorCode::parse, {"input.dat:2", "'1e400' is beyond the range of a double"});
  expect_refusal([] { read("1\n-1e-400\n"); }, ErrorCode::parse, {"input.dat:2", "beyond the range"});
  expect_refusal([] { read(std::string("\0\0\0\n1\n", 6)); }, ErrorCode::parse, {"input.dat:1", "'\\x00\\x00\\x00' is not a number"});
  expect_refusal([] { chaos::read_series("/tmp"); }, ErrorCode::io, {"/tmp: is a directory"});
}

// The reader takes the input in blocks of 2^16 bytes: a CR LF split across two blocks is one line
// end, a line longer than a block is one line, and every line of a long file arrives once, in
// order, with a lone CR and the last line's missing end honoured after many blocks. Expected values
// are the numbers written into the text.
TEST(ReadSeries, LinesAcrossReadBlocks) {
  constexpr std::size_t block = std::size_t{1} << 16;
  for (std::size_t shift = 0; shift < 3; ++shift) {  // the CR LF at block - 2, - 1 (split) and + 0
    std::string text(block - 3 + shift, ' ');          // blank padding on line 1, then its value
    text += "1\r\n2\n";
    EXPECT_EQ(read(text).values, (std::vector<double>{1, 2})) << "shift " << shift;
  }
  std::string long_line(3 * block, ' ');
  EXPECT_EQ(read(long_line + "7 8\n9").values, (std::vector<double>{7, 9}));
  std::string many;
  std::vector<double> expected;
  for (int i = 0; i < 50000; ++i) {
    many += std::to_string(i) + (i % 3 == 0 ? "\r\n" : i % 3 == 1 ? "\r" : "\n");
    expected.push_back(i);
  }
  many += "50000";  // no line end at all
  expected.push_back(50000);
  EXPECT_EQ(read(many).values, expected);
}

// `chaos section` counted the columns with a splitter of its own that knew no lone CR line end
// ("no data columns" for a CR file); it shares the reader's now.
TEST(ReadSeries, CountColumns) {
  std::istringstream cr("# c\r\r1 2 3\r4 5 6\r"), bom("\xEF\xBB\xBFt,x,y\n1,2,3\n"), none("# c\n \n");
  EXPECT_EQ(chaos::count_columns(cr), 3u);
  EXPECT_EQ(chaos::count_columns(bom), 3u);
  EXPECT_EQ(chaos::count_columns(none), 0u);
  expect_refusal([] { chaos::read_text("/tmp"); }, ErrorCode::io, {"/tmp: is a directory"});
}

TEST(ReadSeries, DtTravelsWithTheSeries) {
  ReadOptions options;
  options.dt = 0.01;
  EXPECT_EQ(read("1\n2\n", options).dt, 0.01);
  EXPECT_FALSE(read("1\n2\n").dt.has_value());
}

TEST(ReadSeries, Refusals) {
  expect_refusal([] { read("1\nx2\n3\n"); }, ErrorCode::parse, {"input.dat:2", "'x2' is not a number"});
  expect_refusal([] { read("1\n2.5.3\n"); }, ErrorCode::parse, {"input.dat:2", "'2.5.3'"});
  expect_refusal([] { read("1\nnan\n"); }, ErrorCode::non_finite, {"input.dat:2", "not finite"});
  expect_refusal([] { read("1\n-inf\n"); }, ErrorCode::non_finite, {"input.dat:2"});
  expect_refusal([] { read("1e999\n"); }, ErrorCode::parse, {"input.dat:1"});  // overflow is not a number we accept
  expect_refusal([] { read("# nothing\n\n"); }, ErrorCode::empty, {"input.dat", "no data rows"});
  expect_refusal([] { read(""); }, ErrorCode::empty, {"no data rows"});
  ReadOptions column3;
  column3.column = 3;
  expect_refusal([&] { read("1 2 3\n4 5\n", column3); }, ErrorCode::parse, {"input.dat:2", "column 3", "only 2"});
  ReadOptions skip_all;
  skip_all.skip = 5;
  expect_refusal([&] { read("1\n2\n", skip_all); }, ErrorCode::empty, {"skipping 5", "2 data row"});
  ReadOptions column0;
  column0.column = 0;
  expect_refusal([&] { read("1\n", column0); }, ErrorCode::invalid_parameter, {"column 0"});
  ReadOptions bad_dt;
  bad_dt.dt = -1.0;
  expect_refusal([&] { read("1\n", bad_dt); }, ErrorCode::invalid_parameter, {"dt", "-1"});
}

TEST(ReadSeries, MissingFile) {
  expect_refusal([] { chaos::read_series("/nonexistent/dir/x.dat"); }, ErrorCode::io, {"/nonexistent/dir/x.dat", "cannot open"});
}

TEST(Checks, ConstantFiniteLength) {
  const std::vector<double> constant(50, 2.0);
  expect_refusal([&] { chaos::require_not_constant(constant, "s"); }, ErrorCode::constant, {"50 samples", "2"});
  const std::vector<double> with_nan{1.0, std::nan(""), 2.0};
  expect_refusal([&] { chaos::require_finite(with_nan, "s"); }, ErrorCode::non_finite, {"sample 1"});
  expect_refusal([&] { chaos::require_length(constant, 100, "s", "m = 3, tau = 40"); }, ErrorCode::too_short,
                 {"N = 50", "at least 100", "m = 3, tau = 40"});
  const std::vector<double> tiny{1e-300, 2e-300};
  EXPECT_NO_THROW(chaos::require_not_constant(tiny, "s"));  // tiny but distinct values are dynamics
}

// The estimators rescale internally, so only what double itself cannot hold is refused: values
// beyond 2^1022, where max - min can overflow, and a spread below 2^-1021, where the values are
// subnormal and have lost bits (series.hpp). The bounds are powers of two, so the values either
// side of them are exact.
TEST(Checks, Scale) {
  expect_refusal([] { chaos::require_scale(std::vector<double>{1.0, 0x1.8p1022}, "s"); }, ErrorCode::scale,
                 {"in magnitude", "beyond the 4.49423e+307 (2^1022)", "divide the series"});
  expect_refusal([] { chaos::require_scale(std::vector<double>{-1e308, 1e308}, "s"); }, ErrorCode::scale, {"1e+308"});
  expect_refusal([] { chaos::require_scale(std::vector<double>{3e-310, 4e-310}, "s"); }, ErrorCode::scale,
                 {"span only 1e-310", "below the 4.45015e-308 (2^-1021)", "subnormal", "multiply the series"});
  expect_refusal([] { chaos::require_scale(std::vector<double>{5e-324, 1e-323}, "s"); }, ErrorCode::scale,
                 {"span only"});
  // Inside the bounds, however far from 1: the magnitudes the former 1e+-120 bounds refused.
  EXPECT_NO_THROW(chaos::require_scale(std::vector<double>{-0x1p1022, 0x1p1022}, "s"));
  EXPECT_NO_THROW(chaos::require_scale(std::vector<double>{1.0, 2e150, 1e300}, "s"));
  EXPECT_NO_THROW(chaos::require_scale(std::vector<double>{0.0, 0x1p-1021}, "s"));
  EXPECT_NO_THROW(chaos::require_scale(std::vector<double>{3e-171, 4e-171}, "s"));
  EXPECT_NO_THROW(chaos::require_scale(std::vector<double>(5, 1e-320), "s"));  // constant: named elsewhere
}

}  // namespace
