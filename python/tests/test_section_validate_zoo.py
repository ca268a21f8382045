"""section, validate, zoo and zoo_series against the command's output on the same data (the JSON is built by
the same code in both, chaos/commands/)."""
import json
import re

import numpy as np
import pytest

import chaos
from conftest import cli_json, run_cli


@pytest.fixture(scope="session")
def lorenz3(data_dir):
    """Lorenz x, y, z (three columns), written by `chaos generate`."""
    path = data_dir / "lorenz3.txt"
    path.write_text(run_cli("generate", "lorenz", "-l", 3000).stdout)
    return path


@pytest.fixture(scope="session")
def timed(lorenz3, data_dir):
    """Lorenz x, z with a time column first, its steps uneven (0.01 +- 0.002), as an adaptive
    integrator writes them."""
    rows = np.loadtxt(lorenz3)
    t = np.cumsum(0.01 + 0.002 * np.sin(np.arange(len(rows))))
    path = data_dir / "timed.txt"
    np.savetxt(path, np.column_stack([t, rows[:, 0], rows[:, 2]]), fmt="%.17g")
    return path


def as_array(expected):
    expected = json.loads(json.dumps(expected))
    expected["parameters"]["file"] = "(array)"
    return expected


@pytest.mark.parametrize("cli_args, kwargs", [
    (["--stroboscopic", 7, "--phase", 3], dict(stroboscopic=7, phase=3)),
    (["--hyperplane", 3, "--level", 27], dict(hyperplane=3, level=27.0)),
    (["--hyperplane", 3, "--level", 27, "--direction", "both", "--dt", 0.01],
     dict(hyperplane=3, level=27, direction="both", dt=0.01)),
    (["-c", "1,3", "--hyperplane", 3, "--level", 20, "--direction", "down"],
     dict(columns=[1, 3], hyperplane=3, level=20, direction="down")),
    (["--time-column", 1, "--hyperplane", 3, "--level", 25], dict(time_column=1, hyperplane=3, level=25)),
    (["--time-column", 1, "--stroboscopic", 9], dict(time_column=1, stroboscopic=9)),
])
def test_section_equals_the_command(lorenz3, timed, cli_args, kwargs):
    path = timed if "time_column" in kwargs else lorenz3
    expected = cli_json("section", path, *cli_args)
    assert chaos.section(path, **kwargs).to_dict() == expected
    rows = np.loadtxt(path)
    r = chaos.section(rows, **kwargs)
    assert r.to_dict() == as_array(expected)
    assert r.points.shape == (len(expected["time"]), len(expected["parameters"]["columns"]))
    np.testing.assert_array_equal(r.time, expected["time"])
    if "return_time" in expected:  # None (the first crossing) reads as NaN
        np.testing.assert_array_equal(r.return_time, [np.nan if t is None else t for t in expected["return_time"]])


def test_section_rows_skip_length_and_one_column(lorenz3):
    expected = cli_json("section", lorenz3, "-c", 2, "--stroboscopic", 5, "-x", 10, "-l", 100)
    assert chaos.section(lorenz3, columns=2, stroboscopic=5, skip=10, length=100).to_dict() == expected
    rows = np.loadtxt(lorenz3)[10:110]
    assert chaos.section(rows, columns=2, stroboscopic=5).to_dict() == as_array(expected)
    # A 1-D array is one column, numbered 1.
    one = as_array(expected)
    one["parameters"]["columns"] = [1]
    assert chaos.section(rows[:, 1], stroboscopic=5).to_dict() == one
    # A strided column of a Fortran-ordered array is converted once, with the same result.
    fortran = np.asfortranarray(np.loadtxt(lorenz3)[10:110])
    assert chaos.section(fortran, columns=[2], stroboscopic=5).to_dict() == as_array(expected)


@pytest.mark.parametrize("cli_args, kwargs", [
    (["--hyperplane", 3], dict(hyperplane=3)),
    (["--stroboscopic", 0], dict(stroboscopic=0)),
    (["--stroboscopic", 3, "--phase", 3], dict(stroboscopic=3, phase=3)),
    (["-c", 1, "--hyperplane", 3, "--level", 2], dict(columns=[1], hyperplane=3, level=2)),
    (["--hyperplane", 1, "--level", 0, "--direction", "sideways"], dict(hyperplane=1, level=0, direction="sideways")),
    (["--stroboscopic", 2, "--dt", -1], dict(stroboscopic=2, dt=-1.0)),
    ([], {}),
    (["--time-column", 1, "--hyperplane", 2, "--level", 0], dict(time_column=1, hyperplane=2, level=0)),  # x is no time
])
def test_section_refuses_what_the_command_refuses(lorenz3, cli_args, kwargs):
    p = run_cli("section", lorenz3, *cli_args, check=False)
    assert p.returncode == 3
    message = p.stderr.strip().split(": ", 2)[2]  # 'chaos: error [code]: MESSAGE'
    with pytest.raises(ValueError) as error:
        chaos.section(lorenz3, **kwargs)
    assert str(error.value) == message
    with pytest.raises(ValueError) as error:
        chaos.section(np.loadtxt(lorenz3), **kwargs)
    assert str(error.value) == message


