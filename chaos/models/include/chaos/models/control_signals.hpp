#pragma once
// Control signals for testing the estimators: series that are NOT low-dimensional chaos (coloured
// noise, random walks), series whose dimension is known exactly (periodic: D2 = 1, quasi-periodic on
// a k-torus: D2 = k), and the corruptions real data suffer (measurement noise at a given SNR,
// quantisation). An estimator that reports a confident low dimension or a positive Lyapunov
// exponent on the first group, or anything but 1 or k on the second, is wrong. The page is
// docs/reference/control_signals.md.
//
// Conventions, as in systems.hpp: the output is a pure function of the arguments; random ones take
// an explicit seed (chaos::Random) and are bit-reproducible; every argument is checked before any
// work and a refusal is chaos::InvalidInput whose message names the function, the rule and the
// numbers. Generators return a one-component chaos::Trajectory ("x", dt = 1: time is in samples);
// the transforms (add_noise, quantise_*) take and return plain series.
//
// Short series need no function: take the first N samples of any of these.
// Surrogates of any of these (the linear-Gaussian null) come from chaos/surrogates.hpp:
// SurrogateGenerator(x, {.method = SurrogateMethod::iaaft}).generate(seed).

#include <cstddef>
#include <cstdint>
#include <numbers>
#include <span>
#include <vector>

#include "chaos/models/systems.hpp"

