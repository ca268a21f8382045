#include "study/grid.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "chaos/format.hpp"
#include "study/error.hpp"

namespace study {

namespace {

double parse_number(std::string_view text, std::string_view what) {
  const std::string s(text);
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || end != s.c_str() + s.size())
    throw StudyError("--axis", std::string(what), "'" + s + "' is not a number");
  if (!std::isfinite(v)) throw StudyError("--axis", std::string(what), "'" + s + "' is not finite");
  return v;
}

std::vector<std::string_view> split(std::string_view s, char sep) {
  std::vector<std::string_view> parts;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= s.size(); ++i) {
    if (i == s.size() || s[i] == sep) {
      parts.push_back(s.substr(start, i - start));
      start = i + 1;
    }
  }
  return parts;
}

}  // namespace

std::string exact(double v) { return chaos::format_number(v, chaos::Precision::round_trip); }

Axis parse_axis(std::string_view text) {
  const std::size_t eq = text.find('=');
  if (eq == std::string_view::npos || eq == 0)
    throw StudyError("--axis", std::string(text), "must be key=from:to:count or key=v1,v2,...");
  Axis axis;
  axis.key = std::string(text.substr(0, eq));
  const std::string_view rest = text.substr(eq + 1);
  if (rest.find(':') != std::string_view::npos) {
    const auto parts = split(rest, ':');
    if (parts.size() != 3) throw StudyError("--axis", std::string(text), "a range is from:to:count (three fields)");
    const double from = parse_number(parts[0], axis.key);
    const double to = parse_number(parts[1], axis.key);
    const double count = parse_number(parts[2], axis.key);
    if (count < 1 || count != std::floor(count) || count > 1e7)
      throw StudyError("--axis", std::string(text), "the count must be a whole number from 1 to 1e7");
    const auto n = static_cast<std::size_t>(count);
    if (n > 1 && from == to) throw StudyError("--axis", std::string(text), "from = to with more than one value");
    for (std::size_t i = 0; i < n; ++i)
      axis.values.push_back(n == 1 ? from : from + (to - from) * static_cast<double>(i) / static_cast<double>(n - 1));
  } else {
    for (std::string_view part : split(rest, ',')) axis.values.push_back(parse_number(part, axis.key));
  }
  return axis;
}

Grid::Grid(std::vector<Axis> axes) : axes_(std::move(axes)) {
  if (axes_.size() > 2)
    throw StudyError("--axis", std::to_string(axes_.size()) + " axes", "a sweep has at most two axes");
  if (axes_.size() == 2 && axes_[0].key == axes_[1].key)
    throw StudyError("--axis", axes_[0].key, "the two axes must be different keys");
  for (const Axis& a : axes_)
    if (a.values.empty()) throw StudyError("--axis", a.key, "has no values");
}

std::size_t Grid::size() const {
  std::size_t n = 1;
  for (const Axis& a : axes_) n *= a.values.size();
  return n;
}

std::vector<std::size_t> Grid::indices(std::size_t point) const {
  std::vector<std::size_t> idx;
  for (const Axis& a : axes_) {
    idx.push_back(point % a.values.size());
    point /= a.values.size();
  }
  return idx;
}

std::vector<double> Grid::coordinates(std::size_t point) const {
  const auto idx = indices(point);
  std::vector<double> c;
  for (std::size_t k = 0; k < axes_.size(); ++k) c.push_back(axes_[k].values[idx[k]]);
  return c;
}

std::vector<std::string> Grid::overrides(std::size_t point) const {
  const auto c = coordinates(point);
  std::vector<std::string> o;
  for (std::size_t k = 0; k < axes_.size(); ++k) o.push_back(axes_[k].key + "=" + exact(c[k]));
  return o;
}

}  // namespace study
