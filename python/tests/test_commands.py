"""Each function's result equals the command's --json on the same data, bit for bit (the same
JSON-building code runs in both, chaos/commands/)."""
import json

import numpy as np
import pytest

import chaos
from conftest import as_array_run, cli_json


def check(function, path, cli_args, **kwargs):
    """Array and path input against `chaos <cli_args> path --json`."""
    expected = cli_json(*cli_args, path)
    values = chaos.read(path)[0]
    got = function(values, **kwargs)
    assert got.to_dict() == as_array_run(expected)
    assert function(path, **kwargs).to_dict() == expected
    # Attributes are the JSON's keys.
    for key, value in expected.items():
        if key == "parameters":
            continue
        attribute = got[key]
        if isinstance(value, list) and value and all(isinstance(v, (int, float)) and not isinstance(v, bool)
                                                     for v in value):
            np.testing.assert_array_equal(attribute, np.array(value, dtype=attribute.dtype))
    return got


def test_d2_the_issue_bar(lorenz_file):
    expected = cli_json("d2", lorenz_file, "-d", 1, "-m", 1, "-M", 4, "-t", 10)
    x = np.loadtxt(lorenz_file)
    r = chaos.d2(x, delay=1, min_dimension=1, max_dimension=4, theiler=10)
    assert r.to_dict() == as_array_run(expected)
    assert r.d2 == expected["d2"] and r.status == expected["status"]
    assert r.local_slope.shape == (4, 40)
    assert r.correlation_sum.shape == (4, 40)


@pytest.mark.parametrize("cli_args, kwargs", [
    ([], {}),
    (["-d", 10, "-M", 6, "--search", "kd", "-#", 20], dict(delay=10, max_dimension=6, search="kd", radii=20)),
    (["-d", 8, "-M", 5, "-t", 30, "--norm", "euclidean", "--halves", "--dt", 0.01],
     dict(delay=8, max_dimension=5, theiler=30, norm="euclidean", halves=True, dt=0.01)),
    (["-d", 8, "-M", 4, "--reference-points", 500, "--seed", 3, "-r", 0.5, "-R", 10],
     dict(delay=8, max_dimension=4, reference_points=500, seed=3, min_radius=0.5, max_radius=10)),
    (["-d", 8, "-M", 3, "--inclusive"], dict(delay=8, max_dimension=3, inclusive=True)),
    (["-d", 8, "-M", 5, "--no-halves"], dict(delay=8, max_dimension=5, halves=False)),
    (["-d", 8, "-M", 5, "--delay-check", "--delay-tolerance", 0.08],
     dict(delay=8, max_dimension=5, delay_check=True, delay_tolerance=0.08)),
    (["-d", 8, "-M", 4, "--fast", "--fast-start", 100, "--fast-target", 0.05],
     dict(delay=8, max_dimension=4, fast=True, fast_start=100, fast_target=0.05)),
])
def test_d2(lorenz_file, cli_args, kwargs):
    check(chaos.d2, lorenz_file, ["d2", *cli_args], **kwargs)


def test_d2_threads_give_the_command_result(lorenz_file):
    one = chaos.d2(lorenz_file, delay=10, max_dimension=5, threads=1).to_dict()
    check(chaos.d2, lorenz_file, ["d2", "-d", 10, "-M", 5, "--threads", 2], delay=10, max_dimension=5, threads=2)
    two = chaos.d2(lorenz_file, delay=10, max_dimension=5, threads=2).to_dict()
    assert two["parameters"].pop("threads") == 2 and one["parameters"].pop("threads") == 1
    assert one == two


@pytest.mark.parametrize("cli_args, kwargs", [
    ([], {}), (["-D", 40, "-b", 32, "--estimator", "equiprobable", "--dt", 0.01],
               dict(max_delay=40, boxes=32, estimator="equiprobable", dt=0.01))])
