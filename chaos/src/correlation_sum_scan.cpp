#include "correlation_sum_scan.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

namespace chaos::correlation_detail {

namespace {

void bin_portable(const AccBins::Lookup& bins, const double* a, std::size_t n, Count* h) noexcept {
  std::size_t u = 0;
  for (; u + histogram_copies <= n; u += histogram_copies) {  // unrolled by hand: the compiler keeps the loop
    ++h[bins.inside(a[u]) * histogram_copies];
    ++h[bins.inside(a[u + 1]) * histogram_copies + 1];
    ++h[bins.inside(a[u + 2]) * histogram_copies + 2];
    ++h[bins.inside(a[u + 3]) * histogram_copies + 3];
  }
  for (; u < n; ++u) ++h[bins.inside(a[u]) * histogram_copies];
}

#if defined(__x86_64__) && defined(__GNUC__)
// The same bins in two passes: the cell numbers computed four at a time (max with the floor, shift
// of the bit pattern, subtraction of the base: the scalar cell_of lane by lane, so the same
// integers) into `cells`, then the table reads, the rare fix-ups and the increments.
__attribute__((target("avx2"))) void bin_avx2(const AccBins::Lookup& bins, const double* a, std::size_t n, Count* h,
                                              std::uint32_t* cells) noexcept {
  const __m256d floor = _mm256_set1_pd(bins.floor);
  const __m128i shift = _mm_cvtsi32_si128(bins.shift);
  const __m256i base = _mm256_set1_epi64x(static_cast<long long>(bins.base));
  // The low 32 bits of each 64-bit lane (cell numbers are below 4096), packed into the low half.
  const __m256i low_halves = _mm256_setr_epi32(0, 2, 4, 6, 0, 2, 4, 6);
  const std::size_t vector_end = n / 4 * 4;
  for (std::size_t u = 0; u < vector_end; u += 4) {
    const __m256d v = _mm256_max_pd(_mm256_loadu_pd(a + u), floor);
    const __m256i c = _mm256_sub_epi64(_mm256_srl_epi64(_mm256_castpd_si256(v), shift), base);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(cells + u),
                     _mm256_castsi256_si128(_mm256_permutevar8x32_epi32(c, low_halves)));
  }
  const auto bump = [&](std::size_t u, std::size_t copy) {
    const std::int32_t e = bins.cell[cells[u]];
    ++h[(e >= 0 ? static_cast<std::size_t>(e) : bins.fix(e, a[u])) * histogram_copies + copy];
  };
  for (std::size_t u = 0; u < vector_end; u += 4) {
    bump(u, 0);
    bump(u + 1, 1);
    bump(u + 2, 2);
    bump(u + 3, 3);
  }
  bin_portable(bins, a + vector_end, n - vector_end, h);
}
#endif

}  // namespace

void Survivors::flush() noexcept {
  const AccBins::Lookup bins = pb_.bins->lookup();
  for (std::size_t level = first_; level < levels_; ++level) {
    Count* h = wide_.data() + (level + 2 - pb_.min_m) * pb_.nr * copies;
#if defined(__x86_64__) && defined(__GNUC__)
    if (simd_)
      bin_avx2(bins, buffer(level), n_[level], h, cells_.get());
    else
#endif
      bin_portable(bins, buffer(level), n_[level], h);
    n_[level] = 0;
  }
}

