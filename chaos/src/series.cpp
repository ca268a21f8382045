#include "chaos/series.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string_view>

#include "chaos/error.hpp"
#include "chaos/format.hpp"

namespace chaos {

namespace {

// Splits a data line into tokens at whitespace and commas; a '#' ends the line. `tokens` is
// reused from line to line (one allocation per file, not one per line).
void tokenize(std::string_view line, std::vector<std::string_view>& tokens) {
  if (const auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
  tokens.clear();
  std::size_t pos = 0;
  const auto is_separator = [](char c) { return c == ',' || c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; };
  while (pos < line.size()) {
    while (pos < line.size() && is_separator(line[pos])) ++pos;
    const std::size_t start = pos;
    while (pos < line.size() && !is_separator(line[pos])) ++pos;
    if (pos > start) tokens.push_back(line.substr(start, pos - start));
  }
}

// Splits a data line of a CSV file at commas only, each field trimmed of blanks, empty fields kept
// (a pandas index column has an empty name; a date-time field "2020-01-01 00:00:00" holds a blank);
// a '#' ends the line. A line with nothing but separators gives no tokens, as a blank line does.
void tokenize_csv(std::string_view line, std::vector<std::string_view>& tokens) {
  if (const auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
  tokens.clear();
  const auto is_blank = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; };
  bool any = false;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    std::string_view field = line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
    while (!field.empty() && is_blank(field.front())) field.remove_prefix(1);
    while (!field.empty() && is_blank(field.back())) field.remove_suffix(1);
    any = any || !field.empty();
    tokens.push_back(field);
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  if (!any) tokens.clear();
}

enum class Parsed { number, not_a_number, out_of_range };

Parsed parse_double(std::string_view token, double& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (end != token.data() + token.size()) return Parsed::not_a_number;
  if (ec == std::errc::result_out_of_range) return Parsed::out_of_range;  // 1e400, 1e-400
  return ec == std::errc() ? Parsed::number : Parsed::not_a_number;
}

// The lines of a stream, read a block at a time (a character at a time costs half the reading of
// a 10^5-row file). A line ends at LF, CR LF or a lone CR (a classic Mac file, or lines mixed by
// editors): with only LF as the end, a CR-separated file read as one line of many columns, and
// column 1 of it as a one-sample series (corrupt-file tier). It reads ahead of the line
// it returns, so the stream is spent once the reader is done with it. A UTF-8 byte-order mark at
// the start of the first line (spreadsheet exports) is not part of the line.
constexpr std::string_view byte_order_mark = "\xEF\xBB\xBF";

class LineReader {
 public:
  explicit LineReader(std::istream& in) : in_(in) {}

  // The next line without its end (valid until the next call); false at the end of the input.
  bool next(std::string_view& line) {
    for (;;) {
      const std::string_view rest = std::string_view(buffer_).substr(pos_);
      std::size_t end = scanned_;  // a line longer than a block is not scanned again from its start
      while (end < rest.size() && rest[end] != '\n' && rest[end] != '\r') ++end;
      scanned_ = end;
      // A CR last in what has been read may be the first half of a CR LF: read on before deciding.
      const bool undecided = end + 1 == rest.size() && rest[end] == '\r' && !spent_;
      if (end < rest.size() && !undecided) {
        deliver(line, rest.substr(0, end));
        const bool crlf = rest[end] == '\r' && end + 1 < rest.size() && rest[end + 1] == '\n';
        pos_ += end + (crlf ? 2 : 1);
        scanned_ = 0;
        return true;
      }
      if (!spent_) {
        fill();  // moves the buffer: `rest` is taken again
        continue;
      }
      if (rest.empty()) {
        in_.setstate(std::ios::eofbit);
        return false;
      }
      deliver(line, rest);  // the last line has no end
      pos_ = buffer_.size();
      scanned_ = 0;
      return true;
    }
  }

 private:
  void deliver(std::string_view& line, std::string_view text) {
    if (first_ && text.substr(0, byte_order_mark.size()) == byte_order_mark) text.remove_prefix(byte_order_mark.size());
    first_ = false;
    line = text;
  }

  // Appends the next block after dropping what was returned; at the end of the input, spent_.
  void fill() {
    constexpr std::size_t block = std::size_t{1} << 16;
    buffer_.erase(0, pos_);
    pos_ = 0;
    const std::size_t kept = buffer_.size();
    buffer_.resize(kept + block);
    const std::streamsize got = in_.rdbuf()->sgetn(buffer_.data() + kept, static_cast<std::streamsize>(block));
    buffer_.resize(kept + static_cast<std::size_t>(std::max<std::streamsize>(got, 0)));
    spent_ = got <= 0;
  }

  std::istream& in_;
  std::string buffer_;
  std::size_t pos_ = 0;      // start of the next line in buffer_
  std::size_t scanned_ = 0;  // bytes after pos_ known to hold no line end
  bool spent_ = false;       // the stream has nothing more to give
  bool first_ = true;        // the next line is the first
};

// The length of the valid UTF-8 sequence at the start of `s` (2 to 4 bytes), or 0.
std::size_t utf8_sequence(std::string_view s) {
  const auto lead = static_cast<unsigned char>(s[0]);
  const std::size_t length = lead >= 0xC2 && lead <= 0xDF   ? 2
                             : lead >= 0xE0 && lead <= 0xEF ? 3
                             : lead >= 0xF0 && lead <= 0xF4 ? 4
                                                            : 0;
  if (length == 0 || s.size() < length) return 0;
  for (std::size_t k = 1; k < length; ++k)
    if ((static_cast<unsigned char>(s[k]) & 0xC0) != 0x80) return 0;
  return length;
}

// A token as a message shows it: at most 60 bytes (a 1 MB token echoed whole buries the message),
// a byte-order mark as <BOM>, control bytes and bytes that are not UTF-8 (binary garbage) as \xHH.
std::string shown(std::string_view token) {
  constexpr std::size_t limit = 60;
  std::string out;
  std::size_t i = 0;
  for (; i < token.size() && i < limit; ++i) {
    if (token.substr(i, 3) == byte_order_mark) {
      out += "<BOM>";
      i += 2;
      continue;
    }
    const auto c = static_cast<unsigned char>(token[i]);
    if (const std::size_t length = c >= 0x80 ? utf8_sequence(token.substr(i)) : 0; length > 0) {
      out += token.substr(i, length);
      i += length - 1;
    } else if (c < 0x20 || c >= 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02X", c);
      out += hex;
    } else {
      out += token[i];
    }
  }
  if (i < token.size()) out += "... (" + std::to_string(token.size()) + " bytes)";
  return out;
}

// A header names columns: every token starts like a name, not like a number ("1e999" and "2.5.3"
// are bad numbers, not names; a token starting with a NUL or another control byte is neither), and
// none is NaN or infinity spelled out.
bool is_header(const std::vector<std::string_view>& tokens) {
  bool named = false;
  for (const auto token : tokens) {
    if (token.empty()) continue;  // an unnamed column of a CSV header (pandas' index)
    named = true;
    const auto c = static_cast<unsigned char>(token.front());
    if ((c >= '0' && c <= '9') || c == '+' || c == '-' || c == '.' || c < 0x20 || c == 0x7f) return false;
    std::string lower(token);
    for (char& ch : lower) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    if (lower == "nan" || lower == "inf" || lower == "infinity") return false;
  }
  return named;
}

}  // namespace

void ReadOptions::validate() const {
  if (column == 0)
    throw InvalidInput(ErrorCode::invalid_parameter, "column numbers start at 1 (got column 0)");
  if (length == 0)
    throw InvalidInput(ErrorCode::invalid_parameter, "number of rows to use (-l) must be at least 1 (got 0)");
  if (dt && !(std::isfinite(*dt) && *dt > 0.0))
    throw InvalidInput(ErrorCode::invalid_parameter,
                       "sampling interval dt must be finite and positive (got " + format_number(*dt) + ")");
}

Series read_series(std::istream& in, const std::string& source_name, const ReadOptions& options) {
  options.validate();
  Series series;
  series.dt = options.dt;
  series.column = options.column;
  LineReader reader(in);
  std::string_view line;
  std::vector<std::string_view> tokens;
  std::size_t line_number = 0;
  std::size_t data_rows = 0;
  std::vector<std::string> header;  // the column names, when the first data line holds them
  bool first = true;
  bool csv = false;  // a header of names with commas: every line is split at commas only
  const auto where = [&] { return source_name + ":" + std::to_string(line_number) + ": "; };
  while (series.values.size() < options.length && reader.next(line)) {
    ++line_number;
    if (csv) tokenize_csv(line, tokens);
    else tokenize(line, tokens);
    if (tokens.empty()) continue;  // blank line or comment
    if (first) {
      first = false;
      if (line.substr(0, line.find('#')).find(',') != std::string_view::npos) {
        std::vector<std::string_view> fields;
        tokenize_csv(line, fields);
        if (is_header(fields)) {
          csv = true;
          tokens = fields;
        }
      }
      if (is_header(tokens)) {
        for (const auto t : tokens) header.emplace_back(t);
        if (!options.column_name.empty()) {
          const auto at = std::find(header.begin(), header.end(), options.column_name);
          if (at == header.end()) {
            std::string names;
            for (const auto& h : header) names += (names.empty() ? "" : ", ") + shown(h);
            throw InvalidInput(ErrorCode::parse, where() + "no column named '" + shown(options.column_name) +
                                                     "' in the header (" + names + ")");
          }
          series.column = static_cast<std::size_t>(at - header.begin()) + 1;
        }
        continue;
      }
      if (!options.column_name.empty())
        throw InvalidInput(ErrorCode::parse, where() + "-c " + shown(options.column_name) +
                                                 " names a column, but the first data line is not a header of names");
    }
    if (data_rows++ < options.skip) continue;
    const std::size_t column = series.column;
    if (tokens.size() < column)
      throw InvalidInput(ErrorCode::parse, where() + "column " + std::to_string(column) +
                                               " requested but the line has only " + std::to_string(tokens.size()) +
                                               " column(s)");
    const std::string_view token = tokens[column - 1];
    if (token.empty())
      throw InvalidInput(ErrorCode::parse, where() + "column " + std::to_string(column) + " is empty (a CSV field with no value)");
    double value = 0.0;
    const Parsed parsed = parse_double(token, value);
    if (parsed == Parsed::out_of_range)
      throw InvalidInput(ErrorCode::parse, where() + "column " + std::to_string(column) + ": '" + shown(token) +
                                               "' is beyond the range of a double (magnitudes from 4.9e-324 to 1.8e308)");
    if (parsed != Parsed::number)
      throw InvalidInput(ErrorCode::parse, where() + "column " + std::to_string(column) + ": '" + shown(token) +
                                               "' is not a number" +
                                               (token.find(byte_order_mark) != std::string_view::npos
                                                    ? " (a UTF-8 byte-order mark inside the file; remove it)"
                                                    : std::string()));
    if (!std::isfinite(value))
      throw InvalidInput(ErrorCode::non_finite, where() + "column " + std::to_string(column) + ": '" + shown(token) +
                                                    "' is not finite; NaN and infinity are refused");
    series.values.push_back(value);
  }
  if (in.bad()) throw InvalidInput(ErrorCode::io, source_name + ": read error");
  if (series.values.empty())
    throw InvalidInput(ErrorCode::empty, source_name + ": no data rows" +
                                             (options.skip > 0 ? " after skipping " + std::to_string(options.skip) +
                                                                     " row(s) (-x); the input has " +
                                                                     std::to_string(data_rows) + " data row(s)"
                                                               : header.empty() ? std::string(" (only blank lines or # comments)")
                                                                                : std::string(" (only a header row)")));
  return series;
}

namespace {

std::ifstream open_file(const std::string& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error))
    throw InvalidInput(ErrorCode::io, path + ": is a directory, not a series file");
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InvalidInput(ErrorCode::io, path + ": cannot open file (missing or unreadable)");
  return file;
}

}  // namespace