def test_mutual(lorenz_file, cli_args, kwargs):
    r = check(chaos.mutual, lorenz_file, ["mutual", *cli_args], **kwargs)
    assert r.first_minimum is None or r.first_minimum in list(r.delay)


@pytest.mark.parametrize("cli_args, kwargs", [([], {}), (["-D", 50, "--dt", 0.01], dict(max_lag=50, dt=0.01))])
def test_autocorrelation(lorenz_file, cli_args, kwargs):
    r = check(chaos.autocorrelation, lorenz_file, ["autocorrelation", *cli_args], **kwargs)
    assert r.autocorrelation[0] == 1.0  # r(0) = 1 by the formula


@pytest.mark.parametrize("cli_args, kwargs", [
    ([], {}), (["-d", 10, "-M", 6, "-t", 20, "--norm", "euclidean", "--level", 0.7, "--change", 0.2, "--sigmas", 3],
               dict(delay=10, max_dimension=6, theiler=20, norm="euclidean", level=0.7, change=0.2, sigmas=3))])
def test_cao(lorenz_file, cli_args, kwargs):
    check(chaos.cao, lorenz_file, ["cao", *cli_args], **kwargs)


@pytest.mark.parametrize("cli_args, kwargs", [
    ([], {}), (["-d", 10, "-m", 2, "-M", 6, "-t", 20, "--rtol", 15, "--atol", 1.5, "--norm", "max"],
               dict(delay=10, min_dimension=2, max_dimension=6, theiler=20, rtol=15, atol=1.5, norm="max"))])
def test_fnn(lorenz_file, cli_args, kwargs):
    check(chaos.fnn, lorenz_file, ["fnn", *cli_args], **kwargs)


@pytest.mark.parametrize("cli_args, kwargs", [
    (["-d", 10, "-m", 3], dict(delay=10, dimension=3)),
    (["-d", 10, "-m", 3, "--dt", 0.01, "--method", "kantz", "--threads", 2],
     dict(delay=10, dimension=3, dt=0.01, method="kantz", threads=2)),
])
def test_lyapunov(lorenz_file, cli_args, kwargs):
    r = check(chaos.lyapunov, lorenz_file, ["lyapunov", *cli_args], **kwargs)
    assert r.lambda_ is r["lambda"] or r.lambda_ == r["lambda"]


def test_lyapunov_henon(data_dir):
    r = check(chaos.lyapunov, data_dir / "henon.txt", ["lyapunov", "-m", 2], dimension=2)
    # The other method's verdict (the cross-check) comes with the result, as in the command's JSON.
    assert r["cross_check"]["method"] == "kantz"
    single = check(chaos.lyapunov, data_dir / "henon.txt", ["lyapunov", "-m", 2, "--no-cross-check"],
                   dimension=2, cross_check=False)
    assert single["cross_check"] is None and single["parameters"]["cross_check"] is False
    # The local-map check runs with the cross-check, as in analyze (clean Henon: consistent).
    assert r["local_maps"]["status"] == "consistent" and single["local_maps"] is None
    halves = check(chaos.lyapunov, data_dir / "henon.txt", ["lyapunov", "-m", 2, "--halves"], dimension=2, halves=True)
    assert halves["parameters"]["halves"] is True
    # The halves check is the default (as in analyze); halves=False is the command's --no-halves.
    assert r["parameters"]["halves"] is True and r.to_dict() == halves.to_dict()
    plain = check(chaos.lyapunov, data_dir / "henon.txt", ["lyapunov", "-m", 2, "--no-halves"], dimension=2, halves=False)
    assert plain["parameters"]["halves"] is False


