"""chaos.study.sweep against `study sweep` with the same options: the same files, byte for byte (the
same library code writes them), and the arrays equal to the command's tables read back."""
import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

from chaos import mechanism, study
from conftest import run_study

# The fast scene of tests/study/cli/run_cli_tests.sh: dopri5 at 1e-5 with a small sigma1 velocity.
FAST = ["joint.slider.friction.sigma1_velocity=1e-3", 'integrator.method="dopri5"',
        "integrator.relative_tolerance=1e-5"]
TABLES = ["spec.txt", "samples.tsv", "points.tsv"]


def sets(overrides):
    return [a for o in overrides for a in ("--set", o)]


def same_files(a, b, names):
    for name in names:
        assert (Path(a) / name).read_bytes() == (Path(b) / name).read_bytes(), name


def test_sweep_writes_the_command_s_files(tmp_path):
    args = ["--axis", "joint.slider.clearance=1e-4:4e-4:3", "--periods", 6, "--keep", 2, "--analysis",
            "--analysis-periods", 3, "--analysis-samples-per-period", 40, "--max-dimension", 6, "--threads", 1, "-q"]
    cli_summary = run_study("sweep", *sets(FAST), *args, "-o", tmp_path / "cli").stdout
    s = study.sweep(set=FAST, axis="joint.slider.clearance=1e-4:4e-4:3", periods=6, keep=2, analysis=True,
                    analysis_periods=3, analysis_samples_per_period=40, max_dimension=6, threads=2,
                    output=tmp_path / "py")
    same_files(tmp_path / "cli", tmp_path / "py", TABLES + ["analysis.tsv"])
    assert list(s.analysis["nonlinearity"]) == ["not asked"] * 3
    assert s.directory == str(tmp_path / "py")
    # The arrays are the command's table read back (np.loadtxt, an independent reader).
    table = np.loadtxt(tmp_path / "cli" / "samples.tsv")
    assert list(s.samples) == ["point", "joint.slider.clearance", "revolution", "t", "slider_y", "slider_vy"]
    for k, name in enumerate(s.samples):
        np.testing.assert_array_equal(s.samples[name], table[:, k])
    assert s.samples["point"].dtype == np.int64 and not s.samples["slider_y"].flags.writeable
    assert list(s.points["status"]) == ["completed"] * 3
    # The command's summary, key for key (its printed JSON), with the values of this run.
    cli = json.loads(cli_summary)
    assert set(s.summary) == set(cli)
    assert {k: v for k, v in s.summary.items() if k not in ("directory", "wall_seconds")} == dict(
        points=3, computed=3, resumed_from_disk=0, failed=0, analysis_failed=0, lyapunov_failed=0, threads=2, ranks=1)
    assert s.summary["directory"] == str(tmp_path / "py") and s.summary["wall_seconds"] > 0
    assert len(s.analysis["d2_status"]) == 3 and s.analysis["E1_6"].dtype == float


def test_two_axes_continuation_and_a_scene_object(tmp_path):
    scene = mechanism.default_scene().set("joint.slider.friction.sigma1_velocity", 1e-3)
    rest = FAST[1:]
    run_study("sweep", "--set", "joint.slider.friction.sigma1_velocity=0.001", *sets(rest),
              "--axis", "joint.slider.clearance=1e-4,3e-4", "--axis", "driver.speed_rpm=150,200",
              "--initial", "continuation", "--periods", 4, "--keep", 1, "--signals", "slider_y", "-q",
              "-o", tmp_path / "cli")
    s = study.sweep(scene, set=rest, axis={"joint.slider.clearance": "1e-4,3e-4", "driver.speed_rpm": "150,200"},
                    initial="continuation", periods=4, keep=1, signals="slider_y", output=tmp_path / "py")
    same_files(tmp_path / "cli", tmp_path / "py", TABLES)
    assert s.analysis is None and len(s.points["point"]) == 4
    np.testing.assert_array_equal(s.points["driver.speed_rpm"], [150, 150, 200, 200])


def test_temporary_directory_resume_and_refusals(tmp_path):
    kwargs = dict(set=FAST, axis="joint.slider.clearance=1e-4,2e-4", periods=3, keep=1)
    temporary = study.sweep(**kwargs)
    assert temporary.directory is None
    first = study.sweep(**kwargs, output=tmp_path / "a")
    for name in ("samples", "points"):
        for column in getattr(first, name):
            np.testing.assert_array_equal(getattr(temporary, name)[column], getattr(first, name)[column])
    # An existing directory: refused without resume (the command's message), resumed with it.
    p = run_study("sweep", *sets(FAST), "--axis", "joint.slider.clearance=1e-4,2e-4", "--periods", 3, "--keep", 1,
                  "-q", "-o", tmp_path / "a", check=False)
    assert p.returncode == 3
    with pytest.raises(ValueError) as error:
        study.sweep(**kwargs, output=tmp_path / "a")
    assert "study: " + str(error.value) == p.stderr.strip()
    os.remove(tmp_path / "a" / "points" / "000001.tsv")
    again = study.sweep(**kwargs, output=tmp_path / "a", resume=True)
    assert again.summary["computed"] == 1 and again.summary["resumed_from_disk"] == 1


