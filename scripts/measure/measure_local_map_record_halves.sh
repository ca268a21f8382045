#!/usr/bin/env bash
# Would a "halves of the record" variant catch the local-map lambda_1 that reads low at N = 5*10^4 on
# windmi (docs/notes/zoo-notes.md, section 14)? For every flow or delay system (tau > 1) whose local-map
# lambda_1 is `consistent` in docs/validation/zoo.md at N = 10^5 or in docs/notes/zoo-length.md at 2*10^4 or 5*10^4:
# `chaos lyapunov-maps` on the first N samples of the zoo's series at the row's tau and w, at Cao's m
# or, where that is not consistent, at m + 1 (the pipeline's order), then the same on each half of
# that record. Each row: the base over lambda_1 from the equations, each half's base over the full
# record's, and the larger deviation. (The estimator's own "halves" variant splits the chain, not the
# record: both halves keep the whole record's neighbours.)
#   scripts/measure/measure_local_map_record_halves.sh [build-dir] > table.md
# JOBS (default 2) runs cases in parallel; each system's series is generated once, before them.
set -euo pipefail
cd "$(dirname "$0")/../.."
[[ -f docs/notes/zoo-length.md ]] || { echo "docs/notes/zoo-length.md is missing (scripts/measure/measure_length_neighbourhood.sh writes it)" >&2; exit 2; }
source scripts/measure/zoo_neighbourhood_common.sh "$@"

case_row() {  # name N tau m w lambda_1: one Markdown row
  local name=$1 n=$2 tau=$3 m=$4 w=$5 lam=$6 dt dim status base first second
  local dir="$work/$name.$n"
  mkdir -p "$dir"
  dt=$(cat "$work/$name.dt")
  head -n "$n" "$work/$name.dat" > "$dir/all.dat"
  head -n $((n / 2)) "$dir/all.dat" > "$dir/first.dat"
  tail -n $((n / 2)) "$dir/all.dat" > "$dir/second.dat"
  local per_time=()
  [[ -n $dt ]] && per_time=(--dt "$dt")
  maps() {  # file m -> "status base"
    "$chaos" lyapunov-maps "$1" -d "$tau" -m "$2" -t "$w" "${per_time[@]}" --json |
      jq -r '"\(.status) \(.variants[0].lambda)"'
  }
  dim=$m
  read -r status base < <(maps "$dir/all.dat" "$dim")
  if [[ $status != consistent ]]; then
    dim=$((m + 1))
    read -r status base < <(maps "$dir/all.dat" "$dim")
  fi
  read -r _ first < <(maps "$dir/first.dat" "$dim")
  read -r _ second < <(maps "$dir/second.dat" "$dim")
  awk -v name="$name" -v n="$n" -v m="$dim" -v status="$status" -v base="$base" -v a="$first" -v b="$second" -v lam="$lam" 'BEGIN {
    da = a / base - 1; db = b / base - 1; dev = (da < 0 ? -da : da); if ((db < 0 ? -db : db) > dev) dev = (db < 0 ? -db : db)
    printf "| %s | %d | %d | %s | %.3f | %.3f | %.3f | %.1f%% |\n", name, n, m, status, base / lam, a / base, b / base, 100 * dev }' \
    > "$work/$name.$n.row"
}
export -f case_row

{
  # docs/notes/zoo-length.md: system | N | tau | m | w | D2 | band | verdict | Rosenstein | v | Kantz | v | local maps | v | lambda_1
  awk -F'|' '$14 ~ / consistent/ && $4 + 0 > 1 { gsub(/ /, "", $2); print $2, $3 + 0, $4 + 0, $5 + 0, $6 + 0, $16 + 0 }' docs/notes/zoo-length.md
  # docs/validation/zoo.md at N = 10^5 (a consistent local-map cell reads "VALUE [LOW, HIGH] consistent ...")
  zoo_columns "system	N	tau	m	w	lambda local maps	lambda_1 eq." |
    awk '$2 == 100000 && $6 ~ /\]consistent/ && $3 + 0 > 1 { print $1, 100000, $3 + 0, $4 + 0, $5 + 0, $7 + 0 }'
} > "$work/cases"
start=$(date +%s)
# One series per system (zoo_series writes $work/NAME.dat and prints the sampling step), made here
# because a system's cases at several N run in parallel and would otherwise write the same files.
while read -r name; do zoo_series "$name" > "$work/$name.dt"; done < <(cut -d' ' -f1 "$work/cases" | sort -u)
xargs -P "$jobs" -L 1 bash -c 'case_row "$@"' _ < "$work/cases"
echo "Made by \`scripts/measure/measure_local_map_record_halves.sh\` (commit $(git rev-parse --short HEAD), $(zoo_machine), $(( $(date +%s) - start )) s)."
echo
echo "| system | N | m | status (whole record) | base / lambda_1 | first half / base | second half / base | larger deviation |"
echo "|---|---|---|---|---|---|---|---|"
while read -r name n _; do cat "$work/$name.$n.row"; done < "$work/cases"
