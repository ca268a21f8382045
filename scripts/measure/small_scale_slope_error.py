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

Prints, per radius: the mean radius, the median pair count of m = 6, the mean and the standard
deviation over the records of the local slope averaged over m = 4..6, what independent pairs would
give (4 / sqrt(pairs)), and the factor c = std * sqrt(pairs); then the root mean square of c over the
small scales, the radii with at most 5*10^5 pairs, where the rule applies (above them the records'
radii, which differ by up to 3%, and the slope's change with scale add to the spread).

Usage: scripts/measure/small_scale_slope_error.py CHAOS_BINARY [--seeds K] [--jobs J]
Needs numpy and scipy. Seeds 101 .. 100 + K (default 12), the seeds of textbook_heldout.py.
"""
import json
import subprocess

import numpy as np

from outside_records import command_line, record, run_parallel

N = 100000


def main():
    chaos, seeds, jobs = command_line(__doc__, 12)
    tasks = list(range(101, 101 + seeds))

    def judge(path, dt):
        out = subprocess.run([chaos, "d2", path, "-M", "6", "--json", "-q"], capture_output=True, text=True)
        if out.returncode != 0:
            raise RuntimeError(out.stderr.strip())
        return json.loads(out.stdout)

    results = [d for _, d in run_parallel(tasks, lambda seed: (record("lorenz", N, seed), 0.01), judge, jobs,
                                          "slope-error-")]
    dims = [results[0]["dimension"].index(m) for m in (4, 5, 6)]
    print(f"# {len(results)} Lorenz x records, N = {N}: local slope of m = 4..6 (mean over m) at radius k")
    print("k\tradius\tpairs (m = 6)\tmean slope\tstd over records\t4 / sqrt(pairs)\tstd * sqrt(pairs)")
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
    print(f"# small scales ({len(small)} radii, at most 5*10^5 pairs): c = {np.sqrt(np.mean(np.square(small))):.1f} "
          f"(root mean square; from {min(small):.1f} to {max(small):.1f})")


if __name__ == "__main__":
    main()
