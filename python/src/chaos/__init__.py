"""chaos: the chaos library's analyses on NumPy arrays.

Each function runs the same code as the matching ``chaos`` command (the library's shared command
layer, chaos/commands/) and returns a frozen result whose attributes are the keys of the command's
``--json`` output; ``result.to_dict()`` equals that JSON object exactly, and ``result.plot()``
draws the command's figure with matplotlib.

The series is a 1-D array (a float64 C-contiguous array is used in place, anything else, lists
included, is converted once to float64) or the path of a text file, read as the command reads it
(``column``, ``skip``, ``length``). Parameters are keyword arguments named after the command's long
options (``--max-dimension`` -> ``max_dimension``), with the command's defaults. The GIL is released
while the library computes. Invalid input raises ValueError with the library's message (NaN or
infinity, an empty, constant or too short series, an impossible parameter) or TypeError (a
parameter or series of the wrong type).

Conventions (docs/reference/conventions.md): delays, Theiler windows and steps in samples; the max norm unless
said otherwise; correlation sums count pairs with distance < eps and |i - j| > theiler; mutual
information in nats.

A result's JSON names the series in ``parameters["file"]``: the path for a file, ``"(array)"`` for
an array.
"""
import functools
import inspect
import os
import sys

import numpy as np

from . import _core
from ._results import Result, make as _make

__all__ = ["generate", "spectrum", "mutual", "autocorrelation", "cao", "fnn", "d2", "correlation_sum", "lyapunov", "lyapunov_maps", "analyze", "surrogates",
           "nonlinearity", "density", "section", "validate", "validation_cases", "zoo", "zoo_series", "embed",
           "read", "builtin_lorenz", "Result"]
__version__ = "0.1.0"

ARRAY_NAME = "(array)"


def _parameters(command):
    """Gives the decorated function the keyword arguments of the command's parameter table (the
    table the ``chaos`` command's options come from, chaos/commands/parameter_tables.cpp), with
    the command's defaults, ahead of the function's own keyword arguments. The function takes them
    as ``**params``, every one of them present (its default where the caller left it out), and hands
    them to _core; ``inspect.signature`` and ``help`` show them with their defaults."""
    table = _core.parameters(command)

    def decorate(function):
        own = inspect.signature(function).parameters.values()
        keyword = [p for p in own if p.kind is inspect.Parameter.KEYWORD_ONLY]
        leading = [p for p in own if p.kind in (inspect.Parameter.POSITIONAL_ONLY,
                                                inspect.Parameter.POSITIONAL_OR_KEYWORD)]
        # A table parameter the function takes by position (chaos.zoo's ``only``) keeps its place and
        # is handed on by the function itself; its default there is the table's (a test checks it).
        defaults = {name: default for name, default, _ in table if name not in {p.name for p in leading}}
        accepted = set(defaults) | {p.name for p in own if p.kind is not inspect.Parameter.VAR_KEYWORD}

        @functools.wraps(function)
        def with_parameters(*args, **kwargs):
            for name in kwargs:
                if name not in accepted:
                    raise TypeError(f"{function.__name__}() got an unexpected keyword argument '{name}'")
            return function(*args, **{**defaults, **kwargs})

        table_parameters = [inspect.Parameter(name, inspect.Parameter.KEYWORD_ONLY, default=default)
                            for name, default in defaults.items()]
        with_parameters.__signature__ = inspect.Signature(leading + table_parameters + keyword)
        return with_parameters
    return decorate


def _series(x, dt, column=1, skip=0, length=None):
    """(values, file, column, dt): a float64 C-contiguous array, viewed without a copy when it is one."""
    if isinstance(x, (str, os.PathLike)):
        path = os.fspath(x)
        values, column, dt = _core.read(path, column, skip, length, dt)
        return values, path, column, dt
    if column != 1 or skip != 0 or length is not None:
        raise TypeError("column, skip and length select rows of a file; slice an array instead")
    if isinstance(x, np.ma.MaskedArray) and np.ma.count_masked(x) > 0:
        # np.asarray would hand over the masked values as if they were data. Dropping them
        # (x.compressed()) would join the samples on either side of each gap, which is a choice the
        # caller must make: the series is refused instead.
        raise ValueError(f"the series is a masked array with {np.ma.count_masked(x)} masked value(s) of {x.size}: "
                         "pass x.compressed() to analyse the unmasked values joined across the gaps, "
                         "or x.filled(value), or analyse each unmasked stretch on its own")
    a = np.asarray(x)
    if a.dtype.kind not in "iuf":
        raise TypeError(f"the series must hold real numbers (got an array of dtype {a.dtype})")
    if a.ndim != 1:
        raise ValueError(f"the series must be one-dimensional (got shape {a.shape})")
    if a.dtype != np.float64 or not a.flags.c_contiguous:
        a = np.ascontiguousarray(a, dtype=np.float64)
    return a, ARRAY_NAME, 1, dt


