#!/usr/bin/env python3
"""lambda_1 answers of `chaos analyze` on every chaotic zoo system, against lambda_1 from the equations.

For each system: the zoo's series (`chaos zoo --series`), its first N samples for each N asked,
`chaos lyapunov --json` with every default (the same lambda_1 as `chaos analyze` gives, without its
D2 and surrogate steps), and its `lambda_1` answer (value, interval, status). Prints one row per system
and N, then, per N:
  coverage     confident and within 10% of lambda_1 from the equations (the zoo's band);
  calibration  the reference inside the stated interval, over confident and rough answers;
  worst        confident answers farther from the reference than twice their half-width;
  reach        the answer's value within 10% whatever its status, and some value of the three
               estimators within 10%: what a better rule for status or value could reach at most.
The references are the "lambda_1 eq." column of docs/validation/zoo.md (chaos spectrum, from the equations).

Usage: scripts/measure/lyapunov_answers.py CHAOS_BINARY [N ...] [--jobs J] [--only a,b] [--save DIR]
(--save keeps each run's whole JSON as DIR/SYSTEM-N.json.)
"""
import json
import os
import re
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def references():
    """System -> lambda_1 from the equations, read from docs/validation/zoo.md's table."""
    out, column = {}, None
    for line in open(os.path.join(ROOT, "docs/validation/zoo.md")):
        cells = [c.strip() for c in line.split("|")]
        if "lambda_1 eq." in cells:  # the chaotic systems' table header: find the column by name
            column = cells.index("lambda_1 eq.")
        elif column and len(cells) > column and re.fullmatch(r"[0-9]+", cells[2] or "") and cells[1] not in out:
            try:
                out[cells[1]] = float(cells[column])
            except ValueError:
                pass
    return out


def run(chaos, name, n, workdir, save=None):
    series = os.path.join(workdir, name + ".json")
    if not os.path.exists(series):
        with open(series, "w") as f:
            subprocess.run([chaos, "zoo", "--series", name, "--json"], stdout=f, check=True)
    data = json.load(open(series))
    dt = data["parameters"].get("dt")
    values = data.get("x") or next(v for k, v in data.items() if isinstance(v, list))
    path = os.path.join(workdir, f"{name}-{n}.txt")
    with open(path, "w") as f:
        f.write("\n".join(repr(v) for v in values[:n]) + "\n")
    cmd = [chaos, "lyapunov", path, "-q", "--json"] + (["--dt", str(dt)] if dt else [])
    done = subprocess.run(cmd, capture_output=True, text=True)
    if done.returncode != 0:
        return {"status": "error", "reason": done.stderr.strip()[:200]}
    if save:
        with open(os.path.join(save, f"{name}-{n}.json"), "w") as f:
            f.write(done.stdout)
    result = json.loads(done.stdout)
    answer = dict(result["lambda_1"])
    # Every value the three estimators give, per time unit: the answer, Rosenstein's and Kantz's
    # readings (strict or not), the local maps' value and their base estimate (also where their
    # variants disagree). Whether any lies within 10% bounds what any rule choosing among them reaches.
    maps = result.get("local_maps") or {}
    kantz = (result.get("cross_check") or {}).get("estimate") or {}
    answer["evidence"] = [v for v in (answer.get("value"), (result.get("estimate") or {}).get("value"),
                                      kantz.get("value"), maps.get("lambda"), maps.get("base")) if v is not None]
    return answer


def main():
    args = sys.argv[1:]
    jobs, only, save = 2, None, None
    if "--save" in args:
        i = args.index("--save")
        save = args[i + 1]
        os.makedirs(save, exist_ok=True)
        del args[i:i + 2]
    if "--jobs" in args:
        i = args.index("--jobs")
        jobs = int(args[i + 1])
        del args[i:i + 2]
    if "--only" in args:
        i = args.index("--only")
        only = set(args[i + 1].split(","))
        del args[i:i + 2]
    chaos = args[0]
    lengths = [int(a) for a in args[1:]] or [20000, 100000]
    refs = references()
    names = [n for n in refs if only is None or n in only]
    workdir = tempfile.mkdtemp(prefix="lyapunov-answers-")
    # One series file per system first (sequentially: the cheap part), then the analyses in parallel.
    for name in names:
        run_series = os.path.join(workdir, name + ".json")
        with open(run_series, "w") as f:
            subprocess.run([chaos, "zoo", "--series", name, "--json"], stdout=f, check=True)
    tasks = [(name, n) for n in lengths for name in names]
    with ThreadPoolExecutor(jobs) as pool:
        answers = list(pool.map(lambda t: run(chaos, t[0], t[1], workdir, save), tasks))
    print("system\tN\tlambda_eq\tvalue\tlow\thigh\tstatus\tinside\treason")
    summary = {n: {"confident": 0, "good": 0, "stated": 0, "held": 0, "worst": 0, "systems": 0, "value_close": 0,
                   "any_close": 0} for n in lengths}
    for (name, n), a in zip(tasks, answers):
        ref = refs[name]
        close = lambda x: abs(x - ref) <= 0.1 * abs(ref)  # noqa: E731 (the zoo's 10% band)
        s = summary[n]
        s["systems"] += 1
        v, iv, st = a.get("value"), a.get("interval"), a.get("status")
        inside = iv is not None and iv[0] <= ref <= iv[1]
        s["value_close"] += v is not None and close(v)
        s["any_close"] += any(close(e) for e in a.get("evidence", []))
        if st in ("confident", "rough") and v is not None:
            s["stated"] += 1
            s["held"] += inside
        if st == "confident":
            s["confident"] += 1
            s["good"] += close(v)
            half = 0.5 * (iv[1] - iv[0]) if iv else 0.0
            s["worst"] += abs(v - ref) > 2 * half and not close(v)
        fmt = lambda x: "-" if x is None else f"{x:.4g}"
        print(f"{name}\t{n}\t{ref:.4g}\t{fmt(v)}\t{fmt(iv[0] if iv else None)}\t{fmt(iv[1] if iv else None)}\t{st}\t"
              f"{'yes' if inside else 'no'}\t{a.get('reason', '')[:160]}")
    for n, s in summary.items():
        print(f"# N = {n}: {s['systems']} systems; confident {s['confident']}, of which within 10% of lambda_1 eq. "
              f"{s['good']} (coverage {100 * s['good'] / max(1, s['systems']):.1f}%); reference inside the interval "
              f"in {s['held']} of {s['stated']} confident or rough answers "
              f"({100 * s['held'] / max(1, s['stated']):.1f}%); confident and farther than twice the half-width "
              f"(and 10%): {s['worst']}")
        print(f"# N = {n}: the answer's value within 10% (any status): {s['value_close']}; some value of the three "
              f"estimators within 10% (the answer, either curve, the local maps or their base): {s['any_close']}")


if __name__ == "__main__":
    main()
