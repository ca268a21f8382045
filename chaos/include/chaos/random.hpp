#pragma once
// Bit-reproducible randomness. Standard-library distributions are implementation-defined, so the
// generator (xoshiro256**, Blackman & Vigna 2018, seeded through splitmix64) and the transforms to
// uniform and Gaussian variates are written here and give the same numbers on every platform.

#include <cstdint>

namespace chaos {

class Random {
 public:
  explicit Random(std::uint64_t seed) noexcept;
  std::uint64_t next() noexcept;   // 64 random bits
  double uniform() noexcept;       // in [0, 1), 53 bits of precision
  double uniform_open() noexcept;  // in (0, 1): safe for log
  double gaussian() noexcept;      // standard normal, Marsaglia's polar method
  std::uint64_t below(std::uint64_t n) noexcept;  // uniform in [0, n), unbiased (Lemire 2019)

 private:
  std::uint64_t s_[4];
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace chaos