def read(path, *, column=1, skip=0, length=None, dt=None):
    """The series of a text file as the ``chaos`` commands read it (TISEAN's -c -x -l, and --dt).

    Returns ``(values, dt)``: a float64 array and the sampling interval (None when not given).
    ``column`` is 1-based, or the name of a column in the file's header row.
    """
    values, _, _, dt = _series(os.fspath(path), dt, column, skip, length)
    return values, dt


def builtin_lorenz(length=100000):
    """The built-in demonstration series of ``chaos analyze``: Lorenz x (sigma=10, rho=28, beta=8/3), RK4
    h = 0.001 sampled every dt = 0.01. Returns ``(values, dt)``."""
    return _core.builtin_series(length)


def _progress_bar(progress, label):
    if progress is None or progress is False:
        return None
    if callable(progress):
        return progress
    state = {"shown": -1}

    def bar(fraction):
        percent = int(fraction * 100)
        if percent != state["shown"]:
            state["shown"] = percent
            filled = percent // 2
            sys.stderr.write(f"\r{label} [{'#' * filled}{'.' * (50 - filled)}] {percent:3d}%")
            sys.stderr.flush()
    return bar


def _run(function, label, progress, *args):
    """Calls _core.function(*args, hook) with the progress bar or callable; a bar ends its line."""
    bar = _progress_bar(progress, label)
    try:
        return _make(function(*args, bar))
    finally:
        if bar is not None and not callable(progress):
            sys.stderr.write("\n")


def _step_bar(progress):
    """analyze's hook: (step, fraction); True draws a bar per step on stderr."""
    if progress is None or progress is False:
        return None
    if callable(progress):
        return progress
    state = {"shown": None}

    def bar(step, fraction):
        percent = int(fraction * 100)
        if state["shown"] != (step, percent):
            if state["shown"] is not None and state["shown"][0] != step:
                sys.stderr.write("\n")
            state["shown"] = (step, percent)
            filled = percent // 2
            sys.stderr.write(f"\r{step} [{'#' * filled}{'.' * (50 - filled)}] {percent:3d}%")
            sys.stderr.flush()
    return bar


@_parameters("mutual")
def mutual(x, *, dt=None, column=1, skip=0, length=None, **params):
    """Average mutual information I(tau) in nats and its first minimum (``chaos mutual``).

    I(tau) = sum_ij p_ij(tau) ln(p_ij(tau) / (p_i p_j)) over a partition of the range into ``boxes``
    bins per axis (``estimator="equal_width"``, TISEAN's mutual) or of equal occupation
    (``"equiprobable"``), for tau = 0..max_delay. The first minimum is Fraser and Swinney's delay
    (Phys. Rev. A 33, 1134, 1986). Without ``max_delay`` the search is the automatic one of
    ``analyze``: 100 delays (at most N/10), and where the information has no minimum there, on to
    two Theiler windows. Where there is no minimum, ``no_minimum`` says why. docs/reference/mutual_information.md.

    Result keys: delay, [delay_time], mutual_information, first_minimum, first_minimum_time, no_minimum.
    """
    values, file, column, dt = _series(x, dt, column, skip, length)
    return _make(_core.mutual(values, file, column, dt, params))


@_parameters("autocorrelation")
def autocorrelation(x, *, dt=None, column=1, skip=0, length=None, **params):
    """Autocorrelation r(k) by FFT, its first zero crossing and 1/e time (``chaos autocorrelation``).

    r(k) = sum_i (x_i - m)(x_{i+k} - m) / sum_i (x_i - m)^2 for k = 0..max_lag (default N/10, at most
    1000); the 1/e time is interpolated linearly where r first falls below exp(-1).
    docs/reference/autocorrelation.md.

    Result keys: lag, autocorrelation, first_zero_crossing, decorrelation_time, [decorrelation_time_units].
    """
    values, file, column, dt = _series(x, dt, column, skip, length)
    return _make(_core.autocorrelation(values, file, column, dt, params))


@_parameters("cao")
def cao(x, *, progress=None, dt=None, column=1, skip=0, length=None, **params):
    """Cao's E1(m) and E2(m) and the embedding dimension where E1 saturates (``chaos cao``).

    ``delay`` and ``theiler`` left out are chosen as ``analyze`` chooses them (the first
    mutual-information minimum; the longer of the 1/e time and half the dominant period, at least
    the delay); ``parameters`` names each rule (``delay_source``, ``theiler_source``).

    E(m) = mean_i |y_i(m+1) - y_n(i,m)(m+1)| / |y_i(m) - y_n(i,m)(m)| with n(i, m) the nearest
    neighbour of point i in dimension m (|i - n| > theiler), E1(m) = E(m+1)/E(m); E*(m) = mean_i
    |x_{i+m tau} - x_{n+m tau}|, E2(m) = E*(m+1)/E*(m). The dimension is the first m with E1 >= level
    that changes by <= change from there on; the series is stochastic when every |E2 - 1| is within
    ``sigmas`` standard errors. L. Cao, Physica D 110, 43 (1997). docs/reference/cao.md.

    Result keys: dimension, E1, E2, E, E_star, E2_standard_error, embedding_dimension, e1_saturation,
    stochastic, max_E2_deviation, points_without_neighbor.

    ``progress=True`` draws a bar on stderr (or pass a callable taking the fraction done); Ctrl-C
    stops the search within 4096 points.
    """
    values, file, column, dt = _series(x, dt, column, skip, length)
    return _run(_core.cao, "Cao's method", progress, values, file, column, dt, params)