@pytest.mark.parametrize("cli_args, kwargs", [
    (["-m", 2], dict(dimension=2)),
    (["-m", 3, "-d", 10, "-t", 40, "--dt", 0.01, "--step", 3, "-k", 20, "--cutoff", 0.2, "--max-residual", 0.5,
      "--tolerance", 0.1, "--norm", "euclidean", "--threads", 2],
     dict(dimension=3, delay=10, theiler=40, dt=0.01, step=3, neighbours=20, cutoff=0.2, max_residual=0.5,
          tolerance=0.1, norm="euclidean", threads=2)),
])
def test_lyapunov_maps(lorenz_file, cli_args, kwargs):
    r = check(chaos.lyapunov_maps, lorenz_file, ["lyapunov-maps", *cli_args], **kwargs)
    assert type(r).__name__ == "LyapunovMapsResult"
    # two delay variants (tau -+ tau/4) when tau >= 2
    assert r.variants[0]["name"] == "base" and len(r.variants) == (9 if r.parameters["delay"] == 1 else 11)


def test_lyapunov_maps_value_and_refusals():
    # Henon x at N = 2 10^4: lambda_1 = 0.4192 (Sprott 2003), within the CLI test's +-5%.
    x = chaos.generate("henon", length=20000, components="x").components["x"]
    r = chaos.lyapunov_maps(x, dimension=2)
    assert r.status == "consistent" and 0.3983 < r.lambda_ < 0.4402
    two = chaos.lyapunov_maps(x, dimension=2, threads=2).to_dict()
    two["parameters"]["threads"] = 1
    assert two == r.to_dict()  # identical to the last bit on any thread count
    with pytest.raises(ValueError, match="constant"):
        chaos.lyapunov_maps(np.ones(1000))
    with pytest.raises(ValueError, match="residual threshold"):
        chaos.lyapunov_maps(x, max_residual=2.0)


def test_analyze(lorenz_file):
    r = check(chaos.analyze, lorenz_file, ["analyze", "--dt", 0.01, "--test-length", 1024, "--surrogates", 9],
              dt=0.01, test_length=1024, surrogates=9)
    assert r.delay_source


def test_analyze_delay_check(lorenz_file):
    r = check(chaos.analyze, lorenz_file, ["analyze", "--dt", 0.01, "--test-length", 512, "--surrogates", 9,
                                           "--delay-check"],
              dt=0.01, test_length=512, surrogates=9, delay_check=True)
    # The check ran when D2 saturated at the chosen delay: its variant is at twice that delay.
    if r.d2_delay_variant is not None:
        assert r.d2_delay_variant["delay"] == 2 * r.delay


def test_analyze_noise(data_dir):
    check(chaos.analyze, data_dir / "noise.txt", ["analyze", "--test-length", 512], test_length=512)


def test_analyze_builtin():
    expected = cli_json("analyze", "--builtin-length", 5000, "--test-length", 512)
    assert chaos.analyze(builtin_length=5000, test_length=512).to_dict() == expected


def test_results_are_frozen(lorenz):
    r = chaos.autocorrelation(lorenz)
    with pytest.raises(AttributeError):
        r.decorrelation_time = 3
    with pytest.raises(ValueError):
        r.autocorrelation[0] = 2.0  # read-only array
    d = r.to_dict()
    d["lag"].clear()
    assert len(r.to_dict()["lag"]) == len(r.lag)  # to_dict() is a copy


def test_embed_is_a_view_with_the_library_layout(lorenz):
    y = chaos.embed(lorenz, 3, 5)
    assert y.shape == (len(lorenz) - 10, 3)
    assert np.shares_memory(y, lorenz)
    np.testing.assert_array_equal(y[7], [lorenz[7], lorenz[12], lorenz[17]])  # y_i = (x_i, x_{i+tau}, ...)
    with pytest.raises(ValueError):
        chaos.embed(lorenz[:5], 4, 2)
    with pytest.raises(ValueError):
        chaos.embed(lorenz, 0, 1)


