"""Records made outside the project, and `chaos analyze` run on them: the pieces shared by
textbook_heldout.py and transformed_linear.py (imported from the scripts' own directory).

- record(name, n, seed): x of Lorenz (sigma 10, rho 28, beta 8/3; dt 0.01; 100 time units dropped) or
  Roessler (a = b = 0.2, c = 5.7; dt 0.1; 1000 time units dropped) by scipy's solve_ivp (DOP853,
  rtol = atol = 1e-10) from a random start, or Henon x (a 1.4, b 0.3; 1000 iterations dropped) in numpy.
- analyze_lines(chaos, path, dt): `chaos analyze FILE -q [--dt DT]`, its result lines as {name: field}.
- answer(field): (value, low, high, status) of a field "V in [L, H] ... (status)"; value, low and high
  are None where there is no value ("none (none)", "not run").
- run_parallel(tasks, make, judge, jobs, prefix): for each task, make(task) gives (series, dt); the series
  is written to a temporary file and judge(path, dt) runs on it; the files are removed at the end.
- command_line(usage, seeds): the chaos binary and the --seeds and --jobs options from sys.argv (the
  script's default seed count; the usage text and exit when no binary is given).

Needs numpy and scipy (Debian: python3-numpy, python3-scipy).
"""
import os
import shutil
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor

import numpy as np
from scipy.integrate import solve_ivp


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
    elif name == "rossler":
        def f(t, s):
            return [-s[1] - s[2], s[0] + 0.2 * s[1], 0.2 + s[2] * (s[0] - 5.7)]
        dt, drop, start = 0.1, 1000.0, np.append(rng.uniform(-5, 5, 2), 0.1)
    else:
        raise ValueError("no record named " + name)
    t = drop + dt * np.arange(n)
    return solve_ivp(f, (0, t[-1]), start, method="DOP853", rtol=1e-10, atol=1e-10, t_eval=t).y[0]


def analyze_lines(chaos, path, dt):
    cmd = [chaos, "analyze", path, "-q"] + (["--dt", str(dt)] if dt else [])
    done = subprocess.run(cmd, capture_output=True, text=True)
    lines = {line.split("\t")[0]: line.split("\t")[1] for line in done.stdout.splitlines() if "\t" in line}
    if not lines:
        lines["error"] = done.stderr.strip()[:120]
    return lines


def answer(field):
    status = field[field.rfind("(") + 1:field.rfind(")")] if "(" in field else field.split()[0]
    if " in [" not in field:
        return None, None, None, status
    value = float(field.split(" in [")[0])
    low, high = (float(v) for v in field.split(" in [")[1].split("]")[0].split(","))
    return value, low, high, status


def run_parallel(tasks, make, judge, jobs, prefix):
    work = tempfile.mkdtemp(prefix=prefix)

    def one(index_task):
        index, task = index_task
        series, dt = make(task)
        path = os.path.join(work, f"{index}.txt")
        np.savetxt(path, series, fmt="%.17g")
        return task, judge(path, dt)

    try:
        with ThreadPoolExecutor(jobs) as pool:
            return list(pool.map(one, enumerate(tasks)))
    finally:
        shutil.rmtree(work)


def command_line(usage, seeds):
    """(chaos binary, seeds, jobs) from sys.argv; exits with `usage` when the binary is missing."""
    args = sys.argv[1:]
    if not args:
        sys.exit(usage)
    jobs = 2
    if "--seeds" in args:
        seeds = int(args[args.index("--seeds") + 1])
    if "--jobs" in args:
        jobs = int(args[args.index("--jobs") + 1])
    return args[0], seeds, jobs
