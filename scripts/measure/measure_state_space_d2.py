#!/usr/bin/env python3
"""The zoo's confident D2 beside the local slopes of each system's own state (docs/notes/zoo-state-space.md).

A D2 band with no literature value is only a ceiling (D_KY + 0.1), so a plateau read too low passes
it unseen. This peer needs no embedding: every component of the state from the equations
(`chaos generate NAME -l N`, at the zoo's sampling step), all pairs outside the zoo's Theiler
window, maximum norm, brute force. It is a peer, not a judge: at the N it can afford its smallest
scales are noisy, and where the components differ in scale the norm weighs them unevenly.

    /usr/bin/python3 scripts/measure/measure_state_space_d2.py [--chaos build/chaos/chaos] [--n 20000]
        [--jobs 2] [--only NAME ...] > docs/notes/zoo-state-space.md

Rows: every system of docs/validation/zoo.md whose automatic D2 at N = 10^5 is saturated (delay systems
are left out: their state is a function, not a vector; a one-dimensional map's state is its series).
"""
import argparse
import json
import multiprocessing
import os
import platform
import subprocess
import sys
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SMALL = (0.002, 0.02)  # eps / range of the state: the small scales
LARGE = (0.02, 0.1)    # and the scales above them
MIN_PAIRS = 2000       # a slope between two radii needs this many pairs at the lower one


def zoo_rows(path):
    """(system, w, D2 cell, band, D_KY) of the saturated automatic rows at N = 10^5."""
    rows, column, width = [], None, 0
    with open(path) as f:
        for line in f:
            cells = [c.strip() for c in line.split('|')]
            if len(cells) > 2 and cells[1] == 'system' and 'D_KY eq.' in cells:  # columns by their names
                column, width = {name: i for i, name in enumerate(cells)}, len(cells)
            elif column and len(cells) == width and cells[2] == '100000' and \
                    ' saturated' in cells[column['D2']]:
                rows.append((cells[1], int(cells[column['w']]), cells[column['D2']], cells[column['D2 band']],
                             cells[column['D_KY eq.']]))
    return rows


def slopes(chaos, name, w, n):
    meta = json.loads(subprocess.run([chaos, 'zoo', '--series', name, '--json'], check=True,
                                     capture_output=True, text=True).stdout)
    command = [chaos, 'generate', name, '-l', str(n)]
    if meta['parameters'].get('dt'):
        command += ['-p', 'dt=%r' % meta['parameters']['dt']]
    text = subprocess.run(command, check=True, capture_output=True, text=True).stdout
    x = np.loadtxt(text.splitlines(), comments='#', ndmin=2)
    if x.shape[1] < 2 and meta['parameters'].get('dt'):
        return None  # a delay system: its state is a function, `generate` gives one component
    extent = float((x.max(0) - x.min(0)).max())
    radii = np.logspace(np.log10(extent / 1000), np.log10(extent / 4), 25)
    counts = np.zeros(len(radii))
    for i in range(len(x) - w - 1):  # pairs i < j with j - i > w, each once
        d = np.abs(x[i + w + 1:] - x[i]).max(1)
        d.sort()
        counts += np.searchsorted(d, radii)  # d < r, as the library counts
    local = np.diff(np.log(np.maximum(counts, 1))) / np.diff(np.log(radii))
    middle = np.sqrt(radii[1:] * radii[:-1]) / extent
    keep = counts[:-1] >= MIN_PAIRS
    return x.shape[1], middle[keep], local[keep]


def span(middle, local, window):
    inside = local[(middle >= window[0]) & (middle <= window[1])]
    return (float(inside.min()), float(inside.max())) if len(inside) else None


def cpu_name():
    try:
        with open('/proc/cpuinfo') as f:
            for line in f:
                if line.startswith('model name'):
                    return line.split(':', 1)[1].strip()
    except OSError:
        pass
    return platform.machine()


def measure(job):
    chaos, n, (name, w, d2, band, dky) = job
    start = time.time()
    result = slopes(chaos, name, w, n)
    return name, w, d2, band, dky, result, time.time() - start


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('--chaos', default=os.path.join(ROOT, 'build/chaos/chaos'))
    parser.add_argument('--zoo', default=os.path.join(ROOT, 'docs/validation/zoo.md'))
    parser.add_argument('--n', type=int, default=20000)
    parser.add_argument('--jobs', type=int, default=2)
    parser.add_argument('--only', nargs='*', default=[])
    args = parser.parse_args()
    rows = [r for r in zoo_rows(args.zoo) if not args.only or r[0] in args.only]
    start = time.time()
    with multiprocessing.Pool(args.jobs) as pool:
        results = pool.map(measure, [(args.chaos, args.n, r) for r in rows], chunksize=1)
    commit = subprocess.run(['git', '-C', ROOT, 'rev-parse', '--short', 'HEAD'], capture_output=True,
                            text=True).stdout.strip()
    print('# The zoo\'s D2 beside the slopes of each system\'s state\n')
    print('Made by `/usr/bin/python3 scripts/measure/measure_state_space_d2.py --n %d --jobs %d` (commit %s, %s, '
          '%d cores, %.0f s). The script\'s docstring says what it computes and why.\n'
          % (args.n, args.jobs, commit, cpu_name(), os.cpu_count(),
             time.time() - start))
    print('"ours" is the automatic D2 of docs/validation/zoo.md at N = 10^5 (x, delay embedding); the two slope '
          'columns are the smallest and largest local slope of the state\'s correlation sum (N = %d, '
          'every component, the zoo\'s Theiler window w, max norm, radii with at least %d pairs) at '
          'eps from %g to %g and from %g to %g of the state\'s range. "below" marks ours more than 0.1 '
          'under the smallest small-scale slope.\n' % (args.n, MIN_PAIRS, SMALL[0], SMALL[1], LARGE[0], LARGE[1]))
    print('| system | components | w | ours | band | D_KY | state, small scales | state, larger scales | ours vs state |')
    print('|---|---|---|---|---|---|---|---|---|')
    for name, w, d2, band, dky, result, _ in results:
        if result is None:
            print('| %s | 1 | %d | %s | %s | %s | - | - | delay system: no state vector |' % (name, w, d2, band, dky))
            continue
        dims, middle, local = result
        small, large = span(middle, local, SMALL), span(middle, local, LARGE)
        ours = float(d2.split()[0])
        fmt = lambda s: '%.2f-%.2f' % s if s else '-'
        verdict = 'below' if small and ours < small[0] - 0.1 else ('above' if small and ours > small[1] + 0.1 else 'within 0.1')
        print('| %s | %d | %d | %s | %s | %s | %s | %s | %s |' % (name, dims, w, d2, band, dky, fmt(small), fmt(large), verdict))


if __name__ == '__main__':
    sys.exit(main())