@pytest.mark.parametrize("cli_args, kwargs", [
    ([], {}),
    (["--method", "aaft", "-n", 3, "--seed", 5], dict(method="aaft", count=3, seed=5)),
    (["--method", "iaaft", "-n", 2, "--max-iterations", 50, "--tolerance", 1e-6, "--end-match", "--max-trim", 0.2],
     dict(method="iaaft", count=2, max_iterations=50, tolerance=1e-6, end_match=True, max_trim=0.2)),
])
def test_surrogates(data_dir, cli_args, kwargs):
    r = check(chaos.surrogates, data_dir / "henon.txt", ["surrogates", *cli_args], **kwargs)
    assert r.surrogates.shape == (kwargs.get("count", 1), r.length)
    if kwargs.get("method", "iaaft") != "ft":  # AAFT and IAAFT surrogates are permutations of the data
        x = chaos.read(data_dir / "henon.txt")[0][r.offset:r.offset + r.length]
        np.testing.assert_array_equal(np.sort(r.surrogates[0]), np.sort(x))


@pytest.mark.parametrize("cli_args, kwargs", [
    (["-n", 9, "-m", 2], dict(count=9, dimension=2)),
    (["-n", 19, "--statistic", "time_reversal_asymmetry", "--alternative", "larger", "--method", "ft", "-d", 2,
      "--end-match"],
     dict(count=19, statistic="time_reversal_asymmetry", alternative="larger", method="ft", delay=2, end_match=True)),
])
def test_nonlinearity(data_dir, cli_args, kwargs):
    r = check(chaos.nonlinearity, data_dir / "henon.txt", ["nonlinearity", *cli_args], **kwargs)
    assert r.count == kwargs["count"] and len(r.surrogate_statistics) == kwargs["count"]


@pytest.mark.parametrize("cli_args, kwargs", [
    (["lorenz", "-l", 500], dict(length=500)),
    (["henon", "-l", 300, "--components", "x"], dict(length=300, components="x")),
    (["lorenz84", "-l", 200, "-p", "a=0.3"], dict(length=200, parameter={"a": 0.3})),
    (["white_noise", "-l", 50, "--seed", 2], dict(length=50, seed=2)),
    (["mackey_glass", "-l", 100, "-p", "tau=34"], dict(length=100, parameter={"tau": 34})),
])
def test_generate(cli_args, kwargs):
    expected = cli_json("generate", *cli_args)
    r = chaos.generate(cli_args[0], **kwargs)
    assert r.to_dict() == expected
    for name, values in expected["components"].items():
        np.testing.assert_array_equal(r.components[name], values)


@pytest.mark.parametrize("system, kwargs", [("nosuch", {}), ("lorenz", dict(length=0)),
                                            ("lorenz", dict(components="w")), ("lorenz", dict(parameter={"sigma": "x"}))])
def test_generate_refuses(system, kwargs):
    with pytest.raises((ValueError, TypeError)):
        chaos.generate(system, **kwargs)


def test_generate_refuses_with_the_command_s_message():
    from conftest import run_cli
    p = run_cli("generate", "mackey_glass", "-p", "tau=30", check=False)  # dt = 1 is no multiple of the step 30/170
    with pytest.raises(ValueError) as error:
        chaos.generate("mackey_glass", parameter={"tau": 30})
    assert p.returncode == 3 and p.stderr.strip() == f"chaos: error [invalid_parameter]: {error.value}"


@pytest.mark.parametrize("cli_args, kwargs", [
    (["henon", "--iterations", 20000], dict(iterations=20000)),
    (["logistic", "--iterations", 5000, "--seed", 3, "-p", "r=3.9"], dict(iterations=5000, seed=3, parameter={"r": 3.9})),
    (["lorenz", "--time", 50, "--transient", 10, "--interval", 0.2, "--step", 0.005],
     dict(time=50, transient=10, interval=0.2, step=0.005)),
    (["lozi", "--iterations", 10000, "--identity"], dict(iterations=10000, identity=True)),
    (["mackey_glass", "--time", 200, "--exponents", 2], dict(time=200, exponents=2)),
])
def test_spectrum(cli_args, kwargs):
    expected = cli_json("spectrum", *cli_args)
    r = chaos.spectrum(cli_args[0], **kwargs)
    assert r.to_dict() == expected
    assert r.sum == pytest.approx(sum(r.exponents), rel=1e-12, abs=1e-12)  # sum of the exponents, by definition


