#!/usr/bin/env python3
"""The determinism line of `chaos analyze` on a transformed linear process and on a laser-like chaos.

Two kinds of record, each through `chaos analyze FILE` with its defaults:
  - a linear stochastic oscillation seen through a saturating static nonlinearity: an AR(2) process
    with poles at radius 0.98 and period 40 samples, driven by Gaussian noise (1000 samples dropped),
    observed as atan(x / 80). Expected: not called deterministic (Cao's E2 departs from 1, but its
    IAAFT surrogates share its spectrum and amplitude distribution), and no confident D2 or lambda_1.
  - a chaotic laser-like intensity: the single-mode laser equations are the Lorenz equations (Haken,
    Phys. Lett. A 53, 1975), a far-infrared NH3 laser follows them (Weiss et al., Appl. Phys. B 61,
    1995; the Santa Fe data set A came from such a laser), and a detector sees the intensity, the
    square of the field. So x^2 of Lorenz (sigma 10, rho 28, beta 8/3; dt 0.01; 100 time units
    dropped; scipy solve_ivp, DOP853, tolerances 1e-10, random starts). Expected: deterministic,
    linearity rejected, and a D2 in the zoo's band for Lorenz at these scales, [1.86, 2.18] (within
    0.1 of the interval of the state's own D2, docs/validation/zoo-automatic.md; x -> x^2 is smooth
    and two-to-one, which keeps D2).

Usage: scripts/measure/transformed_linear.py CHAOS_BINARY [--seeds K] [--jobs J]
Needs numpy and scipy. Seeds 1 .. K (default 5); lengths 5000 and 20000.
"""
import os
import shutil
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor

import numpy as np
from scipy.integrate import solve_ivp

LENGTHS = (5000, 20000)
D2_BAND = (1.86, 2.18)


def ar_through_atan(n, seed):
    rng = np.random.default_rng(seed)
    a1, a2 = 2 * 0.98 * np.cos(2 * np.pi / 40), -0.98 ** 2
    e = rng.standard_normal(n + 1000)
    x = np.zeros(n + 1000)
    for t in range(2, n + 1000):
        x[t] = a1 * x[t - 1] + a2 * x[t - 2] + e[t]
    return np.arctan(x[1000:] / 80)


def laser_intensity(n, seed):
    rng = np.random.default_rng(seed)

    def f(t, s):
        return [10 * (s[1] - s[0]), s[0] * (28 - s[2]) - s[1], s[0] * s[1] - 8 / 3 * s[2]]
    t = 100.0 + 0.01 * np.arange(n)
    start = rng.uniform(-10, 10, 3) + [0, 0, 20]
    return solve_ivp(f, (0, t[-1]), start, method="DOP853", rtol=1e-10, atol=1e-10, t_eval=t).y[0] ** 2


def analyze(chaos, path, dt):
    cmd = [chaos, "analyze", path, "-q"] + (["--dt", str(dt)] if dt else [])
    out = subprocess.run(cmd, capture_output=True, text=True).stdout
    lines = {line.split("\t")[0]: line.split("\t")[1] for line in out.splitlines() if "\t" in line}

    def status(field):  # "V in [L, H] ... (status)", "none (none)", "not run", "rejected (...)", ...
        return field[field.rfind("(") + 1:field.rfind(")")] if "(" in field else field.split()[0]
    d2 = lines.get("correlation_dimension", "missing")
    d2_value = float(d2.split(" in [")[0]) if " in [" in d2 else None
    return {
        "determinism": lines.get("determinism", "missing").split(":")[0],
        "nonlinearity": lines.get("nonlinearity", "missing").split(" (")[0].split(":")[0].replace(" ", "_"),
        "d2": d2_value,
        "d2_status": status(d2),
        "lambda_status": status(lines.get("largest_lyapunov_exponent", "missing")),
    }


def main():
    args = sys.argv[1:]
    if not args:
        sys.exit(__doc__)
    chaos, seeds, jobs = args[0], 5, 2
    if "--seeds" in args:
        seeds = int(args[args.index("--seeds") + 1])
    if "--jobs" in args:
        jobs = int(args[args.index("--jobs") + 1])
    work = tempfile.mkdtemp(prefix="transformed-")
    tasks = [(kind, n, seed) for kind in ("ar2_atan", "laser") for n in LENGTHS for seed in range(1, seeds + 1)]

    def one(task):
        kind, n, seed = task
        x = ar_through_atan(n, seed) if kind == "ar2_atan" else laser_intensity(n, seed)
        path = os.path.join(work, f"{kind}-{n}-{seed}.txt")
        np.savetxt(path, x, fmt="%.17g")
        return task, analyze(chaos, path, None if kind == "ar2_atan" else 0.01)

    with ThreadPoolExecutor(jobs) as pool:
        results = list(pool.map(one, tasks))
    shutil.rmtree(work)
    print("series\tN\tseed\tdeterminism\tnonlinearity\tD2\tD2 status\tlambda_1 status\tas expected")
    tally = {}
    for (kind, n, seed), r in results:
        if kind == "ar2_atan":
            ok = r["determinism"] != "deterministic" and r["d2_status"] != "confident" and r["lambda_status"] != "confident"
        else:
            ok = (r["determinism"] == "deterministic" and r["nonlinearity"] == "rejected" and r["d2"] is not None
                  and D2_BAND[0] <= r["d2"] <= D2_BAND[1])
        t = tally.setdefault((kind, n), [0, 0])
        t[0] += 1
        t[1] += ok
        d2 = "-" if r["d2"] is None else f"{r['d2']:.3f}"
        print(f"{kind}\t{n}\t{seed}\t{r['determinism']}\t{r['nonlinearity']}\t{d2}\t{r['d2_status']}\t"
              f"{r['lambda_status']}\t{'yes' if ok else 'no'}")
    for (kind, n), (count, ok) in sorted(tally.items()):
        what = ("not deterministic, no confident D2 or lambda_1" if kind == "ar2_atan"
                else f"deterministic, linearity rejected, D2 in [{D2_BAND[0]}, {D2_BAND[1]}]")
        print(f"# {kind} N = {n}: {ok} of {count} records {what}")


if __name__ == "__main__":
    main()
