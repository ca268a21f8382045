#!/usr/bin/env bash
# `chaos d2 --fast` out of sample: on every chaotic zoo system that the pipeline embeds, the zoo's
# series at N = 10^5 with the zoo's automatic delay, Theiler window and dimensions (m = 1 .. Cao's
# m + 3, 40 radii from range/1000 to range/4: exactly the correlation sums of `chaos analyze`), the
# exact D2 against `--fast` for several seeds and first-round sizes. --fast was built on Lorenz and
# Hénon; this asks whether its promise holds on series nobody tuned it to.
#
# The promise (docs/reference/correlation_dimension.md, "A budget chosen by the data"): an accepted budget
# gives a saturated D2 within --fast-target (0.02) of the exact counts' D2; otherwise --fast uses the
# exact counts. So a row is
#   exact      --fast fell back to the exact counts (same answer as the exact run, slower)
#   ok         accepted, the exact D2 saturated too, and |fast - exact| <= target
#   MISS       accepted and saturated, but more than the target from the exact D2, or the exact
#              counts do not saturate at all (a confident answer where the exact one is unsure)
#   unsure     accepted, not saturated (the subset's counts decline to answer)
# Times are each process's wall time (reading the series included), one thread.
#
# Usage: scripts/measure/measure_fast_d2.sh [build-dir] > table.md
# Environment: JOBS (2) parallel systems (timings are then shared-machine figures; use JOBS=1 for
# the time columns), ONLY=name,name, SEEDS ("1 2 3"), STARTS (first-round sizes, each run with
# every seed; default 500, the option's default), TARGET (0.02).
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/measure/zoo_neighbourhood_common.sh "$@"
seeds=${SEEDS:-1 2 3}
starts=${STARTS:-500}
target=${TARGET:-0.02}

zoo_choices | zoo_only > "$work/systems"
[[ -s $work/systems ]] || { echo "no automatic-choice rows at N = 10^5 found in docs/validation/zoo.md (or none ONLY selects)" >&2; exit 3; }

timed() {  # out-json time-file args...: chaos d2 with its wall time (the estimator alone: --no-halves)
  local json=$1 tfile=$2
  shift 2
  /usr/bin/time -f '%e' -o "$tfile" "$chaos" d2 "$@" --no-halves --json -q > "$json"
}

case_rows() {  # name tau m w -> $work/rows.name
  local name=$1 tau=$2 m=$3 w=$4 out="$work/rows.$1" max exact_d2 exact_status exact_t seed start json
  max=$((m + 3))
  zoo_series "$name" > /dev/null
  local args=("$work/$name.dat" -d "$tau" -t "$w" -M "$max")
  timed "$work/$name.exact.json" "$work/$name.exact.t" "${args[@]}"
  exact_d2=$(jq -r '.d2 // "null"' "$work/$name.exact.json")
  exact_status=$(jq -r '.status' "$work/$name.exact.json")
  exact_t=$(cat "$work/$name.exact.t")
  : > "$out"
  for start in $starts; do
    for seed in $seeds; do
      json="$work/$name.$start.$seed.json"
      # --fast-budget 0: the rounds double until they settle (the command's default budget is one round)
      timed "$json" "$work/$name.fast.t" "${args[@]}" --fast --fast-start "$start" --fast-budget 0 --seed "$seed"
      jq -r --arg name "$name" --arg tau "$tau" --arg m "$m" --arg w "$w" --arg start "$start" --arg seed "$seed" \
        --arg xd2 "$exact_d2" --arg xst "$exact_status" --arg xt "$exact_t" --arg t "$(cat "$work/$name.fast.t")" \
        --arg target "$target" '
        def num: if . == null then "-" else (. * 10000 | round / 10000 | tostring) end;
        (if .fast.exact then "exact"
         elif .status != "saturated" then "unsure"
         elif $xst != "saturated" then "MISS"
         elif ((.d2 - ($xd2 | tonumber)) | fabs) <= ($target | tonumber) then "ok" else "MISS" end) as $v |
        [$name, $tau, $m, $w, "\($xd2 | tonumber? // null | num) \($xst)", $xt, $start, $seed,
         (if .fast.exact then "exact" else (.fast.reference_points | tostring) end),
         "\(.d2 | num) \(.status)",
         (if .d2 != null and $xst == "saturated" then ((.d2 - ($xd2 | tonumber)) | fabs | num) else "-" end),
         $t, $v] | @tsv' "$json" >> "$out"
    done
  done
  echo "done $name" >&2
}
export -f case_rows timed zoo_series
export chaos work seeds starts target

start_time=$(date +%s)
xargs -P "$jobs" -L 1 bash -c 'case_rows "$@"' _ < "$work/systems"
elapsed=$(($(date +%s) - start_time))

echo "# --fast against the exact D2 on the zoo's chaotic series"
echo
echo "Made by \`JOBS=$jobs scripts/measure/measure_fast_d2.sh\` at $(git rev-parse --short HEAD) in ${elapsed} s"
echo "($(nproc) cores, $(lscpu | sed -n 's/^Model name: *//p' | head -1)); seeds $seeds, first rounds of $starts points, target $target."
echo
echo "| system | tau | m | w | exact D2 | exact s | start | seed | budget | fast D2 | \\|fast - exact\\| | fast s | verdict |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
zoo_table_rows
echo
cat "$work"/rows.* | awk -F'\t' '{ n[$7] += 1; v[$7 " " $13] += 1 }
  END { for (s in n) { printf "- first round %s: %d runs: ok %d, exact fallback %d, unsure %d, MISS %d\n", s, n[s],
        v[s " ok"], v[s " exact"], v[s " unsure"], v[s " MISS"] } }' | sort