namespace {

template <class N, bool check_window>
void scan_scalar(const Problem& pb, const PointLayout& g, std::size_t p, std::size_t qb, std::size_t qe, Survivors& s,
                 double t) {
  const std::size_t levels = s.levels(), first = s.first_stored(), w = pb.w, i = g.index[p];
  const double* c0 = g.coordinate(0);
  const double* c1 = g.coordinate(1);
  double a[Survivors::block];
  for (std::size_t q0 = qb; q0 < qe; q0 += Survivors::block) {
    const std::size_t len = std::min(Survivors::block, qe - q0);
    s.make_room();
    for (std::size_t level = 0; level < levels; ++level) {
      const double* ck = g.coordinate(level + 1) + q0;
      const double ak = g.coordinate(level + 1)[p];
      double* out = s.buffer(level);
      std::size_t n = s.count(level), alive = 0;
      for (std::size_t u = 0; u < len; ++u) {
        double v = level == 0 ? N::add(N::add(0.0, std::abs(c0[p] - c0[q0 + u])), std::abs(c1[p] - ck[u]))
                              : N::add(a[u], std::abs(ak - ck[u]));
        if constexpr (check_window)
          if (level == 0 && in_window(i, g.index[q0 + u], w)) v = infinity;  // never survives
        a[u] = v;
        out[n] = v;
        const bool keep = v < t;
        n += keep && level >= first;
        alive += keep;
      }
      s.count(level) = n;
      if (alive == 0) break;
    }
  }
}


#if defined(__x86_64__) && defined(__GNUC__)
// For each 4-lane comparison mask, the permutation that moves the kept lanes to the front (AVX2
// has no compress instruction).
struct CompressTable {
  alignas(32) std::int32_t index[16][8];
};
constexpr CompressTable make_compress_table() {
  CompressTable table{};
  for (int mask = 0; mask < 16; ++mask) {
    int out = 0;
    for (int lane = 0; lane < 4; ++lane)
      if (mask & (1 << lane)) {
        table.index[mask][2 * out] = 2 * lane;
        table.index[mask][2 * out + 1] = 2 * lane + 1;
        ++out;
      }
  }
  return table;
}
constexpr CompressTable compress_table = make_compress_table();

// The loops the vector scans share: blocks of candidates, and in each block the levels (one more
// coordinate each) until no candidate of the block survives. `pass(q0, len, level, out, n, store)`
// filters one level of the block [q0, q0 + len), `width` candidates at a time, appends the
// survivors to `out` from position n, advances n by their number where the level is stored, and
// returns that number. Returns where the candidates that fill whole vectors end; the caller scans
// the rest. (The passes carry the target attributes; a lambda would not.)
template <std::size_t width, class Pass>
std::size_t scan_vector_blocks(std::size_t qb, std::size_t qe, Survivors& s, Pass& pass) {
  const std::size_t levels = s.levels(), first = s.first_stored();
  const std::size_t vector_end = qb + (qe - qb) / width * width;
  for (std::size_t q0 = qb; q0 < vector_end; q0 += Survivors::block) {
    const std::size_t len = std::min(Survivors::block, vector_end - q0);
    s.make_room();
    for (std::size_t level = 0; level < levels; ++level)
      if (pass(q0, len, level, s.buffer(level), s.count(level), level >= first) == 0) break;
  }
  return vector_end;
}

// Four candidates at a time with AVX2. The operations are the scalar ones lane by lane (subtract,
// absolute value, max or multiply-then-add without fusing: AVX2 alone does not enable FMA), so the
// accumulators are bit-identical. Survivors are packed with a permutation chosen by the mask.
template <class N>
struct Avx2Pass {
  Avx2Pass(const PointLayout& layout, std::size_t point, double threshold)
      : c0(layout.coordinate(0)), g(layout), p(point), t(threshold) {}
  const double* c0;  // coordinate 0 of every position
  const PointLayout& g;
  std::size_t p;
  double t;
  alignas(32) double a[Survivors::block];  // the block's accumulators, written at level 0 before any read

  __attribute__((target("avx2,popcnt"))) std::size_t operator()(std::size_t q0, std::size_t len, std::size_t level,
                                                                 double* out, std::size_t& count, bool store) {
    const __m256d sign = _mm256_set1_pd(-0.0), tv = _mm256_set1_pd(t), a0 = _mm256_set1_pd(c0[p]);
    const double* ck = g.coordinate(level + 1) + q0;
    const __m256d ak = _mm256_set1_pd(g.coordinate(level + 1)[p]);
    std::size_t n = count, alive = 0;
    for (std::size_t u = 0; u < len; u += 4) {
      const __m256d dk = _mm256_andnot_pd(sign, _mm256_sub_pd(ak, _mm256_loadu_pd(ck + u)));
      __m256d v;
      if (level == 0) {
        const __m256d d0 = _mm256_andnot_pd(sign, _mm256_sub_pd(a0, _mm256_loadu_pd(c0 + q0 + u)));
        if constexpr (std::is_same_v<N, MaxNorm>)
          v = _mm256_max_pd(d0, dk);
        else
          v = _mm256_add_pd(_mm256_mul_pd(d0, d0), _mm256_mul_pd(dk, dk));
      } else {
        const __m256d prev = _mm256_load_pd(a + u);
        if constexpr (std::is_same_v<N, MaxNorm>)
          v = _mm256_max_pd(prev, dk);
        else
          v = _mm256_add_pd(prev, _mm256_mul_pd(dk, dk));
      }
      _mm256_store_pd(a + u, v);
      const int mask = _mm256_movemask_pd(_mm256_cmp_pd(v, tv, _CMP_LT_OQ));
      const __m256i perm = _mm256_load_si256(reinterpret_cast<const __m256i*>(compress_table.index[mask]));
      _mm256_storeu_ps(reinterpret_cast<float*>(out + n), _mm256_permutevar8x32_ps(_mm256_castpd_ps(v), perm));
      const auto k = static_cast<std::size_t>(__builtin_popcount(static_cast<unsigned>(mask)));
      n += store ? k : 0;
      alive += k;
    }
    count = n;
    return alive;
  }
};

template <class N>
void scan_avx2(const Problem& pb, const PointLayout& g, std::size_t p, std::size_t qb, std::size_t qe, Survivors& s,
               double t) {
  Avx2Pass<N> pass(g, p, t);
  const std::size_t vector_end = scan_vector_blocks<4>(qb, qe, s, pass);
  if (vector_end < qe) scan_scalar<N, false>(pb, g, p, vector_end, qe, s, t);
}

// Eight candidates at a time with AVX-512, for the maximum norm only: its lanes take max and
// absolute value, which no compiler contracts, while the Euclidean sum of products could be fused
// into FMA under this target and change the accumulators' last bits. Survivors are packed with the
// compress instruction (into a register, then stored: the memory form is slow on some processors).
__attribute__((target("avx512f"), always_inline)) inline __m512d abs512(__m512d x) {
  return _mm512_castsi512_pd(_mm512_and_si512(_mm512_castpd_si512(x), _mm512_set1_epi64(0x7fffffffffffffff)));
}
struct Avx512MaxPass {
  Avx512MaxPass(const PointLayout& layout, std::size_t point, double threshold)
      : c0(layout.coordinate(0)), g(layout), p(point), t(threshold) {}
  const double* c0;
  const PointLayout& g;
  std::size_t p;
  double t;
  alignas(64) double a[Survivors::block];

