"""The package imported is the installed one, not the repository's C++ chaos/ folder."""
import os
import subprocess
import sys
from pathlib import Path

import chaos
from conftest import REPO


def test_imports_the_installed_package():
    assert Path(chaos.__file__).resolve().parent != (REPO / "chaos").resolve()
    assert hasattr(chaos, "d2") and hasattr(chaos._core, "d2")
    assert Path(os.getcwd()).resolve() != REPO  # CI runs pytest from outside the checkout


def test_help_carries_the_formula_and_citation():
    assert "Grassberger" in chaos.d2.__doc__ and "C(eps, m)" in chaos.d2.__doc__
    assert "Cao" in chaos.cao.__doc__ and "Physica D 110" in chaos.cao.__doc__


def _run_setup(code, tmp_path, **env):
    """Runs python/setup.py's module code in a fresh interpreter (from tmp_path, so nothing is
    written into the checkout) after `code`, with setuptools.setup() made a no-op."""
    script = ("import runpy, setuptools, sys\n" + code + "\nsetuptools.setup = lambda **kw: None\n"
              f"g = runpy.run_path({str(REPO / 'python' / 'setup.py')!r})\n")
    return subprocess.run([sys.executable, "-c", script], cwd=tmp_path, capture_output=True, text=True,
                          env={**os.environ, **env})


def test_a_python_without_wheel_is_told_before_any_build(tmp_path):
    # A pyenv or conda python3 first on PATH made a venv without the `wheel` package, and
    # `pip install --no-build-isolation ./python` ended in "invalid command 'bdist_wheel'". The
    # message must name the missing package and Debian's Python (expected: setup.py's message).
    block = "sys.modules['wheel'] = None; sys.modules['wheel.bdist_wheel'] = None\n" \
            "sys.modules['setuptools.command.bdist_wheel'] = None\nsys.argv = ['setup.py', 'dist_info']"
    p = _run_setup(block, tmp_path)
    assert p.returncode != 0
    assert "needs the 'wheel' package" in p.stderr and "/usr/bin/python3 -m venv" in p.stderr, p.stderr


def test_a_given_build_directory_is_taken_from_the_checkout_root(tmp_path):
    # pip runs setup.py from python/, so CHAOS_BUILD_DIR=build (written from the checkout's root)
    # named python/build, held no build, and the whole project was compiled again there. A relative
    # path is the checkout root's; one without a CMake build is refused, saying so (expected: the
    # paths themselves and setup.py's message).
    call = ("try:\n    print(g['build_directory']())\n"
            "except RuntimeError as e:\n    print('refused:', e)\n")
    p = _run_setup("", tmp_path, CHAOS_BUILD_DIR="no-such-build-dir")  # loading alone refuses nothing
    assert p.returncode == 0, p.stderr
    p = _run_setup_then(call, tmp_path, CHAOS_BUILD_DIR="no-such-build-dir")
    assert (f"refused: CHAOS_BUILD_DIR=no-such-build-dir: {(REPO / 'no-such-build-dir').resolve()} "
            "holds no configured CMake build") in p.stdout, p.stdout + p.stderr
    (tmp_path / "b").mkdir()
    (tmp_path / "b" / "CMakeCache.txt").write_text("")
    p = _run_setup_then(call, tmp_path, CHAOS_BUILD_DIR=str(tmp_path / "b"))
    assert p.stdout.strip() == repr(((tmp_path / "b").resolve(), True)), p.stdout + p.stderr


def _run_setup_then(after, tmp_path, **env):
    """As _run_setup, then `after` with the module's globals as `g`."""
    script = ("import runpy, setuptools\nsetuptools.setup = lambda **kw: None\n"
              f"g = runpy.run_path({str(REPO / 'python' / 'setup.py')!r})\n" + after)
    return subprocess.run([sys.executable, "-c", script], cwd=tmp_path, capture_output=True, text=True,
                          env={**os.environ, **env})