Series read_series(const std::string& path, const ReadOptions& options) {
  if (path == "-") return read_series(std::cin, "<stdin>", options);
  std::ifstream file = open_file(path);
  return read_series(file, path, options);
}

std::string read_text(const std::string& path) {
  std::ostringstream text;
  if (path == "-") {
    text << std::cin.rdbuf();
  } else {
    std::ifstream file = open_file(path);
    text << file.rdbuf();
  }
  return text.str();
}

std::size_t count_columns(std::istream& in) {
  LineReader reader(in);
  std::string_view line;
  std::vector<std::string_view> tokens;
  while (reader.next(line)) {
    tokenize(line, tokens);
    if (!tokens.empty()) return tokens.size();
  }
  return 0;
}

void require_finite(std::span<const double> x, const std::string& what) {
  for (std::size_t i = 0; i < x.size(); ++i)
    if (!std::isfinite(x[i]))
      throw InvalidInput(ErrorCode::non_finite,
                         what + ": sample " + std::to_string(i) + " is " + format_number(x[i]) + "; values must be finite");
}

void require_not_constant(std::span<const double> x, const std::string& what) {
  if (x.empty()) return;
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  if (*lo == *hi)
    throw InvalidInput(ErrorCode::constant, what + ": the series is constant (all " + std::to_string(x.size()) +
                                                " samples equal " + format_number(*lo) + "); there are no dynamics to analyse");
}

