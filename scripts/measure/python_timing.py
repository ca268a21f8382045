#!/usr/bin/env python3
"""The Python package's cost over the library (docs/validation/performance-python.md).

1. Call overhead on a small series: a call's wall time minus the library's own time for the same
   work (the shared command code run in C++ by chaos._core._compute_seconds, no Python in the loop);
   the difference is the input conversion, the parameters, the JSON handed over as Python objects
   and the result object.
2. Exact D2 on Lorenz x, N = 100 000 (the built-in series of `chaos analyze`): chaos.d2(x) against
   `chaos d2 FILE --json` on the same samples, same parameters, best of --repeats runs each.

Usage: python scripts/measure/python_timing.py [--cli build/chaos/chaos] [--repeats 3] [--n 100000]
Run it with the venv's python from outside the checkout's root (or the chaos/ folder shadows the package).
"""
import argparse
import os
import resource
import subprocess
import tempfile
import time
import timeit

import numpy as np

import chaos
from chaos import _core


def overhead(name, function, x, params, number):
    library = min(_core._compute_seconds(name, x, params, number) for _ in range(5))
    call = min(timeit.repeat(lambda: function(x, **params), number=number, repeat=5)) / number
    return call, library


def main():
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    parser = argparse.ArgumentParser()
    parser.add_argument("--cli", default=os.path.join(root, "build", "chaos", "chaos"))
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--n", type=int, default=100000)
    parser.add_argument("--skip-d2", action="store_true")
    args = parser.parse_args()

    rng = np.random.default_rng(1)
    small = np.sin(0.3 * np.arange(200)) + 0.1 * rng.standard_normal(200)
    print("call overhead (wall time per call, best of 5 rounds of many calls, each side):")
    for name, function, params, number in [
            ("autocorrelation", chaos.autocorrelation, dict(max_lag=10), 20000),
            ("mutual", chaos.mutual, dict(max_delay=5, boxes=4), 5000)]:
        call, library = overhead(name, function, small, params, number)
        print(f"  {name:16s} N = {len(small)}: call {call * 1e6:7.1f} us, library {library * 1e6:7.1f} us, "
              f"overhead {(call - library) * 1e6:6.1f} us")
    if args.skip_d2:
        return

    x, dt = chaos.builtin_lorenz(args.n)
    d2_args = dict(delay=19, max_dimension=6, theiler=31)  # the delay and window chaos analyze chooses
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "lorenz.txt")
        np.savetxt(path, x, fmt="%.17g")
        assert np.array_equal(chaos.read(path)[0], x)
        command = [args.cli, "d2", path, "-d", "19", "-M", "6", "-t", "31", "-q", "--json"]
        cli_times, py_times, cli_cpu, py_cpu, module_times = [], [], [], [], []
        for _ in range(args.repeats):
            children = resource.getrusage(resource.RUSAGE_CHILDREN)
            start = time.perf_counter()
            out = subprocess.run(command, check=True, capture_output=True).stdout
            cli_times.append(time.perf_counter() - start)
            after = resource.getrusage(resource.RUSAGE_CHILDREN)
            cli_cpu.append(after.ru_utime + after.ru_stime - children.ru_utime - children.ru_stime)
            start, cpu = time.perf_counter(), time.process_time()
            r = chaos.d2(x, **d2_args)
            py_times.append(time.perf_counter() - start)
            py_cpu.append(time.process_time() - cpu)
            # The same work inside the module without the Python layer (no conversions, no result object).
            module_times.append(_core._compute_seconds("d2", x, d2_args, 1))
        import json
        expected = json.loads(out)
        expected["parameters"]["file"] = "(array)"
        assert r.to_dict() == expected, "Python and command differ"
    cli, py = min(cli_times), min(py_times)
    cli_median, py_median = float(np.median(cli_times)), float(np.median(py_times))
    print(f"exact D2, Lorenz x N = {len(x)}, -d 19 -M 6 -t 31 (box-assisted, 1 thread), best of {args.repeats}:")
    print(f"  chaos d2 (command, file read included): {cli:.3f} s   all: {', '.join(f'{t:.3f}' for t in cli_times)}")
    print(f"  chaos.d2 (Python, array):               {py:.3f} s   all: {', '.join(f'{t:.3f}' for t in py_times)}")
    print(f"  the module's C++ alone:                 {min(module_times):.3f} s   all: "
          f"{', '.join(f'{t:.3f}' for t in module_times)}")
    print(f"  CPU time, best: command {min(cli_cpu):.3f} s, Python {min(py_cpu):.3f} s, "
          f"ratio {min(py_cpu) / min(cli_cpu):.3f}")
    print(f"  Python / command: best {py / cli:.3f}, median {py_median / cli_median:.3f}; "
          f"D2 = {r.d2} ({r.status}), identical JSON")


if __name__ == "__main__":
    main()
