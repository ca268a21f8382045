"""Builds chaos._core with the project's CMake (the static libraries compiled position-independent,
then the pybind11 module), so the extension runs exactly the code behind the `chaos` command.

Environment:
  CHAOS_BUILD_DIR   CMake build directory to (re)use; default <repo>/build-python. CI points it at
                    the Release build that already holds the libraries, so only the module is added.
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


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        if not (ROOT / "chaos" / "commands" / "commands.hpp").exists():
            raise RuntimeError(f"{ROOT}: not the chaos-mechanism checkout (install from the repository's python/ folder)")
        build_dir = Path(os.environ.get("CHAOS_BUILD_DIR", ROOT / "build-python")).resolve()
        jobs = os.environ.get("CHAOS_BUILD_JOBS", "2")
        configure = ["cmake", "-S", str(ROOT), "-B", str(build_dir), "-DCHAOS_BUILD_PYTHON=ON",
                     f"-DPython3_EXECUTABLE={sys.executable}"]
        # A build of its own needs no nanoflann: only `chaos neighbors` and the tests compare with it.
        if not (build_dir / "CMakeCache.txt").exists():
            configure += ["-DCMAKE_BUILD_TYPE=Release", "-DCHAOS_BUILD_TESTS=OFF", "-DSTUDY_WITH_MPI=OFF",
                          "-DCHAOS_WITH_NANOFLANN=OFF"]
        subprocess.run(configure, check=True)
        subprocess.run(["cmake", "--build", str(build_dir), "--target", "_core", "-j", jobs], check=True)
        built = sorted((build_dir / "python" / "chaos").glob("_core*.so"))
        if not built:
            raise RuntimeError(f"no _core module under {build_dir / 'python' / 'chaos'}")
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[-1], target)


setup(ext_modules=[Extension("chaos._core", sources=[])], cmdclass={"build_ext": CMakeBuild})
