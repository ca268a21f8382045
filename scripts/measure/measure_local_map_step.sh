#!/usr/bin/env bash
# The local-maps estimator's step on the zoo's flows where it is unsure (docs/notes/lyapunov-maps-step.md,
# and docs/notes/zoo-notes.md section 4).
#   scripts/measure/measure_local_map_step.sh [build-dir] > table.md
# For every system whose local-map lambda_1 at N = 10^5 is `inconsistent` in docs/validation/zoo.md: `chaos
# lyapunov-maps` on the zoo's series at the zoo's delay and Theiler window, at Cao's m and m + 1 (the
# two runs of the pipeline), with the default step (half the delay), a quarter of the delay and one
# sample. Each row: the status, the base estimate over lambda_1 from the equations, and the variant
# farthest from the base. JOBS (default 2) runs systems in parallel; ONLY=name,name selects systems.
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/measure/zoo_neighbourhood_common.sh "$@"

case_rows() {  # name tau m w lambda_1: six Markdown rows
  local name=$1 tau=$2 m=$3 w=$4 lam=$5 dt quarter dim step
  dt=$(zoo_series "$name")
  local per_time=()
  [[ -n $dt ]] && per_time=(--dt "$dt")
  quarter=$(( (tau + 2) / 4 ))
  (( quarter >= 1 )) || quarter=1
  for dim in "$m" $((m + 1)); do
    for step in 0 "$quarter" 1; do
      "$chaos" lyapunov-maps "$work/$name.dat" -d "$tau" -m "$dim" -t "$w" --step "$step" "${per_time[@]}" --json |
        jq -r --arg name "$name" --argjson lam "$lam" '
          (.variants // []) as $v | ($v | map(select(.name == "base"))[0].lambda) as $base |
          ([$v[] | select(.name != "base" and .lambda != null) | {name, off: (.lambda / $base - 1)}]
            | max_by(.off | fabs)) as $worst |
          "| \($name) | \(.parameters.dimension) | \(.parameters.step) | \(.status) | " +
          (if $base then "\($base * 10000 | round / 10000) | \($base / $lam * 1000 | round / 1000)" else "- | -" end) +
          " | " + (if $worst then "\($worst.name) (\($worst.off * 100 | round)%)" else "-" end) + " |"'
    done
  done > "$work/$name.rows"
}
export -f case_rows

# Rows of zoo.md's automatic choices at N = 10^5 whose local-map lambda_1 is inconsistent:
zoo_columns "system	N	tau	m	w	lambda local maps	lambda_1 eq." |
  awk '$2 == 100000 && $6 ~ /inconsistent/ { print $1, $3, $4, $5, $7 + 0 }' | zoo_only > "$work/cases"
start=$(date +%s)
xargs -P "$jobs" -L 1 bash -c 'case_rows "$@"' _ < "$work/cases"
echo "Made by \`scripts/measure/measure_local_map_step.sh\` (commit $(git rev-parse --short HEAD), $(zoo_machine), $(( $(date +%s) - start )) s)."
echo
echo "| system | m | step (samples) | status | base lambda | base / lambda_1 | variant farthest from the base |"
echo "|---|---|---|---|---|---|---|"
while read -r name _; do cat "$work/$name.rows"; done < "$work/cases"
