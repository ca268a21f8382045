"""Parameter sweeps of the clearance-joint slider-crank simulator (the ``study sweep`` command).

    from chaos import mechanism, study
    scene = mechanism.default_scene().set("integrator.method", "dopri5")
    s = study.sweep(scene, axis="joint.slider.clearance=1e-4:4e-4:4", periods=8, keep=3)
    s.samples["slider_y"], s.samples["joint.slider.clearance"]    # one row per point and kept revolution
    s.points["status"], s.points["max_penetration"]              # one row per point
    s.analysis["d2"]                                             # with analysis=True
    s.lyapunov["lambda_1"]                                       # with lyapunov=True

The sweep runs the code behind ``study sweep`` (ResultStore, run_sweep, assemble) with the GIL
released: the result directory holds exactly the files the command writes for the same options
(docs/reference/study.md), and the tables come back as read-only NumPy arrays by column name.
"""
import os
import shutil
import tempfile
import types

import numpy as np

from . import _core, _parameters
from .mechanism import Scene

__all__ = ["sweep", "Sweep", "read_table"]


def _column(values):
    if all(v.lstrip("-").isdigit() for v in values) and values:
        return np.array([int(v) for v in values], dtype=np.int64)
    try:
        return np.array([np.nan if v == "-" else float(v) for v in values], dtype=float)
    except ValueError:
        return np.array(values, dtype=str)


def read_table(path):
    """A table of a sweep's result directory (samples.tsv, points.tsv, analysis.tsv) as a read-only
    mapping column name -> array: whole numbers as int64, numbers as float64 (``-``, "no value",
    as NaN), anything else (status, message) as strings. The names are those of the table's last
    '#' line."""
    names, rows = None, []
    with open(path, encoding="utf-8") as f:
        for line in f:
            line = line.rstrip("\n")
            if line.startswith("#"):
                if "\t" in line:
                    names = line[2:].split("\t")
                continue
            rows.append(line.split("\t"))
    if names is None:
        raise ValueError(f"{path}: no header line naming the columns")
    columns = {}
    for k, name in enumerate(names):
        a = _column([r[k] if k < len(r) else "" for r in rows])
        a.flags.writeable = False
        columns[name] = a
    return types.MappingProxyType(columns)


class Sweep:
    """A finished sweep: ``samples``, ``points``, ``analysis`` (None without ``analysis=True``) and
    ``lyapunov`` (None without ``lyapunov=True``),
    each a read-only mapping column name -> array, as the command's tables hold them; ``summary``
    (the command's summary, key for key: directory, points, computed, resumed_from_disk, failed,
    analysis_failed, lyapunov_failed, threads, ranks, wall_seconds); ``spec`` (spec.txt, the
    canonical text of the sweep); ``warnings`` (what the command prints about the scene);
    ``directory`` (None, in the summary too, when the result went to a temporary directory, since
    removed)."""

    def __init__(self, directory, summary, warnings, keep_directory):
        self.samples = read_table(os.path.join(directory, "samples.tsv"))
        self.points = read_table(os.path.join(directory, "points.tsv"))
        analysis = os.path.join(directory, "analysis.tsv")
        self.analysis = read_table(analysis) if os.path.exists(analysis) else None
        lyapunov = os.path.join(directory, "lyapunov.tsv")
        self.lyapunov = read_table(lyapunov) if os.path.exists(lyapunov) else None
        with open(os.path.join(directory, "spec.txt"), encoding="utf-8") as f:
            self.spec = f.read()
        self.directory = directory if keep_directory else None
        self.summary = dict(summary, directory=self.directory)
        self.warnings = tuple(warnings)

    def __repr__(self):
        return (f"<Sweep {self.summary['points']} points, {self.summary['failed']} failed"
                f"{', analysed' if self.analysis is not None else ''}>")


def _axes(axis):
    if isinstance(axis, str):
        return [axis]
    if isinstance(axis, dict):
        out = []
        for key, values in axis.items():
            if isinstance(values, str):
                out.append(f"{key}={values}")
            else:
                out.append(f"{key}=" + ",".join(repr(float(v)) for v in values))
        return out
    axes = list(axis)
    if not all(isinstance(a, str) for a in axes):
        raise TypeError("axis: a string key=from:to:count or key=v1,v2,..., a list of them, or a dict key -> values")
    return axes


