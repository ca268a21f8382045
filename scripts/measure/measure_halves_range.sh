#!/usr/bin/env bash
# How far each saturated automatic D2 of the zoo lies outside the range of its own halves' D2
# (docs/notes/zoo-notes.md, section 13: a rule "the full record's D2 must lie within its halves' range"
# was measured and not adopted).
#   scripts/measure/measure_halves_range.sh [build-dir] > table.md
# For every system whose automatic D2 at N = 10^5 is saturated in docs/validation/zoo.md: `chaos d2` on the
# zoo's series at the zoo's choices (tau, w, m up to Cao's + 3, the embedding range `chaos analyze`
# gives D2), the halves counted (the default), and the distance of the full record's D2 outside
# [min, max] of the halves' D2 (0 inside; "-" where a half has no D2). JOBS (default 2) runs
# systems in parallel. ONLY=name,name measures those systems alone.
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/measure/zoo_neighbourhood_common.sh "$@"

case_row() {  # name tau m w band: one Markdown row
  local name=$1 tau=$2 m=$3 w=$4 band=$5
  zoo_series "$name" > /dev/null
  "$chaos" d2 "$work/$name.dat" -d "$tau" -t "$w" -M $((m + 3)) --json |
    /usr/bin/python3 -c '
import json, sys
name, band = sys.argv[1], sys.argv[2]
d = json.load(sys.stdin)
low, high = (float(v) for v in band.strip("[]").split(","))
def num(v):
    return "-" if v is None else "%.3f" % v
full = d.get("d2")
halves = [d.get(h, {}).get("d2") for h in ("first_half", "second_half")]
status = [d.get(h, {}).get("status", "-") for h in ("first_half", "second_half")]
if full is None or None in halves:
    outside = "-"
else:
    outside = "%.3f" % max(0.0, min(halves) - full, full - max(halves))
verdict = "-" if full is None else ("in band" if low <= full <= high else "**out of band**")
print("| %s | %s | %s %s | %s | %s (%s) | %s (%s) | %s |" % (name, band, num(full), d["status"], verdict,
      num(halves[0]), status[0], num(halves[1]), status[1], outside))
' "$name" "$band" > "$work/$name.row"
}
export -f case_row

zoo_saturated_cases > "$work/cases"
start=$(date +%s)
xargs -P "$jobs" -L 1 bash -c 'case_row "$@"' _ < "$work/cases"
echo "Made by \`scripts/measure/measure_halves_range.sh\` (commit $(git rev-parse --short HEAD), $(zoo_machine), $(( $(date +%s) - start )) s)."
echo
echo "| system | band | D2 (full record) | verdict | first half | second half | outside the halves' range by |"
echo "|---|---|---|---|---|---|---|"
while read -r name _; do cat "$work/$name.row"; done < "$work/cases"
