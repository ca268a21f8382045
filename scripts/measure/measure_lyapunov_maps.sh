#!/usr/bin/env bash
# lambda_1 from local linear maps (`chaos lyapunov-maps`, chaos/include/chaos/lyapunov_local_maps.hpp)
# on the zoo, measured outside `chaos zoo` (docs/reference/lyapunov-maps.md): every chaotic system with tau, m
# and w from the automatic-choice rows of docs/validation/zoo.md, judged against the zoo's band (lambda_1 from the
# equations +- 10%); the zoo's neighbourhood grid (N = 10^4 and 10^5, m from the automatic m to m + 3,
# w = 1, 2, 3 times the automatic window, tau fixed at the automatic delay of that N); and the
# controls at four fixed embeddings (m, tau) = (2, 1), (3, 1), (4, 5), (5, 10), automatic w, where no
# status but `consistent` with a positive value counts as confident.
#
# Prints three Markdown tables. A confident value is status `consistent`; every other status is unsure.
# Usage: scripts/measure/measure_lyapunov_maps.sh [build-dir]
# Environment: ONLY (comma list of zoo case names; default all), JOBS (2), GRID (1; 0 skips the grid),
# DELAYS (0; 1 adds the delay neighbourhood: at N = 10^5, the automatic m and w with the delay at
# tau/2, 3 tau/2 and 2 tau, as a fourth table).
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
chaos="$build/chaos/chaos"
[[ -x $chaos ]] || { echo "build $chaos first: cmake --build $build" >&2; exit 2; }
command -v jq > /dev/null || { echo "jq is needed" >&2; exit 2; }
jobs=${JOBS:-2}
grid=${GRID:-1}
delays=${DELAYS:-0}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# name N tau m w lambda_1, from the chaotic rows that the pipeline analysed (m > 0)
source scripts/measure/zoo_columns.sh
zoo_columns "system	N	tau	m	w	lambda_1 eq." | awk '$4 + 0 > 0' > "$work/systems"
[[ -s $work/systems ]] || { echo "no automatic-choice rows found in docs/validation/zoo.md" >&2; exit 3; }

series() {  # name -> $work/name.dat, and the sampling interval on stdout (empty for maps)
  local name=$1
  if [[ ! -s $work/$name.json ]]; then
    "$chaos" zoo --series "$name" --json > "$work/$name.json.tmp"
    jq -r '.x[]' "$work/$name.json.tmp" > "$work/$name.dat"
    mv "$work/$name.json.tmp" "$work/$name.json"
  fi
  jq -r '.parameters.dt // empty' "$work/$name.json"
}

# One estimate: prints "status lambda_per_time_or_sample" (lambda "-" when none).
estimate() {  # name N tau m w [dt]
  local name=$1 n=$2 tau=$3 m=$4 w=$5 dt=${6:-}
  "$chaos" lyapunov-maps "$work/$name.dat" -l "$n" -d "$tau" -m "$m" -t "$w" ${dt:+--dt $dt} --json 2> /dev/null |
    jq -r '"\(.status) \(.lambda // "-")"' || echo "error -"
}

case_rows() {  # name N tau m w lambda_1 -> $work/rows.name.N
  local name=$1 n=$2 tau=$3 m=$4 w=$5 lam=$6 dt out
  dt=$(flock "$work/lock.$name" bash -c "$(declare -f series); work=$work chaos=$chaos series $name")
  out="$work/rows.$name.$n"
  : > "$out"
  echo "auto $m $w $(estimate "$name" "$n" "$tau" "$m" "$w" "$dt") $lam" >> "$out"
  if [[ $grid == 1 ]]; then
    for f in 1 2 3; do
      for ((k = m; k <= m + 3; ++k)); do
        echo "grid $k $((f * w)) $(estimate "$name" "$n" "$tau" "$k" "$((f * w))" "$dt") $lam" >> "$out"
      done
    done
  fi
  if [[ $delays == 1 && $n == 100000 ]]; then
    local done_delays=" $tau "
    for t in $(((tau + 1) / 2)) $(((3 * tau + 1) / 2)) $((2 * tau)); do
      [[ $done_delays == *" $t "* ]] && continue  # tau = 1: 3 tau/2 and 2 tau are both 2
      done_delays+="$t "
      echo "delay $t $w $(estimate "$name" "$n" "$t" "$m" "$w" "$dt") $lam" >> "$out"
    done
  fi
}
export -f series estimate case_rows
export chaos work grid delays

while read -r name n tau m w lam; do
  if [[ -z ${ONLY:-} || ,$ONLY, == *,$name,* ]]; then echo "$name $n $tau $m $w $lam"; fi