@_parameters("fnn")
def fnn(x, *, progress=None, dt=None, column=1, skip=0, length=None, **params):
    """The fraction of false nearest neighbours against m (``chaos fnn``).

    ``delay`` and ``theiler`` left out are chosen as ``analyze`` chooses them (the first
    mutual-information minimum; the longer of the 1/e time and half the dominant period, at least
    the delay); ``parameters`` names each rule (``delay_source``, ``theiler_source``).

    A neighbour is false when |x_{i+m tau} - x_{n+m tau}| / R_m(i) > rtol (criterion 1) or R_{m+1}(i) /
    sigma > atol (criterion 2); the dimension is the first m whose fraction is <= threshold.
    M. B. Kennel, R. Brown, H. D. I. Abarbanel, Phys. Rev. A 45, 3403 (1992). docs/reference/fnn.md.

    Result keys: dimension, false_fraction, embedding_dimension.

    ``progress=True`` draws a bar on stderr (or pass a callable taking the fraction done); Ctrl-C
    stops the search within 4096 points.
    """
    values, file, column, dt = _series(x, dt, column, skip, length)
    return _run(_core.fnn, "false nearest neighbours", progress, values, file, column, dt, params)


@_parameters("d2")
def d2(x, *, progress=None, dt=None, column=1, skip=0, length=None, **params):
    """Correlation sums C(eps, m), local slopes, the scaling region and the correlation dimension D2
    (``chaos d2``).

    C(eps, m) = #{(i, j): |i - j| > theiler, ||y_i - y_j|| < eps} / #{(i, j): |i - j| > theiler}, over
    the delay vectors y_i = (x_i, x_{i+tau}, ..., x_{i+(m-1)tau}), for m = min_dimension..max_dimension
    in one pass, exactly (box-assisted, kd-tree or brute-force search give identical counts) unless
    ``pairs_per_radius`` or ``reference_points`` ask for an estimate. ``inclusive=True`` counts
    ||y_i - y_j|| <= eps instead, as TISEAN's d2 does (``--inclusive``). Local slopes d ln C / d ln eps;
    the scaling region is the widest range of radii where the slopes of the highest
    ``saturation_dimensions`` dimensions agree within ``tolerance`` over a factor of at least
    ``min_plateau_ratio`` in eps; D2 is their mean there, with an interval. No lower dimension
    m >= 2 D2 + 1 may read a mean local slope over that plateau more than ``projection_tolerance`` above
    it (a projection cannot have a larger dimension; ``float('inf')`` turns the check off). A plateau below
    which, over three consecutive radii, every saturating dimension m reads a local slope more than
    ``noise_fill_fraction`` of the way from the plateau's slope to m (and not above m) is bounded by
    noise: status ``noise_limited``, ``noise_floor`` gives that radius, no D2 (``float('inf')`` turns
    the check off). Defaults: delay and theiler as ``analyze`` chooses them (the first
    mutual-information minimum; the longer of the 1/e time and half the dominant period, at least
    the delay; ``parameters`` names each rule), radii from range/1000 to range/4. P. Grassberger and I. Procaccia, Phys. Rev. Lett. 50, 346 (1983);
    J. Theiler, Phys. Rev. A 34, 2427 (1986). docs/reference/correlation_sum.md, docs/reference/correlation_dimension.md.

    The answer is ``r["estimate"]``: ``value``, ``interval``, ``status`` (``confident``, ``rough``
    or ``none``) and ``reason`` (docs/reference/statuses.md); the detailed ``status`` is its
    explanation.

    ``fast=True`` (``--fast``) is a quick look: two disjoint subsets of ``fast_start`` = 200
    reference points, one from each half of the record (with ``halves``), give a ``rough`` D2 with
    an interval that spans what they show. ``fast_budget`` (400 reference points in all) lets more
    rounds run; with ``fast_budget=0`` the subsets (drawn from the whole record, the halves counted
    after) double until they agree on one unambiguous plateau within ``fast_target``, or the counts
    so far answer ``rough`` from an eighth of the points
    (``fast["settled"]`` is False); the result's ``fast`` key gives the budget and the rounds
    (docs/reference/correlation_dimension.md). With a subset or a cap the result also has
    local_slope_error, d2_standard_error and slopes_too_uncertain (jackknife over groups of
    reference points).

    ``threads`` gives identical results for any number. ``progress=True`` draws a bar on stderr (or
    pass a callable taking the fraction done; with ``halves`` it starts again from 0 for each half of
    the record); Ctrl-C stops the sums within a thousandth of the work.

    Result keys: parameters, dimension, radius, correlation_sum (2-D), pairs (2-D), local_slope (2-D),
    d2_by_dimension, d2_by_dimension_interval, d2, d2_interval, d2_standard_error, scaling_region, plateaus,
    other_plateaus, noise_floor, smallest_scales, steepest_lower, saturated,
    status, explanation, takens_theiler, takens_theiler_error, eckmann_ruelle_limit,
    exceeds_eckmann_ruelle (and first_half, second_half with ``halves=True``; delay_variant with
    ``delay_check=True``, which requires a saturated D2 to be reproduced at twice the delay within
    ``delay_tolerance``, as ``chaos analyze`` does).

    ``halves=True`` (the default, as in ``chaos analyze``) counts the same sums over each half of the
    record: a saturated D2 that both halves do not reproduce gets status ``not_reproduced`` and no
    value (with ``fast=True`` the quick look's two subsets are the halves; with ``fast_budget=0`` each
    half gets the budget the rounds chose). ``halves=False`` gives the
    plain estimate.
    """
    values, file, column, dt = _series(x, dt, column, skip, length)
    bar = _progress_bar(progress, "correlation sums")
    try:
        return _make(_core.d2(values, file, column, dt, params, bar))
    finally:
        if bar is not None and not callable(progress):
            sys.stderr.write("\n")