void require_length(std::span<const double> x, std::size_t minimum, const std::string& what,
                    const std::string& reason) {
  if (x.size() < minimum)
    throw InvalidInput(ErrorCode::too_short, what + ": series too short: N = " + std::to_string(x.size()) +
                                                 " samples, but at least " + std::to_string(minimum) +
                                                 " are needed (" + reason + ")");
}

ValueTies value_ties(std::span<const double> x) {
  ValueTies out;
  if (x.size() < 2) return out;
  std::vector<double> sorted(x.begin(), x.end());
  std::sort(sorted.begin(), sorted.end());
  std::vector<double> value;
  std::vector<double> count;
  for (std::size_t g = 0, end = 0; g < sorted.size(); g = end) {
    for (end = g; end < sorted.size() && sorted[end] == sorted[g];) ++end;
    value.push_back(sorted[g]);
    count.push_back(static_cast<double>(end - g));
  }
  out.distinct = value.size();
  const double n = static_cast<double>(x.size());
  const double pairs = n * (n - 1.0) / 2.0, floor = 0.01 * pairs;
  double repeats = 0.0;  // pairs at distance 0
  for (const double c : count) repeats += c * (c - 1.0) / 2.0;
  std::vector<std::pair<double, double>> by_distance{{0.0, repeats}};  // (distance, pairs at it)
  constexpr std::size_t most_values = 512;
  if (value.size() <= most_values)
    for (std::size_t a = 0; a < value.size(); ++a)
      for (std::size_t b = a + 1; b < value.size(); ++b) by_distance.emplace_back(value[b] - value[a], count[a] * count[b]);
  std::sort(by_distance.begin(), by_distance.end());
  double tied = 0.0;
  for (std::size_t g = 0, end = 0; g < by_distance.size(); g = end) {
    double at = 0.0;
    for (end = g; end < by_distance.size() && by_distance[end].first == by_distance[g].first; ++end)
      at += by_distance[end].second;
    if (at >= floor) tied += at;
  }
  out.tied_pairs = tied / pairs;
  return out;
}

