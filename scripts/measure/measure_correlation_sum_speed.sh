#!/usr/bin/env bash
# Times the two exact correlation-sum target jobs with `chaos d2` on one thread (and
# two), and prints the pair throughput and a checksum of every pair count, so a faster kernel can
# be checked to count exactly what the previous one counted.
#   Lorenz x, N = 10^5: -d 17 -t 200 -M 6 -r 0.25 -R 5 -# 40
#   Henon x,  N = 10^5: -d 1 -t 10 -M 4 -r 0.005 -R 0.4 -# 40
# Usage: scripts/measure/measure_correlation_sum_speed.sh [build-dir]   (default: build, Release)
# Environment: REPEATS (default 3) runs per job; the fastest and the median wall time and the
# smallest user CPU time are shown (each run is one process, reading the series from a text file
# included). THREADS (default "1 2"). BASELINE=/path/to/another/chaos times that executable too,
# each of its runs alternated with one of this build's, and prints its rows and checksums beside
# (the checksums must agree: the counts are exact).
#
# Throughput columns (pairs per second per core, from the fastest run):
#   admissible/s  the admissible pairs M = (P - w - 1)(P - w)/2 over the time: the rate a brute
#                 force would need to match (every pair, every m);
#   cell-list/s   the pairs closer than r_max in m = 2: the pairs any exact method that bins each
#                 close pair must touch at least once (a perfect cell list examines no others);
#   binned/s      the (pair, m) histogram increments, sum over m >= 2 of the pairs closer than r_max.
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
chaos="$build/chaos/chaos"
[[ -x $chaos ]] || { echo "build the chaos command first: cmake --build $build --target chaos_cli" >&2; exit 2; }
command -v jq > /dev/null || { echo "jq is needed" >&2; exit 2; }
[[ -x /usr/bin/time ]] || { echo "/usr/bin/time (GNU time) is needed" >&2; exit 2; }
repeats=${REPEATS:-3}
threads_list=${THREADS:-1 2}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$chaos" generate lorenz -l 100000 --components x > "$work/lorenz.dat"
"$chaos" generate henon -l 100000 --components x > "$work/henon.dat"
lorenz_args=(-d 17 -t 200 -M 6 -r 0.25 -R 5 -# 40)
henon_args=(-d 1 -t 10 -M 4 -r 0.005 -R 0.4 -# 40)

echo "# $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores; load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "# commit $(git rev-parse --short HEAD 2>/dev/null || echo unknown); $repeats runs per row"
programs=("$chaos")
labels=(this)
if [[ -n ${BASELINE:-} ]]; then
  [[ -x $BASELINE ]] || { echo "BASELINE=$BASELINE is not an executable" >&2; exit 2; }
  programs=("$BASELINE" "$chaos")
  labels=(baseline this)
fi
# The counting alone: `chaos d2` also counts each half of the record to check a
# saturated D2 (half a job more); builds from before then neither know --no-halves nor check.
plain=()
for ((e = 0; e < ${#programs[@]}; e++)); do
  if "${programs[$e]}" d2 --help | grep -q -- '--no-halves'; then plain+=(--no-halves); else plain+=(""); fi
done
printf 'job\tprogram\tthreads\tbest_s\tmedian_s\tbest_user_s\tpeak_MiB\tadmissible/s\tcell-list/s\tbinned/s\tcounts_md5\n'

# job NAME DATA N TAU W MAXM ARGS...: for each thread count, the repeats of every executable in
# $programs alternated back to back (so a change in the machine's load hits all of them alike).
job() {
  local name=$1 data=$2 n=$3 tau=$4 w=$5 maxm=$6
  shift 6
  local threads s u k i e md5
  for threads in $threads_list; do
    for ((e = 0; e < ${#programs[@]}; e++)); do : > "$work/times$e"; : > "$work/kib$e"; done
    for ((i = 0; i < repeats; i++)); do
      for ((e = 0; e < ${#programs[@]}; e++)); do
        /usr/bin/time -f '%e %U %M' -o "$work/time" "${programs[$e]}" d2 "$data" "$@" ${plain[$e]} --threads "$threads" --json -q > "$work/out$e.json"
        read -r s u k < "$work/time"
        echo "$s $u" >> "$work/times$e"
        echo "$k" >> "$work/kib$e"
      done
    done
    for ((e = 0; e < ${#programs[@]}; e++)); do
      md5=$(jq -c '.pairs' "$work/out$e.json" | md5sum | cut -c1-12)
      jq -r '.pairs | map(.[-1]) | @tsv' "$work/out$e.json" > "$work/rmax"
      awk -v name="$name" -v thr="$threads" -v n="$n" -v tau="$tau" -v w="$w" -v maxm="$maxm" -v md5="$md5" \
        -v prog="${labels[$e]}" -v rmax="$(cat "$work/rmax")" -v kib="$(sort -g "$work/kib$e" | tail -1)" \
        -v walls="$(cut -d' ' -f1 "$work/times$e" | sort -g | tr '\n' ' ')" \
        -v users="$(cut -d' ' -f2 "$work/times$e" | sort -g | tr '\n' ' ')" 'BEGIN {
          c = split(walls, t, " "); best = t[1]; median = t[int((c + 1) / 2)]
          split(users, us, " "); user = us[1]
          p = n - (maxm - 1) * tau; m = (p - w - 1) * (p - w) / 2
          k = split(rmax, r, "\t"); cell = r[2]; binned = 0
          for (j = 2; j <= k; j++) binned += r[j]
          core = best * thr
          printf "%s\t%s\t%d\t%.2f\t%.2f\t%.2f\t%.0f\t%.3g\t%.3g\t%.3g\t%s\n", name, prog, thr, best, median, user, kib / 1024, m / core, cell / core, binned / core, md5
        }'
    done
  done
}

job lorenz "$work/lorenz.dat" 100000 17 200 6 "${lorenz_args[@]}"
job henon "$work/henon.dat" 100000 1 10 4 "${henon_args[@]}"
echo "# load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