@pytest.mark.parametrize("bad, error", [
    (np.array([[1.0, 2.0], [np.nan, 3.0], [4.0, 5.0]]), ValueError),
    (np.array([[1.0, np.inf]] * 5), ValueError),
    (np.empty((0, 2)), ValueError),
    (np.zeros((2, 2, 2)), ValueError),
    (np.array(["a", "b"]), TypeError),
])
def test_section_bad_arrays(bad, error):
    with pytest.raises(error):
        chaos.section(bad, stroboscopic=1)


def test_section_checks_the_options_before_the_data(tmp_path):
    """As the command: a missing section is named before a missing file or a bad column."""
    p = run_cli("section", tmp_path / "missing.txt", check=False)
    assert p.returncode == 3 and "choose one section" in p.stderr
    with pytest.raises(ValueError, match="choose one section"):
        chaos.section(tmp_path / "missing.txt")
    with pytest.raises(ValueError, match="choose one section"):
        chaos.section(np.zeros((5, 2)), columns=[7])


def test_section_takes_numpy_integers(lorenz3):
    expected = cli_json("section", lorenz3, "-c", "1,3", "--hyperplane", 3, "--level", 20)
    got = chaos.section(lorenz3, columns=np.array([1, 3]), hyperplane=np.int64(3), level=20)
    assert got.to_dict() == expected


def test_section_bad_column_numbers():
    rows = np.arange(20.0).reshape(10, 2)
    with pytest.raises(ValueError, match="requested but the array has 2 column"):
        chaos.section(rows, columns=[3], stroboscopic=1)
    with pytest.raises(TypeError):
        chaos.section(rows, columns=["x"], stroboscopic=1)
    with pytest.raises(TypeError):
        chaos.section(rows, stroboscopic=1.5)


def test_section_stroboscopic_formula():
    """Every P-th row from the phase, by the definition."""
    rows = np.column_stack([np.arange(50.0), np.arange(50.0) ** 2])
    r = chaos.section(rows, stroboscopic=7, phase=2)
    np.testing.assert_array_equal(r.points, rows[2::7])
    np.testing.assert_array_equal(r.time, np.arange(2, 50, 7, dtype=float))


FAST_CASES = "logistic.spectrum"  # analytic: ln 2 (a fraction of a second)


def without_seconds(result):
    for case in result["cases"]:
        assert case.pop("seconds") >= 0
    return result


def test_validate_equals_the_command():
    expected = cli_json("validate", "--filter", FAST_CASES)
    seen = []
    r = chaos.validate(FAST_CASES, progress=seen.append)
    assert without_seconds(r.to_dict()) == without_seconds(expected)
    assert r.passed == expected["passed"] and r.failed == 0 and len(r.cases) == r.passed
    assert seen == [(k + 1) / len(r.cases) for k in range(len(r.cases))]
    # The logistic map at r = 4: lambda = ln 2 exactly (Ulam and von Neumann), inside each band.
    for case in r.cases:
        assert case["low"] <= case["measured"] <= case["high"]


def test_validation_cases_are_the_command_s_list():
    rows = [line.split("\t") for line in run_cli("validate", "--list", "--filter", "henon").stdout.splitlines()
            if not line.startswith("#")]
    cases = chaos.validation_cases("henon")
    assert [c["id"] for c in cases] == [row[0] for row in rows]
    assert [c["quantity"] for c in cases] == [row[1] for row in rows]
    assert [c["source"] for c in cases] == [row[4] for row in rows]


def test_validate_refuses_a_filter_that_matches_nothing():
    p = run_cli("validate", "--filter", "no_such_case", check=False)
    assert p.returncode == 3
    with pytest.raises(ValueError) as error:
        chaos.validate("no_such_case")
    assert str(error.value) == p.stderr.strip().split(": ", 2)[2]
    with pytest.raises(TypeError):
        chaos.validate(3)


