"""The commands' figures with matplotlib (result.plot(ax=None)); each returns the axes it drew on."""
import numpy as np


def _axes(ax, count=1):
    import matplotlib.pyplot as plt
    if ax is not None:
        return ax
    if count == 1:
        return plt.subplots()[1]
    return plt.subplots(count, 1, figsize=(6.4, 2.6 * count), constrained_layout=True)[1]


def _pair(ax):
    """Two axes (top, bottom): given as a pair, or a new figure; a single axis draws the bottom panel only."""
    if ax is None:
        return tuple(_axes(None, 2))
    if isinstance(ax, (list, tuple, np.ndarray)):
        return tuple(ax)[:2]
    return None, ax


def mutual(r, ax=None):
    ax = _axes(ax)
    scale = r.parameters["dt"] or 1.0
    tau = r.delay * scale
    ax.plot(tau, r.mutual_information, "o-", ms=3, label="I(tau)")
    if r.first_minimum is not None:
        k = list(r.delay).index(r.first_minimum)
        ax.axvline(tau[k], ls="--", color="gray")
        ax.plot(tau[k], r.mutual_information[k], "o", mfc="none", ms=10, label="first minimum")
    ax.set_xlabel("delay tau (time units)" if r.parameters["dt"] else "delay tau (samples)")
    ax.set_ylabel("I(tau) (nats)")
    ax.set_title(f"average mutual information: first minimum at tau = {r.first_minimum}")
    ax.grid(True)
    ax.legend()
    return ax


def autocorrelation(r, ax=None):
    ax = _axes(ax)
    scale = r.parameters["dt"] or 1.0
    ax.plot(r.lag * scale, r.autocorrelation, lw=2, label="r(lag)")
    ax.axhline(np.exp(-1), ls="--", color="gray")
    if r.decorrelation_time is not None:
        ax.axvline(r.decorrelation_time * scale, ls="--", color="gray")
        ax.plot(r.decorrelation_time * scale, np.exp(-1), "o", mfc="none", ms=10, label="1/e crossing")
    ax.set_ylim(-1, 1)
    ax.set_xlabel("lag (time units)" if r.parameters["dt"] else "lag (samples)")
    ax.set_ylabel("r(lag)")
    ax.set_title(f"autocorrelation: 1/e time {r.decorrelation_time}, first zero crossing {r.first_zero_crossing}")
    ax.grid(True)
    ax.legend()
    return ax


def cao(r, ax=None):
    ax = _axes(ax)
    ax.plot(r.dimension, r.E1, "o-", label="E1")
    ax.plot(r.dimension, r.E2, "s-", label="E2")
    ax.axhline(1.0, ls="--", color="gray")
    if r.embedding_dimension is not None:
        ax.axvline(r.embedding_dimension, ls="--", color="black")
    what = (f"E1 saturates at m = {r.embedding_dimension}" if r.embedding_dimension is not None
            else "none, E2 stays near 1 (stochastic)" if r.stochastic else "none, E1 does not settle")
    ax.set_title(f"Cao's method: {what}")
    ax.set_xlabel("embedding dimension m")
    ax.set_ylabel("E1(m), E2(m)")
    ax.grid(True)
    ax.legend(loc="lower right")
    return ax


def fnn(r, ax=None):
    ax = _axes(ax)
    threshold = r.parameters["threshold"]
    ax.plot(r.dimension, r.false_fraction, "o-", label="false fraction")
    ax.axhline(threshold, ls="--", color="gray")
    if r.embedding_dimension is not None:
        ax.axvline(r.embedding_dimension, ls="--", color="black")
    ax.set_ylim(bottom=0)
    ax.set_title(f"false nearest neighbours: m = {r.embedding_dimension}")
    ax.set_xlabel("embedding dimension m")
    ax.set_ylabel("false nearest neighbours (fraction)")
    ax.grid(True)
    return ax


