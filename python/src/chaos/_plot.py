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


def analyze(r, ax=None):
    """Cao's E1/E2 and the false-neighbour fraction (the evidence in the JSON), with the choices."""
    if ax is None:
        import matplotlib.pyplot as plt
        ax = plt.subplots(1, 2, figsize=(10, 3.6), constrained_layout=True)[1]
    left, right = ax
    if "cao" in r.keys():
        c = r["cao"]
        left.plot(c["dimension"], c["E1"], "o-", label="E1")
        left.plot(c["dimension"], c["E2"], "s-", label="E2")
        left.axhline(1.0, ls="--", color="gray")
        if r.embedding_dimension is not None:
            left.axvline(r.embedding_dimension, ls="--", color="black")
        left.legend(loc="lower right")
    left.set_title(f"Cao: m = {r.embedding_dimension}\ndelay {r.delay}, Theiler window {r.theiler}")
    left.set_xlabel("embedding dimension m")
    left.grid(True)
    if "fnn" in r.keys():
        f = r["fnn"]
        right.plot(f["dimension"], f["false_fraction"], "o-")
    d2 = f"D2 = {r.d2:.4g}" if r.d2 is not None else f"D2 {r.d2_status}"
    lam = r["lambda"]
    lyap = f"lambda = {lam:.4g}" if lam is not None else f"lambda {r.lambda_status}"
    right.set_title(f"false neighbours: m = {r.fnn_embedding_dimension}\n{d2}; {lyap}")
    right.set_xlabel("embedding dimension m")
    right.grid(True)
    return ax


def section(r, ax=None):
    """The section's points: the first two columns read against each other, or for one column the
    return map (value of point k against point k + 1)."""
    ax = _axes(ax)
    points = r.points
    columns = r.parameters["columns"].split(",")
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
