#!/usr/bin/env bash
# The automatic pipeline on the same flows sampled at other rates: for every chaotic flow (and delay
# system) of docs/validation/zoo.md that the pipeline analyses, the zoo's observable at N = 10^5 sampled at the
# zoo's step dt, at dt / 2 and at 2 dt (`chaos generate NAME -p dt=...`: the same equations,
# parameters, integration step and transient, so the same attractor), and `chaos analyze --dt` with
# every choice automatic (delay, Cao's m, Theiler window). The sampling interval is a choice of
# whoever records the data, and it moves every automatic choice at once (the delay and the window in
# samples, the record's length in time), which the zoo's grid (m, w and N at one sampling) and the
# delay neighbourhood (docs/notes/zoo-delay.md) do not. Maps have no sampling step and are left out.
#
# Bands, fixed before the run and the same as the zoo's row: D2 (status saturated) inside the row's
# D2 band; lambda_1 per time unit (Rosenstein and Kantz: linear_region; local maps: consistent)
# within 10% of lambda_1 from the equations. A confident estimate outside its band is WRONG.
#
# Usage: scripts/measure/measure_sampling_neighbourhood.sh [build-dir] > table.md
# Environment: JOBS (2) parallel systems; ONLY=name,name to restrict the systems.
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/measure/zoo_neighbourhood_common.sh "$@"

zoo_systems > "$work/systems"
[[ -s $work/systems ]] || { echo "no automatic-choice rows at N = 10^5 found in docs/validation/zoo.md" >&2; exit 3; }

# The first column (the zoo's observable) of `chaos generate NAME` at sampling step $2, N = 10^5.
sampled() {
  "$chaos" generate "$1" -l 100000 -p "dt=$2" | awk '!/^#/ { print $1 }'
}

case_rows() {  # name tau w d2_low d2_high lambda_1 -> $work/rows.name
  local name=$1 lo=$4 hi=$5 lam=$6 dt step label json file out="$work/rows.$1"
  dt=$(zoo_series "$name")
  : > "$out"
  [[ -n $dt ]] || { echo "done $name (a map: no sampling step)" >&2; return 0; }
  # The generator at the zoo's own step must give the zoo's series, value for value: otherwise the
  # other rates would not be the same observable of the same orbit.
  if ! sampled "$name" "$dt" | awk 'NR == FNR { z[FNR] = $1; n = FNR; next } { if ($1 + 0 != z[FNR] + 0) bad = 1; m = FNR }
                                    END { exit (bad || m != n) }' "$work/$name.dat" -; then
    echo "$name: chaos generate at dt = $dt does not reproduce the zoo's series; skipped" >&2
    return 0
  fi
  for label in zoo half double; do
    case $label in
      zoo) step=$dt ;;
      half) step=$(awk -v d="$dt" 'BEGIN { printf "%.15g", d / 2 }') ;;
      double) step=$(awk -v d="$dt" 'BEGIN { printf "%.15g", d * 2 }') ;;
    esac
    file="$work/$name.dat"  # the zoo's own series, already checked above
    if [[ $label != zoo ]]; then
      file="$work/$name.$label.dat"
      sampled "$name" "$step" > "$file"
    fi
    json=$("$chaos" analyze "$file" --dt "$step" --json -q 2> /dev/null) || json='{}'
    jq -r --arg name "$name" --arg step "$step" --arg lo "$lo" --arg hi "$hi" --arg lam "$lam" "$zoo_verdicts"'
      [$name, $step, automatic_columns, lambda_columns, $lam] | join("\t")' <<< "$json" >> "$out"
    [[ $label == zoo ]] || rm -f "$file"
  done
  echo "done $name" >&2
}
export -f case_rows sampled

zoo_run_cases < <(zoo_only < "$work/systems")

echo "# The automatic pipeline at other sampling steps (written by scripts/measure/measure_sampling_neighbourhood.sh)"
echo
echo "Commit $(git rev-parse --short HEAD 2> /dev/null || echo unknown); $(zoo_machine); $elapsed s."
echo
echo "| system | dt | tau | m (Cao) | w | D2 | D2 band | D2 verdict | lambda Rosenstein | verdict | lambda Kantz | verdict | lambda local maps | verdict | lambda_1 (equations) |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
zoo_table_rows
echo
cat "$work"/rows.* | awk -F'\t' '
  { rows++; n[$1]++
    d[$8]++; r[$10]++; k[$12]++; l[$14]++
    lam = ($10 == "in_band" || $12 == "in_band" || $14 == "in_band")
    if (n[$1] == 1) { zd[$1] = $8; zl[$1] = lam } else { if ($8 == "in_band") od[$1]++; if (lam) ol[$1]++ } }
  END {
    printf "Rows: %d (%d systems x 3 steps). D2: %d in band, %d unsure, %d wrong. lambda_1 by Rosenstein: %d / %d / %d; Kantz: %d / %d / %d; local maps: %d / %d / %d (in band / unsure / wrong).\n",
      rows, length(n), d["in_band"], d["unsure"], d["WRONG"], r["in_band"], r["unsure"], r["WRONG"], k["in_band"], k["unsure"], k["WRONG"], l["in_band"], l["unsure"], l["WRONG"]
    for (s in n) { if (zd[s] == "in_band") zdc++; if (zl[s]) zlc++; if (od[s] == 2) bd++; if (ol[s] == 2) bl++ }
    printf "At the zoo step: D2 in band on %d systems, lambda_1 (any method) on %d. In band at both other steps: D2 on %d, lambda_1 on %d.\n", zdc, zlc, bd, bl
  }'
