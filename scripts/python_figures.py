#!/usr/bin/env python3
"""The figures of docs/python.md, made by the package: a real-looking series (Lorenz x observed with
2% noise, N = 20 000), chaos.analyze, then the correlation sums and local slopes of chaos.d2 in the
embedding analyze chose. Writes docs/python/*.png and prints the numbers the page quotes.

Usage (the venv's python, from outside the checkout's root): python scripts/python_figures.py
"""
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import chaos  # noqa: E402

out = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "docs", "python")
os.makedirs(out, exist_ok=True)

x, dt = chaos.builtin_lorenz(20000)
x = x + 0.02 * np.std(x) * np.random.default_rng(7).standard_normal(len(x))  # measurement noise

a = chaos.analyze(x, dt=dt, test_length=2048)
print(a)
print(f"delay {a.delay} ({a.delay_source}), theiler {a.theiler} ({a.theiler_source}), m = {a.embedding_dimension}")
print(f"D2 = {a.d2} in {a.d2_interval} ({a.d2_status}); lambda = {a.lambda_} per time unit ({a.lambda_status})")
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