done < "$work/systems" | xargs -P "$jobs" -L 1 bash -c 'case_rows "$@"' _

verdict() {  # status lambda lambda_1 -> in_band | unsure | wrong
  awk -v s="$1" -v l="$2" -v t="$3" 'BEGIN {
    if (s != "consistent") print "unsure"; else if (l >= 0.9 * t && l <= 1.1 * t) print "in_band"; else print "wrong" }'
}

echo "# lambda_1 from local linear maps on the zoo"
echo
echo "Written by \`DELAYS=$delays GRID=$grid scripts/measure/measure_lyapunov_maps.sh\` (the method and what these tables show: docs/reference/lyapunov-maps.md)."
echo "A confident value is status \`consistent\`; the band is lambda_1 from the equations +- 10%; lambda per time unit for flows, per iteration for maps."
echo
echo "| system | N | tau | m | w | status | lambda | lambda_1 (equations) | verdict | grid: in band / unsure / wrong |"
echo "|---|---|---|---|---|---|---|---|---|---|"
auto_in=0 auto_wrong=0 auto_total=0 grid_in=0 grid_unsure=0 grid_wrong=0
while read -r name n tau m w lam; do
  [[ -z ${ONLY:-} || ,$ONLY, == *,$name,* ]] || continue
  rows="$work/rows.$name.$n"
  read -r _ _ _ status value _ < <(grep '^auto ' "$rows")
  v=$(verdict "$status" "$value" "$lam")
  gi=0 gu=0 gw=0
  while read -r _ _ _ s l t; do
    case $(verdict "$s" "$l" "$t") in in_band) gi=$((gi + 1)) ;; unsure) gu=$((gu + 1)) ;; wrong) gw=$((gw + 1)) ;; esac
  done < <(grep '^grid ' "$rows")
  grid_in=$((grid_in + gi)) grid_unsure=$((grid_unsure + gu)) grid_wrong=$((grid_wrong + gw))
  if [[ $n == 100000 ]]; then
    auto_total=$((auto_total + 1))
    [[ $v == in_band ]] && auto_in=$((auto_in + 1))
  fi
  [[ $v == wrong ]] && auto_wrong=$((auto_wrong + 1))
  echo "| $name | $n | $tau | $m | $w | $status | $value | $lam | $v | $gi / $gu / $gw |"
done < "$work/systems"
echo
echo "Automatic choices at N = 10^5: $auto_in of $auto_total analysed systems confident and in band; confident and wrong at either N: $auto_wrong."
[[ $grid == 1 ]] && echo "Grid, all systems: $grid_in in band, $grid_unsure unsure, $grid_wrong wrong."

if [[ $delays == 1 ]]; then
  echo
  echo "| system | tau (automatic) | tau | m | w | status | lambda | lambda_1 (equations) | verdict |"
  echo "|---|---|---|---|---|---|---|---|---|"
  di=0 du=0 dw=0
  while read -r name n tau m w lam; do
    [[ $n == 100000 && ( -z ${ONLY:-} || ,$ONLY, == *,$name,* ) ]] || continue
    while read -r _ t _ s l _; do
      v=$(verdict "$s" "$l" "$lam")
      case $v in in_band) di=$((di + 1)) ;; unsure) du=$((du + 1)) ;; wrong) dw=$((dw + 1)) ;; esac
      echo "| $name | $tau | $t | $m | $w | $s | $l | $lam | $v |"
    done < <(grep '^delay ' "$work/rows.$name.$n")
  done < "$work/systems"
  echo
  echo "Delay neighbourhood (tau/2, 3 tau/2, 2 tau at N = 10^5): $di in band, $du unsure, $dw wrong."
fi

echo
echo "| control | (m, tau) = (2, 1) | (3, 1) | (4, 5) | (5, 10) |"
echo "|---|---|---|---|---|"
controls=(white_noise ar1 pink_noise brown_noise random_walk lorenz_iaaft henon_iaaft periodic_integer periodic_rational
  periodic_irrational torus2 torus2_rational_first torus3 lorenz_snr20 lorenz_snr10 henon_snr20 lorenz_quantised
  henon_quantised lorenz_short henon_short)
for name in "${controls[@]}"; do
  [[ -z ${ONLY:-} || ,$ONLY, == *,$name,* ]] || continue
  series "$name" > /dev/null
  line="| $name |"
  for mt in "2 1" "3 1" "4 5" "5 10"; do
    read -r m tau <<< "$mt"
    line+=" $("$chaos" lyapunov-maps "$work/$name.dat" -m "$m" -d "$tau" --json 2> /dev/null |
      jq -r '"\(.status)\(if .lambda then " \(.lambda)" else "" end)"' || echo error) |"
  done
  echo "$line"
done