correlation_sum = d2  # the correlation sums are part of d2's result (correlation_sum, pairs, radius)


@_parameters("lyapunov")
def lyapunov(x, *, progress=None, dt=None, column=1, skip=0, length=None, **params):
    """The largest Lyapunov exponent from the series (``chaos lyapunov``).

    ``delay``, ``theiler`` and ``dimension`` left out are chosen as ``analyze`` chooses them (the
    first mutual-information minimum; the longer of the 1/e time and half the dominant period, at
    least the delay; Cao's E1); ``parameters`` names each rule (``delay_source``, ...).

    Rosenstein: S(k) = < ln d_i(k) >, d_i(k) the distance after k steps of point i and its nearest
    neighbour (|i - n| > theiler); Kantz: S(k) = < ln < |x_{i+k} - x_{j+k}| >_{U_eps(i)} >. lambda is
    the slope of S(k) over the linear region found automatically (local slopes agreeing within
    ``tolerance`` in ``dimensions`` embedding dimensions m, m+1, ...), per sample, and per time unit
    when ``dt`` is given (then ``lambda`` is per time unit). M. T. Rosenstein, J. J. Collins,
    C. J. De Luca, Physica D 65, 117 (1993); H. Kantz, Phys. Lett. A 185, 77 (1994). docs/reference/lyapunov.md.

    The answer is ``r["estimate"]`` (this method) and ``r["lambda_1"]`` (Rosenstein, Kantz and the
    local maps combined, as ``analyze`` gives it; None with the checks off): ``value``, ``interval``
    (the spread over fit range, dimensions and estimators), ``status`` (``confident``: narrow and
    every check passed; ``rough``: a value, wider or with a check that disagrees; ``none``: no fit)
    and ``reason``. ``lambda`` and ``status`` below are the strict linear-region fit and its checks,
    the detailed evidence behind the answer.

    ``cross_check`` (default) also runs the other method with the same settings: a linear region it
    does not confirm within ``tolerance`` gives status ``unconfirmed`` and no value (the other
    method's verdict is under ``cross_check``). It also runs ``lyapunov_maps`` at the same m, delay,
    window and norm (at m + 1 where m is inconsistent, as ``analyze`` does; its verdict is under
    ``local_maps``): a slope more than ``tolerance`` from a consistent local-map exponent, or beside
    ``not_deterministic`` maps (noise at the neighbours' scale, which biases both curves low alike),
    is ``unconfirmed`` too. ``halves`` (default, as in ``analyze``) runs the
    estimator over each half of the record as well: a linear region that neither half shows, or that a
    half puts more than ``tolerance`` away, gives status ``not_reproduced``; ``halves=False`` gives the
    plain estimate.

    ``reference_points`` left out averages over at most 10^4 evenly spaced reference points, as
    ``analyze`` does; 0 uses every point.

    The result's key ``lambda`` is a Python keyword: read it as ``r.lambda_`` or ``r["lambda"]``.

    ``progress=True`` draws a bar on stderr (or pass a callable taking the fraction done; it starts
    from 0 again for each of the ``dimensions`` curves); Ctrl-C stops the curve within a block of
    reference points.
    """
    values, file, column, dt = _series(x, dt, column, skip, length)
    return _run(_core.lyapunov, "divergence curve", progress, values, file, column, dt, params)


