#pragma once
// A scalar time series and the reader that gets one from a text file, with TISEAN's conventions:
// whitespace- or comma-separated columns, '#' comments, a column to use (-c), rows to skip (-x)
// and rows to use (-l). The sampling interval travels with the values so delays can be shown in
// time units.

#include <cstddef>
#include <iosfwd>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace chaos {

struct Series {
  std::vector<double> values;
  std::optional<double> dt;  // sampling interval in time units, when known
  std::size_t column = 1;    // the column read (1-based), found by name when one was given
};

struct ReadOptions {
  std::size_t column = 1;  // 1-based, as in TISEAN
  std::string column_name;  // when not empty: the header's column of this name, instead of `column`
  std::size_t skip = 0;    // data rows skipped after comments and blank lines are dropped
  std::size_t length = std::numeric_limits<std::size_t>::max();  // data rows used after the skip
  std::optional<double> dt;
  void validate() const;
};

// Reads the series from a file; "-" reads standard input. Every refusal names the source, the line
// and the rule: missing file, empty input, non-numeric token, NaN or infinity, missing column.
// A UTF-8 byte-order mark at the start is skipped, and a first data line on which no token is a
// number is a header (column names, as a spreadsheet's CSV export writes): it is not a data row,
// and `column_name` picks a column by it. A refused token is shown cut to 60 bytes, with control
// bytes and a byte-order mark made visible.
Series read_series(const std::string& path, const ReadOptions& options = {});
Series read_series(std::istream& in, const std::string& source_name, const ReadOptions& options = {});
// The whole of a file ("-": standard input) as text, for a reader that takes several columns from
// it; a missing file or a directory is refused as read_series refuses it.
std::string read_text(const std::string& path);
// The columns of the first line that is not blank or a comment (a header row counts), split and
// ended as read_series splits and ends lines; 0 when there is none.
std::size_t count_columns(std::istream& in);

// Checks shared by every estimator; each throws InvalidInput naming `what` and the numbers.
void require_finite(std::span<const double> x, const std::string& what);
void require_not_constant(std::span<const double> x, const std::string& what);
// The estimators square and sum distances and Fourier coefficients, which would overflow or
// underflow double far from magnitude 1; each works on the series divided by a power of two where
// its magnitude needs it (exact, so every estimate of a series equals that of its rescaled copy,
// and values with units come back in the data's units). What is left to refuse: values beyond
// 2^1022 in magnitude, where max - min itself can overflow, and a spread (max - min) below 2^-1021,
// where the values are subnormal doubles with fewer significant bits than 53 relative to the spread
// (the input has lost its precision, whatever the scale). A constant series (spread 0) passes, for
// require_not_constant to name.
inline constexpr double largest_magnitude = 0x1p1022;   // 4.49e307
inline constexpr double smallest_spread = 0x1p-1021;    // 4.45e-308
void require_scale(std::span<const double> x, const std::string& what);

// How much the pairs of samples tie. Quantised data (a few levels) put most pairs of samples, and
// so of delay vectors, at one of a few distances: nearest neighbours are then chosen among ties,
// and a neighbourhood radius takes thousands of points at once or none. `tied_pairs` is the
// fraction of pairs (i < j) whose distance |x_i - x_j| is shared by at least 1% of all pairs
// (computed over the distinct values when there are at most 512 of them; beyond, only exact repeats,
// distance 0, are counted). 0 for untied data.
struct ValueTies {
  std::size_t distinct = 0;  // distinct values
  double tied_pairs = 0.0;
  bool most_pairs_tie() const noexcept { return tied_pairs > 0.5; }
};
ValueTies value_ties(std::span<const double> x);
// A sentence for a result's explanation when most pairs tie, else empty.
std::string ties_note(const ValueTies& ties);

void require_length(std::span<const double> x, std::size_t minimum, const std::string& what,
                    const std::string& reason);

}  // namespace chaos