@pytest.mark.parametrize("system, kwargs", [("nosuch", {}), ("lorenz", dict(iterations=10)),
                                            ("henon", dict(time=10.0)), ("lorenz", dict(exponents=2))])
def test_spectrum_refuses_as_the_command(system, kwargs):
    with pytest.raises(ValueError):
        chaos.spectrum(system, **kwargs)


@pytest.fixture(scope="session")
def diagram_file(data_dir):
    """A bifurcation diagram of the logistic map: rows of (r, x) for 6 values of r, 300 samples each."""
    rows = []
    for r in np.linspace(3.5, 4.0, 6):
        x = cli_json("generate", "logistic", "-l", 300, "-p", f"r={r!r}")["components"]["x"]
        rows += [(r, v) for v in x]
    path = data_dir / "diagram.txt"
    np.savetxt(path, rows, fmt="%.17g")
    return path


@pytest.mark.parametrize("cli_args, kwargs", [
    ([], {}),
    (["-b", 30, "--low", 0, "--high", 1], dict(bins=30, low=0.0, high=1.0)),
    (["--kde", "--max-bins", 50, "--padding", 0.1], dict(kde=True, max_bins=50, padding=0.1)),
    (["--kde", "--bandwidth", 0.02, "-b", 40], dict(kde=True, bandwidth=0.02, bins=40)),
])
def test_density(diagram_file, cli_args, kwargs):
    expected = cli_json("density", diagram_file, *cli_args)
    assert chaos.density(diagram_file, **kwargs).to_dict() == expected
    rows = np.loadtxt(diagram_file)
    got = chaos.density(rows[:, 0], rows[:, 1], **kwargs)
    assert got.to_dict() == as_array_run(expected)
    assert got.density.shape == (6, len(got.bin_centre))


@pytest.mark.parametrize("kwargs", [dict(max_bins=0), dict(bandwidth=0.1), dict(low=0.0), dict(bins=0)])
def test_density_refuses(diagram_file, kwargs):
    with pytest.raises(ValueError):
        chaos.density(diagram_file, **kwargs)


def test_density_needs_equal_lengths():
    with pytest.raises(ValueError):
        chaos.density([1.0, 2.0, 3.0], [1.0, 2.0])


def test_left_out_choices_are_the_automatic_ones():
    # Called with the series alone, d2 chooses the delay and window as analyze does (chaos/choose.hpp)
    # and says which rule gave them. Lorenz x at dt 0.01, N = 2*10^4: D2 = 2.05 (Grassberger &
    # Procaccia 1983, references/references.tsv), within 0.1; the delay is analyze's.
    x = chaos.generate("lorenz", length=20000, components="x").components["x"]
    r = chaos.d2(x, dt=0.01)
    assert r.parameters["delay"] == chaos.analyze(x, dt=0.01).delay
    assert r.parameters["delay_source"] == "first mutual-information minimum"
    assert r.parameters["theiler"] >= r.parameters["delay"]
    assert r.d2 == pytest.approx(2.05, abs=0.1)


def test_mutual_searches_as_far_as_the_automatic_delay():
    # Lorenz x at dt 0.005: the information's first minimum lies near 0.16 time units, 14..20 samples
    # at dt 0.01 (references/references.tsv), so 28..40 samples here; without max_delay the search
    # reaches it (a fixed 20 lags did not) and, where a given range holds no minimum, says why.
    x = chaos.generate("lorenz", length=40000, parameter={"dt": 0.005}, components="x").components["x"]
    r = chaos.mutual(x)
    assert 28 <= r.first_minimum <= 40
    assert r.no_minimum is None
    short = chaos.mutual(x, max_delay=20)
    assert short.first_minimum is None
    assert "still falling" in short.no_minimum


