#!/usr/bin/env bash
# The automatic pipeline at record lengths between the zoo's two: for every chaotic system of
# docs/validation/zoo.md that the pipeline analyses, the first N samples of the zoo's series (as the zoo's
# N = 10^4 rows take the first 10^4) for each N of LENGTHS (default 2, 3, 5 and 7 * 10^4), then
# `chaos analyze` with every choice automatic. The issue asks for N from 10^4 to 10^5; the zoo's
# grid measures only the two ends.
#
# Bands, fixed before the run: the system's, read from its docs/validation/zoo.md row at N = 10^5 (neither the
# D2 nor lambda_1 of an attractor depends on how much of it was recorded). A confident D2
# (saturated) must lie in the D2 band and a confident lambda_1 (Rosenstein and Kantz:
# linear_region, local maps: consistent) within 10% of lambda_1 from the equations, or the row is
# wrong; any other status is unsure.
#
# Usage: scripts/measure/measure_length_neighbourhood.sh [build-dir] > table.md
# Environment: JOBS (2) parallel cases; ONLY=name,name to restrict the systems; LENGTHS
# ("20000 30000 50000 70000", the lengths of docs/notes/zoo-length.md); RESUME_FROM=DIR (zoo_neighbourhood_common.sh).
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/measure/zoo_neighbourhood_common.sh "$@"
lengths=${LENGTHS:-20000 30000 50000 70000}
for n in $lengths; do
  if ! [[ $n =~ ^[0-9]+$ ]] || ((n < 1000 || n > 100000)); then
    echo "LENGTHS: each length must be a whole number from 1000 to 100000 (the zoo's series), got '$n'" >&2
    exit 2
  fi
done

zoo_systems > "$work/systems"
[[ -s $work/systems ]] || { echo "no automatic-choice rows at N = 10^5 found in docs/validation/zoo.md" >&2; exit 3; }

case_rows() {  # name d2_low d2_high lambda_1 -> $work/rows.name
  local name=$1 lo=$2 hi=$3 lam=$4 dt n json out="$work/rows.$1"
  dt=$(zoo_series "$name")
  : > "$out"
  for n in $lengths; do
    head -n "$n" "$work/$name.dat" > "$work/$name.$n.dat"
    json=$("$chaos" analyze "$work/$name.$n.dat" ${dt:+--dt $dt} --json -q 2> /dev/null) || json='{}'
    jq -r --arg name "$name" --arg n "$n" --arg lo "$lo" --arg hi "$hi" --arg lam "$lam" "$zoo_verdicts"'
      [$name, $n, automatic_columns, lambda_columns, $lam] | join("\t")' <<< "$json" >> "$out"
  done
  echo "done $name" >&2
}
export -f case_rows
export lengths

zoo_run_cases < <(zoo_band_cases)

echo "# The automatic pipeline at record lengths between the zoo's (written by scripts/measure/measure_length_neighbourhood.sh)"
echo
echo "Commit $(git rev-parse --short HEAD 2> /dev/null || echo unknown), lengths $lengths (the first N samples of the zoo's series); $(zoo_machine); $elapsed s."
echo
echo "| system | N | tau | m (Cao) | w | D2 | D2 band | D2 verdict | lambda Rosenstein | verdict | lambda Kantz | verdict | lambda local maps | verdict | lambda_1 (equations) |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
zoo_table_rows
echo
zoo_keyed_summary "N = %s" | sort -V
