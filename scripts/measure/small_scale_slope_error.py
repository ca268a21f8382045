#!/usr/bin/env python3
"""How much a local slope of the correlation sum scatters at small scales, against its pair count.

D2 is the small-scale limit, so `chaos d2` weighs readings below its plateau (another plateau, the
smallest well-counted scales) against the value it reads, each by its counting error, modelled as
pair_counting_error / sqrt(pairs) (chaos/include/chaos/correlation_dimension.hpp). This measures that
error directly: Lorenz x records made outside the project (scipy, random starts, outside_records.py;
dt 0.01, N = 10^5) are independent samples of one attractor, so at one radius the spread of their
local slopes over the records is the counting error. Each record goes through `chaos d2 FILE -M 6`
with its automatic delay and Theiler window (m = 4..6 saturate on every record, as in `chaos
analyze`); the radii are the data range / 1000 to / 4 of each record, which differ by under 3%
between records, so radius k is compared across records.

--system henon does the same on Henon x records (numpy, random starts; `chaos d2 FILE -M 5`, delay 1,
m = 3..5), to see whether a map's slopes scatter as a flow's do: the library's constant was measured
on Lorenz x. --length sets N (default 10^5): shorter records count fewer pairs at the smallest radii.

Prints, per radius: the mean radius, the median pair count of the highest dimension (m = 6; Henon 5),
the mean and the standard deviation over the records of the local slope averaged over the saturating
dimensions (m = 4..6; Henon 3..5), what independent pairs would give (4 / sqrt(pairs)), and the
factor c = std * sqrt(pairs); then the root mean square of c over the small scales, the radii with at most 5*10^5 pairs, where the rule applies (above them the records'
radii, which differ by up to 3%, and the slope's change with scale add to the spread).

Usage: scripts/measure/small_scale_slope_error.py CHAOS_BINARY [--seeds K] [--jobs J] [--system lorenz|henon] [--length N]
Needs numpy and scipy. Seeds 101 .. 100 + K (default 12), the seeds of textbook_heldout.py.
"""
import json
import subprocess
import sys

import numpy as np

from outside_records import command_line, record, run_parallel

N = 100000
# The record, its sampling step, the highest dimension counted and the saturating dimensions read.
SYSTEMS = {"lorenz": ("Lorenz", 0.01, 6, (4, 5, 6)), "henon": ("Henon", None, 5, (3, 4, 5))}


def main():
    chaos, seeds, jobs = command_line(__doc__, 12)
    system = sys.argv[sys.argv.index("--system") + 1] if "--system" in sys.argv else "lorenz"
    if system not in SYSTEMS:
        sys.exit(f"--system must be one of {', '.join(SYSTEMS)} (got {system})")
    title, dt, highest, saturating = SYSTEMS[system]
    n = int(sys.argv[sys.argv.index("--length") + 1]) if "--length" in sys.argv else N
    tasks = list(range(101, 101 + seeds))

    def judge(path, dt):
        out = subprocess.run([chaos, "d2", path, "-M", str(highest), "--json", "-q"], capture_output=True, text=True)
        if out.returncode != 0:
            raise RuntimeError(out.stderr.strip())
        return json.loads(out.stdout)

    results = [d for _, d in run_parallel(tasks, lambda seed: (record(system, n, seed), dt), judge, jobs,
                                          "slope-error-")]
    dims = [results[0]["dimension"].index(m) for m in saturating]
    print(f"# {len(results)} {title} x records, N = {n}: local slope of m = {saturating[0]}..{saturating[-1]} "
          f"(mean over m) at radius k")
    print(f"k\tradius\tpairs (m = {highest})\tmean slope\tstd over records\t4 / sqrt(pairs)\tstd * sqrt(pairs)")
    small = []
    for k in range(len(results[0]["radius"])):
        slopes, pairs, radii = [], [], []
        for d in results:
            values = [d["local_slope"][i][k] for i in dims]
            if None in values:
                continue
            slopes.append(np.mean(values))
            pairs.append(d["pairs"][dims[-1]][k])
            radii.append(d["radius"][k])
        if len(slopes) < 3:
            continue
        p = float(np.median(pairs))
        std = float(np.std(slopes, ddof=1))
        print(f"{k}\t{np.mean(radii):.4f}\t{p:.0f}\t{np.mean(slopes):.3f}\t{std:.3f}\t{4 / np.sqrt(p):.3f}\t"
              f"{std * np.sqrt(p):.1f}")
        if p <= 5e5:
            small.append(std * np.sqrt(p))
    if not small:
        sys.exit("# no radius with at most 5*10^5 pairs: try a shorter --length")
    print(f"# small scales ({len(small)} radii, at most 5*10^5 pairs): c = {np.sqrt(np.mean(np.square(small))):.1f} "
          f"(root mean square; from {min(small):.1f} to {max(small):.1f})")


if __name__ == "__main__":
    main()