def test_lambda_1_is_one_answer_with_an_interval_and_a_status():
    # Lorenz x at dt 0.01, N = 2*10^4, defaults only: lambda_1 = 0.9056 (Sprott 2003,
    # references/references.tsv), within 10% and confident (the bar of the answers); analyze and
    # lyapunov give the same answer, and its interval holds its value.
    x = chaos.generate("lorenz", length=20000, components="x").components["x"]
    a = chaos.analyze(x, dt=0.01)["lambda_1"]
    assert a["status"] == "confident", a["reason"]
    assert a["value"] == pytest.approx(0.9056, rel=0.1)
    assert a["interval"][0] <= a["value"] <= a["interval"][1]
    r = chaos.lyapunov(x, dt=0.01)
    for key in ("value", "status", "source"):
        assert r["lambda_1"][key] == a[key]
    assert list(r["lambda_1"]["interval"]) == list(a["interval"])
    assert r["estimate"]["status"] in ("confident", "rough")
    # Without the checks there is no combined answer and the method's own is rough at best.
    plain = chaos.lyapunov(x, dt=0.01, cross_check=False, halves=False)
    assert plain["lambda_1"] is None
    assert plain["estimate"]["status"] != "confident"


def test_d2_is_one_answer_with_an_interval_and_a_status():
    # Lorenz x at dt 0.01, N = 2*10^4, defaults only: D2 = 2.05 +- 0.01 (Grassberger & Procaccia
    # 1983, references/references.tsv), within 0.1 and confident; analyze and d2 answer in the same
    # shape, and the interval holds the value. White noise has no D2: the answer is none, never a
    # value (its D2(m) follows m).
    x = chaos.generate("lorenz", length=20000, components="x").components["x"]
    a = chaos.analyze(x, dt=0.01)["d2_estimate"]
    assert a["status"] == "confident", a["reason"]
    assert a["value"] == pytest.approx(2.05, abs=0.1)
    assert a["interval"][0] <= a["value"] <= a["interval"][1]
    r = chaos.d2(x, dt=0.01)
    assert r["estimate"]["status"] == "confident"
    assert r["estimate"]["value"] == pytest.approx(r["d2"])
    noise = np.random.default_rng(4).standard_normal(5000)
    n = chaos.d2(noise, delay=1, theiler=0)["estimate"]
    assert n["status"] == "none" and n["value"] is None, n


def test_a_transformed_linear_oscillation_is_not_called_deterministic():
    # A linear stochastic oscillation (AR(2), poles at radius 0.98, period 40 samples) seen through
    # the static nonlinearity atan(x / 80): Cao's E2 departs from 1 (max|E2 - 1| about 0.23), as for
    # a deterministic series, but the IAAFT surrogates share its spectrum and amplitude distribution,
    # so the surrogate test does not reject and analyze does not claim determinism. (The test's
    # significance is 5%: about one seed in 20 would reject by chance; this seed does not.) Lorenz x
    # is deterministic by both.
    rng = np.random.default_rng(1)
    a1, a2 = 2 * 0.98 * np.cos(2 * np.pi / 40), -0.98 ** 2
    x = np.zeros(6000)
    e = rng.standard_normal(6000)
    for t in range(2, 6000):
        x[t] = a1 * x[t - 1] + a2 * x[t - 2] + e[t]
    r = chaos.analyze(np.arctan(x[1000:] / 80))
    assert r["max_E2_deviation"] > 0.1 and not r["stochastic"]
    assert r["nonlinearity"]["rejected"] is False
    assert r["determinism"] == "not_shown", r["determinism_explanation"]
    lorenz = chaos.generate("lorenz", length=20000, components="x").components["x"]
    assert chaos.analyze(lorenz, dt=0.01)["determinism"] == "deterministic"