  __attribute__((target("avx512f,popcnt"))) std::size_t operator()(std::size_t q0, std::size_t len, std::size_t level,
                                                                   double* out, std::size_t& count, bool store) {
    const __m512d tv = _mm512_set1_pd(t), a0 = _mm512_set1_pd(c0[p]);
    const double* ck = g.coordinate(level + 1) + q0;
    const __m512d ak = _mm512_set1_pd(g.coordinate(level + 1)[p]);
    std::size_t n = count, alive = 0;
    for (std::size_t u = 0; u < len; u += 8) {
      const __m512d dk = abs512(_mm512_sub_pd(ak, _mm512_loadu_pd(ck + u)));
      const __m512d prev = level == 0 ? abs512(_mm512_sub_pd(a0, _mm512_loadu_pd(c0 + q0 + u))) : _mm512_load_pd(a + u);
      const __m512d v = _mm512_maskz_max_pd(0xff, prev, dk);  // maskz: GCC 12's unmasked form warns of an undefined operand
      _mm512_store_pd(a + u, v);
      const __mmask8 mask = _mm512_cmp_pd_mask(v, tv, _CMP_LT_OQ);
      _mm512_storeu_pd(out + n, _mm512_maskz_compress_pd(mask, v));
      const auto k = static_cast<std::size_t>(__builtin_popcount(static_cast<unsigned>(mask)));
      n += store ? k : 0;
      alive += k;
    }
    count = n;
    return alive;
  }
};

void scan_avx512_max(const Problem& pb, const PointLayout& g, std::size_t p, std::size_t qb, std::size_t qe, Survivors& s,
                     double t) {
  Avx512MaxPass pass(g, p, t);
  const std::size_t vector_end = scan_vector_blocks<8>(qb, qe, s, pass);
  if (vector_end < qe) scan_avx2<MaxNorm>(pb, g, p, vector_end, qe, s, t);  // fewer than 8 left
}

#endif

}  // namespace

#if defined(__x86_64__) && defined(__GNUC__)
Simd simd_level() {
  static const bool avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("popcnt");
  static const bool avx512 = avx2 && __builtin_cpu_supports("avx512f");
  if (!avx2 || env_flag("CHAOS_NO_SIMD")) return Simd::none;
  return avx512 && !env_flag("CHAOS_NO_AVX512") ? Simd::avx512 : Simd::avx2;
}
#else
Simd simd_level() { return Simd::none; }
#endif

template <class N, bool check_window>
void scan_candidates(const Problem& pb, const PointLayout& g, std::size_t p, std::size_t qb, std::size_t qe, Survivors& s,
                     Simd simd, double t) {
#if defined(__x86_64__) && defined(__GNUC__)
  if (!check_window && simd == Simd::avx512 && std::is_same_v<N, MaxNorm>) return scan_avx512_max(pb, g, p, qb, qe, s, t);
  if (!check_window && simd != Simd::none) return scan_avx2<N>(pb, g, p, qb, qe, s, t);
#endif
  (void)simd;
  scan_scalar<N, check_window>(pb, g, p, qb, qe, s, t);
}

template void scan_candidates<MaxNorm, false>(const Problem&, const PointLayout&, std::size_t, std::size_t, std::size_t,
                                              Survivors&, Simd, double);
template void scan_candidates<MaxNorm, true>(const Problem&, const PointLayout&, std::size_t, std::size_t, std::size_t,
                                             Survivors&, Simd, double);
template void scan_candidates<EuclideanNorm, false>(const Problem&, const PointLayout&, std::size_t, std::size_t,
                                                    std::size_t, Survivors&, Simd, double);
template void scan_candidates<EuclideanNorm, true>(const Problem&, const PointLayout&, std::size_t, std::size_t,
                                                   std::size_t, Survivors&, Simd, double);

}  // namespace chaos::correlation_detail
