#!/usr/bin/env bash
# `chaos d2 --fast` with the command's defaults (one round of two subsets of 200 reference points,
# one from each half of the record) against the exact D2, on every chaotic zoo series that the
# pipeline embeds: N = 10^5, the zoo's delay, Theiler window and dimensions (m = 1 .. Cao's m + 3,
# the automatic radii), as measure_fast_d2.sh. The quick look answers rough unless its subsets
# settle; what it promises is an interval that holds the exact counts' D2. So a row is
#   holds      the answer's interval holds the exact D2 (the exact counts saturate)
#   MISS       it does not; a confident MISS is the failure that matters most
#   none       the quick look gives no value
#   no exact   the exact counts do not saturate: nothing to hold
# Times are each process's wall time (reading the series included), one thread.
#
# Usage: scripts/measure/measure_quick_d2.sh [build-dir] > table.md
# Environment: JOBS (2) parallel systems (use JOBS=1 for the time columns), ONLY=name,name,
# SEEDS ("1 2 3").
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/measure/zoo_neighbourhood_common.sh "$@"
seeds=${SEEDS:-1 2 3}

zoo_choices | zoo_only > "$work/systems"
[[ -s $work/systems ]] || { echo "no automatic-choice rows at N = 10^5 found in docs/validation/zoo.md (or none ONLY selects)" >&2; exit 3; }

case_rows() {  # name tau m w -> $work/rows.name
  local name=$1 tau=$2 m=$3 w=$4 out="$work/rows.$1" exact_d2 exact_status exact_t seed json
  zoo_series "$name" > /dev/null
  local args=("$work/$name.dat" -d "$tau" -t "$w" -M "$((m + 3))")
  /usr/bin/time -f '%e' -o "$work/$name.exact.t" "$chaos" d2 "${args[@]}" --no-halves --json -q > "$work/$name.exact.json"
  exact_d2=$(jq -r '.d2 // "null"' "$work/$name.exact.json")
  exact_status=$(jq -r '.status' "$work/$name.exact.json")
  exact_t=$(cat "$work/$name.exact.t")
  : > "$out"
  for seed in $seeds; do
    json="$work/$name.$seed.json"
    /usr/bin/time -f '%e' -o "$work/$name.fast.t" "$chaos" d2 "${args[@]}" --fast --seed "$seed" --json -q > "$json"
    jq -r --arg name "$name" --arg tau "$tau" --arg m "$m" --arg w "$w" --arg seed "$seed" --arg xd2 "$exact_d2" \
      --arg xst "$exact_status" --arg xt "$exact_t" --arg t "$(cat "$work/$name.fast.t")" '
      def num: if . == null then "-" else (. * 10000 | round / 10000 | tostring) end;
      .estimate as $e |
      (if $xst != "saturated" then "no exact"
       elif $e.value == null then "none"
       elif ($xd2 | tonumber) >= $e.interval[0] and ($xd2 | tonumber) <= $e.interval[1] then "holds"
       else "MISS" end) as $v |
      [$name, $tau, $m, $w, "\($xd2 | tonumber? // null | num) \($xst)", $xt, $seed,
       "\($e.value | num) [\($e.interval[0] | num), \($e.interval[1] | num)] \($e.status)",
       (if $e.value != null and $xst == "saturated" then (($e.value - ($xd2 | tonumber)) | fabs | num) else "-" end),
       $t, $v] | @tsv' "$json" >> "$out"
  done
  echo "done $name" >&2
}
export -f case_rows zoo_series
export chaos work seeds

zoo_run_cases < "$work/systems"

echo "# \`chaos d2 --fast\` (defaults) against the exact D2 on the zoo's chaotic series"
echo
echo "Made by \`JOBS=$jobs scripts/measure/measure_quick_d2.sh\` at $(git rev-parse --short HEAD) in ${elapsed} s ($(zoo_machine)); seeds $seeds."
echo
echo "| system | tau | m | w | exact D2 | exact s | seed | --fast answer | \\|fast - exact\\| | fast s | verdict |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
zoo_table_rows
echo
cat "$work"/rows.* | awk -F'\t' '{ n += 1; v[$11] += 1; if ($8 ~ /confident$/) { c += 1; if ($11 == "MISS") cm += 1 }
  t += $10; if ($10 > tmax) tmax = $10 }
  END { printf "- %d runs: holds %d, MISS %d, none %d, no exact D2 %d; confident %d (of them MISS %d); fast time mean %.2f s, max %.2f s\n",
        n, v["holds"], v["MISS"], v["none"], v["no exact"], c, cm, t / n, tmax }'
