#!/usr/bin/env bash
# `chaos lyapunov` with every check (the default: Rosenstein and Kantz curves over m, m+1, m+2, the
# cross-check between them, the halves of the record and the local-map check) beside TISEAN's
# lyap_k on the same file, runs alternated back to back, user CPU time of each process.
#   Lorenz x, N = 10^5, dt = 0.01 (`chaos generate lorenz -l 100000 --components x`).
# chaos runs with its defaults; lyap_k with the embedding chaos chose (read from its JSON): minimum
# and maximum dimension m and m + 2, the delay, the Theiler window, the steps and the first
# 10^4 reference points (lyap_k takes the first n, chaos n evenly spaced), at its default five radii
# (-r range/1000 to -R range/100) and, as a second row, at the one radius Kantz used (-# 1).
# A second chaos row gives m, the delay and the window (-m -d -t), so Cao's method and the other
# automatic choices are not timed: the estimators and their checks alone.
#
# Usage: scripts/measure/measure_lyapunov_speed.sh LYAP_K [build-dir]
#   LYAP_K: a lyap_k executable, built from TISEAN's source_c (lyap_k.c and routines/), e.g.
#     gcc -O3 -o lyap_k lyap_k.c routines/{check_alloc,check_option,get_series,myfgets,rescale_data,\
#       scan_help,search_datafile,test_outfile,what_i_do}.c -lm
# Environment: REPEATS (default 5) rounds; BASELINE=/path/to/another/chaos adds its rows (each of its
# runs alternated with the others) and checks that its JSON equals this build's byte for byte.
set -euo pipefail
cd "$(dirname "$0")/../.."
lyap_k=${1:?usage: $0 LYAP_K [build-dir]}
build=${2:-build}
chaos="$build/chaos/chaos"
[[ -x $chaos ]] || { echo "build the chaos command first: cmake --build $build --target chaos_cli" >&2; exit 2; }
[[ -x $lyap_k ]] || { echo "$lyap_k is not an executable" >&2; exit 2; }
command -v jq > /dev/null || { echo "jq is needed" >&2; exit 2; }
[[ -x /usr/bin/time ]] || { echo "/usr/bin/time (GNU time) is needed" >&2; exit 2; }
repeats=${REPEATS:-5}
baseline=${BASELINE:-}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$chaos" generate lorenz -l 100000 --components x > "$work/lorenz.dat"
grep -v '^#' "$work/lorenz.dat" > "$work/lorenz.x"  # lyap_k reads plain numbers
"$chaos" lyapunov "$work/lorenz.dat" --dt 0.01 --json -q > "$work/chosen.json"
read -r m tau w steps refs < <(jq -r '.parameters | "\(.dimension) \(.delay) \(.theiler) \(.steps) \(.reference_points)"' "$work/chosen.json")
eps=$(jq -r '.cross_check.radius' "$work/chosen.json")
[[ $eps != null ]] || eps=$(jq -r '.parameters.radius' "$work/chosen.json")

echo "# $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores; load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "# commit $(git rev-parse --short HEAD 2>/dev/null || echo unknown); $repeats rounds, user CPU seconds (min / median)"
echo "# chaos chose m = $m, tau = $tau, w = $w, K = $steps, $refs reference points; Kantz eps = $eps"

names=() commands=()
add() { names+=("$1"); commands+=("$2"); }
add "chaos lyapunov --dt 0.01 (every default)" "$chaos lyapunov $work/lorenz.dat --dt 0.01 --json -q -o $work/this.json"
add "chaos lyapunov --dt 0.01 -m $m -d $tau -t $w" "$chaos lyapunov $work/lorenz.dat --dt 0.01 -m $m -d $tau -t $w --json -q -o $work/this_given.json"
if [[ -n $baseline ]]; then
  add "baseline: every default" "$baseline lyapunov $work/lorenz.dat --dt 0.01 --json -q -o $work/base.json"
  add "baseline: -m $m -d $tau -t $w" "$baseline lyapunov $work/lorenz.dat --dt 0.01 -m $m -d $tau -t $w --json -q -o $work/base_given.json"
fi
add "lyap_k -m $m -M $((m + 2)) -d $tau -t $w -s $steps -n $refs (5 radii)" \
  "$lyap_k $work/lorenz.x -m $m -M $((m + 2)) -d $tau -t $w -s $steps -n $refs -V 0 -o $work/tisean5.lyap"
add "lyap_k ... -# 1 -r $eps (Kantz's radius)" \
  "$lyap_k $work/lorenz.x -m $m -M $((m + 2)) -d $tau -t $w -s $steps -n $refs -# 1 -r $eps -V 0 -o $work/tisean1.lyap"

for ((round = 0; round < repeats; ++round)); do
  for c in "${!commands[@]}"; do
    /usr/bin/time -f '%U' -o "$work/time.$c.$round" ${commands[$c]} 2> /dev/null
  done
done
stats() {  # min and median of the rounds of command $1
  cat "$work"/time."$1".* | sort -g | awk '{ v[NR] = $1 } END { printf "%.2f / %.2f", v[1], v[int((NR + 1) / 2)] }'
}
echo "| run | user s (min / median) |"
echo "|---|---|"
for c in "${!commands[@]}"; do echo "| ${names[$c]} | $(stats "$c") |"; done
if [[ -n $baseline ]]; then
  # The keys that record the bounds (max_neighbours, max_maps, capped_neighbourhoods) are new; every
  # other value must be the same to the last digit.
  same() { cmp -s <(jq -c "$drop" "$1") <(jq -c "$drop" "$2"); }
  drop='del(.parameters.max_neighbours, .parameters.max_maps, .capped_neighbourhoods)'
  same "$work/this.json" "$work/base.json" && echo "# JSON identical to the baseline's (defaults)" || echo "# JSON DIFFERS from the baseline's (defaults)"
  same "$work/this_given.json" "$work/base_given.json" && echo "# JSON identical to the baseline's (-m -d -t)" || echo "# JSON DIFFERS from the baseline's (-m -d -t)"
fi
