#!/usr/bin/env bash
# `chaos d2` at the zoo's delay, window and dimensions, over other radius grids: for every chaotic
# system of docs/validation/zoo.md that the pipeline analyses, the zoo's series at N = 10^5 and
# `chaos d2 -d TAU -t W -M M+3` (the pipeline's dimensions: Cao's m plus 3) with
#   - the pipeline's grid: 40 log-spaced radii from range/1000 to range/4 (the default of both);
#   - 30 and 60 radii over the same span (a coarser and a finer grid);
#   - the same 40 radii shifted up by half a step (every radius times q^(1/2), q the ratio of
#     neighbouring radii: the grid between the default's radii) and by a quarter step (q^(1/4));
#   - a wider span at the same density: 50 radii from range/2000 to range/2.
# The number and the span of the radii are the user's choices (TISEAN's -# -r -R); the zoo's grid
# varies m, w and N at the default radii only. A plateau that moves with half a step of the grid is
# a reading of the grid, not of the data (docs/notes/zoo-notes.md, section 5: the three-torus).
#
# Band, fixed before the run: the D2 band of the system's row in docs/validation/zoo.md (a cited D2 +- 0.1,
# else at most D_KY + 0.1). A `saturated` D2 outside it is WRONG; any other status is unsure.
#
# Usage: scripts/measure/measure_radius_neighbourhood.sh [build-dir] > table.md
# Environment: JOBS (2) parallel systems; ONLY=name,name to restrict the systems.
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/measure/zoo_neighbourhood_common.sh "$@"

zoo_systems > "$work/systems"
zoo_choices > "$work/choices"
[[ -s $work/choices ]] || { echo "no automatic-choice rows at N = 10^5 found in docs/validation/zoo.md" >&2; exit 3; }

case_rows() {  # name tau m w -> $work/rows.name
  local name=$1 tau=$2 m=$3 w=$4 lo hi range out="$work/rows.$1" json
  read -r lo hi < <(awk -v n="$name" '$1 == n { print $4, $5 }' "$work/systems")
  zoo_series "$name" > /dev/null
  range=$(awk 'NR == 1 { a = b = $1 } { if ($1 < a) a = $1; if ($1 > b) b = $1 } END { printf "%.17g", b - a }' "$work/$name.dat")
  : > "$out"
  # label|r_min|r_max|count; s = q^(1/2), half a step of 40 radii over a span of 250 (q = 250^(1/39))
  while IFS='|' read -r label rmin rmax count; do
    json=$("$chaos" d2 "$work/$name.dat" -d "$tau" -t "$w" -M $((m + 3)) -r "$rmin" -R "$rmax" -# "$count" --json -q 2> /dev/null) ||
      json='{}'
    jq -r --arg name "$name" --arg tau "$tau" --arg m "$((m + 3))" --arg w "$w" --arg lo "$lo" --arg hi "$hi" --arg grid "$label" '
      def num: if . == null then "-" else (. * 10000 | round / 10000 | tostring) end;
      [$name, $tau, $m, $w, $grid,
       "\(.d2 | num) \(.status // "error")",
       (if .scaling_region == null then "-" else "[\(.scaling_region[0] | num), \(.scaling_region[1] | num)]" end),
       "[\($lo), \($hi)]",
       (if .status != "saturated" then "unsure"
        elif .d2 >= ($lo | tonumber) and .d2 <= ($hi | tonumber) then "in_band" else "WRONG" end)] | join("\t")' \
      <<< "$json" >> "$out"
  done < <(awk -v r="$range" 'BEGIN {
      s = exp(log(250) / 78); lo = r / 1000; hi = r / 4
      printf "40 radii, range/1000 .. range/4 (default)|%.17g|%.17g|40\n", lo, hi
      printf "30 radii|%.17g|%.17g|30\n", lo, hi
      printf "60 radii|%.17g|%.17g|60\n", lo, hi
      printf "40 radii, half a step up|%.17g|%.17g|40\n", lo * s, hi * s
      printf "40 radii, a quarter step up|%.17g|%.17g|40\n", lo * sqrt(s), hi * sqrt(s)
      printf "50 radii, range/2000 .. range/2|%.17g|%.17g|50\n", r / 2000, r / 2 }')
  echo "done $name" >&2
}
export -f case_rows

zoo_run_cases < <(zoo_only < "$work/choices")

echo "# \`chaos d2\` over other radius grids (written by scripts/measure/measure_radius_neighbourhood.sh)"
echo
echo "Commit $(git rev-parse --short HEAD 2> /dev/null || echo unknown); $(zoo_machine); $elapsed s."
echo
echo "| system | tau | M | w | radii | D2 | scaling region (eps) | D2 band | verdict |"
echo "|---|---|---|---|---|---|---|---|---|"
zoo_table_rows
echo
cat "$work"/rows.* | awk -F'\t' '{ n[$5]++; v[$5 "\t" $9]++; labels[$5] = 1 }
  END {
    for (l in labels)
      printf "- %s: %d in band / %d unsure / %d wrong\n", l, v[l "\tin_band"] + 0, v[l "\tunsure"] + 0, v[l "\tWRONG"] + 0
  }' | sort
