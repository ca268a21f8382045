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
The records and the parsing of `chaos analyze` are outside_records.py's.
"""
import sys

from outside_records import analyze_lines, answer, record, run_parallel, seeds_and_jobs

# name, N, dt (None for a map), literature lambda_1, the bar's relative band
CASES = [("lorenz", 20000, 0.01, 0.9056, 0.10), ("lorenz", 100000, 0.01, 0.9056, 0.10),
         ("rossler", 20000, 0.1, 0.0714, 0.15), ("henon", 10000, None, 0.419, 0.05)]


def lambda_1(chaos, path, dt):
    lines = analyze_lines(chaos, path, dt)
    if "largest_lyapunov_exponent" not in lines:
        return None, None, None, "error: " + lines.get("error", "no lambda_1 line")
    return answer(lines["largest_lyapunov_exponent"])


def main():
    args = sys.argv[1:]
    if not args:
        sys.exit(__doc__)
    chaos = args[0]
    seeds, jobs = seeds_and_jobs(args, 12)
    tasks = [(case, seed) for case in CASES for seed in range(101, 101 + seeds)]
    results = run_parallel(tasks, lambda task: (record(task[0][0], task[0][1], task[1]), task[0][2]),
                           lambda path, dt: lambda_1(chaos, path, dt), jobs, "textbook-")
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