@pytest.mark.parametrize("name, fast", [("henon", True), ("lorenz", False)])
def test_zoo_series_equals_the_command(name, fast):
    args = ["zoo", "--series", name] + (["--fast"] if fast else [])
    expected = json.loads(run_cli(*args, "--json").stdout)
    r = chaos.zoo_series(name, fast=fast)
    assert r.to_dict() == expected
    assert r.parameters["N"] == len(r.x) and not r.x.flags.writeable
    # The text output holds the same values in full precision (%.17g reads back exactly).
    text = run_cli(*args).stdout
    np.testing.assert_array_equal(np.loadtxt(text.splitlines()), r.x)


def test_zoo_series_refuses_an_unknown_case():
    p = run_cli("zoo", "--series", "no_such_system", check=False)
    assert p.returncode == 3
    with pytest.raises(ValueError) as error:
        chaos.zoo_series("no_such_system")
    assert str(error.value) == p.stderr.strip().split(": ", 2)[2]
    with pytest.raises(ValueError, match="--threads must be at least 1"):
        chaos.zoo_series("henon", threads=0)


def masked(markdown):
    """The report without what differs between runs: the wall time and each system's seconds."""
    markdown = re.sub(r"Wall time: [0-9.e+-]+ s", "Wall time: T s", markdown)
    return re.sub(r"\| [0-9.e+-]+ \|$", "| S |", markdown, flags=re.M)


def test_zoo_equals_the_command():
    cases = ["henon", "white_noise", "torus2"]
    text = run_cli("zoo", "--fast", "--no-grid", "--only", ",".join(cases), "-q").stdout
    seen = []
    r = chaos.zoo(cases, fast=True, grid=False, progress=seen.append)
    assert masked(r.markdown) == masked(text)
    assert seen == [1 / 3, 2 / 3, 1.0]
    assert r.wrong == 0 and r.chaotic == 1 and r.parameters["only"] == tuple(cases)
    # One row per case at the automatic choices; the report's rows say the same.
    assert [row["case"] for row in r.rows] == cases and all(row["automatic"] for row in r.rows)
    henon = r.rows[0]
    line = next(line for line in text.splitlines() if line.startswith("| henon | 10000 |"))
    assert f"| {henon['delay']} | {henon['dimension']} | {henon['theiler']} |" in line
    assert henon["d2"]["status"] in line and henon["rosenstein"]["status"] in line
    # The verdicts follow the bands' rule: a confident value is in band or wrong, anything else unsure.
    for row in r.rows:
        for estimate in (row["d2"], row["rosenstein"], row["kantz"], row["local_maps"]):
            confident = estimate["status"] in ("saturated", "linear_region", "consistent")
            assert (estimate["verdict"] != "unsure") == confident


def test_zoo_checkpoint_resumes_and_belongs_to_one_build(tmp_path):
    path = tmp_path / "zoo.jsonl"
    first = chaos.zoo("random_walk", fast=True, checkpoint=path)
    assert first.resumed == 0 and first.parameters["checkpoint"] == str(path)
    seen = []
    second = chaos.zoo(["random_walk", "white_noise"], fast=True, checkpoint=path, progress=seen.append)
    # The stored case is read, not run: one case left to run, and its row is the first run's,
    # seconds included.
    assert second.resumed == 1 and seen == [1.0]
    walk = [row for row in second.to_dict()["rows"] if row["case"] == "random_walk"]
    assert walk == first.to_dict()["rows"]
    assert "the other 1 were read from a checkpoint" in second.markdown
    # The command is another build (another binary) than this module: it refuses the file, and
    # this module refuses the command's.
    before = path.read_bytes()
    p = run_cli("zoo", "--fast", "--only", "random_walk", "--checkpoint", str(path), "-q", check=False)
    assert p.returncode == 3 and "another build" in p.stderr and path.read_bytes() == before
    command_file = tmp_path / "command.jsonl"
    run_cli("zoo", "--fast", "--only", "random_walk", "--checkpoint", str(command_file), "-q")
    with pytest.raises(ValueError, match="another build or with other options"):
        chaos.zoo("random_walk", fast=True, checkpoint=command_file)


def test_zoo_refuses_what_the_command_refuses():
    p = run_cli("zoo", "--only", "no_such_case", "-q", check=False)
    assert p.returncode == 3
    with pytest.raises(ValueError) as error:
        chaos.zoo("no_such_case")
    assert str(error.value) == p.stderr.strip().split(": ", 2)[2]
    with pytest.raises(ValueError, match="--threads must be at least 1"):
        chaos.zoo("henon", threads=0)
    with pytest.raises(TypeError):
        chaos.zoo([1, 2])