namespace chaos {

// ---- Noise -------------------------------------------------------------------------------------

// Gaussian power-law ("1/f^alpha") noise by spectral shaping (Timmer & König 1995, A&A 300:707):
// for the Fourier frequencies f_k = k / n, k = 1 .. floor(n/2), draw Re X_k and Im X_k independent
// N(0, 1) and scale both by f_k^(-alpha/2), so E|X_k|^2 is proportional to f_k^(-alpha); X_0 = 0
// (zero mean) and, for even n, Im X_{n/2} = 0 (the Nyquist bin of a real series is real). The
// series is the inverse real FFT (FFTW c2r, FFTW_ESTIMATE), then shifted and scaled to sample mean
// 0 and sample variance 1 (divided by n).
// alpha = 0 is white, 1 is pink ("flicker"), 2 is red/Brownian-like noise; any finite alpha >= 0.
// Because no longer series is drawn and cut (T&K's remedy for red-noise leakage), the output is
// one period of a periodic process: its periodogram at the Fourier frequencies is exactly
// C f_k^(-alpha) E_k with E_k i.i.d. Exp(1) (chi-square with 2 degrees of freedom over 2), so the
// OLS slope of log periodogram against log f is -alpha with standard error
// sqrt((pi^2/6) / sum_k (ln f_k - mean)^2), about sqrt(1.645 / (n/2)). Draws: for k = 1, 2, ...
// Re then Im from Random(seed).gaussian(), both drawn even where Im is then set to 0.
// Refuses n < 2, n > 2^31 - 1 (FFTW's int sizes) and alpha not finite or < 0.
Trajectory power_law_noise(std::size_t n, double alpha, std::uint64_t seed = 1);

// Random walk (discrete Brownian motion): x_0 = 0, x_t = x_{t-1} + e_t, e_t ~ N(0, 1) i.i.d. from
// Random(seed).gaussian() in order (e_1 is the first draw). Non-stationary: Var x_t = t. Its
// periodogram falls as f^-2, like power_law_noise(n, 2) but without the wrap-around. Coloured noise of
// this kind gives a finite, spurious D2 (Osborne & Provenzale 1989, Physica D 35:357).
// Refuses n = 0.
Trajectory random_walk(std::size_t n, std::uint64_t seed = 1);

// ---- Periodic and quasi-periodic ---------------------------------------------------------------

// A period of exactly numerator / denominator samples (p / q). It is reduced by g = gcd(p, q)
// before use, so {634, 6} is the same period as {317, 3}.
struct RationalPeriod {
  std::uint64_t numerator = 25;
  std::uint64_t denominator = 1;
};

// x_n = sum_{h=1}^{H} a_h sin(2 pi h n / P), n = 0 .. count - 1, with a = `amplitudes` (a_1 first;
// the default {1} is the pure sine sin(2 pi n / P)). Pass e.g. {1, 0.5} so that the delay-embedded
// orbit is not a pure ellipse.
//
// Rational P = p / q (gcd(p, q) = 1 after reduction): the phase is computed in integers,
// r_n = (n q) mod p, and each term as sin(2 pi (h r_n mod p) / p) reduced to the first quadrant in
// integers, so that:
//  - the series repeats exactly, bit for bit: x_{n+p} == x_n (and no shorter period exists,
//    because n -> n q mod p is a bijection of Z_p);
//  - the orbit has exactly p distinct phases r = 0 .. p - 1, hence exactly p distinct delay vectors
//    (x_n, x_{n+1}) once count >= p + 1 (p > 2 makes sin(2 pi q / p) != 0, which makes the pair
//    determine the phase);
//  - the number of distinct VALUES x_n is smaller than p in two documented cases, because equal
//    values come out as equal bits here (the integer reduction makes the symmetries exact):
//    (a) odd harmonics only (the pure sine included): sin(h (pi - t)) = sin(h t) pairs the phases,
//        giving p values for odd p, p/2 for p = 2 (mod 4) and p/2 + 1 for p = 0 (mod 4);
//    (b) with a nonzero even harmonic the pairing is broken and the count is p for odd p but
//        p - 1 for even p, since every sum of sines vanishes at both t = 0 and t = pi (r = 0 and
//        r = p/2); other equalities would be coincidences of the chosen amplitudes.
//    So P = 317/3 gives 317 values with or without a harmonic, P = 25 gives 25, P = 100 gives 51
//    (pure sine) or 99 (amplitudes {1, 0.5}). Delay vectors are always p.
//  These counts hold while neighbouring values stay apart in double precision (the closest pair,
//  beside the peak, differs by about pi^2 / p^2: p up to about 10^7 is safe).
// Real P (a double): r_n = fmod(n, P) / P, an exact fmod and one rounding; each term
// sin(2 pi fmod(h n, P) / P). For irrational P every sample has its own phase, so an orbit of
// `count` samples has `count` distinct values (no exact repetition). A whole-number P (e.g. 25.0,
// up to 2^53) is handed to the rational overload as {P, 1}, so it repeats exactly too.
//
// Refuses count = 0; P <= 2 (at P = 2 the sine is sin(pi n) = 0 and 1 < P < 2 is the alias of
// the period P / (P - 1) > 2); p or q = 0 or above 2^53; a non-finite P; an empty list of
// amplitudes, a non-finite amplitude or all of them zero; a nonzero a_h at or above the Nyquist
// frequency (2 h >= P: it would alias to a lower harmonic).
Trajectory periodic(std::size_t count, RationalPeriod period, const std::vector<double>& amplitudes = {1.0});
Trajectory periodic(std::size_t count, double period, const std::vector<double>& amplitudes = {1.0});

// x_n = sum_j sin(2 pi n / P_j) with unit amplitudes, each term as in the real-P `periodic`. When
// 1, 1/P_1, ..., 1/P_k are rationally independent the sampled phases fill the k-torus densely
// (Weyl) and D2 = k; the caller is responsible for that choice (it cannot be checked in floating
// point). Refuses count = 0, no periods, and a period not finite or <= 2.
Trajectory quasi_periodic_signal(std::size_t count, std::span<const double> periods);

// The same with the first period an exact rational p / q, computed in integers as in `periodic`.
// With such a first tone the sampled orbit is NOT dense on the 2-torus: the first phase takes only
// p values, so the points lie on p closed curves (circles of the second phase). At scales above
// their spacing the correlation sum sees a 2-torus (D2 ~ 2), below it p separate curves (D2 -> 1);
// an automatic scaling region must not straddle the crossover. Refuses as above.
Trajectory quasi_periodic_signal(std::size_t count, RationalPeriod first, std::span<const double> other_periods);

// Documented choices (periods in samples). With P_1 = 10 pi, f_j = 1 / P_j = c (1, phi, sqrt 2),
// c = 1 / (10 pi), phi the golden mean (1 + sqrt 5) / 2: 1, f_1, f_2, f_3 are rationally
// independent (a + c (b + b' phi + b'' sqrt 2) = 0 with rational coefficients forces a = 0, because
// pi is transcendental, then b = b' = b'' = 0, because 1, sqrt 5, sqrt 2 are independent).
inline constexpr double torus_period_1 = 10.0 * std::numbers::pi;                        // 31.4159...
inline constexpr double torus_period_2 = 10.0 * std::numbers::pi / std::numbers::phi;    // 19.4161...
inline constexpr double torus_period_3 = 10.0 * std::numbers::pi / std::numbers::sqrt2;  // 22.2144...

// Two incommensurate frequencies: periods 10 pi and 10 pi / phi samples. D2 = 2.
Trajectory two_torus(std::size_t count);
// Three: periods 10 pi, 10 pi / phi and 10 pi / sqrt 2 samples. D2 = 3.
Trajectory three_torus(std::size_t count);
// two_torus with its first period replaced by the exact rational `first` (default 25 samples); the
// second stays 10 pi / phi. See the rational quasi_periodic_signal for what that does to D2.
Trajectory two_torus_rational_first(std::size_t count, RationalPeriod first = {25, 1});

// ---- Corruptions of a clean series --------------------------------------------------------------

// Additive white Gaussian measurement noise at a signal-to-noise ratio of `snr_db` decibels:
// y_t = x_t + sigma e_t, sigma = std(x) / 10^(snr_db / 20), std the population standard deviation
// (divided by N), e_t ~ N(0, 1) from Random(seed).gaussian() in order. The realised SNR,
// 20 log10(std(x) / std(y - x)), scatters about snr_db with a standard deviation of about
// 8.69 / sqrt(2 N) dB. Any finite snr_db (negative: more noise than signal).
// Refuses an empty series (empty), non-finite samples (non_finite), a constant series (constant: the
// SNR is undefined) and a non-finite snr_db.
std::vector<double> add_noise(std::span<const double> x, double snr_db, std::uint64_t seed = 1);

// Rounding to `levels` equally spaced values spanning the series' range (a mid-tread quantiser
// whose end levels are the minimum and the maximum): Delta = (max - min) / (levels - 1),
// y_t = min + k_t Delta, k_t = round((x_t - min) / Delta) in 0 .. levels - 1 (std::round, halves
// away from zero). The output has at most `levels` distinct values, exactly `levels` when every
// level is hit. Refuses empty, non-finite and constant series and levels < 2.
std::vector<double> quantise_levels(std::span<const double> x, std::size_t levels);

// Rounding to a grid of spacing `step` through 0, as a fixed-resolution instrument records:
// y_t = step * round(x_t / step). Refuses empty and non-finite series, a step not finite or <= 0,
// and a step so small that x_t / step is not finite.
std::vector<double> quantise_step(std::span<const double> x, double step);

}  // namespace chaos
