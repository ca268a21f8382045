"""result.plot() draws the command's figure from the result's own values (matplotlib, Agg)."""
import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

import chaos  # noqa: E402


@pytest.fixture(autouse=True)
def close_figures():
    yield
    plt.close("all")


def test_mutual_plot(lorenz):
    r = chaos.mutual(lorenz, max_delay=30)
    ax = r.plot()
    np.testing.assert_array_equal(ax.lines[0].get_ydata(), r.mutual_information)


def test_autocorrelation_cao_fnn_plots(lorenz):
    r = chaos.autocorrelation(lorenz, dt=0.01)
    np.testing.assert_array_equal(r.plot().lines[0].get_ydata(), r.autocorrelation)
    c = chaos.cao(lorenz, delay=10, max_dimension=6)
    ax = c.plot()
    np.testing.assert_array_equal(ax.lines[0].get_ydata(), c.E1)
    np.testing.assert_array_equal(ax.lines[1].get_ydata(), c.E2)
    f = chaos.fnn(lorenz, delay=10, max_dimension=6)
    np.testing.assert_array_equal(f.plot().lines[0].get_ydata(), f.false_fraction)


def test_d2_plot_two_panels_or_one(lorenz):
    r = chaos.d2(lorenz, delay=10, max_dimension=5)
    top, bottom = r.plot()
    assert len(top.lines) == 5 and len(bottom.lines) >= 5
    np.testing.assert_array_equal(bottom.lines[2].get_ydata(), r.local_slope[2])
    _, ax = plt.subplots()
    assert r.plot(ax=ax) is ax


def test_lyapunov_and_analyze_plots(lorenz):
    r = chaos.lyapunov(lorenz, delay=10, dimension=3, dt=0.01)
    top, bottom = r.plot()
    np.testing.assert_array_equal(top.lines[0].get_ydata(), r.divergence)
    a = chaos.analyze(lorenz, dt=0.01, test_length=512, surrogates=9)
    left, right = a.plot()
    np.testing.assert_array_equal(left.lines[0].get_ydata(), a["cao"]["E1"])
