#!/usr/bin/env python3
"""The D2 projection check measured on the zoo (docs/reference/correlation_dimension.md, step 3).

For every chaotic system of docs/validation/zoo.md that gets a delay and a dimension: the automatic rows at
N = 10^4 and 10^5 (with the halves check), the grid m = Cao..Cao+3 with w = 1..3 autocorrelation
times at N = 10^4 and w = 1 at N = 10^5 (without halves), each with radii range/1000..range/4 as the
pipeline takes them. For each saturated row: the largest relative excess of a lower dimension's mean
local slope over the shared plateau, every lower dimension counted (so it bounds the rule, which
counts only m >= 2 D2 + 1), and that dimension. The check itself is off here, so that every row that
would saturate without it is seen.

Output, one row per case: system, N, tau, m, w, automatic, status, D2, plateau low, plateau high,
excess, steepest lower m. A summary goes to standard error.

Usage: python scripts/measure/measure_projection_check.py [--zoo docs/validation/zoo.md] [--part K --parts P] > rows.tsv
Run it with the package on PYTHONPATH, from outside the checkout's root (or the chaos/ folder shadows
the package). Parts split the rows for parallel runs (about 40 minutes on 2 cores with --parts 2).
"""
import argparse
import math
import re
import sys

import numpy as np

import chaos


def automatic_rows(zoo_md):
    rows = []
    for line in open(zoo_md):
        m = re.match(r"^\| ([a-z0-9_]+) \| (\d+) \| (\d+) \| (\d+) \| (\d+) \|", line)
        if m and int(m.group(4)) > 0:
            rows.append((m.group(1), int(m.group(2)), int(m.group(3)), int(m.group(4)), int(m.group(5))))
    return rows


def steepest_lower(r):
    """(excess, m) over every dimension below the saturating ones, or None."""
    lo, hi = r["scaling_region"]
    radius = np.asarray(r["radius"])
    inside = [k for k in range(len(radius)) if lo * (1 - 1e-12) <= radius[k] <= hi * (1 + 1e-12)]
    dims = list(r["dimension"])
    lowest_saturating = max(dims) - 2  # the three highest dimensions saturate
    plateau = r["plateaus"][0]["slope"]
    best = None
    for i, m in enumerate(dims):
        if m >= lowest_saturating:
            break
        slopes = [r["local_slope"][i][k] for k in inside]
        slopes = [s for s in slopes if s is not None and not math.isnan(s)]
        if 2 * len(slopes) < len(inside) or not slopes:
            continue
        excess = (float(np.mean(slopes)) - plateau) / plateau
        if best is None or excess > best[0]:
            best = (excess, m)
    return best


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--zoo", default="docs/validation/zoo.md")
    ap.add_argument("--part", type=int, default=0)
    ap.add_argument("--parts", type=int, default=1)
    a = ap.parse_args()
    work = []
    for system, n, tau, m, w in automatic_rows(a.zoo):
        for mm in range(m, m + 4):
            for ww in (w, 2 * w, 3 * w) if n <= 10000 else (w,):
                work.append((system, n, tau, mm, ww, mm == m and ww == w))
    work = work[a.part::a.parts]
    series, excesses = {}, []
    for system, n, tau, m, w, auto in work:
        if system not in series:
            series[system] = np.asarray(chaos.zoo_series(system)["x"])
        x = series[system][:n]
        span = float(x.max() - x.min())
        r = chaos.d2(x, delay=tau, max_dimension=m + 3, theiler=w, min_radius=span / 1000, max_radius=span / 4,
                     radii=40, halves=auto, projection_tolerance=math.inf)
        fields = [system, n, tau, m, w, auto, r["status"]]
        if r["status"] == "saturated":
            lo, hi = r["scaling_region"]
            best = steepest_lower(r)
            fields += [r["d2"], lo, hi] + (list(best) if best else ["", ""])
            if best:
                excesses.append(best[0])
        print(*fields, sep="\t", flush=True)
    if excesses:
        e = sorted(excesses)
        q = lambda p: e[min(len(e) - 1, int(p * len(e)))]
        print(f"{len(work)} rows, {len(e)} saturated with a lower dimension: excess median {q(0.5):.3f}, "
              f"90% {q(0.9):.3f}, 99% {q(0.99):.3f}, max {e[-1]:.3f}; above 0.05: {sum(v > 0.05 for v in e)}, "
              f"above 0.1: {sum(v > 0.1 for v in e)}", file=sys.stderr)


if __name__ == "__main__":
    main()
