#!/usr/bin/env bash
# Regenerates docs/validation/performance-d2.md: the speed/accuracy trade of the correlation-dimension knobs
# of `chaos d2` (threads, pair cap -N, reference-point subset, search mode, series length N) on
# Lorenz x and Henon x, N = 10^5. Wall time and peak memory from /usr/bin/time, D2 and its
# scaling region from `chaos d2 --json` through jq.
# Usage: scripts/measure/measure_d2_knobs.sh [build-dir]   (default: build, Release)
# Environment: REPEATS (default 3) runs of each setting, the fastest wall time is reported
# (the results themselves are deterministic); BRUTE_LIMIT (default 60) seconds for a brute-force run.
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
chaos="$build/chaos/chaos"
[[ -x $chaos ]] || { echo "build the chaos command first: cmake --build $build --target chaos_cli" >&2; exit 2; }
command -v jq > /dev/null || { echo "jq is needed" >&2; exit 2; }
[[ -x /usr/bin/time ]] || { echo "/usr/bin/time (GNU time) is needed" >&2; exit 2; }
repeats=${REPEATS:-3}
brute_limit=${BRUTE_LIMIT:-60}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
out=docs/validation/performance-d2.md

# --no-halves: the knobs of the counting alone (chaos d2 also checks a saturated D2
# on the record's halves by default, which adds about half an exact job, or, after --fast, the
# chosen budget again).
lorenz_args=(-d 17 -t 200 -M 6 -r 0.25 -R 5 -# 40 --no-halves)
henon_args=(-d 1 -t 10 -M 4 -r 0.005 -R 0.4 -# 40 --no-halves)

# measure ID LIMIT DATA ARGS...: runs `chaos d2 DATA ARGS --json` $repeats times (LIMIT seconds
# each, 0: none), keeps the JSON in $work/ID.json and "seconds MiB" (fastest run) in $work/ID.cost.
# Fails when a run exceeds the limit.
measure() {
  local id=$1 limit=$2 data=$3
  shift 3
  local best="" kib=0 s k i
  for ((i = 0; i < repeats; i++)); do
    rm -f "$work/time"
    if ((limit > 0)); then
      timeout "$limit" /usr/bin/time -f '%e %M' -o "$work/time" "$chaos" d2 "$data" "$@" --json > "$work/$id.json" || return 1
    else
      /usr/bin/time -f '%e %M' -o "$work/time" "$chaos" d2 "$data" "$@" --json > "$work/$id.json"
    fi
    read -r s k < "$work/time"
    if [[ -z $best ]] || awk -v a="$s" -v b="$best" 'BEGIN { exit !(a < b) }'; then best=$s; fi
    if ((k > kib)); then kib=$k; fi
  done
  printf '%s %s\n' "$best" "$(awk -v k="$kib" 'BEGIN { printf "%.0f", k / 1024 }')" > "$work/$id.cost"
}

# row CASE KIND ID REF SETTING: prints the table row of run ID (its D2 compared with the D2 of run
# REF) and appends "case kind setting seconds d2 diff" to $work/rows.tsv for the conclusion.
row() {
  local cs=$1 kind=$2 id=$3 ref=$4 setting=$5 seconds mib status d2 lo hi r0 r1 refd2
  read -r seconds mib < "$work/$id.cost"
  IFS=$'\t' read -r status d2 lo hi r0 r1 < <(jq -r '[.status, .d2, .d2_interval[0], .d2_interval[1], .scaling_region[0], .scaling_region[1]] | map(. // "-") | @tsv' "$work/$id.json")
  refd2=$(jq -r '.d2 // "-"' "$work/$ref.json")
  awk -F'\t' -v OFS='\t' -v setting="$setting" -v s="$seconds" -v mib="$mib" -v status="$status" -v d2="$d2" \
    -v lo="$lo" -v hi="$hi" -v r0="$r0" -v r1="$r1" -v ref="$refd2" -v cs="$cs" -v kind="$kind" \
    -v rows="$work/rows.tsv" 'BEGIN {
      num = (d2 != "-")
      shown = num ? sprintf("%.4f", d2) : status
      interval = num ? sprintf("[%.3f, %.3f]", lo, hi) : "-"
      diff = (num && ref != "-") ? sprintf("%.4f", (d2 > ref ? d2 - ref : ref - d2)) : "-"
      region = (r0 != "-") ? sprintf("[%.4g, %.4g]", r0, r1) : "-"
      printf "| %s | %.2f | %s | %s | %s | %s | %s |\n", setting, s, mib, shown, interval, diff, region
      print cs, kind, setting, s, (num ? sprintf("%.4f", d2) : status), diff >> rows
    }'
}

# knobs CASE DATA ARGS...: the exact run, two threads, pair caps and reference subsets.
knobs() {
  local case=$1 data=$2
  shift 2
  measure "$case-exact" 0 "$data" "$@"
  measure "$case-threads2" 0 "$data" "$@" --threads 2
  for cap in 1000 10000 100000 1000000; do measure "$case-N$cap" 0 "$data" "$@" -N "$cap"; done
  for refs in 1000 10000 30000; do measure "$case-R$refs" 0 "$data" "$@" --reference-points "$refs"; done
  measure "$case-quick" 0 "$data" "$@" --fast
  measure "$case-fast" 0 "$data" "$@" --fast --fast-budget 0
  row "$case" exact "$case-exact" "$case-exact" "exact (no cap, 1 thread)"
  row "$case" threads "$case-threads2" "$case-exact" "exact, \`--threads 2\`"
  for cap in 1000 10000 100000 1000000; do row "$case" cap "$case-N$cap" "$case-exact" "pair cap \`-N $cap\`"; done
  for refs in 1000 10000 30000; do
    row "$case" subset "$case-R$refs" "$case-exact" "\`--reference-points $refs\`"
  done
  local budget
  budget=$(jq -r 'if .fast.exact then "fell back to the exact counts" else "\(.fast.reference_points) reference points" end' "$work/$case-fast.json")
  row "$case" quick "$case-quick" "$case-exact" "\`--fast\` (one round of 2 x 200 reference points)"
  row "$case" fast "$case-fast" "$case-exact" "\`--fast --fast-budget 0\` ($budget)"
}

# seeds CASE DATA ARGS...: a fixed subset of 1000 reference points and --fast over seeds 1-5 (one
# run each), against the exact D2 of run CASE-exact: what a fixed budget risks and what --fast does.
seeds() {
  local case=$1 data=$2 s kind id seconds status d2 budget exact
  shift 2
  exact=$(jq -r '.d2' "$work/$case-exact.json")
  echo "| setting | seed | wall s | status | d2 | \\|d2 - exact d2\\| | scaling region (eps) | reference points |"
  echo "|---|---|---|---|---|---|---|---|"
  for kind in subset fast; do
    for s in 1 2 3 4 5; do
      id="$case-seed-$kind-$s"
      if [[ $kind == subset ]]; then
        /usr/bin/time -f '%e' -o "$work/time" "$chaos" d2 "$data" "$@" --reference-points 1000 --seed "$s" --json > "$work/$id.json"
      else
        /usr/bin/time -f '%e' -o "$work/time" "$chaos" d2 "$data" "$@" --fast --fast-budget 0 --seed "$s" --json > "$work/$id.json"
      fi
      seconds=$(cat "$work/time")
      # shellcheck disable=SC2016  # Markdown code spans: the backticks are literal
      jq -r --arg setting "$([[ $kind == subset ]] && echo '`--reference-points 1000`' || echo '`--fast --fast-budget 0`')" \
        --arg seed "$s" --arg seconds "$seconds" --argjson exact "$exact" '
        [$setting, $seed, $seconds, .status,
         (if .d2 == null then "-" else (.d2 * 10000 | round / 10000 | tostring) end),
         (if .d2 == null then "-" else ((.d2 - $exact) | fabs * 10000 | round / 10000 | tostring) end),
         (if .scaling_region == null then "-" else "[\(.scaling_region[0] * 10000 | round / 10000), \(.scaling_region[1] * 10000 | round / 10000)]" end),
         (if .fast == null then "1000" else (.fast.reference_points | tostring) end)]
        | "| " + join(" | ") + " |"' "$work/$id.json"
    done
  done
}

# brute CASE DATA20K ARGS...: box-assisted and brute force at N = 20000; prints the brute row only
# when every brute run finishes within $brute_limit seconds, otherwise a note.
brute() {
  local case=$1 data=$2
  shift 2
  measure "$case-box20k" 0 "$data" "$@"
  row "$case" small "$case-box20k" "$case-box20k" "N = 20000, box-assisted (default), exact"
  if measure "$case-brute20k" "$brute_limit" "$data" "$@" --search brute; then
    row "$case" brute "$case-brute20k" "$case-box20k" "N = 20000, \`--search brute\`"
  else
    echo "| N = 20000, \`--search brute\` | > $brute_limit | | omitted: did not finish within $brute_limit s | | | |"
  fi
}

header() {
  echo "| setting | wall s | peak MiB | d2 (or status) | d2_interval | \\|d2 - exact d2\\| | scaling region (eps) |"
  echo "|---|---|---|---|---|---|---|"
}

"$chaos" generate lorenz -l 100000 --components x > "$work/lorenz.dat"
"$chaos" generate henon -l 100000 --components x > "$work/henon.dat"
"$chaos" generate lorenz -l 20000 --components x > "$work/lorenz20k.dat"
"$chaos" generate henon -l 20000 --components x > "$work/henon20k.dat"
"$chaos" generate lorenz -l 10000 --components x > "$work/lorenz10k.dat"
"$chaos" generate lorenz -l 30000 --components x > "$work/lorenz30k.dat"
: > "$work/rows.tsv"
load_before=$(cut -d' ' -f1-3 /proc/loadavg)

lorenz_table=$({
  header
  knobs lorenz "$work/lorenz.dat" "${lorenz_args[@]}"
  brute lorenz "$work/lorenz20k.dat" "${lorenz_args[@]}"
})
henon_table=$({
  header
  knobs henon "$work/henon.dat" "${henon_args[@]}"
  brute henon "$work/henon20k.dat" "${henon_args[@]}"
})
n_table=$({
  header
  measure lorenz-n10k 0 "$work/lorenz10k.dat" "${lorenz_args[@]}"
  measure lorenz-n30k 0 "$work/lorenz30k.dat" "${lorenz_args[@]}"
  row lorenz n lorenz-n10k lorenz-exact "N = 10^4, exact"
  row lorenz n lorenz-n30k lorenz-exact "N = 3·10^4, exact"
  row lorenz n lorenz-exact lorenz-exact "N = 10^5, exact"
})
lorenz_seeds=$(seeds lorenz "$work/lorenz.dat" "${lorenz_args[@]}")
henon_seeds=$(seeds henon "$work/henon.dat" "${henon_args[@]}")
load_after=$(cut -d' ' -f1-3 /proc/loadavg)

# The conclusion, from the measured rows.
# fastest CASE KINDS: "setting<TAB>seconds<TAB>d2<TAB>diff" of the fastest row among KINDS
# (a regular expression) whose D2 is within 0.02 of the exact one.
fastest() {
  awk -F'\t' -v c="$1" -v kinds="$2" '$1 == c && $2 ~ kinds && $6 != "-" && $6 + 0 <= 0.02 {
      if (best == "" || $4 + 0 < t) { best = $3 "\t" $4 "\t" $5 "\t" $6; t = $4 + 0 } }
    END { print best }' "$work/rows.tsv"
}
# field CASE KIND SETTING COLUMN
field() { awk -F'\t' -v c="$1" -v k="$2" -v col="$3" '$1 == c && $2 == k { print $col; exit }' "$work/rows.tsv"; }
verdict() { awk -v a="$1" -v b="$2" 'BEGIN { print (a + 0 < b + 0) ? "met" : "not met" }'; }

