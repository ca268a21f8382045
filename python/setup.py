"""Builds chaos._core with the project's CMake (the static libraries compiled position-independent,
then the pybind11 module), so the extension runs exactly the code behind the `chaos` command.

Needs: Python >= 3.9 with setuptools >= 61 and wheel (Debian 12: python3-setuptools, python3-wheel;
use a venv of /usr/bin/python3 with --system-site-packages and pip's --no-build-isolation), and
CMake, a C++20 compiler, pybind11 and the libraries of scripts/install-deps.sh. A missing wheel
package is said before anything is built.

Environment:
  CHAOS_BUILD_DIR   CMake build directory to (re)use; a relative path is taken from the checkout's
                    root (pip runs this file from python/). It must hold a configured build
                    (CMakeCache.txt); only the module is compiled there, plus the libraries when that
                    build was configured without -DCHAOS_BUILD_PYTHON=ON (they are then recompiled
                    position-independent). Unset: <repo>/build-python, configured here (Release,
                    tests off), with Ninja when it is installed.
  CHAOS_BUILD_JOBS  parallel jobs (default 2).
"""
import os
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent


def require_wheel():
    """setuptools before 70.1 builds wheels only with the separate `wheel` package; without it pip's
    --no-build-isolation ends in "invalid command 'bdist_wheel'" (a pyenv or conda python3 first on
    PATH makes a venv without it). Say what is missing and how to get it, before any build."""
    if not {"bdist_wheel", "dist_info", "editable_wheel"} & set(sys.argv):  # pip's metadata step needs it too
        return
    try:
        import setuptools.command.bdist_wheel  # noqa: F401  (setuptools >= 70.1 has its own)
        return
    except ImportError:
        pass
    try:
        import wheel.bdist_wheel  # noqa: F401
    except ImportError:
        sys.exit(f"chaos: installing the package needs the 'wheel' package, which this Python ({sys.executable}) "
                 "lacks. On Debian make the venv with Debian's Python, which has it (python3-wheel): "
                 "/usr/bin/python3 -m venv --system-site-packages .venv && .venv/bin/pip install "
                 "--no-build-isolation ./python. With another Python, `pip install wheel` into its venv first, "
                 "or leave out --no-build-isolation (pip then fetches setuptools and wheel).")


require_wheel()


def build_directory():
    given = os.environ.get("CHAOS_BUILD_DIR")
    if not given:
        return ROOT / "build-python", False
    path = Path(given)
    path = (path if path.is_absolute() else ROOT / path).resolve()
    if not (path / "CMakeCache.txt").exists():
        raise RuntimeError(f"CHAOS_BUILD_DIR={given}: {path} holds no configured CMake build (no CMakeCache.txt); "
                           "a relative path is taken from the checkout's root. Configure one "
                           f"(cmake -S {ROOT} -B {path} -DCMAKE_BUILD_TYPE=Release -DCHAOS_BUILD_PYTHON=ON), "
                           "or leave CHAOS_BUILD_DIR unset to build into build-python/")
    return path, True


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        if not (ROOT / "chaos" / "commands" / "commands.hpp").exists():
            raise RuntimeError(f"{ROOT}: not the chaos-mechanism checkout (install from the repository's python/ folder)")
        build_dir, given = build_directory()
        jobs = os.environ.get("CHAOS_BUILD_JOBS", "2")
        configure = ["cmake", "-S", str(ROOT), "-B", str(build_dir), "-DCHAOS_BUILD_PYTHON=ON",
                     f"-DPython3_EXECUTABLE={sys.executable}"]
        # A build of its own needs no nanoflann: only `chaos neighbors` and the tests compare with it.
        # Ninja builds the same targets as Make in less time on 2 cores (scripts/test.sh).
        if not (build_dir / "CMakeCache.txt").exists():
            configure += ["-DCMAKE_BUILD_TYPE=Release", "-DCHAOS_BUILD_TESTS=OFF", "-DSTUDY_WITH_MPI=OFF",
                          "-DCHAOS_WITH_NANOFLANN=OFF"]
            if shutil.which("ninja"):
                configure += ["-G", "Ninja"]
        print(f"chaos: building the extension in {build_dir} "
              f"({'the given build' if given else 'a build of its own'}, {jobs} jobs)", flush=True)
        subprocess.run(configure, check=True)
        subprocess.run(["cmake", "--build", str(build_dir), "--target", "_core", "-j", jobs], check=True)
        built = sorted((build_dir / "python" / "chaos").glob("_core*.so"))
        if not built:
            raise RuntimeError(f"no _core module under {build_dir / 'python' / 'chaos'}")
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[-1], target)


setup(ext_modules=[Extension("chaos._core", sources=[])], cmdclass={"build_ext": CMakeBuild})