@pytest.mark.parametrize("cli_args, kwargs", [
    (["--axis", "joint.slider.clearance=1e-4:2e-4"], dict(axis="joint.slider.clearance=1e-4:2e-4")),
    (["--periods", 5, "--keep", 6], dict(periods=5, keep=6)),
    (["--axis", "joint.slider.clearance=0,1e-4"], dict(axis="joint.slider.clearance=0,1e-4")),
    (["--signals", "slider_height"], dict(signals="slider_height")),
    (["--analysis", "--max-delay", 0], dict(analysis=True, max_delay=0)),
    (["--surrogates", 19], dict(surrogates=19)),
    (["--initial", "bogus"], dict(initial="bogus")),
    # The seed scene's phase space has 6 dimensions (the slider's 3 coordinates and their rates).
    (["--lyapunov", "--lyapunov-exponents", 7], dict(lyapunov=True, lyapunov_exponents=7)),
])
def test_refused_sweeps_raise_the_command_s_message(tmp_path, cli_args, kwargs):
    p = run_study("sweep", *cli_args, "-o", tmp_path / "cli", check=False)
    assert p.returncode == 3
    with pytest.raises(ValueError) as error:
        study.sweep(**kwargs, output=tmp_path / "py")
    assert p.stderr.strip().endswith(str(error.value))
    assert not (tmp_path / "py" / "points").exists()


def test_progress_reports_each_point():
    seen = []
    study.sweep(set=FAST, axis="joint.slider.clearance=1e-4,2e-4,3e-4", periods=2, keep=1, threads=1,
                progress=seen.append)
    assert seen == [1 / 3, 2 / 3, 1.0]


def test_ctrl_c_stops_a_sweep_after_the_point_being_computed(tmp_path):
    import _thread
    import threading
    import time
    # 40 points of 20 revolutions: several seconds uninterrupted (the test sweep of 3 points of 6
    # revolutions above takes about 0.15 s).
    timer = threading.Timer(0.3, _thread.interrupt_main)
    # CPU time, not wall time: the bound is on the work done between two checks for Ctrl-C, and on a
    # machine shared with other jobs the same work takes longer by the clock (the d2 test of
    # test_behaviour.py took 1.61 s in a CI run beside a two-thread `chaos zoo`).
    started = time.process_time()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        study.sweep(set=FAST, axis="joint.slider.clearance=1e-4:4e-4:40", periods=20, keep=1, threads=1,
                    output=tmp_path / "k")
    elapsed = time.process_time() - started
    timer.join()
    assert elapsed < 0.3 + 1.0
    finished = len(list((tmp_path / "k" / "points").glob("*.tsv")))
    assert 0 < finished < 40 and not (tmp_path / "k" / "samples.tsv").exists()


def test_a_sweep_into_a_full_file_system_raises_with_the_path_and_reason(tmp_path):
    """The sweep's files go through the commands' one safe writer (support/safe_output.hpp): a full
    file system (simulated by a 1 KiB file size limit, SIGXFSZ ignored, in a child process so
    that pytest's own files are not limited) raises ValueError naming the file and the system's
    reason, and leaves neither the file nor a temporary one."""
    import sys
    script = (
        "import resource, signal, sys\n"
        "from chaos import study\n"
        "signal.signal(signal.SIGXFSZ, signal.SIG_IGN)\n"
        "resource.setrlimit(resource.RLIMIT_FSIZE, (1024, resource.RLIM_INFINITY))\n"
        "try:\n"
        f"    study.sweep(set={FAST!r}, periods=4, keep=2, threads=1, output=sys.argv[1])\n"
        "except ValueError as e:\n"
        "    print(e)\n"
        "    sys.exit(7)\n")
    out = tmp_path / "full"
    p = subprocess.run([sys.executable, "-c", script, str(out)], capture_output=True, text=True)
    assert p.returncode == 7, p.stdout + p.stderr
    assert "spec.txt" in p.stdout and "File too large" in p.stdout, p.stdout
    left = [f.name for f in out.rglob("*")] if out.exists() else []
    assert "spec.txt" not in left and not any(".tmp." in f for f in left), left


def test_lyapunov_exponents_per_point_as_the_command_writes_them(tmp_path):
    # The keyword arguments of --lyapunov and its options come from the same table as the command's
    # options (study/commands/sweep_parameters.cpp): the same lyapunov.tsv, byte for byte.
    options = ["--periods", 12, "--keep", 1, "--lyapunov", "--lyapunov-periods", 10, "--lyapunov-exponents", 2,
               "--lyapunov-intervals", 20]
    run_study("sweep", *sets(FAST), *options, "-q", "-o", tmp_path / "cli")
    s = study.sweep(set=FAST, periods=12, keep=1, lyapunov=True, lyapunov_periods=10, lyapunov_exponents=2,
                    lyapunov_intervals=20, output=tmp_path / "py")
    same_files(tmp_path / "cli", tmp_path / "py", TABLES + ["lyapunov.tsv"])
    assert list(s.lyapunov["status"]) == ["completed"] and np.isfinite(s.lyapunov["lambda_2"]).all()
    assert s.summary["lyapunov_failed"] == 0
