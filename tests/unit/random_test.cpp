// chaos::Random against an independent transcription of the published algorithms (xoshiro256**
// and splitmix64, Blackman & Vigna 2018), anchored on published test vectors, plus statistical
// checks of the variates with bounds derived from their known distributions.
#include "chaos/random.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace {

// Written straight from the reference C code (prng.di.unimi.it), independently of chaos/src.
struct ReferenceXoshiro {
  std::uint64_t s[4];
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t next() {
    const std::uint64_t result = rotl(s[1] * 5, 7) * 9;
    const std::uint64_t t = s[1] << 17;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = rotl(s[3], 45);
    return result;
  }
};

std::uint64_t reference_splitmix64(std::uint64_t& x) {
  std::uint64_t z = (x += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

ReferenceXoshiro seeded_reference(std::uint64_t seed) {
  ReferenceXoshiro r{};
  for (auto& w : r.s) w = reference_splitmix64(seed);
  return r;
}

TEST(Random, ReferenceTranscriptionMatchesPublishedVectors) {
  // Published outputs of xoshiro256** from the state {1, 2, 3, 4} (rand_xoshiro's `reference`
  // test, "produced with the reference implementation").
  ReferenceXoshiro r{{1, 2, 3, 4}};
  const std::array<std::uint64_t, 10> expected = {
      11520ULL, 0ULL, 1509978240ULL, 1215971899390074240ULL, 1216172134540287360ULL,
      607988272756665600ULL, 16172922978634559625ULL, 8476171486693032832ULL,
      10595114339597558777ULL, 2904607092377533576ULL};
  for (const auto e : expected) EXPECT_EQ(r.next(), e);
  // Published first outputs of splitmix64 from the seed 0.
  std::uint64_t x = 0;
  EXPECT_EQ(reference_splitmix64(x), 0xE220A8397B1DCDAFULL);
  EXPECT_EQ(reference_splitmix64(x), 0x6E789E6AA1B965F4ULL);
  EXPECT_EQ(reference_splitmix64(x), 0x06C45D188009454FULL);
  EXPECT_EQ(reference_splitmix64(x), 0xF88BB8A8724C81ECULL);
}

TEST(Random, NextMatchesTheReferenceAlgorithmSeededBySplitmix) {
  for (const std::uint64_t seed : {0ULL, 1ULL, 42ULL, 0xdeadbeefcafef00dULL, ~0ULL}) {
    chaos::Random rng(seed);
    ReferenceXoshiro ref = seeded_reference(seed);
    for (int i = 0; i < 1000; ++i) ASSERT_EQ(rng.next(), ref.next()) << "seed " << seed << " draw " << i;
  }
}

TEST(Random, UniformIsTheTop53BitsScaled) {
  // Definition: uniform() = (next() >> 11) * 2^-53, uniform_open() = ((next() >> 11) + 1/2) * 2^-53.
  chaos::Random rng(7);
  ReferenceXoshiro ref = seeded_reference(7);
  for (int i = 0; i < 1000; ++i) {
    ASSERT_EQ(rng.uniform(), std::ldexp(static_cast<double>(ref.next() >> 11), -53));
    ASSERT_EQ(rng.uniform_open(), std::ldexp(static_cast<double>(ref.next() >> 11) + 0.5, -53));
  }
}

TEST(Random, SameSeedSameStreamDifferentSeedsDiffer) {
  chaos::Random a(123), b(123), c(124);
  int equal_to_other_seed = 0;
  for (int i = 0; i < 1000; ++i) {
    const double ga = a.gaussian(), gb = b.gaussian();
    ASSERT_EQ(ga, gb);  // bit for bit, spare included
    ASSERT_EQ(a.below(1000), b.below(1000));
    const std::uint64_t na = a.next();
    ASSERT_EQ(na, b.next());
    if (na == c.next()) ++equal_to_other_seed;
  }
  // Two independent 64-bit streams agree at a position with probability 2^-64.
  EXPECT_EQ(equal_to_other_seed, 0);
}

TEST(Random, GaussianIsMarsagliaPolarOnTheUniforms) {
  // The polar method written out independently on the reference uniforms: same bits expected.
  chaos::Random rng(99);
  ReferenceXoshiro ref = seeded_reference(99);
  auto u = [&] { return std::ldexp(static_cast<double>(ref.next() >> 11), -53); };
  for (int i = 0; i < 500; ++i) {
    double v1, v2, s;
    do {
      v1 = 2.0 * u() - 1.0;
      v2 = 2.0 * u() - 1.0;
      s = v1 * v1 + v2 * v2;
    } while (s >= 1.0 || s == 0.0);
    const double f = std::sqrt(-2.0 * std::log(s) / s);
    ASSERT_EQ(rng.gaussian(), v1 * f);
    ASSERT_EQ(rng.gaussian(), v2 * f);
  }
}

TEST(Random, UniformMomentsOverAMillionDraws) {
  // U(0,1): mean 1/2 (sd of the sample mean 1/sqrt(12 N)), variance 1/12 (sd of the sample
  // variance sqrt(1/180 / N)); bounds at 5 standard errors.
  const int n = 1'000'000;
  chaos::Random rng(2024);
  double sum = 0.0, sum2 = 0.0, min_open = 1.0, max_open = 0.0;
  for (int i = 0; i < n; ++i) {
    const double x = rng.uniform();
    ASSERT_GE(x, 0.0);
    ASSERT_LT(x, 1.0);
    sum += x;
    sum2 += x * x;
    const double y = rng.uniform_open();
    min_open = std::min(min_open, y);
    max_open = std::max(max_open, y);
  }
  const double mean = sum / n, var = sum2 / n - mean * mean;
  EXPECT_NEAR(mean, 0.5, 5.0 / std::sqrt(12.0 * n));
  EXPECT_NEAR(var, 1.0 / 12.0, 5.0 * std::sqrt(1.0 / 180.0 / n));
  EXPECT_GT(min_open, 0.0);
  EXPECT_LT(max_open, 1.0);
}

TEST(Random, GaussianMomentsOverAMillionDraws) {
  // N(0,1): E x = 0, E x^2 = 1, E x^3 = 0, E x^4 = 3; the standard errors of the sample moments are
  // sqrt(Var x^k / N) with Var x = 1, Var x^2 = 2, Var x^3 = 15, Var x^4 = 96. Bounds at 5 of them.
  const int n = 1'000'000;
  chaos::Random rng(31337);
  double m1 = 0, m2 = 0, m3 = 0, m4 = 0;
  for (int i = 0; i < n; ++i) {
    const double x = rng.gaussian();
    ASSERT_TRUE(std::isfinite(x));
    m1 += x;
    m2 += x * x;
    m3 += x * x * x;
    m4 += x * x * x * x;
  }
  m1 /= n;
  m2 /= n;
  m3 /= n;
  m4 /= n;
  const double se = 1.0 / std::sqrt(static_cast<double>(n));
  EXPECT_NEAR(m1, 0.0, 5 * se);
  EXPECT_NEAR(m2, 1.0, 5 * std::sqrt(2.0) * se);
  EXPECT_NEAR(m3, 0.0, 5 * std::sqrt(15.0) * se);
  EXPECT_NEAR(m4, 3.0, 5 * std::sqrt(96.0) * se);
}

TEST(Random, BelowStaysInRangeAndIsUniform) {
  chaos::Random rng(5);
  EXPECT_EQ(rng.below(1), 0u);
  // A range that is not a power of two, where a plain modulo would be biased; chi-square with
  // 6 degrees of freedom, 99.99th percentile 27.86.
  const std::uint64_t k = 7;
  const int n = 700'000;
  std::vector<int> counts(k, 0);
  for (int i = 0; i < n; ++i) {
    const auto v = rng.below(k);
    ASSERT_LT(v, k);
    ++counts[v];
  }
  double chi2 = 0.0;
  for (const int c : counts) chi2 += (c - n / 7.0) * (c - n / 7.0) / (n / 7.0);
  EXPECT_LT(chi2, 27.86);
  // A bound above 2^63, where the rejection threshold 2^64 mod n = 2^62 is large: the values must
  // stay below the bound and fall in its top third a third of the time.
  const std::uint64_t big = 3ULL << 62;
  int top_third = 0;
  for (int i = 0; i < 30'000; ++i) {
    const auto v = rng.below(big);
    ASSERT_LT(v, big);
    if (v >= (2ULL << 62)) ++top_third;
  }
  // Binomial(30000, 1/3): sd ~ 81.6; 5 sd bound.
  EXPECT_NEAR(top_third, 10'000, 410);
}

}  // namespace
