#!/usr/bin/env python3
"""How many of its own correlation times a non-stationary record seems to hold.

The automatic choices refuse a record shorter than 50 of its own correlation times (the autocorrelation's
1/e time, chaos/time_scales.hpp), the mark of a random walk, a drift or 1/f^2 noise. This prints, for random
walks (cumulative Gaussian steps) and 1/f^2 noise (amplitudes 1/f, random phases) of several lengths, the
largest, the 99th percentile and the median N / (1/e time) over SEEDS seeds (300 by default: the threshold is
about the tail, which 20 seeds do not reach), and how many seeds reach 30, 40 and 50, the 1/e time read by
`chaos autocorrelation` with the lags the automatic choices examine (min(N/4, 5000)); 0 where the
autocorrelation stays above 1/e over them.

Usage: scripts/measure/stationarity_threshold.py CHAOS_BINARY [SEEDS]
Needs numpy.
"""
import os
import subprocess
import sys
import tempfile

import numpy as np


def correlation_times(chaos, x, path):
    n = len(x)
    np.savetxt(path, x, fmt="%.10g")
    out = subprocess.run([chaos, "autocorrelation", path, "-D", str(max(1, min(n // 4, 5000)))],
                         capture_output=True, text=True).stdout
    for line in out.splitlines():
        if line.startswith("# decorrelation_time"):
            value = line.split("=")[1].strip()
            return n / float(value) if value[0].isdigit() else 0.0
    raise RuntimeError("no 1/e time in the output of chaos autocorrelation")


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    chaos = sys.argv[1]
    seeds = int(sys.argv[2]) if len(sys.argv) > 2 else 300
    with tempfile.TemporaryDirectory() as work:
        path = os.path.join(work, "series.txt")
        print("series\tN\tseeds\tlargest N / (1/e time)\t99th percentile\tmedian\tseeds >= 30 / 40 / 50")
        for kind in ("random walk", "1/f^2 noise"):
            for n in (1000, 5000, 20000, 100000):
                ratios = []
                for seed in range(1, seeds + 1):
                    rng = np.random.default_rng(seed)
                    if kind == "random walk":
                        x = np.cumsum(rng.standard_normal(n))
                    else:
                        f = np.fft.rfftfreq(n)
                        amplitude = np.zeros_like(f)
                        amplitude[1:] = 1 / f[1:]
                        x = np.fft.irfft(amplitude * (rng.standard_normal(len(f)) + 1j * rng.standard_normal(len(f))), n)
                    ratios.append(correlation_times(chaos, x, path))
                r = np.array(ratios)
                reached = " / ".join(str(int((r >= t).sum())) for t in (30, 40, 50))
                print(f"{kind}\t{n}\t{seeds}\t{r.max():.1f}\t{np.quantile(r, 0.99):.1f}\t{np.median(r):.1f}\t{reached}",
                      flush=True)


if __name__ == "__main__":
    main()