std::string ties_note(const ValueTies& ties) {
  if (!ties.most_pairs_tie()) return {};
  return "most pairs of samples tie (" + std::to_string(static_cast<int>(std::lround(100.0 * ties.tied_pairs))) +
         "% lie at a distance shared by at least 1% of all pairs; the series takes " + std::to_string(ties.distinct) +
         " distinct values): quantised data, whose neighbours are chosen among ties, so the estimate describes "
         "the quantisation lattice as much as the dynamics";
}

void require_scale(std::span<const double> x, const std::string& what) {
  if (x.empty()) return;
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  const double magnitude = std::max(std::fabs(*lo), std::fabs(*hi));
  if (magnitude > largest_magnitude)
    throw InvalidInput(ErrorCode::scale,
                       what + ": the values reach " + format_number(magnitude, Precision::message) + " in magnitude, beyond the " +
                           format_number(largest_magnitude, Precision::message) +
                           " (2^1022) where their range max - min can overflow double; divide the series by a power "
                           "of ten (the estimates do not depend on the scale)");
  const double spread = *hi - *lo;
  if (spread > 0.0 && spread < smallest_spread)
    throw InvalidInput(ErrorCode::scale,
                       what + ": the values span only " + format_number(spread, Precision::message) + " (max - min), below the " +
                           format_number(smallest_spread, Precision::message) +
                           " (2^-1021) under which doubles are subnormal and hold fewer than 53 significant bits; "
                           "multiply the series by a power of ten (the estimates do not depend on the scale)");
}

}  // namespace chaos