def d2(r, ax=None):
    top, bottom = _pair(ax)
    if top is not None:
        for m, c in zip(r.dimension, r.correlation_sum):
            keep = c > 0
            top.loglog(r.radius[keep], c[keep], "o-", ms=2, label=f"m={m}")
        top.set_xlabel("eps")
        top.set_ylabel("C(eps, m)")
        top.set_title("correlation sums")
        top.grid(True)
        top.legend(fontsize="small", ncol=2)
    for m, s in zip(r.dimension, r.local_slope):
        bottom.semilogx(r.radius, s, "o-", ms=2, label=f"m={m}")
    if r.scaling_region is not None and not np.isnan(r.scaling_region).any():
        bottom.axvspan(*r.scaling_region, color="#dddddd", zorder=0)
    title = r.status
    if r.d2 is not None:
        bottom.axhline(r.d2, ls="--", color="black")
        title += f": D2 = {r.d2:.4g} in [{r.d2_interval[0]:.4g}, {r.d2_interval[1]:.4g}]"
    bottom.set_title(title)
    bottom.set_xlabel("eps")
    bottom.set_ylabel("d ln C / d ln eps")
    bottom.grid(True)
    return (top, bottom) if top is not None else bottom


def lyapunov(r, ax=None):
    top, bottom = _pair(ax)
    dt = r.parameters["dt"]
    t = r.step * (dt or 1.0)
    unit = "time unit" if dt else "sample"
    lam = r["lambda"]
    if top is not None:
        top.plot(t, r.divergence, "o-", ms=2, label="divergence")
        if r.region is not None and not np.isnan(r.region).any():
            first, last = (int(v) for v in r.region)
            top.axvspan(first * (dt or 1.0), last * (dt or 1.0), color="#dddddd", zorder=0)
            k = np.arange(first, last + 1)
            ok = ~np.isnan(r.divergence[k])
            slope = r.lambda_per_sample
            intercept = np.mean(r.divergence[k][ok]) - slope * np.mean(k[ok])
            top.plot(np.array([first, last]) * (dt or 1.0), intercept + slope * np.array([first, last]), lw=2,
                     label="fit")
        top.set_xlabel("time" if dt else "step (samples)")
        top.set_ylabel("divergence")
        top.set_title(f"{r.parameters['method']} divergence: {r.status}"
                      + (f", lambda = {lam:.4g} per {unit}" if lam is not None else ""))
        top.grid(True)
        top.legend()
    bottom.plot(t, r.local_slope / (dt or 1.0), "o-", ms=2)
    if lam is not None:
        bottom.axhline(lam, ls="--", color="black")
    bottom.set_xlabel("time" if dt else "step (samples)")
    bottom.set_ylabel(f"local slope (per {unit})")
    bottom.set_title("local slopes")
    bottom.grid(True)
    return (top, bottom) if top is not None else bottom


def _not_run(ax, title, why):
    """An empty panel that says why it has nothing to show (as the command's plot does)."""
    ax.set_title(title)
    ax.text(0.5, 0.5, f"not run: {why[:57] + '...' if len(why) > 60 else why}", ha="center", va="center",
            transform=ax.transAxes)
    ax.set_xticks([])
    ax.set_yticks([])