@_parameters("lyapunov_maps")
def lyapunov_maps(x, *, dt=None, column=1, skip=0, length=None, **params):
    """The largest Lyapunov exponent from local linear maps (``chaos lyapunov-maps``).

    ``delay``, ``theiler`` and ``dimension`` left out are chosen as ``analyze`` chooses them (the
    first mutual-information minimum; the longer of the 1/e time and half the dominant period, at
    least the delay; Cao's E1); ``parameters`` names each rule (``delay_source``, ...).

    At points X_0, X_s, X_2s, ... of the delay embedding, an affine map from the ``neighbours``
    nearest neighbours (0: 5 m; outside the Theiler window) to their images ``step`` samples later
    (0: half the delay, at least 1), fitted on the neighbourhood's directions whose singular values
    are at least ``cutoff`` times the largest; a tangent vector goes through the maps and lambda is
    its mean log growth per sample (per time unit with ``dt``). Maps leaving more than
    ``max_residual`` of their image spread unexplained are not averaged. J.-P. Eckmann & D. Ruelle,
    Rev. Mod. Phys. 57, 617 (1985); M. Sano & Y. Sawada, Phys. Rev. Lett. 55, 1082 (1985).
    docs/reference/lyapunov-maps.md.

    A value is given only with status ``consistent``: the variants of the estimator's own choices
    (k = 3m and 8m, m + 1, half and twice the cutoff, twice the residual limit, the delay -+ tau/4
    when tau >= 2, the chain's halves) all lie within ``tolerance`` of the base (listed under
    ``variants``). Otherwise ``lambda`` is None and ``status`` (not_deterministic, not_positive,
    inconsistent) and ``explanation`` say why; a base that is not deterministic or not positive
    lists only itself and its halves, as no variant could change that status.

    The result's key ``lambda`` is a Python keyword: read it as ``r.lambda_`` or ``r["lambda"]``.
    """
    values, file, column, dt = _series(x, dt, column, skip, length)
    return _make(_core.lyapunov_maps(values, file, column, dt, params))


@_parameters("analyze")
def analyze(x=None, *, progress=None, dt=None, column=1, skip=0, length=None, **params):
    """The embedding parameters chosen and justified, then D2, lambda_1 and a nonlinearity test
    (``chaos analyze``).

    The library's automatic pipeline (chaos/automatic_analysis.hpp, the one ``chaos zoo`` validates):
    Theiler window = max(autocorrelation 1/e time, half the dominant period); delay 1 for a series
    decorrelated within a sample, else the first minimum of the mutual information up to ``max_delay``
    (else the autocorrelation's first zero crossing; where neither lies within ``max_delay``, both
    rules once more up to twice the Theiler window, so a finely sampled flow still gets one); embedding
    dimension where Cao's E1 saturates (unless E2 says stochastic), corroborated by false nearest
    neighbours; D2 with its scaling region, as one answer ``r["d2_estimate"]`` (``value``,
    ``interval``, ``status``, ``reason``, as for lambda_1); lambda_1 by Rosenstein and by Kantz over m..m+2 and by
    local maps, combined into one answer ``r["lambda_1"]`` with ``value``, ``interval``, ``status``
    (``confident`` / ``rough`` / ``none``) and ``reason`` (each method's own answer under
    ``lambda_estimate``, ``lambda_kantz_estimate``); a one-sided rank-order test against IAAFT surrogates (prediction error). ``delay_check=True``
    (``--delay-check``) also requires a saturated D2 to be reproduced at twice the delay within 0.05
    (the result's d2_delay_variant gives that D2). With ``x=None`` it analyses
    the built-in Lorenz x series (``builtin_length`` samples, dt = 0.01), as ``chaos analyze`` with no
    file does.

    ``progress=True`` draws a bar per step on stderr (the steps of the command's progress line:
    Cao's method, false nearest neighbours, correlation sums, the Lyapunov curves, the nonlinearity
    test), or pass a callable taking ``(step, fraction)``; Ctrl-C stops the step that is running at
    its next report (the mutual information and the autocorrelation, a fraction of a second, have
    none).
    """
    if x is None:
        values, builtin_dt = _core.builtin_series(params["builtin_length"])
        file, column, dt = _core.builtin_series_name, 1, builtin_dt
    else:
        values, file, column, dt = _series(x, dt, column, skip, length)
    bar = _step_bar(progress)
    try:
        json, evidence = _core.analyze(values, file, column, dt, params, bar)
        return _make(json, evidence=evidence)
    finally:
        if bar is not None and not callable(progress):
            sys.stderr.write("\n")


@_parameters("surrogates")
def surrogates(x, *, progress=None, dt=None, column=1, skip=0, length=None, **params):
    """FT, AAFT or IAAFT surrogate series (``chaos surrogates``).

    FT: the data's Fourier amplitudes with uniformly random phases (Theiler et al., Physica D 58, 77,
    1992); AAFT: a Gaussian series rank-ordered like the data, phase-randomised, rescaled to the data's
    values; IAAFT: alternately imposes the amplitudes and the values until a fixed point or
    ``max_iterations`` (Schreiber and Schmitz, Phys. Rev. Lett. 77, 635, 1996). Surrogate k uses the
    k-th draw of the seed's stream. ``end_match`` first trims the series to the segment whose ends
    match best (TISEAN endtoend). docs/reference/surrogates.md.

    Result keys: offset, length, status, iterations, spectral_deviation, surrogates (count x length).

    ``progress=True`` draws a bar on stderr (or pass a callable taking the fraction of all the
    surrogates done); Ctrl-C stops the IAAFT loop within one iteration.
    """
    values, file, column, dt = _series(x, dt, column, skip, length)
    return _run(_core.surrogates, "surrogates", progress, values, file, column, dt, params)


