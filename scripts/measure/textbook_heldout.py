#!/usr/bin/env python3
"""The textbook lambda_1 cases on records made outside the project.

`chaos analyze FILE` with its defaults (and --dt for flows) on records that `chaos generate` did not
make: Lorenz x (sigma 10, rho 28, beta 8/3; dt 0.01; 100 time units dropped) and Roessler x (a = b = 0.2,
c = 5.7; dt 0.1; 1000 time units dropped) integrated by scipy's solve_ivp (DOP853, rtol = atol = 1e-10)
from random starts, and Henon x (a 1.4, b 0.3; 1000 iterations dropped) iterated in numpy. Each
record's lambda_1 answer is judged as the answers bar judges the project's own series: confident and
within 10% (Lorenz), 15% (Roessler) or 5% (Henon) of the literature value (Sprott, Chaos and Time-Series
Analysis, 2003: 0.9056, 0.0714, 0.419), and, for confident and rough answers, whether the interval
holds it.

Usage: scripts/measure/textbook_heldout.py CHAOS_BINARY [--seeds K] [--jobs J]
Needs numpy and scipy (Debian: python3-numpy, python3-scipy). Seeds 101 .. 100 + K (default 12).
"""
import os
import shutil
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor

import numpy as np
from scipy.integrate import solve_ivp

# name, N, dt (None for a map), literature lambda_1, the bar's relative band
CASES = [("lorenz", 20000, 0.01, 0.9056, 0.10), ("lorenz", 100000, 0.01, 0.9056, 0.10),
         ("rossler", 20000, 0.1, 0.0714, 0.15), ("henon", 10000, None, 0.419, 0.05)]


def record(name, n, seed):
    rng = np.random.default_rng(seed)
    if name == "henon":
        x, y = rng.uniform(-0.1, 0.1, 2)
        for _ in range(1000):
            x, y = 1 - 1.4 * x * x + y, 0.3 * x
        out = np.empty(n)
        for k in range(n):
            x, y = 1 - 1.4 * x * x + y, 0.3 * x
            out[k] = x
        return out
    if name == "lorenz":
        def f(t, s):
            return [10 * (s[1] - s[0]), s[0] * (28 - s[2]) - s[1], s[0] * s[1] - 8 / 3 * s[2]]
        dt, drop, start = 0.01, 100.0, rng.uniform(-10, 10, 3) + [0, 0, 20]
    else:
        def f(t, s):
            return [-s[1] - s[2], s[0] + 0.2 * s[1], 0.2 + s[2] * (s[0] - 5.7)]
        dt, drop, start = 0.1, 1000.0, np.append(rng.uniform(-5, 5, 2), 0.1)
    t = drop + dt * np.arange(n)
    return solve_ivp(f, (0, t[-1]), start, method="DOP853", rtol=1e-10, atol=1e-10, t_eval=t).y[0]


def answer(chaos, path, dt):
    cmd = [chaos, "analyze", path, "-q"] + (["--dt", str(dt)] if dt else [])
    done = subprocess.run(cmd, capture_output=True, text=True)
    for line in done.stdout.splitlines():
        if line.startswith("largest_lyapunov_exponent\t"):
            field = line.split("\t")[1]  # "V in [L, H] per ... (status)" or "none (none)"
            status = field[field.rfind("(") + 1:field.rfind(")")]
            if " in [" not in field:
                return None, None, None, status
            value = float(field.split(" in [")[0])
            low, high = (float(v) for v in field.split(" in [")[1].split("]")[0].split(","))
            return value, low, high, status
    return None, None, None, "error: " + done.stderr.strip()[:120]


def main():
    args = sys.argv[1:]
    if not args:
        sys.exit(__doc__)
    chaos, seeds, jobs = args[0], 12, 2
    if "--seeds" in args:
        seeds = int(args[args.index("--seeds") + 1])
    if "--jobs" in args:
        jobs = int(args[args.index("--jobs") + 1])
    work = tempfile.mkdtemp(prefix="textbook-")

    def one(task):
        (name, n, dt, reference, band), seed = task
        path = os.path.join(work, f"{name}-{n}-{seed}.txt")
        np.savetxt(path, record(name, n, seed), fmt="%.17g")
        return task, answer(chaos, path, dt)

    tasks = [(case, seed) for case in CASES for seed in range(101, 101 + seeds)]
    with ThreadPoolExecutor(jobs) as pool:
        results = list(pool.map(one, tasks))
    shutil.rmtree(work)
    print("system\tN\tseed\tlambda_1\tlow\thigh\tstatus\tconfident within the band")
    tally = {}
    for ((name, n, dt, reference, band), seed), (value, low, high, status) in results:
        sharp = status == "confident" and abs(value - reference) <= band * reference
        holds = value is not None and low <= reference <= high
        t = tally.setdefault((name, n), [0, 0, 0, 0])
        t[0] += 1
        t[1] += sharp
        t[2] += value is not None
        t[3] += holds
        fmt = lambda v: "-" if v is None else f"{v:.4g}"
        print(f"{name}\t{n}\t{seed}\t{fmt(value)}\t{fmt(low)}\t{fmt(high)}\t{status}\t{'yes' if sharp else 'no'}")
    for (name, n, dt, reference, band) in CASES:
        records, sharp, answered, holds = tally[(name, n)]
        print(f"# {name} N = {n}: {records} records; confident within {band:.0%} of {reference}: {sharp}; "
              f"the interval holds it in {holds} of {answered} answers")


if __name__ == "__main__":
    main()
