#!/usr/bin/env bash
# The whole test suite from a clean checkout: install dependencies, build in Release, run every
# tier (unit, property, reference, slow, command line), then rebuild the unit and property tiers
# with AddressSanitizer + UndefinedBehaviorSanitizer and run them again, with the hostile-input
# command-line tests (the output tests of the commands run in Release only: tests/CMakeLists.txt).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)

bash scripts/install-deps.sh

# A new build directory is generated for Ninja, which builds the same targets as Make in less
# time on 2 cores (no per-target dependency scan); one that exists keeps its generator (CMake
# refuses to switch it).
configure() {
  local dir=$1
  shift
  local generator=()
  grep -qs '^CMAKE_GENERATOR:INTERNAL=' "$dir/CMakeCache.txt" || generator=(-G Ninja)
  cmake "${generator[@]}" -S . -B "$dir" "$@"
}

configure build -DCMAKE_BUILD_TYPE=Release -DCHAOS_BUILD_BENCHMARKS=ON -DCHAOS_BUILD_PYTHON=ON
cmake --build build -j"$jobs"
ctest --test-dir build -j"$jobs" --output-on-failure

# The Python package (python/): installed into a fresh venv as the README says, its extension taken
# from the Release build above (CHAOS_BUILD_DIR: nothing is compiled twice), and its pytest suite run
# from outside the checkout (the repository's chaos/ folder would shadow the package there), with the
# command just built as the source of the expected values.
root=$PWD
rm -rf build/venv
/usr/bin/python3 -m venv --system-site-packages build/venv
CHAOS_BUILD_DIR="$root/build" CHAOS_BUILD_JOBS="$jobs" build/venv/bin/pip install -q --no-build-isolation ./python
(cd "$(mktemp -d)" && CHAOS_CLI="$root/build/chaos/chaos" "$root/build/venv/bin/python" -m pytest -p no:cacheprovider -q \
  "$root/python/tests")

# Open MPI's own allocations read as leaks under LeakSanitizer: the sanitizer build leaves MPI out
# (the Release build above runs the two-rank test).
# -O1 -g1: the sanitizers need neither full optimisation nor full debug information, and the
# build is the longest step of CI on 2 cores (the command-line front ends compile at -O0 there:
# CMakeLists.txt, command_line_build_flags).
configure build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" \
  -DCHAOS_SANITIZE=ON -DSTUDY_WITH_MPI=OFF
cmake --build build-sanitize -j"$jobs"
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --test-dir build-sanitize -j"$jobs" --output-on-failure -L 'unit|property'