@_parameters("nonlinearity")
def nonlinearity(x, *, progress=None, dt=None, column=1, skip=0, length=None, **params):
    """Rank-order surrogate test for nonlinearity (``chaos nonlinearity``).

    The statistic (the locally constant predictor's error in a delay embedding, or the time-reversal
    asymmetry Q = <(x_{i+d} - x_i)^3> / <(x_{i+d} - x_i)^2>^(3/2)) of the data is ranked among
    ``count`` surrogates; the null hypothesis (a linear Gaussian process, measured through a monotonic
    function) is rejected at significance 1/(count+1) one-sided, 2/(count+1) two-sided, when the data
    rank first or last. Schreiber and Schmitz, Physica D 142, 346 (2000). docs/reference/nonlinearity_test.md.

    ``delay``, ``dimension`` and ``theiler`` left out are chosen on the data as ``analyze`` chooses
    them (the same embedding for the data and every surrogate); ``parameters`` names each rule.

    Result keys: statistic, statistic_name, surrogate_statistics, rank, count, below, above, ties,
    rejected, significance, surrogates_not_converged. Statistics within 1e-9 relative of the data's
    are ties (neither below nor above); a tie never rejects.

    ``progress=True`` draws a bar on stderr (or pass a callable taking the fraction of the surrogates
    done); Ctrl-C stops the surrogates' IAAFT loop within one iteration.
    """
    values, file, column, dt = _series(x, dt, column, skip, length)
    return _run(_core.nonlinearity, "nonlinearity test", progress, values, file, column, dt, params)


@_parameters("generate")
def generate(system, **params):
    """A series of a reference system or a zoo system (``chaos generate SYSTEM``).

    ``system``: lorenz, rossler, henon, logistic, ikeda, mackey_glass, sine, quasi_periodic,
    white_noise, uniform_noise, ar1, or one of the 47 zoo systems (``chaos generate --list``).
    ``parameter``: a dict of system parameters and sampling settings by name (``-p name=value``:
    ``{"rho": 28, "dt": 0.01}``); ``components``: "all" or a comma-separated list ("x,z"). Flows are
    integrated by RK4 at ``step`` and sampled every ``dt`` after ``transient``. docs/reference/systems.md.

    Result keys: parameters (every parameter and the sampling used, defaults included), components
    (a read-only mapping name -> array).
    """
    import types
    json, columns = _core.generate(system, params)
    arrays = {}
    for name, values in columns:
        values.flags.writeable = False
        arrays[name] = values
    return _make(json, {"components": types.MappingProxyType(arrays)})


@_parameters("spectrum")
def spectrum(system, **params):
    """The Lyapunov spectrum and the Kaplan-Yorke dimension of a system from its equations
    (``chaos spectrum SYSTEM``).

    Tangent dynamics with QR re-orthonormalisation every ``interval`` time units (flows, RK4 at
    ``step``, averaged over ``time`` after ``transient``) or ``map_interval`` iterations (maps,
    ``iterations`` after ``map_transient``): lambda_i = (1/T) sum ln |R_ii| (Benettin et al.,
    Meccanica 15, 9, 1980; Shimada and Nagashima, Prog. Theor. Phys. 61, 1605, 1979).
    D_KY = k + (lambda_1 + ... + lambda_k) / |lambda_{k+1}| (Kaplan and Yorke 1979). ``parameter``:
    model parameters by name (``-p``); ``identity``: zoo systems, also what the sum must equal;
    ``exponents``: delay systems, how many leading exponents. Defaults are each system's own.
    docs/reference/lyapunov_spectrum.md.

    Result keys: parameters, exponents, sum, kaplan_yorke_dimension, renormalisations,
    averaging_length, initial_state (and identity).
    """
    return _make(_core.spectrum(system, params))


@_parameters("density")
def density(parameter, value=None, *, column=1, value_column=2, skip=0, length=None, **params):
    """The density map of a bifurcation diagram (``chaos density``): the values observed at each
    parameter value (rows of (parameter, value), e.g. the stroboscopic samples of a sweep) as a
    density on common bins: a histogram with a fixed number of ``bins`` or the Freedman-Diaconis rule
    (width 2 IQR n^(-1/3) on the pooled values, at most ``max_bins``), or with ``kde=True`` a Gaussian
    kernel estimate (Silverman's bandwidth 0.9 min(s, IQR/1.34) n^(-1/5), or ``bandwidth``) averaged
    over each bin. The range is ``low``..``high`` or the pooled min/max widened by ``padding`` of the
    span on each side. docs/reference/poincare.md.

    ``parameter`` and ``value``: two 1-D arrays of the same length; or ``parameter`` the path of a file
    whose ``column`` holds the parameter and ``value_column`` the value (``-c``, ``-v``, ``-x``, ``-l``).

    Result keys: parameter, bin_centre, edges, density (parameters x bins), in_range (and bandwidth,
    kernel_mass with ``kde``).
    """
    if isinstance(parameter, (str, os.PathLike)):
        if value is not None:
            raise TypeError("density: give a file, or the parameter and value arrays")
        path = os.fspath(parameter)
        if value_column == column:
            raise ValueError(f"the value column ({value_column}) must differ from the parameter column (-c {column})")
        p_values, column, _ = _core.read(path, column, skip, length, None)
        v_values, value_column, _ = _core.read(path, value_column, skip, length, None)
        return _make(_core.density(p_values, v_values, path, column, value_column, params))
    if value is None:
        raise TypeError("density: the value array is missing")
    p_values, file, _, _ = _series(parameter, None)
    v_values, _, _, _ = _series(value, None)
    return _make(_core.density(p_values, v_values, file, 1, 2, params))


