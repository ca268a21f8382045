#!/usr/bin/env bash
# The automatic pipeline on the other observables of each system: for every chaotic system of
# docs/validation/zoo.md that the pipeline analyses, the zoo's trajectory at N = 10^5 (the same run, sampling
# and transient as the zoo's series, which is its first component), read through its second and
# third state variables, then `chaos analyze` with every choice automatic. The zoo analyses one
# component per system; a user with a recording has whichever variable was measured.
#
# Components: `chaos generate NAME -l 100000 --components all` (its first column is the zoo's series,
# checked below), columns 2 and 3 where the system has them. Skipped: the phase of a forced flow
# (a clock, not an observable of the attractor). Delay systems and one-variable maps have no other
# component.
#
# Bands, fixed before the run: the system's own, read from the same docs/validation/zoo.md row. D2 and the
# Lyapunov exponents are invariants of the attractor, so every generic smooth observable has the
# same ones (Takens 1981; Sauer, Yorke & Casdagli 1991). A confident D2 (saturated) must lie in the
# row's D2 band and a confident lambda_1 (Rosenstein and Kantz: linear_region, local maps:
# consistent) within 10% of lambda_1 from the equations, or the row is wrong. Any other status is
# unsure. A symmetric observable (Lorenz z, invariant under (x, y) -> (-x, -y)) sees the attractor
# folded onto itself, which changes neither D2 nor lambda_1 locally, so it keeps the bands.
#
# Usage: scripts/measure/measure_component_neighbourhood.sh [build-dir] > table.md
# Environment: JOBS (2) parallel cases; ONLY=name,name to restrict the systems.
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/measure/zoo_neighbourhood_common.sh "$@"

zoo_systems > "$work/systems"
[[ -s $work/systems ]] || { echo "no automatic-choice rows at N = 10^5 found in docs/validation/zoo.md" >&2; exit 3; }
"$chaos" generate --list | awk -F'\t' 'NR > 1 { print $1, ($2 ~ /forced/ ? "forced" : "free"), $3 }' > "$work/kinds"

case_rows() {  # name d2_low d2_high lambda_1 -> $work/rows.name
  local name=$1 lo=$2 hi=$3 lam=$4 dt kind dim last c names var json out="$work/rows.$1"
  read -r kind dim < <(awk -v n="$name" '$1 == n { print $2, $3 }' "$work/kinds")
  last=$dim
  [[ $kind == forced ]] && last=$((dim - 1))
  : > "$out"
  ((last >= 2)) || { echo "done $name (one observable)" >&2; return 0; }
  dt=$(zoo_series "$name")
  "$chaos" generate "$name" -l 100000 > "$work/$name.all"
  names=$(grep '^# ' "$work/$name.all" | tail -1 | sed 's/^# //')
  grep -v '^#' "$work/$name.all" > "$work/$name.cols"
  # The first column must be the zoo's series: the same trajectory, so only the observable differs.
  if ! paste "$work/$name.dat" <(cut -f1 "$work/$name.cols") | awk '$1 + 0 != $2 + 0 { bad = 1 } END { exit bad }'; then
    echo "$name: chaos generate's first column is not the zoo's series" >&2
    return 1
  fi
  for c in $(seq 2 $((last < 3 ? last : 3))); do
    var=$(cut -d$'\t' -f"$c" <<< "$names")
    cut -f"$c" "$work/$name.cols" > "$work/$name.$c.dat"
    json=$("$chaos" analyze "$work/$name.$c.dat" ${dt:+--dt $dt} --json -q 2> /dev/null) || json='{}'
    jq -r --arg name "$name" --arg var "$var" --arg lo "$lo" --arg hi "$hi" --arg lam "$lam" "$zoo_verdicts"'
      [$name, $var, automatic_columns, lambda_columns, $lam] | join("\t")' <<< "$json" >> "$out"
  done
  echo "done $name" >&2
}
export -f case_rows

zoo_run_cases < <(zoo_band_cases)

echo "# The automatic pipeline on each system's other observables (written by scripts/measure/measure_component_neighbourhood.sh)"
echo
echo "Commit $(git rev-parse --short HEAD 2> /dev/null || echo unknown); $(zoo_machine); $elapsed s."
echo
echo "| system | observable | tau | m (Cao) | w | D2 | D2 band | D2 verdict | lambda Rosenstein | verdict | lambda Kantz | verdict | lambda local maps | verdict | lambda_1 (equations) |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
zoo_table_rows
echo
cat "$work"/rows.* | awk -F'\t' '{
    rows++; d[$8]++; r[$10]++; k[$12]++; l[$14]++
    if ($8 == "WRONG" || $10 == "WRONG" || $12 == "WRONG" || $14 == "WRONG") wrong = wrong " " $1 "(" $2 ")"
  } END {
    printf "%d rows. D2: %d in band, %d unsure, %d wrong. lambda_1 by Rosenstein: %d / %d / %d; Kantz: %d / %d / %d; local maps: %d / %d / %d (in band / unsure / wrong). Rows with a wrong estimate:%s.\n",
      rows, d["in_band"], d["unsure"], d["WRONG"], r["in_band"], r["unsure"], r["WRONG"],
      k["in_band"], k["unsure"], k["WRONG"], l["in_band"], l["unsure"], l["WRONG"], (wrong == "" ? " none" : wrong)
  }'
