#include "chaos/random.hpp"

#include <cmath>

namespace chaos {

namespace {

// GCC/Clang 128-bit product; __extension__ keeps -Wpedantic quiet about the non-ISO type.
__extension__ typedef unsigned __int128 uint128;

constexpr std::uint64_t rotl(std::uint64_t x, int k) noexcept { return (x << k) | (x >> (64 - k)); }

// splitmix64 (Steele, Lea & Flood 2014), the seeding generator recommended by Blackman & Vigna:
// it spreads any 64-bit seed, 0 included, over the 256-bit state, which is then never all zero.
std::uint64_t splitmix64(std::uint64_t& x) noexcept {
  std::uint64_t z = (x += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

constexpr double two_pow_minus_53 = 0x1.0p-53;

}  // namespace

Random::Random(std::uint64_t seed) noexcept {
  for (auto& word : s_) word = splitmix64(seed);
}

// xoshiro256** 1.0 (Blackman & Vigna 2018), transcribed from the reference C code.
std::uint64_t Random::next() noexcept {
  const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
  const std::uint64_t t = s_[1] << 17;
  s_[2] ^= s_[0];
  s_[3] ^= s_[1];
  s_[1] ^= s_[2];
  s_[0] ^= s_[3];
  s_[2] ^= t;
  s_[3] = rotl(s_[3], 45);
  return result;
}

// The top 53 bits, the best-mixed ones, give every multiple of 2^-53 in [0, 1) with equal weight.
double Random::uniform() noexcept { return static_cast<double>(next() >> 11) * two_pow_minus_53; }

// Midpoints of the same grid: (k + 1/2) 2^-53 is exact in a double and never 0 or 1.
double Random::uniform_open() noexcept {
  return (static_cast<double>(next() >> 11) + 0.5) * two_pow_minus_53;
}

// Marsaglia's polar method: a point uniform in the unit disc gives two independent normals, the
// second cached. Only +, *, sqrt (correctly rounded by IEEE 754) and log are used; no standard
// distribution, whose algorithm is implementation-defined.
double Random::gaussian() noexcept {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  double u = 0.0, v = 0.0, s = 0.0;
  do {
    u = 2.0 * uniform() - 1.0;
    v = 2.0 * uniform() - 1.0;
    s = u * u + v * v;
  } while (s >= 1.0 || s == 0.0);
  const double factor = std::sqrt(-2.0 * std::log(s) / s);
  spare_ = v * factor;
  has_spare_ = true;
  return u * factor;
}

// Lemire (2019), "Fast random integer generation in an interval": the high word of next() * n is
// uniform on [0, n) once the low word is rejected below 2^64 mod n, which removes the bias of a
// plain modulo. below(0) has no valid answer and returns 0 without drawing.
std::uint64_t Random::below(std::uint64_t n) noexcept {
  if (n == 0) return 0;
  uint128 m = static_cast<uint128>(next()) * n;
  auto low = static_cast<std::uint64_t>(m);
  if (low < n) {
    const std::uint64_t threshold = (0 - n) % n;  // 2^64 mod n
    while (low < threshold) {
      m = static_cast<uint128>(next()) * n;
      low = static_cast<std::uint64_t>(m);
    }
  }
  return static_cast<std::uint64_t>(m >> 64);
}

}  // namespace chaos
