"""Shared fixtures: the `chaos` command built from the same checkout (CHAOS_CLI, or <repo>/build/chaos/chaos)
gives the expected values; series are written by `chaos generate` into a temporary directory."""
import json
import os
import signal
import subprocess
from pathlib import Path

import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[2]
CLI = Path(os.environ.get("CHAOS_CLI", REPO / "build" / "chaos" / "chaos"))
STUDY = Path(os.environ.get("STUDY_CLI", CLI.parent.parent / "study" / "study"))


@pytest.fixture(scope="session", autouse=True)
def ctrl_c_raises():
    """Ctrl-C raises KeyboardInterrupt, as in any interactive Python. A process started in the
    background by a non-interactive shell (`cmd &`, nohup, some CI runners) inherits SIGINT ignored;
    Python then installs no handler, and _thread.interrupt_main(), which the Ctrl-C tests use to
    press Ctrl-C, does nothing (its documented behaviour for an ignored signal). Every Ctrl-C test
    failed that way with DID NOT RAISE when the suite ran under `nohup ... &`."""
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, previous)


def _run(tool, variable, args, check):
    name = tool.name  # "chaos" or "study"
    if not tool.exists():
        pytest.skip(f"the {name} command is not built at {tool} (set {variable})")
    p = subprocess.run([str(tool), *map(str, args)], capture_output=True, text=True)
    if check and p.returncode != 0:
        raise AssertionError(f"{name} {' '.join(map(str, args))} failed ({p.returncode}): {p.stderr}")
    return p


def run_cli(*args, check=True):
    """Runs the chaos command; returns the CompletedProcess."""
    return _run(CLI, "CHAOS_CLI", args, check)


def run_study(*args, check=True):
    """Runs the study command (STUDY_CLI, or beside the chaos command's build); returns the CompletedProcess."""
    return _run(STUDY, "STUDY_CLI", args, check)


def cli_json(*args):
    return json.loads(run_cli(*args, "--json").stdout)


def as_array_run(expected):
    """The CLI's JSON as it reads for an array: parameters.file is "(array)"."""
    expected = json.loads(json.dumps(expected))
    expected["parameters"]["file"] = "(array)"
    return expected


@pytest.fixture(scope="session")
def data_dir(tmp_path_factory):
    d = tmp_path_factory.mktemp("series")
    for name, args in {"lorenz": ["lorenz", "-l", "4000", "--components", "x"],
                       "henon": ["henon", "-l", "3000", "--components", "x"],
                       "noise": ["white_noise", "-l", "2000"]}.items():
        (d / f"{name}.txt").write_text(run_cli("generate", *args).stdout)
    return d


@pytest.fixture(scope="session")
def lorenz_file(data_dir):
    return data_dir / "lorenz.txt"


@pytest.fixture(scope="session")
def lorenz(lorenz_file):
    import chaos
    return chaos.read(lorenz_file)[0]
