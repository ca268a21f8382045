#!/usr/bin/env python3
"""The textbook lambda_1 cases, and their D2, on records made outside the project.

`chaos analyze FILE` with its defaults (and --dt for flows) on records that `chaos generate` did not
make: Lorenz x (sigma 10, rho 28, beta 8/3; dt 0.01; 100 time units dropped) and Roessler x (a = b = 0.2,
c = 5.7; dt 0.1; 1000 time units dropped) integrated by scipy's solve_ivp (DOP853, rtol = atol = 1e-10)
from random starts, and Henon x (a 1.4, b 0.3; 1000 iterations dropped) iterated in numpy. Each
record's lambda_1 answer is judged as the answers bar judges the project's own series: confident and
within 10% (Lorenz), 15% (Roessler) or 5% (Henon) of the literature value (Sprott, Chaos and Time-Series
Analysis, 2003: 0.9056, 0.0714, 0.419), and, for confident and rough answers, whether the interval
holds it.

The same runs' D2 answers are judged as the zoo judges D2: against the attractor's own D2 at the same N and
scales, the plateau of the full state's correlation sums from the equations (docs/validation/zoo.md,
"D2 of the state"). A record of 10^4 or 10^5 samples gets the zoo's band at that N (the state's interval
+-0.1); a record of 2*10^4, between the zoo's two lengths, the union of both bands and of both states'
intervals. A D2 is confident within the band, and, for confident and rough answers, the interval meets
the state's interval (the reference is an interval itself).

Usage: scripts/measure/textbook_heldout.py CHAOS_BINARY [--seeds K] [--jobs J]
Needs numpy and scipy (Debian: python3-numpy, python3-scipy). Seeds 101 .. 100 + K (default 12).
The records and the parsing of `chaos analyze` are outside_records.py's.
"""

from outside_records import analyze_lines, answer, command_line, record, run_parallel

# name, N, dt (None for a map), literature lambda_1, the bar's relative band
CASES = [("lorenz", 20000, 0.01, 0.9056, 0.10), ("lorenz", 100000, 0.01, 0.9056, 0.10),
         ("rossler", 20000, 0.1, 0.0714, 0.15), ("henon", 10000, None, 0.419, 0.05)]


# D2: (name, N) -> the zoo's band and the state's own interval (docs/validation/zoo.md, the rows at
# N = 10^4 and 10^5; at 2*10^4 the union of the two lengths' bands and intervals).
D2_REFERENCE = {("lorenz", 20000): ((1.86, 2.28), (1.96, 2.18)), ("lorenz", 100000): ((1.86, 2.18), (1.96, 2.08)),
                ("rossler", 20000): ((1.67, 2.05), (1.77, 1.95)), ("henon", 10000): ((1.06, 1.36), (1.16, 1.26))}


def answers(chaos, path, dt):
    """The lambda_1 and D2 answers of one `chaos analyze` run, each (value, low, high, status)."""
    lines = analyze_lines(chaos, path, dt)
    out = []
    for field in ("largest_lyapunov_exponent", "correlation_dimension"):
        if field not in lines:
            out.append((None, None, None, "error: " + lines.get("error", "no " + field + " line")))
        else:
            out.append(answer(lines[field]))
    return out


def main():
    chaos, seeds, jobs = command_line(__doc__, 12)
    tasks = [(case, seed) for case in CASES for seed in range(101, 101 + seeds)]
    results = run_parallel(tasks, lambda task: (record(task[0][0], task[0][1], task[1]), task[0][2]),
                           lambda path, dt: answers(chaos, path, dt), jobs, "textbook-")
    fmt = lambda v: "-" if v is None else f"{v:.4g}"
    print("system\tN\tseed\tlambda_1\tlow\thigh\tstatus\tconfident within the band")
    tally = {}
    for ((name, n, dt, reference, band), seed), ((value, low, high, status), _) in results:
        sharp = status == "confident" and abs(value - reference) <= band * reference
        holds = value is not None and low <= reference <= high
        t = tally.setdefault((name, n), [0, 0, 0, 0])
        t[0] += 1
        t[1] += sharp
        t[2] += value is not None
        t[3] += holds
        print(f"{name}\t{n}\t{seed}\t{fmt(value)}\t{fmt(low)}\t{fmt(high)}\t{status}\t{'yes' if sharp else 'no'}")
    for (name, n, dt, reference, band) in CASES:
        records, sharp, answered, holds = tally[(name, n)]
        print(f"# {name} N = {n}: {records} records; confident within {band:.0%} of {reference}: {sharp}; "
              f"the interval holds it in {holds} of {answered} answers")
    print()
    print("system\tN\tseed\tD2\tlow\thigh\tstatus\tconfident within the band")
    tally = {}
    for ((name, n, dt, reference, band), seed), (_, (value, low, high, status)) in results:
        (band_low, band_high), (state_low, state_high) = D2_REFERENCE[(name, n)]
        sharp = status == "confident" and band_low <= value <= band_high
        meets = value is not None and low <= state_high and state_low <= high
        t = tally.setdefault((name, n), [0, 0, 0, 0, [], []])
        t[0] += 1
        t[1] += sharp
        t[2] += value is not None
        t[3] += meets
        if status in ("confident", "rough"):
            t[4 if status == "confident" else 5].append(value)
        print(f"{name}\t{n}\t{seed}\t{fmt(value)}\t{fmt(low)}\t{fmt(high)}\t{status}\t{'yes' if sharp else 'no'}")
    for (name, n, dt, reference, band) in CASES:
        records, sharp, answered, meets, confident, rough = tally[(name, n)]
        (band_low, band_high), (state_low, state_high) = D2_REFERENCE[(name, n)]
        span = lambda v: f"{min(v):.3f}-{max(v):.3f}" if v else "none"
        print(f"# {name} N = {n}: {records} records; D2 confident within [{band_low}, {band_high}]: {sharp} "
              f"(confident {span(confident)}, rough {span(rough)}); the interval meets the state's "
              f"[{state_low}, {state_high}] in {meets} of {answered} answers")


if __name__ == "__main__":
    main()
