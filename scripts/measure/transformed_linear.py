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
Needs numpy and scipy. Seeds 1 .. K (default 5); lengths 5000 and 20000. The Lorenz record and the
parsing of `chaos analyze` are outside_records.py's.
"""

import numpy as np

from outside_records import analyze_lines, answer, command_line, record, run_parallel

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


def make(task):
    kind, n, seed = task
    if kind == "ar2_atan":
        return ar_through_atan(n, seed), None
    return record("lorenz", n, seed) ** 2, 0.01  # the laser-like intensity


def analyze(chaos, path, dt):
    lines = analyze_lines(chaos, path, dt)
    d2_value, _, _, d2_status = answer(lines.get("correlation_dimension", "missing"))
    return {
        "determinism": lines.get("determinism", "missing").split(":")[0],
        "nonlinearity": lines.get("nonlinearity", "missing").split(" (")[0].split(":")[0].replace(" ", "_"),
        "d2": d2_value,
        "d2_status": d2_status,
        "lambda_status": answer(lines.get("largest_lyapunov_exponent", "missing"))[3],
    }


def main():
    chaos, seeds, jobs = command_line(__doc__, 5)
    tasks = [(kind, n, seed) for kind in ("ar2_atan", "laser") for n in LENGTHS for seed in range(1, seeds + 1)]
    results = run_parallel(tasks, make, lambda path, dt: analyze(chaos, path, dt), jobs, "transformed-")
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
