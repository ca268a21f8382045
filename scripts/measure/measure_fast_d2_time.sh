#!/usr/bin/env bash
# `chaos d2 --fast` (the quick look, every default) on the two target series, Lorenz x (dt 0.01) and
# Hénon x at N = 10^5 (`chaos generate lorenz|henon -l 100000 --components x`): its wall time, and
# whether its interval holds the exact counts' D2 (one exact run, `chaos d2` with every default).
# With a TISEAN d2 executable as the first argument, TISEAN's d2 at its defaults (m = 1..10, 100
# radii, at most 1000 pairs per radius) with the delay and Theiler window chaos chose runs beside it,
# the two alternated back to back. Wall time of each process, reading the series included; min and
# median over REPEATS rounds (default 11).
#
# Usage: scripts/measure/measure_fast_d2_time.sh [TISEAN_D2] [build-dir]
#   TISEAN_D2: d2 built from TISEAN's source_c (d2.c and routines/), e.g.
#     gcc -O3 -o d2 d2.c routines/{check_alloc,check_option,get_series,get_multi_series,myfgets,\
#       rescale_data,scan_help,search_datafile,test_outfile,what_i_do,variance,rand}.c -lm
set -euo pipefail
cd "$(dirname "$0")/../.."
tisean=${1:-}
build=${2:-build}
chaos="$build/chaos/chaos"
[[ -x $chaos ]] || { echo "build the chaos command first: cmake --build $build --target chaos_cli" >&2; exit 2; }
[[ -z $tisean || -x $tisean ]] || { echo "$tisean is not an executable" >&2; exit 2; }
command -v jq > /dev/null || { echo "jq is needed" >&2; exit 2; }
repeats=${REPEATS:-11}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

wall_ms() {  # command...: its wall time in ms, output discarded
  local s e
  s=$(date +%s%N)
  "$@" > /dev/null 2>&1
  e=$(date +%s%N)
  echo $(((e - s) / 1000000))
}
min_median() {  # numbers on stdin -> "min / median"
  sort -n | awk '{a[NR] = $1} END {printf "%d / %d", a[1], a[int((NR + 1) / 2)]}'
}

echo "| series | exact D2 (s) | \`--fast\` answer | holds | \`--fast\` ms, min / median |$([[ -n $tisean ]] && echo " TISEAN d2 ms, min / median |")"
echo "|---|---|---|---|---|$([[ -n $tisean ]] && echo "---|")"
for system in lorenz henon; do
  f="$work/$system.dat"
  "$chaos" generate "$system" -l 100000 --components x -q > "$f"
  s=$(date +%s%N)
  "$chaos" d2 "$f" --json -q > "$work/exact.json"
  exact_s=$(( ($(date +%s%N) - s) / 1000000 ))
  "$chaos" d2 "$f" --fast --json -q > "$work/fast.json"
  exact=$(jq -r '.estimate.value // "none"' "$work/exact.json")
  answer=$(jq -r 'def r: if . == null then "-" else (. * 1000 | round / 1000 | tostring) end;
    .estimate | "\(.value | r) [\(.interval[0] | r), \(.interval[1] | r)] \(.status)"' "$work/fast.json")
  holds=$(jq -r --arg x "$exact" '.estimate | if $x == "none" or .value == null then "-"
    elif ($x | tonumber) >= .interval[0] and ($x | tonumber) <= .interval[1] then "yes" else "NO" end' "$work/fast.json")
  tau=$(jq -r '.parameters.delay' "$work/fast.json")
  w=$(jq -r '.parameters.theiler' "$work/fast.json")
  : > "$work/fast.t"
  : > "$work/tisean.t"
  for _ in $(seq "$repeats"); do
    wall_ms "$chaos" d2 "$f" --fast -q >> "$work/fast.t"
    if [[ -n $tisean ]]; then
      wall_ms "$tisean" "$f" -d "$tau" -t "$w" -M 1,10 -V 0 -o "$work/tisean" >> "$work/tisean.t"
    fi
  done
  row="| $system x | $(awk -v x="$exact" 'BEGIN {printf (x == "none" ? "none" : "%.3f"), x}') ($(awk -v ms="$exact_s" 'BEGIN {printf "%.1f", ms / 1000}')) | $answer | $holds | $(min_median < "$work/fast.t") |"
  [[ -n $tisean ]] && row="$row $(min_median < "$work/tisean.t") |"
  echo "$row"
done
echo
echo "$(nproc) cores ($(lscpu | sed -n 's/^Model name: *//p' | head -1)), $repeats rounds, commit $(git rev-parse --short HEAD)."
