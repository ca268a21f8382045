#include "lyapunov_ties.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <unordered_map>

namespace chaos::lyapunov_detail {

double DelayVectors::distance(std::size_t i, std::size_t j) const noexcept {
  double d = 0.0;
  for (std::size_t l = 0; l < m; ++l) {
    const double e = std::abs(y[i + l * tau] - y[j + l * tau]);
    d = norm == Norm::max ? std::max(d, e) : d + e * e;
  }
  return norm == Norm::euclidean ? std::sqrt(d) : d;
}

bool DelayVectors::less(std::size_t a, std::size_t b) const noexcept {
  for (std::size_t l = 0; l < m; ++l) {
    const double x = y[a + l * tau], z = y[b + l * tau];
    if (x < z) return true;
    if (z < x) return false;
  }
  return false;
}

namespace {

// Kept (index, weight) pairs in index order, as the mean sums them.
void write_sorted(std::vector<std::pair<std::size_t, double>>& kept, Thinned& out) {
  std::sort(kept.begin(), kept.end());
  out.index.resize(kept.size());
  out.weight.resize(kept.size());
  for (std::size_t r = 0; r < kept.size(); ++r) {
    out.index[r] = kept[r].first;
    out.weight[r] = kept[r].second;
  }
}

}  // namespace

bool thin_ties(const DelayVectors& v, std::size_t i, std::span<const std::size_t> members, std::size_t cap,
               std::vector<std::pair<double, std::size_t>>& scratch, Thinned& out) {
  if (cap == 0 || members.size() <= cap) return false;
  scratch.clear();
  for (const std::size_t j : members) scratch.emplace_back(v.distance(i, j), j);
  // Untied data answer quickly: either no distance repeats more than cap times among the first
  // few distinct ones, or past 16 distinct distances the sort below decides.
  std::array<std::pair<double, std::size_t>, 16> seen;
  std::size_t distinct = 0;
  bool any = false, many = false;
  for (const auto& [d, j] : scratch) {
    std::size_t at = 0;
    while (at < distinct && seen[at].first != d) ++at;
    if (at == distinct) {
      if (distinct == seen.size()) {
        many = true;
        break;
      }
      seen[distinct++] = {d, 0};
    }
    if (++seen[at].second > cap) any = true;
  }
  if (!many && !any) return false;
  std::sort(scratch.begin(), scratch.end());  // by distance, then index
  any = false;
  for (std::size_t g = 0, end = 0; g < scratch.size() && !any; g = end) {
    for (end = g; end < scratch.size() && scratch[end].first == scratch[g].first;) ++end;
    any = end - g > cap;
  }
  if (!any) return false;
  std::vector<std::pair<std::size_t, double>> kept;
  for (std::size_t g = 0, end = 0; g < scratch.size(); g = end) {
    for (end = g; end < scratch.size() && scratch[end].first == scratch[g].first;) ++end;
    const std::size_t size = end - g;
    if (size <= cap) {
      for (std::size_t r = g; r < end; ++r) kept.emplace_back(scratch[r].second, 1.0);
      continue;
    }
    // The group in the order of the header: by delay vector, then by index.
    std::sort(scratch.begin() + static_cast<std::ptrdiff_t>(g), scratch.begin() + static_cast<std::ptrdiff_t>(end),
              [&](const auto& a, const auto& b) {
                if (v.less(a.second, b.second)) return true;
                if (v.less(b.second, a.second)) return false;
                return a.second < b.second;
              });
    const double weight = static_cast<double>(size) / static_cast<double>(cap);
    for (std::size_t r = 0; r < cap; ++r) kept.emplace_back(scratch[g + r * size / cap].second, weight);
  }
  write_sorted(kept, out);
  return true;
}

std::optional<IdenticalVectors> identical_vectors(const DelayVectors& v, std::size_t points, std::size_t max_classes) {
  const std::size_t limit = max_classes;
  if (limit == 0) return std::nullopt;
  // A hash of the coordinates' bits, with -0 read as +0 so that values equal under == hash alike.
  const auto hash = [&](std::size_t j) {
    std::uint64_t h = 0x9e3779b97f4a7c15ULL;
    for (std::size_t l = 0; l < v.m; ++l) {
      const double x = v.y[j + l * v.tau];
      h ^= std::bit_cast<std::uint64_t>(x == 0.0 ? 0.0 : x) + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
    }
    return h;
  };
  const auto same = [&](std::size_t a, std::size_t b) {
    for (std::size_t l = 0; l < v.m; ++l)
      if (!(v.y[a + l * v.tau] == v.y[b + l * v.tau])) return false;
    return true;
  };
  // Classes found so far, by hash (a chain through `next` where hashes collide), and each point's.
  constexpr std::size_t none = std::numeric_limits<std::size_t>::max();
  IdenticalVectors found;
  std::vector<std::size_t> next, class_of(points);
  std::unordered_map<std::uint64_t, std::size_t> first_with_hash;
  first_with_hash.reserve(std::min<std::size_t>(limit, 4096));
  for (std::size_t j = 0; j < points; ++j) {
    const std::uint64_t h = hash(j);
    const auto slot = first_with_hash.find(h);
    std::size_t c = slot == first_with_hash.end() ? none : slot->second;
    while (c != none && !same(found.representative[c], j)) c = next[c];
    if (c == none) {
      if (found.representative.size() == limit) return std::nullopt;
      c = found.representative.size();
      found.representative.push_back(j);
      next.push_back(slot == first_with_hash.end() ? none : slot->second);
      first_with_hash[h] = c;
    }
    class_of[j] = c;
  }
  found.members.resize(found.representative.size());
  for (std::size_t j = 0; j < points; ++j) found.members[class_of[j]].push_back(j);
  std::vector<std::size_t> order(found.representative.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return v.less(found.representative[a], found.representative[b]); });
  IdenticalVectors sorted;
  for (const std::size_t c : order) {
    sorted.representative.push_back(found.representative[c]);
    sorted.members.push_back(std::move(found.members[c]));
  }
  return sorted;
}

