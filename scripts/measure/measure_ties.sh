#!/usr/bin/env bash
# Tied (quantised) series against the untied series they come from: wall-clock time of the
# commands a user runs, as docs/validation/performance-ties.md reports them. The series: Lorenz x
# (`chaos generate lorenz -l N`), the same quantised to LEVELS levels, floor(LEVELS (x - min) /
# (max - min)) with the top value folded into the last level, and LEVELS-valued white noise (seeded
# awk rand()) beside uniform white noise of the same length. Each command is run REPEAT times and
# the fastest run is kept (the machine may be shared). With BASELINE=/path/to/chaos the same runs of
# another build are listed beside.
#
# Usage: scripts/measure/measure_ties.sh [build-dir] > table.md
# Environment: N (5000), LEVELS (3), REPEAT (3), BASELINE (another chaos executable).
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
chaos=$build/chaos/chaos
[[ -x $chaos ]] || { echo "no chaos executable at $chaos (build first)" >&2; exit 2; }
n=${N:-5000}
levels=${LEVELS:-3}
repeat=${REPEAT:-3}
baseline=${BASELINE:-}
[[ -z $baseline || -x $baseline ]] || { echo "BASELINE=$baseline is not an executable" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$chaos" generate lorenz -l "$n" | grep -v '^#' > "$work/lorenz"
awk -v L="$levels" 'NR == FNR { if (FNR == 1 || $1 < lo) lo = $1; if (FNR == 1 || $1 > hi) hi = $1; next }
  { q = int(L * ($1 - lo) / (hi - lo)); print (q > L - 1 ? L - 1 : q) }' "$work/lorenz" "$work/lorenz" > "$work/lorenz_q"
"$chaos" generate uniform_noise -l "$n" | grep -v '^#' > "$work/noise"
awk -v L="$levels" -v n="$n" 'BEGIN { srand(7); for (i = 0; i < n; i++) print int(L * rand()) }' > "$work/noise_q"

# fastest wall-clock seconds of REPEAT runs of: EXE ARGS...
fastest() {
  local best="" t
  for _ in $(seq "$repeat"); do
    t=$(TIMEFORMAT=%R; { time "$@" > /dev/null 2>&1; } 2>&1)
    if [[ -z $best ]] || awk -v a="$t" -v b="$best" 'BEGIN { exit !(a < b) }'; then best=$t; fi
  done
  echo "$best"
}

echo "N = $n, $levels levels, fastest of $repeat runs; $(nproc) cores; $(date -u +%Y-%m-%d)"
echo
if [[ -n $baseline ]]; then
  echo "| command | untied (s) | tied (s) | ratio | baseline untied (s) | baseline tied (s) |"
  echo "|---|---|---|---|---|---|"
else
  echo "| command | untied (s) | tied (s) | ratio |"
  echo "|---|---|---|---|"
fi
row() {  # label untied-file tied-file ARGS...
  local label=$1 untied=$2 tied=$3
  shift 3
  local a b line
  a=$(fastest "$chaos" "$@" "$untied" -q)
  b=$(fastest "$chaos" "$@" "$tied" -q)
  line="| \`chaos $*\` on $label | $a | $b | $(awk -v a="$a" -v b="$b" 'BEGIN { printf "%.1f", b / a }') |"
  if [[ -n $baseline ]]; then
    line+=" $(fastest "$baseline" "$@" "$untied" -q) | $(fastest "$baseline" "$@" "$tied" -q) |"
  fi
  echo "$line"
}
row "Lorenz x" "$work/lorenz" "$work/lorenz_q" analyze --dt 0.01
row "Lorenz x" "$work/lorenz" "$work/lorenz_q" lyapunov
row "Lorenz x" "$work/lorenz" "$work/lorenz_q" lyapunov --method kantz
row "Lorenz x" "$work/lorenz" "$work/lorenz_q" lyapunov --method kantz -r 1e6
row "white noise" "$work/noise" "$work/noise_q" analyze
row "white noise" "$work/noise" "$work/noise_q" nonlinearity