def _column_numbers(columns, name):
    if columns is None:
        return None
    if isinstance(columns, (int, np.integer)) and not isinstance(columns, bool):
        return [int(columns)]
    if isinstance(columns, (str, bytes)) or not hasattr(columns, "__iter__"):
        raise TypeError(f"{name} must be a column number or a list of them (got {type(columns).__name__})")
    return [int(c) if isinstance(c, np.integer) else c for c in columns]


@_parameters("section")
def section(data, *, skip=0, length=None, **params):
    """A Poincare section of a multi-column series (``chaos section``).

    Stroboscopic (``stroboscopic=P``): every P-th row from row ``phase``, x(t_0 + k P dt), the
    section of a system driven with a period of P rows. Hyperplane (``hyperplane=k, level=c``): the
    crossings of column k through x_k = c (``direction`` up, down or both), each located on the
    cubic through the four rows around it (Lagrange interpolation, error O(dt^4) for a smooth flow;
    linear in the first and last interval), every column interpolated there, and the return times
    t_{j+1} - t_j between crossings (H. Poincare, Les methodes nouvelles de la mecanique celeste,
    1899; the seed's Section 6). docs/reference/poincare.md.

    ``data``: a 2-D array of rows (a 1-D array is one column) or the path of a text file, read as
    the command reads it (``skip``, ``length``). ``columns``: the 1-based columns read (default:
    every column but ``time_column``); ``time_column``: the column holding the time (increasing,
    steps may be uneven), else rows are ``dt`` apart. The hyperplane column must be among
    ``columns``.

    Result keys: parameters, time, points (2-D: one row per section point, one column per column
    read), return_time (hyperplane; NaN for the first crossing).
    """
    time_column = params["time_column"]
    if isinstance(time_column, np.integer):
        time_column = params["time_column"] = int(time_column)
    params["columns"] = _column_numbers(params["columns"], "columns")
    if isinstance(data, (str, os.PathLike)):
        path = os.fspath(data)
        numbers, values, times = _core.section_file_columns(path, params, skip, length)
        params["columns"] = list(numbers)
        return _make(_core.section(values, times, path, params))
    if skip != 0 or length is not None:
        raise TypeError("skip and length select rows of a file; slice an array instead")
    a = np.asarray(data)
    if a.dtype.kind not in "iuf":
        raise TypeError(f"the series must hold real numbers (got an array of dtype {a.dtype})")
    if a.ndim == 1:
        a = a[:, np.newaxis]
    if a.ndim != 2:
        raise ValueError(f"section takes rows of columns: a 1-D or 2-D array (got shape {a.shape})")
    width = a.shape[1]

    def column(number, name):
        if isinstance(number, bool) or not isinstance(number, (int, np.integer)):
            raise TypeError(f"{name} must be an integer (got {type(number).__name__})")
        if not 1 <= number <= width:
            raise ValueError(f"{ARRAY_NAME}: {name} {number} requested but the array has {width} column(s) (1-based)")
        return np.ascontiguousarray(a[:, number - 1], dtype=np.float64)

    _core.check_section(params)  # the option checks first, as the command makes them
    numbers = params["columns"]
    if numbers is None:
        numbers = [c for c in range(1, width + 1) if c != time_column]
        if not numbers:
            raise ValueError(f"{ARRAY_NAME}: no data columns besides the time column")
    values = [column(c, "column") for c in numbers]
    times = column(time_column, "time_column") if time_column is not None else np.empty(0)
    params["columns"] = numbers
    return _make(_core.section(values, times, ARRAY_NAME, params))


@_parameters("validate")
def validate(filter=None, *, progress=None, **params):
    """Runs the reference cases of references/references.tsv on this machine (``chaos validate``).

    Each case regenerates its data from the row's conditions (system, parameters, N, seed), runs the
    estimator and checks that the measured value lies in the row's band [low, high], fixed before
    any run from the cited source (an analytic value, a published one or a peer tool's output;
    references/bibliography.md). ``filter``: only the cases whose id contains this text (a filter
    that matches no id raises ValueError). ``progress``: True for a bar on stderr, or a callable
    taking the fraction of cases done; Ctrl-C stops between cases.

    Returns the command's result: ``cases`` (one read-only mapping per case: id, system, quantity,
    value, low, high, measured, passed, seconds, source, kind, detail), ``passed``, ``failed``. A
    failed case is reported there, not raised (the command exits with 4).
    """
    bar = _progress_bar(progress, "validate")
    try:
        return _make(_core.validate(dict(params, filter=filter), bar))
    finally:
        if bar is not None and not callable(progress):
            sys.stderr.write("\n")