void class_neighbourhood(const IdenticalVectors& classes, const DelayVectors& v, std::size_t i, double eps,
                         std::size_t theiler, ClassNeighbourhood& out) {
  out.entries.clear();
  out.found = 0;
  const std::size_t low = i > theiler ? i - theiler : 0;
  const std::size_t high = i + std::min(theiler, std::numeric_limits<std::size_t>::max() - i);
  for (std::size_t c = 0; c < classes.representative.size(); ++c) {
    const double d = v.distance(i, classes.representative[c]);
    if (!(d > 0.0 && d < eps)) continue;
    const std::vector<std::size_t>& m = classes.members[c];
    const auto begin = static_cast<std::size_t>(std::lower_bound(m.begin(), m.end(), low) - m.begin());
    const auto end = static_cast<std::size_t>(std::upper_bound(m.begin(), m.end(), high) - m.begin());
    const std::size_t admissible = m.size() - (end - begin);
    if (admissible == 0) continue;
    out.entries.push_back({d, c, admissible, begin, end});
    out.found += admissible;
  }
  std::sort(out.entries.begin(), out.entries.end(), [](const ClassNeighbourhood::Entry& a, const ClassNeighbourhood::Entry& b) {
    return a.distance < b.distance || (a.distance == b.distance && a.cls < b.cls);
  });
}

namespace {

// The k-th admissible member of a class (the window's positions skipped).
std::size_t admissible_member(const IdenticalVectors& classes, const ClassNeighbourhood::Entry& e, std::size_t k) {
  return classes.members[e.cls][k < e.window_begin ? k : k + (e.window_end - e.window_begin)];
}

}  // namespace

bool thin_classes(const IdenticalVectors& classes, const ClassNeighbourhood& neighbourhood, std::size_t cap,
                  Thinned& out) {
  if (cap == 0 || neighbourhood.found <= cap) return false;
  const auto& entries = neighbourhood.entries;
  // Groups: runs of entries at one distance, of the size of their admissible members together.
  const auto group_end = [&](std::size_t g) {
    std::size_t end = g;
    while (end < entries.size() && entries[end].distance == entries[g].distance) ++end;
    return end;
  };
  const auto group_size = [&](std::size_t g, std::size_t end) {
    std::size_t size = 0;
    for (std::size_t e = g; e < end; ++e) size += entries[e].admissible;
    return size;
  };
  bool any = false;
  for (std::size_t g = 0, end = 0; g < entries.size() && !any; g = end) {
    end = group_end(g);
    any = group_size(g, end) > cap;
  }
  if (!any) return false;
  std::vector<std::pair<std::size_t, double>> kept;
  for (std::size_t g = 0, end = 0; g < entries.size(); g = end) {
    end = group_end(g);
    const std::size_t size = group_size(g, end);
    if (size <= cap) {
      for (std::size_t e = g; e < end; ++e)
        for (std::size_t k = 0; k < entries[e].admissible; ++k)
          kept.emplace_back(admissible_member(classes, entries[e], k), 1.0);
      continue;
    }
    // Ranks floor(r size / cap) in the order (class, index): classes are numbered in the vectors'
    // lexicographic order, and the ranks grow, so one pass over the group's classes finds them.
    const double weight = static_cast<double>(size) / static_cast<double>(cap);
    std::size_t e = g, before = 0;  // members of the classes ahead of entry e
    for (std::size_t r = 0; r < cap; ++r) {
      const std::size_t rank = r * size / cap;
      while (rank >= before + entries[e].admissible) before += entries[e++].admissible;
      kept.emplace_back(admissible_member(classes, entries[e], rank - before), weight);
    }
  }
  write_sorted(kept, out);
  return true;
}

void list_members(const IdenticalVectors& classes, const ClassNeighbourhood& neighbourhood,
                  std::vector<std::size_t>& out) {
  out.clear();
  for (const auto& e : neighbourhood.entries)
    for (std::size_t k = 0; k < e.admissible; ++k) out.push_back(admissible_member(classes, e, k));
  std::sort(out.begin(), out.end());
}

}  // namespace chaos::lyapunov_detail
