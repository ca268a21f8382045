#!/usr/bin/env bash
# The other plateaus beside each saturated automatic D2 of the zoo (docs/notes/zoo-notes.md, section 6).
#   scripts/measure/measure_other_plateaus.sh [build-dir] > table.md
# For every system whose automatic D2 at N = 10^5 is saturated in docs/validation/zoo.md: `chaos d2` on the
# zoo's series at the zoo's choices (tau, w, m up to Cao's + 3), the record's halves left out (they
# do not change which plateau is chosen), and the plateaus the same rule admitted but did not choose
# (`other_plateaus` in the JSON). JOBS (default 2) runs systems in parallel. ONLY=name,name
# measures those systems alone.
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/measure/zoo_neighbourhood_common.sh "$@"

case_row() {  # name tau m w band: one Markdown row
  local name=$1 tau=$2 m=$3 w=$4 band=$5
  zoo_series "$name" > /dev/null
  "$chaos" d2 "$work/$name.dat" -d "$tau" -t "$w" -M $((m + 3)) --no-halves --json |
    /usr/bin/python3 -c '
import json, sys
name, band = sys.argv[1], sys.argv[2]
d = json.load(sys.stdin)
low, high = (float(v) for v in band.strip("[]").split(","))
def cell(d2, radii):
    mark = "" if low <= d2 <= high else " (out of band)"
    return "%.3f at eps %.3g-%.3g%s" % (d2, radii[0], radii[1], mark)
others = d.get("other_plateaus") or []
far = max((abs(p["slope"] - d["d2"]) for p in others), default=0.0)
print("| %s | %s | %s | %s | %.2f |" % (name, band, cell(d["d2"], d["scaling_region"]),
      "; ".join(cell(p["slope"], p["radii"]) for p in others) or "-", far))
' "$name" "$band" > "$work/$name.row"
}
export -f case_row

zoo_saturated_cases > "$work/cases"
start=$(date +%s)
xargs -P "$jobs" -L 1 bash -c 'case_row "$@"' _ < "$work/cases"
echo "Made by \`scripts/measure/measure_other_plateaus.sh\` (commit $(git rev-parse --short HEAD), $(zoo_machine), $(( $(date +%s) - start )) s)."
echo
echo "| system | band | chosen D2 (region) | other plateaus | largest distance |"
echo "|---|---|---|---|---|"
while read -r name _; do cat "$work/$name.row"; done < "$work/cases"