def analyze(r, ax=None):
    """The evidence, a panel each, as ``chaos analyze --plot`` draws it: I(tau) with the delay chosen,
    Cao's E1 and E2 with the dimension, the false-neighbour fraction, and the local slopes of the
    correlation sums with the scaling region and D2. ``ax``: four axes (a 2 x 2 array or a list),
    or None for a new figure."""
    if ax is None:
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(2, 2, figsize=(11, 7.5), constrained_layout=True)
        fig.suptitle("chaos analyze: the evidence")
    mi_ax, cao_ax, fnn_ax, d2_ax = np.asarray(ax, dtype=object).reshape(-1)[:4]
    evidence = r._evidence
    stopped = r.stopped if r.stationary else "non-stationary series (see stationarity)"
    stopped = stopped or "not run"
    # Mutual information.
    if "mutual" in evidence:
        mi = evidence["mutual"]
        delay, info = np.asarray(mi["delay"]), np.asarray(mi["mutual_information"], dtype=float)
        mi_ax.plot(delay, info, "o-", ms=3, label="I(tau)")
        if r.delay is not None:
            mi_ax.axvline(r.delay, ls="--", color="gray")
            k = np.flatnonzero(delay == r.delay)
            if k.size:
                mi_ax.plot(delay[k], info[k], "o", mfc="none", ms=10, label="delay")
        mi_ax.set_xlabel("delay tau (samples)")
        mi_ax.set_ylabel("I(tau) (nats)")
        mi_ax.set_title(f"mutual information: delay {r.delay if r.delay is not None else 'none'}")
        mi_ax.grid(True)
        mi_ax.legend()
    else:
        _not_run(mi_ax, "mutual information", stopped)
    # Cao.
    if "cao" in r.keys():
        c = r["cao"]
        cao_ax.plot(c["dimension"], c["E1"], "o-", label="E1")
        cao_ax.plot(c["dimension"], c["E2"], "s-", label="E2")
        cao_ax.axhline(1.0, ls="--", color="gray")
        if r.embedding_dimension is not None:
            cao_ax.axvline(r.embedding_dimension, ls="--", color="black")
        m = (r.embedding_dimension if r.embedding_dimension is not None
             else "none (stochastic)" if r.stochastic else "none (not saturated)")
        cao_ax.set_title(f"Cao: m = {m}")
        cao_ax.set_xlabel("embedding dimension m")
        cao_ax.set_ylabel("E1(m), E2(m)")
        cao_ax.grid(True)
        cao_ax.legend(loc="lower right")
    else:
        _not_run(cao_ax, "Cao", stopped)
    # False nearest neighbours.
    if "fnn" in r.keys():
        f = r["fnn"]
        fnn_ax.plot(f["dimension"], f["false_fraction"], "o-", label="false fraction")
        if "fnn_threshold" in evidence:
            fnn_ax.axhline(evidence["fnn_threshold"], ls="--", color="gray")
        if r.fnn_embedding_dimension is not None:
            fnn_ax.axvline(r.fnn_embedding_dimension, ls="--", color="black")
        fnn_ax.set_ylim(bottom=0)
        m = r.fnn_embedding_dimension if r.fnn_embedding_dimension is not None else "none"
        fnn_ax.set_title(f"false nearest neighbours: m = {m}")
        fnn_ax.set_xlabel("embedding dimension m")
        fnn_ax.set_ylabel("false nearest neighbours (fraction)")
        fnn_ax.grid(True)
    else:
        _not_run(fnn_ax, "false nearest neighbours", stopped)
    # D2: local slopes.
    d = evidence.get("d2")
    slopes = None
    if d is not None:
        slopes = np.array([[np.nan if v is None else v for v in row] for row in d["local_slope"]], dtype=float)
    if slopes is not None and slopes.size and not np.isnan(slopes).all():
        radius = np.asarray(d["radius"], dtype=float)
        for m, row in zip(d["dimension"], slopes):
            if not np.isnan(row).all():
                d2_ax.semilogx(radius, row, "o-", ms=2, label=f"m={m}")
        if d["scaling_region"] is not None:
            d2_ax.axvspan(*d["scaling_region"], color="#dddddd", zorder=0)
        title = r.d2_status
        if r.d2 is not None:
            d2_ax.axhline(r.d2, ls="--", color="black")
            title += f": D2 = {r.d2:.4g}"
        d2_ax.set_title(title)
        d2_ax.set_xlabel("eps")
        d2_ax.set_ylabel("d ln C / d ln eps")
        d2_ax.grid(True)
        d2_ax.legend(fontsize="small", ncol=2)
    else:
        _not_run(d2_ax, "correlation dimension", "no local slopes" if d is not None else stopped)
    return np.asarray([[mi_ax, cao_ax], [fnn_ax, d2_ax]], dtype=object)


def section(r, ax=None):
    """The section's points: the first two columns read against each other, or for one column the
    return map (value of point k against point k + 1)."""
    ax = _axes(ax)
    points = r.points
    columns = [str(int(c)) for c in np.atleast_1d(r.parameters["columns"])]
    if points.ndim == 2 and points.shape[1] >= 2:
        ax.plot(points[:, 0], points[:, 1], "o", ms=2)
        ax.set_xlabel(f"column {columns[0]}")
        ax.set_ylabel(f"column {columns[1]}")
    else:
        x = points.reshape(-1)
        ax.plot(x[:-1], x[1:], "o", ms=2)
        ax.set_xlabel(f"column {columns[0]} at point k")
        ax.set_ylabel(f"column {columns[0]} at point k + 1")
    ax.set_title(f"{r.parameters['section']} section: {r.parameters['points']} points")
    ax.grid(True)
    return ax