def validation_cases(filter=None):
    """The reference cases (``chaos validate --list``), without running them: a list of dicts with
    id, system, quantity, value (None where the source gives only a bound), low, high, source, kind."""
    return _core.validate_list(dict(filter=filter))


@_parameters("zoo")
def zoo(only=None, *, progress=None, **params):
    """The out-of-sample regression suite (``chaos zoo``): every chaotic system of the zoo and the
    controls (noise, IAAFT surrogates, random walks, periodic, quasi-periodic, noisy, quantised and
    short chaos) through the automatic pipeline of ``analyze``, each confident estimate judged
    against a band fixed in advance (chaos/models/include/chaos/models/zoo_suite.hpp): D2 within +-0.1 of the
    attractor's own D2 at the same N, Theiler window and scales (the plateau of its full state's
    correlation sums, from the equations, where another coding of the same samples reads it within
    0.1), else of a cited literature D2, else not above D_KY + 0.1
    (Kaplan and Yorke 1979, from the equations); lambda_1
    within 10% of lambda_1 from the equations (``spectrum``); noise, surrogates and random walks:
    no confident value; periodic and quasi-periodic signals: D2 equal to the torus dimension
    +-0.1 and no confident lambda_1. docs/validation/zoo.md is its report.

    ``only``: case names (a list, or a comma-separated string; default every case); ``fast``: the CI
    subset (4 systems and 5 controls at N = 10^4, automatic choices only); ``grid=False``: automatic
    choices only (``--no-grid``); ``grid_points``: grid points per chaotic system at N = 10^5, 1 to
    12 (``--grid-points``; 12: the whole grid); ``threads``: cases run in parallel (nothing depends on it).
    ``checkpoint``: a file path (``--checkpoint``): each finished case is appended to it and the
    cases it already holds are read instead of run, so that a stopped run resumes; the file belongs
    to one build and one choice of ``fast``, ``grid`` and ``grid_points``, and any other run refuses it.
    ``progress``: True for a bar on stderr, or a callable taking the fraction of cases done; Ctrl-C
    stops after the cases being run.

    Result keys: parameters, wrong (confident estimates outside their band: the command exits 4
    when there is one), chaotic, d2_covered, lambda_covered (the chaotic systems whose D2 answer, and whose lambda_1
    answer, is confident and in band at the automatic choices),
    wall_seconds (this run's), resumed (cases read from the checkpoint), rows (one mapping per row: case, kind, n, automatic, delay, dimension, theiler,
    theiler_factor, d2 / rosenstein / kantz / local_maps as value, interval, status, verdict and dimension
    (the m the estimate used where it is not the row's: the pipeline's local maps at m + 1), note,
    seconds, error), markdown (the report ``chaos zoo`` writes).
    """
    if isinstance(only, str):
        only = [name for name in only.split(",") if name]
    if params["checkpoint"] is not None:
        params["checkpoint"] = os.fspath(params["checkpoint"])
    bar = _progress_bar(progress, "zoo")
    try:
        return _make(_core.zoo(dict(params, only=None if only is None else list(only)), bar))
    finally:
        if bar is not None and not callable(progress):
            sys.stderr.write("\n")


@_parameters("zoo_series")
def zoo_series(name, **params):
    """The exact series a case of the zoo regression suite is analysed with (``chaos zoo --series
    NAME``; ``fast=True``: the CI subset's case at N = 10^4), so that any row of docs/validation/zoo.md can be
    reproduced with ``d2``, ``lyapunov`` or ``analyze``. ``name``: a case of docs/validation/zoo.md's first
    column (a zoo system such as ``lorenz``, or a control). ``threads``: the spectra behind the
    cases' bands, computed on that many threads (the series does not depend on it).

    Result keys: parameters (case, kind, description, N, dt), x (the series, a read-only array).
    """
    if not isinstance(name, str):
        raise TypeError(f"name must be a string (got {type(name).__name__})")
    json, values = _core.zoo_series(name, params)
    values.flags.writeable = False
    return _make(json, {"x": values})


def embed(x, dimension, delay=1):
    """The delay embedding y_i = (x_i, x_{i+tau}, ..., x_{i+(m-1)tau}), i = 0..N-(m-1)tau-1, as a read-only
    (N - (m-1) tau) x m array that views the series without copying it (docs/reference/embedding.md)."""
    values, _, _, _ = _series(x, None)
    points = _core.embedding_points(values, dimension, delay)
    view = np.lib.stride_tricks.as_strided(values, shape=(points, dimension),
                                           strides=(values.strides[0], values.strides[0] * delay), writeable=False)
    return view
