#!/usr/bin/env python3
"""The figures of docs/guide/python.md, made by the package: a real-looking series (Lorenz x observed with
2% noise, N = 20 000), chaos.analyze, then the correlation sums and local slopes of chaos.d2 in the
embedding analyze chose, and a small clearance sweep of the simulator (chaos.study.sweep). Writes
docs/guide/python/*.png and prints the numbers the page quotes.

Usage (the venv's python, from outside the checkout's root): python scripts/python_figures.py
"""
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import chaos  # noqa: E402

out = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "docs", "guide", "python")
os.makedirs(out, exist_ok=True)

x, dt = chaos.builtin_lorenz(20000)
x = x + 0.02 * np.std(x) * np.random.default_rng(7).standard_normal(len(x))  # measurement noise

a = chaos.analyze(x, dt=dt, test_length=2048)
print(a)
print(f"delay {a.delay} ({a.delay_source}), theiler {a.theiler} ({a.theiler_source}), m = {a.embedding_dimension}")
print(f"D2 = {a.d2} in {a.d2_interval} ({a.d2_status}); lambda = {a.lambda_} per time unit ({a.lambda_status})")
print(f"D2 answer {a.d2_estimate}; lambda_1 answer {a.lambda_1}")
a.plot()
plt.gcf().savefig(os.path.join(out, "analyze.png"), dpi=90)

r = chaos.d2(x, delay=a.delay, max_dimension=a.embedding_dimension + 4, theiler=a.theiler, threads=2)
print(f"chaos.d2: {r.status}, D2 = {r.d2} in {r.d2_interval}, scaling region {r.scaling_region}")
r.plot()
plt.gcf().savefig(os.path.join(out, "d2.png"), dpi=90)

m = chaos.mutual(x, max_delay=60, dt=dt)
c = chaos.cao(x, delay=a.delay, theiler=a.theiler)
fig, (left, right) = plt.subplots(1, 2, figsize=(11, 3.6), constrained_layout=True)
m.plot(ax=left)
c.plot(ax=right)
fig.savefig(os.path.join(out, "mutual_cao.png"), dpi=90)

# A small clearance sweep of the simulator: the slider's stroboscopic y against the translational
# clearance (the seed's Fig. 4, coarse), with the cheap settings of scripts/demo.sh, by study.sweep
# (the code of `study sweep`) on two threads.
import time  # noqa: E402

from chaos import mechanism, study  # noqa: E402

base = mechanism.default_scene()
for key, value in {"joint.slider.friction.sigma1_velocity": 1e-3, "integrator.method": "dopri5",
                   "integrator.relative_tolerance": 1e-3, "integrator.max_step": 1e-4}.items():
    base.set(key, value)
started = time.perf_counter()
s = study.sweep(base, axis="joint.slider.clearance=1e-5:6e-4:40", periods=250, keep=100, threads=2)
print(f"sweep: {s.summary['points']} clearances x 250 revolutions in {time.perf_counter() - started:.1f} s on 2 threads; "
      f"statuses {sorted(set(s.points['status']))}")
fig, ax = plt.subplots(figsize=(7, 4), constrained_layout=True)
ax.plot(s.samples["joint.slider.clearance"] * 1e3, s.samples["slider_y"] * 1e3, ",k")
ax.set_xlabel("clearance c_t (mm)")
ax.set_ylabel("slider y at each revolution (mm)")
ax.set_title("stroboscopic slider position, last 100 of 250 revolutions")
fig.savefig(os.path.join(out, "sweep.png"), dpi=90)
