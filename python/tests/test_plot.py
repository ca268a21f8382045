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



def test_analyze_plot_has_the_command_s_four_panels(lorenz):
    a = chaos.analyze(lorenz, dt=0.01, test_length=512, surrogates=9)
    (mi, cao), (fnn, d2) = a.plot()
    # The information curve the delay was read from: chaos analyze computes it up to
    # min(max_delay, N/10) with its boxes (chaos/commands/invariant_commands.cpp), i.e. chaos.mutual.
    expected = chaos.mutual(lorenz, max_delay=min(100, len(lorenz) // 10), boxes=16)
    np.testing.assert_array_equal(mi.lines[0].get_ydata(), expected.mutual_information)
    assert a.delay in list(mi.lines[0].get_xdata())
    np.testing.assert_array_equal(cao.lines[0].get_ydata(), a["cao"]["E1"])
    np.testing.assert_array_equal(cao.lines[1].get_ydata(), a["cao"]["E2"])
    np.testing.assert_array_equal(fnn.lines[0].get_ydata(), a["fnn"]["false_fraction"])
    assert fnn.lines[1].get_ydata()[0] == 0.01  # the FNN threshold, FnnOptions' default
    # The local slopes of the D2 step: correlation sums for m = 1 .. m + 3 at the chosen delay and
    # Theiler window over 40 radii from range/1000 to range/4 (automatic_analysis.hpp), which are
    # chaos.d2's defaults.
    slopes = chaos.d2(lorenz, delay=a.delay, max_dimension=a.embedding_dimension + 3, theiler=a.theiler).local_slope
    curves = [line for line in d2.lines if line.get_label().startswith("m=")]
    assert len(curves) == a.embedding_dimension + 3
    for line, expected_row in zip(curves, slopes):
        np.testing.assert_array_equal(line.get_ydata(), expected_row)
    assert d2.get_title().startswith(a.d2_status)
    assert "mutual" not in a.keys() and "local_slope" not in a.keys()


def test_analyze_plot_says_what_did_not_run(data_dir):
    noise = chaos.read(data_dir / "noise.txt")[0]
    a = chaos.analyze(noise, test_length=512, surrogates=9)
    assert a.d2_status == "not_run"  # white noise: Cao's E2 says stochastic, D2 is not run
    (mi, cao), (fnn, d2) = a.plot()
    assert d2.texts and d2.texts[0].get_text().startswith("not run: ")
    assert len(cao.lines) >= 2


def test_section_plot_and_a_command_without_figure():
    rows = np.column_stack([np.sin(np.arange(200) * 0.1), np.cos(np.arange(200) * 0.1)])
    r = chaos.section(rows, stroboscopic=7)
    ax = r.plot()
    np.testing.assert_array_equal(ax.lines[0].get_xdata(), rows[::7, 0])  # every 7th row, by definition
    np.testing.assert_array_equal(ax.lines[0].get_ydata(), rows[::7, 1])
    one = chaos.section(rows[:, 0], stroboscopic=7).plot()  # one column: the return map
    np.testing.assert_array_equal(one.lines[0].get_xdata(), rows[::7, 0][:-1])
    np.testing.assert_array_equal(one.lines[0].get_ydata(), rows[::7, 0][1:])
    with pytest.raises(TypeError, match="has no figure"):
        chaos.zoo_series("henon", fast=True).plot()