conclusion() {
  local case=$1 name=$2 target=$3 other=$4 f fc exact_s exact_d2 thr_s
  exact_s=$(field "$case" exact 4)
  exact_d2=$(field "$case" exact 5)
  thr_s=$(field "$case" threads 4)
  f=$(fastest "$case" '^(exact|threads|cap|subset|fast)$')
  fc=$(fastest "$case" '^cap$')
  IFS=$'\t' read -r fs ft fd fdiff <<< "$f"
  printf -- "- **%s** (exact D2 = %s): the fastest setting within 0.02 of the exact D2 is %s, %.2f s (D2 = %s, off by %s; with seed 1: the five-seed table shows how much a fixed subset depends on the seed)." \
    "$name" "$exact_d2" "$fs" "$ft" "$fd" "$fdiff"
  if [[ -n $fc ]]; then
    IFS=$'\t' read -r cs ct cd cdiff <<< "$fc"
    printf -- " With the pair cap alone, the fastest within 0.02 is %s, %.2f s (D2 = %s, off by %s): the target (within 0.02 in under 1 s) is %s." \
      "$cs" "$ct" "$cd" "$cdiff" "$(verdict "$ct" 1)"
  else
    printf -- " No pair cap measured here gives a D2 within 0.02 of the exact one: the target (within 0.02 in under 1 s) is not met."
  fi
  printf -- " The exact single-thread job takes %.2f s (target under %s s: %s; a widely used box-assisted implementation needs about %s s); two threads: %.2f s, the same D2 (speed-up %s)." \
    "$exact_s" "$target" "$(verdict "$exact_s" "$target")" "$other" "$thr_s" \
    "$(awk -v a="$exact_s" -v b="$thr_s" 'BEGIN { printf "%.2f", a / b }')"
  local fast_s fast_d2 fast_diff
  fast_s=$(field "$case" fast 4)
  fast_d2=$(field "$case" fast 5)
  fast_diff=$(field "$case" fast 6)
  printf -- " \`--fast\` (seed 1): %.2f s, D2 = %s (off by %s; the target: within 0.02 in at most 0.1 s, %s).\n" \
    "$fast_s" "$fast_d2" "$fast_diff" \
    "$(awk -v t="$fast_s" -v d="$fast_diff" 'BEGIN { print (d != "-" && d + 0 <= 0.02 && t + 0 <= 0.1) ? "met" : "not met" }')"
}