@_parameters("study_sweep")
def sweep(scene=None, *, axis=(), set=(), threads=None, output=None, resume=False, progress=None, **params):
    """A one- or two-dimensional sweep over scene keys (``study sweep``; the protocol of docs/reference/study.md).

    Every point's scene is ``scene`` (the seed's when None; a ``mechanism.Scene`` with its settings,
    or the path of a TOML file), then ``set`` (``--set key=value``, strings), then the point's axis
    values. ``axis``: ``"key=from:to:count"`` (linearly spaced) or ``"key=v1,v2,..."``, a list of at
    most two (the first varies fastest), or a dict key -> values. ``initial``: ``fresh`` (the
    seed's Eq. 29 at every point) or ``continuation`` (from the previous point's final state along
    the first axis). Each point runs ``periods`` crank revolutions and keeps the stroboscopic
    samples of ``signals`` (None: slider_y and slider_vy) over the last ``keep``; ``analysis=True`` also analyses slider_y over
    the last ``analysis_periods`` revolutions (mutual-information delay, Fraser and Swinney 1986;
    Cao's E1/E2, Cao 1997; D2 from the correlation sums C(eps, m), Grassberger and Procaccia 1983),
    sampled every ``analysis_interval`` s or ``analysis_samples_per_period`` times a revolution,
    up to ``max_dimension``, the delay searched up to ``max_delay`` and, where no minimum lies there,
    on to two Theiler windows (``--max-delay``). ``surrogates=K`` (with ``analysis``) adds
    the IAAFT surrogate test for nonlinearity on the first ``test_length`` samples, surrogates drawn
    from ``seed`` (``--surrogates``, ``--test-length``, ``--seed``; Theiler et al. 1992, Schreiber and
    Schmitz 2000). ``lyapunov=True`` adds each point's Lyapunov exponents from the equations
    (``lyapunov_periods``, ``lyapunov_exponents``, ``lyapunov_perturbation``,
    ``lyapunov_intervals``; ``mechanism lyapunov``). These keyword arguments and their defaults are
    the command's options (study/commands/sweep_parameters.cpp); ``signals`` may also be one
    comma-separated string.

    ``output``: the result directory (kept; ``resume=True`` continues a sweep already there, as
    ``--resume``); None writes to a temporary directory, read and removed. ``threads``: worker
    threads (default: the cores; the tables do not depend on it). ``progress``: True for a bar on
    stderr, or a callable taking the fraction of points done. Ctrl-C stops the sweep after the
    points being computed; with ``output`` a ``resume=True`` call finishes it.

    A refused sweep (a bad axis, key, value or option, an existing directory without ``resume``)
    raises ValueError with the command's message. Points whose simulation did not complete are
    reported in ``points["status"]`` and ``summary["failed"]``, not raised (the command exits 5).
    """
    from . import _progress_bar
    import sys
    if scene is None:
        toml, source, overrides = "", "", []
    elif isinstance(scene, Scene):
        toml, source, overrides = scene._toml, scene._source, list(scene._overrides)
    elif isinstance(scene, (str, os.PathLike)):
        from .mechanism import load_scene
        loaded = load_scene(scene)
        toml, source, overrides = loaded._toml, loaded._source, []
    else:
        raise TypeError(f"scene must be a mechanism.Scene, a path or None (got {type(scene).__name__})")
    if isinstance(set, str):
        set = [set]
    overrides += list(set)
    if isinstance(params["signals"], str):  # "slider_y,slider_vy", as the command takes them
        params["signals"] = params["signals"].split(",")
    if threads is None:
        threads = os.cpu_count() or 1
    directory = os.fspath(output) if output is not None else tempfile.mkdtemp(prefix="chaos-sweep-")
    bar = _progress_bar(progress, "sweep")
    try:
        summary, warnings = _core.study_sweep(toml, source, overrides, _axes(axis), params, directory,
                                              bool(resume) if output is not None else False, threads, bar)
        return Sweep(directory, summary, warnings, output is not None)
    finally:
        if bar is not None and not callable(progress):
            sys.stderr.write("\n")
        if output is None:
            shutil.rmtree(directory, ignore_errors=True)
