#!/usr/bin/env bash
# The automatic pipeline at its own delay and at others: for every chaotic system of docs/validation/zoo.md
# that the pipeline analyses, `chaos analyze` on the zoo's series at N = 10^5 with the delay forced
# to tau (the automatic choice), tau/2, 3 tau/2 and 2 tau (rounded up; repeats dropped) and the
# automatic Theiler window w; Cao's dimension, D2 and the three lambda_1 estimates are then chosen
# as `analyze` chooses them at that delay. With DELAY_CHECK=1, D2 also goes through the delay check
# (`analyze --delay-check`: the same sums at twice the delay, whose D2 is shown). This is what a user gets who takes the delay from another rule (the
# autocorrelation's 1/e time or zero crossing instead of the mutual-information minimum), which the
# zoo's grid (m and w at the automatic delay) does not vary.
#
# Each confident estimate is judged against the zoo's bands, read from the same docs/validation/zoo.md row:
# D2 (status saturated) inside the row's D2 band; lambda_1 (Rosenstein and Kantz: linear_region,
# local maps: consistent) within 10% of lambda_1 from the equations. Output: a Markdown table, one
# row per (system, delay), and a summary.
#
# Usage: scripts/measure/measure_delay_neighbourhood.sh [build-dir] > table.md
# Environment: JOBS (2) parallel cases; ONLY=name,name to restrict the systems; DELAY_CHECK=1.
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/measure/zoo_neighbourhood_common.sh "$@"
check_flag=
[[ ${DELAY_CHECK:-0} == 1 ]] && check_flag=--delay-check

zoo_systems > "$work/systems"
[[ -s $work/systems ]] || { echo "no automatic-choice rows at N = 10^5 found in docs/validation/zoo.md" >&2; exit 3; }

case_rows() {  # name tau w d2_low d2_high lambda_1 -> $work/rows.name
  local name=$1 tau=$2 w=$3 lo=$4 hi=$5 lam=$6 dt t json out="$work/rows.$1"
  dt=$(zoo_series "$name")
  : > "$out"
  local done_delays=" "
  for t in $tau $(((tau + 1) / 2)) $(((3 * tau + 1) / 2)) $((2 * tau)); do
    [[ $done_delays == *" $t "* ]] && continue
    done_delays+="$t "
    json=$("$chaos" analyze "$work/$name.dat" -d "$t" -t "$w" ${dt:+--dt $dt} $check_flag --json -q 2> /dev/null) || json='{}'
    jq -r --arg name "$name" --arg tau "$tau" --arg t "$t" --arg w "$w" --arg lo "$lo" --arg hi "$hi" --arg lam "$lam" "$zoo_verdicts"'
      [$name, $tau, $t, (.embedding_dimension // "-" | tostring), $w,
       "\(.d2 | num) \(.d2_status // "error")",
       (if .d2_delay_variant == null then "-" else "\(.d2_delay_variant.d2 | num) \(.d2_delay_variant.status) (tau \(.d2_delay_variant.delay))" end),
       "[\($lo), \($hi)]", d2v,
       lambda_columns, $lam] | join("\t")' <<< "$json" >> "$out"
  done
  echo "done $name" >&2
}
export -f case_rows
export check_flag

zoo_run_cases < <(zoo_only < "$work/systems")

echo "# The automatic pipeline at other delays (written by scripts/measure/measure_delay_neighbourhood.sh)"
echo
echo "Commit $(git rev-parse --short HEAD 2> /dev/null || echo unknown), delay check ${check_flag:-off}; $(zoo_machine); $elapsed s."
echo
echo "| system | tau (automatic) | tau | m (Cao) | w | D2 | delay check: D2 at 2 tau | D2 band | D2 verdict | lambda Rosenstein | verdict | lambda Kantz | verdict | lambda local maps | verdict | lambda_1 (equations) |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
zoo_table_rows
echo
cat "$work"/rows.* | awk -F'\t' '{
    d[$9]++; r[$11]++; k[$13]++; l[$15]++; rows++
    if ($9 == "in_band") ds[$1] = 1
    if ($11 == "in_band" || $13 == "in_band" || $15 == "in_band") ls[$1] = 1
    if ($2 == $3) { auto++; if ($9 == "in_band") ad++; if ($9 == "WRONG") aw++ }
  } END {
    printf "Rows: %d. D2: %d in band, %d unsure, %d wrong. lambda_1 by Rosenstein: %d / %d / %d; Kantz: %d / %d / %d; local maps: %d / %d / %d (in band / unsure / wrong).\n",
      rows, d["in_band"], d["unsure"], d["WRONG"], r["in_band"], r["unsure"], r["WRONG"], k["in_band"], k["unsure"], k["WRONG"], l["in_band"], l["unsure"], l["WRONG"]
    printf "Systems with a confident D2 in band at some delay: %d; with a confident lambda_1 in band: %d.\n", length(ds), length(ls)
    printf "At the automatic delay: %d systems, D2 in band on %d, wrong on %d.\n", auto, ad, aw
  }'