# notes: remarks that the measured rows support (each printed only when its rows are there).
notes() {
  local unsat far speedups slow
  unsat=$(awk -F'\t' '$2 == "cap" && $5 !~ /^[0-9.]+$/ { printf "%s%s %s", (n++ ? ", " : ""), ($1 == "henon" ? "Hénon" : "Lorenz"), $3 }' "$work/rows.tsv")
  far=$(awk -F'\t' '$6 != "-" && $6 + 0 > 0.05 { printf "%s%s %s", (n++ ? ", " : ""), ($1 == "henon" ? "Hénon" : "Lorenz"), $3 }' "$work/rows.tsv")
  speedups=$(awk -F'\t' '$2 == "exact" { e[$1] = $4 } $2 == "threads" { t[$1] = $4 }
    END { for (c in e) if (t[c] > 0 && e[c] / t[c] < 1.3) n++; print n + 0 }' "$work/rows.tsv")
  if [[ -n $unsat ]]; then
    echo "No D2 with a small cap ($unsat): the pairs found around one reference point are not"
    echo "independent, and at the largest radii a cap of K pairs is reached after only about K / (P C(eps)) reference"
    echo "points, so the capped C there scatters much more than 1/sqrt(K) would suggest: the local slopes' jackknife"
    echo "errors over groups of reference points exceed the flatness band (docs/reference/correlation_dimension.md, step 7),"
    echo "or the slopes left are too rough for the three highest dimensions to share a plateau."
    echo
  fi
  if [[ -n $far ]]; then
    echo "Off by more than 0.05 ($far): compare the scaling-region column. These runs chose a different"
    echo "region than the exact run (the Hénon local slopes have a second, lower plateau at small eps, part of the"
    echo "lacunarity ripple), so the difference is the choice of region, not only the statistical error of the counts."
    echo
  fi
  slow=$(awk -F'\t' '$2 == "exact" { e[$1] = $4 } $2 == "subset" && $4 + 0 >= e[$1] {
      printf "%s%s %s", (n++ ? ", " : ""), ($1 == "henon" ? "Hénon" : "Lorenz"), $3 }' "$work/rows.tsv")
  if [[ -n $slow ]]; then
    echo "Slower than the exact run ($slow): a reference subset counts, for each of its R points, every partner"
    echo "on both sides (R P ordered pairs, against P^2 / 2 pairs visited once by the exact grid search), and the"
    echo "exact walk counts m = 2 without enumerating pairs (docs/reference/correlation_sum.md), so a subset saves time only"
    echo "for R well below P / 2."
    echo
  fi
  if ((speedups > 0)); then
    echo "Two threads gave less than a 1.3-fold speed-up here, most likely because the second core was busy with"
    echo "other jobs (see the load average above); the counts, hence D2, are identical for any number of threads."
  else
    echo "The counts, hence D2, are identical for any number of threads."
  fi
}

{
  echo "# Correlation dimension: what the knobs cost and buy"
  echo
  echo "Made by \`scripts/measure/measure_d2_knobs.sh\` on $(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'))."
  echo "Release build. Each run is one process: wall time and peak resident memory from \`/usr/bin/time -f '%e %M'\`,"
  echo "including reading the series from a text file; the fastest of $repeats runs (D2 is the same in every run:"
  echo "the counts are exact integers and the capped and subset runs use the fixed seed 1). The machine may be"
  echo "shared with other jobs (load average $load_before before the runs, $load_after after), so times are upper"
  echo "bounds. D2 and its interval and scaling region come from \`chaos d2 --json\` (\`docs/reference/correlation_dimension.md\`);"
  echo "a row shows the status instead of a number when the dimensions did not share a plateau. The pair cap"
  echo "\`-N K\` and the reference subset \`--reference-points R\` are described in \`docs/reference/correlation_sum.md\`."
  echo "Every run has \`--no-halves\`: the table prices the counting; the check of a saturated D2 on the record's"
  echo "halves, on by default, adds about half an exact job (a quarter of the pairs per half), or"
  echo "after \`--fast\` the chosen budget again."
  echo
  echo "Commands (the setting of a row is added to the \`chaos d2\` line):"
  echo
  echo "    chaos generate lorenz -l 100000 --components x > lorenz.dat"
  echo "    chaos d2 lorenz.dat ${lorenz_args[*]} --json"
  echo "    chaos generate henon -l 100000 --components x > henon.dat"
  echo "    chaos d2 henon.dat ${henon_args[*]} --json"
  echo
  echo "The N = 20000 rows use \`chaos generate ... -l 20000\`; their \\|d2 - exact d2\\| column compares the brute-force"
  echo "D2 with the box-assisted D2 at the same N (the counts are identical, so the difference must be 0)."
  echo "Brute force is O(N^2) and is run only at N = 20000, and shown only if it finishes within $brute_limit s."
  echo
  echo "## Lorenz x (dt = 0.01), N = 10^5, tau = 17, w = 200, m = 1..6, 40 radii 0.25 .. 5"
  echo
  echo "$lorenz_table"
  echo
  echo "## Hénon x (a = 1.4, b = 0.3), N = 10^5, tau = 1, w = 10, m = 1..4, 40 radii 0.005 .. 0.4"
  echo
  echo "$henon_table"
  echo
  echo "## The length N (Lorenz x, exact, one thread)"
  echo
  echo "\`chaos generate lorenz -l N --components x\`, then the Lorenz \`chaos d2\` line; compared with N = 10^5."
  echo
  echo "$n_table"
  echo
  echo "## A fixed subset against \`--fast\`, five seeds"
  echo
  echo "One run each; the exact D2 is the exact row's above. A fixed budget of 1000 reference points gives a"
  echo "saturated D2 whatever it lands on; \`--fast\` doubles the subset until two disjoint subsets agree on one"
  echo "unambiguous plateau and scaling region, precisely enough, or uses the exact counts (its last column:"
  echo "\"exact\"). How it decides:"
  echo "\`chaos/include/chaos/adaptive_d2.hpp\` and docs/reference/correlation_dimension.md."
  echo
  echo "Lorenz x:"
  echo
  echo "$lorenz_seeds"
  echo
  echo "Hénon x:"
  echo
  echo "$henon_seeds"
  echo
  echo "## Conclusion"
  echo
  conclusion lorenz "Lorenz x" 10 150
  conclusion henon "Hénon x" 5 125
  echo
  notes
} > "$out"
cat "$out"
