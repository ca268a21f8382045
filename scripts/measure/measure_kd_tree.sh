#!/usr/bin/env bash
# Exact correlation sums by the kd-tree against the box-assisted grid: the same
# `chaos d2` job with --search kd and --search box, runs alternated back to back on one thread,
# over cases that differ in dimension, N, radius range, norm and how clustered the data are. Both
# must give the same pair counts (the md5 of every count is compared; a difference stops the
# script). A third column runs the grid with CHAOS_NO_PLANE=1, which bins m = 2 pair by pair as
# the kd-tree does instead of counting it with the plane sweep (maximum norm only; with the
# Euclidean norm the grid always bins m = 2), so the two search structures are compared on equal
# work. Prints a Markdown table: best and median wall time of each, and the ratios of the bests.
# Usage: scripts/measure/measure_kd_tree.sh [build-dir]   (default: build, Release)
# Environment: REPEATS (default 3) runs per search and case.
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
chaos="$build/chaos/chaos"
[[ -x $chaos ]] || { echo "build the chaos command first: cmake --build $build --target chaos_cli" >&2; exit 2; }
command -v jq > /dev/null || { echo "jq is needed" >&2; exit 2; }
[[ -x /usr/bin/time ]] || { echo "/usr/bin/time (GNU time) is needed" >&2; exit 2; }
repeats=${REPEATS:-3}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$chaos" generate lorenz -l 100000 --components x > "$work/lorenz.dat"
"$chaos" generate henon -l 100000 --components x > "$work/henon.dat"
"$chaos" generate logistic -l 100000 > "$work/logistic.dat"
"$chaos" generate uniform_noise -l 100000 --seed 5 > "$work/uniform.dat"

echo "# $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores; load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "# commit $(git rev-parse --short HEAD 2>/dev/null || echo unknown); $repeats runs per search, alternated; one thread"
echo
echo "| case | chaos d2 arguments | box best / median (s) | box, m = 2 binned: best / median (s) | kd best / median (s) | kd / box | kd / box with m = 2 binned | counts equal |"
echo "|---|---|---|---|---|---|---|---|"

# case NAME FILE ARGS...
case_row() {
  local name=$1 file=$2
  shift 2
  local s i
  for s in box noplane kd; do : > "$work/t_$s"; done
  for ((i = 0; i < repeats; i++)); do
    for s in box noplane kd; do
      local search=$s plane=0
      [[ $s == noplane ]] && search=box plane=1
      # --no-halves: the counting alone (the halves check, on by default, adds half a job).
      CHAOS_NO_PLANE=$plane /usr/bin/time -f '%e' -o "$work/time" "$chaos" d2 "$work/$file" "$@" --search "$search" \
        --no-halves --threads 1 --json -q > "$work/out_$s.json"
      cat "$work/time" >> "$work/t_$s"
    done
  done
  local md5 first=""
  for s in box noplane kd; do
    md5=$(jq -c '.pairs' "$work/out_$s.json" | md5sum | cut -c1-12)
    [[ -z $first ]] && first=$md5
    if [[ $md5 != "$first" ]]; then
      echo "counts differ on $name: $s gives $md5, box $first" >&2
      exit 1
    fi
  done
  awk -v name="$name" -v args="$*" -v box="$(sort -g "$work/t_box" | tr '\n' ' ')" \
    -v noplane="$(sort -g "$work/t_noplane" | tr '\n' ' ')" -v kd="$(sort -g "$work/t_kd" | tr '\n' ' ')" 'BEGIN {
    nb = split(box, b, " "); nn = split(noplane, n, " "); nk = split(kd, k, " ")
    printf "| %s | `%s` | %.2f / %.2f | %.2f / %.2f | %.2f / %.2f | %.2f | %.2f | yes |\n", name, args, b[1], b[int((nb + 1) / 2)],
      n[1], n[int((nn + 1) / 2)], k[1], k[int((nk + 1) / 2)], k[1] / b[1], k[1] / n[1]
  }'
}

case_row "Lorenz x, N = 10^5 (the exact target job)" lorenz.dat -d 17 -t 200 -M 6 -r 0.25 -R 5 -# 40
case_row "Henon x, N = 10^5 (the exact target job)" henon.dat -d 1 -t 10 -M 4 -r 0.005 -R 0.4 -# 40
case_row "Lorenz x, Euclidean norm" lorenz.dat -d 17 -t 200 -M 6 -r 0.25 -R 5 -# 40 --norm euclidean
case_row "Lorenz x, m = 4..6 only" lorenz.dat -d 17 -t 200 -m 4 -M 6 -r 0.25 -R 5 -# 40
case_row "Lorenz x, m up to 10" lorenz.dat -d 17 -t 200 -M 10 -r 0.25 -R 5 -# 40
case_row "Lorenz x, radii to half the range" lorenz.dat -d 17 -t 200 -M 6 -r 1 -R 20 -# 40
case_row "Lorenz x, N = 10^4" lorenz.dat -l 10000 -d 17 -t 200 -M 6 -r 0.25 -R 5 -# 40
case_row "logistic map (density piled up at the edges)" logistic.dat -d 1 -t 0 -M 4 -r 0.001 -R 0.1 -# 40
case_row "uniform noise, m = 1..4" uniform.dat -d 1 -t 0 -M 4 -r 0.01 -R 0.2 -# 40
case_row "uniform noise, m = 3..6" uniform.dat -d 1 -t 0 -m 3 -M 6 -r 0.05 -R 0.4 -# 40
echo
echo "# load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
