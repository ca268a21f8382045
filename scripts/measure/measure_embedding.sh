#!/usr/bin/env bash
# Regenerates docs/validation/performance-embedding.md: wall time and peak memory of `chaos mutual` and
# `chaos cao` (m = 1..10) on Lorenz x (dt = 0.01, tau = 17, w = 100) for N = 10^4, 10^5, 10^6, one
# thread, plus what N buys: Cao's E1(3), E2(1) and the chosen dimension at each N.
# Usage: scripts/measure/measure_embedding.sh [build-dir]   (default: build, Release)
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
chaos="$build/chaos/chaos"
[[ -x $chaos ]] || { echo "build the chaos command first: cmake --build $build --target chaos_cli" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
out=docs/validation/performance-embedding.md

# measure LABEL CMD...: appends "seconds<TAB>MiB" of the command to $work/LABEL.
measure() {
  local label=$1
  shift
  /usr/bin/time -f "%e %M" -o "$work/time" "$@" > "$work/$label.json"
  read -r seconds kib < "$work/time"
  printf '%s\t%s\n' "$seconds" "$(awk -v k="$kib" 'BEGIN { printf "%.0f", k / 1024 }')" > "$work/$label.cost"
}

{
  echo "# Embedding tools: speed, memory and what N buys"
  echo
  echo "Made by \`scripts/measure/measure_embedding.sh\` on $(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'))."
  echo "Each run is one process, one thread: wall time and peak resident memory from \`/usr/bin/time\`,"
  echo "including reading the series from a text file. Lorenz x (sigma 10, rho 28, beta 8/3, RK4 h = 0.001,"
  echo "dt = 0.01); mutual information with 16 boxes and delays 0..50; Cao with tau = 17, w = 100, m = 1..10."
  echo
  echo "| N | mutual: s | mutual: MiB | MI first minimum | cao: s | cao: MiB | E1(2) | E1(3) | E2(1) | dimension |"
  echo "|---|---|---|---|---|---|---|---|---|---|"
  for n in 10000 100000 1000000; do
    "$chaos" generate lorenz -l "$n" --components x > "$work/lorenz.dat"
    measure mutual "$chaos" mutual "$work/lorenz.dat" -D 50 --json
    measure cao "$chaos" cao "$work/lorenz.dat" -d 17 -t 100 -M 10 --json
    IFS=$'\t' read -r ms mm < "$work/mutual.cost"
    IFS=$'\t' read -r cs cm < "$work/cao.cost"
    minimum=$(jq '.first_minimum' "$work/mutual.json")
    read -r e12 e13 e21 dim < <(jq -r '[.["E1"][1], .["E1"][2], .["E2"][0], .embedding_dimension] | map(if type == "number" then (. * 10000 | round / 10000) else . end) | @tsv' "$work/cao.json")
    echo "| $n | $ms | $mm | $minimum | $cs | $cm | $e12 | $e13 | $e21 | $dim |"
  done
  echo
  echo "Target: Cao for m = 1..10 at N = 10^5 under 2 s on one core, memory linear in N."
  echo "What N buys: the chosen embedding dimension is 3 from N = 10^4 on, with E1(3) near 0.91 at every N;"
  echo "E1(2) falls as N grows (finer neighbours in 2 dimensions expose more false neighbours), so the"
  echo "decision gets clearer. The mutual-information minimum is shallow and may move by a sample or two."
} > "$out"
cat "$out"
