#!/usr/bin/env bash
# Regenerates docs/validation/mechanism/performance.md and docs/validation/mechanism/performance.svg: the simulator's
# speed/accuracy trade on the seed scene (5000 rpm) at clearances of 0.5 mm and 0.1 mm, for RK4
# at fixed steps and Dormand-Prince 5(4) at tolerances. For each setting:
#   wall s per simulated s  from a run of SECONDS_TIMED simulated seconds (fastest of REPEATS);
#   short-horizon error     max |slider_y - reference| over the first two crank periods, every
#                           10 us, against RK4 at h = 3.125e-8 s;
#   long-run statistics     the Kolmogorov-Smirnov distance between the stroboscopic slider_y of
#                           PERIODS periods (after 10 periods of transient) and that of the
#                           reference setting (RK4 at h = 2.5e-7 s): 0 for identical distributions;
#                           about 1.36 sqrt(2 / PERIODS) is the 5% critical value for independent
#                           samples.
# Usage: scripts/measure/measure_mechanism_tradeoff.sh [build-dir]
# Environment: PERIODS (1000), SECONDS_TIMED (0.24), REPEATS (3), CLEARANCES ("0.5e-3 0.1e-3"),
#   RK4_STEPS ("2.5e-6 2e-6 1e-6 5e-7 2.5e-7 1e-7"),
#   LIMIT (300) seconds of wall time per run: a run that needs more is reported as over the limit,
#   VARIANTS ("seed sigma1_fading"): the scenes: seed (as printed), sigma1_fading (LuGre's sigma1
#   fading above 1 mm/s, Canudas de Wit 2003), coulomb (Coulomb friction), frictionless.
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/printed_reading.sh
build=${1:-build}
m="$build/mechanism/mechanism"
[[ -x $m ]] || { echo "build the mechanism command first: cmake --build $build --target mechanism_cli" >&2; exit 2; }
command -v jq > /dev/null || { echo "jq is needed" >&2; exit 2; }
periods=${PERIODS:-1000}
timed=${SECONDS_TIMED:-0.24}
repeats=${REPEATS:-3}
clearances=${CLEARANCES:-"0.5e-3 0.1e-3"}
limit=${LIMIT:-300}
variants=${VARIANTS:-"seed sigma1_fading"}

# variant name -> its --set arguments, from the printed reading
variant_args() { echo "$printed_reading $(variant_sets "$1")"; }
variant_sets() {
  case $1 in
    seed) ;;
    sigma1_fading) echo "--set joint.slider.friction.sigma1_velocity=1e-3" ;;
    coulomb) echo "--set joint.slider.friction.law=coulomb" ;;
    frictionless) echo "--set joint.slider.friction.law=none" ;;
    *) echo "unknown variant $1" >&2; exit 2 ;;
  esac
}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
out=docs/validation/mechanism/performance.md
period=0.012

rk4_steps=(${RK4_STEPS:-2.5e-6 2e-6 1e-6 5e-7 2.5e-7 1e-7})
dopri_tolerances=(1e-4 1e-5 1e-6 1e-7 1e-8 1e-9 1e-10 1e-11)

# the simulator under the wall-time limit
sim() { timeout "$limit" "$m" simulate "$@"; }

# settings ID -> the --set arguments of that integrator setting
args_of() {
  case $1 in
    rk4:*) echo "--set integrator.method=rk4 --set integrator.step=${1#rk4:}" ;;
    dopri:*) local tol=${1#dopri:}
      echo "--set integrator.method=dopri5 --set integrator.relative_tolerance=$tol --set integrator.absolute_tolerance=$(awk -v t="$tol" 'BEGIN { printf "%g", t * 1e-3 }')" ;;
  esac
}

# max |y1 - y2| over two single-column files of the same length
max_difference() { paste "$1" "$2" | awk '{ d = $1 - $2; if (d < 0) d = -d; if (d > m) m = d } END { printf "%.3g", m }'; }

# Kolmogorov-Smirnov distance between the samples in two files (one value per line)
ks_distance() {
  sort -g "$1" > "$work/a.sorted"
  sort -g "$2" > "$work/b.sorted"
  awk 'NR == FNR { a[n++] = $1; next } { b[k++] = $1 }
       END { i = 0; j = 0; d = 0
             while (i < n && j < k) {
               v = (a[i] <= b[j]) ? a[i] : b[j]
               while (i < n && a[i] <= v) i++
               while (j < k && b[j] <= v) j++
               e = i / n - j / k; if (e < 0) e = -e; if (e > d) d = e }
             printf "%.3f", d }' "$work/a.sorted" "$work/b.sorted"
}

{
  echo "# Simulator speed against accuracy"
  echo
  echo "Made by \`scripts/measure/measure_mechanism_tradeoff.sh\` ($(date -u +%Y-%m-%d), $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//'),"
  echo "Release build, one thread, load average $(cut -d' ' -f1-3 /proc/loadavg) at the start). The seed scene at 5000 rpm"
  echo "(Lankarani-Nikravesh contact, the face model with the contact-length stiffness, LuGre friction as"
  echo "the seed prints it or with the variant named in each section), \`mechanism simulate\` with the"
  echo "settings below."
  echo
  echo "- **wall s / sim s**: wall time per simulated second, from a run of $timed s (fastest of $repeats)."
  echo "- **error over 2 periods**: max |slider_y - reference| in the first 24 ms, every 10 us, against"
  echo "  RK4 at h = 3.125e-8 s; also as a fraction of the clearance."
  echo "- **KS distance**: Kolmogorov-Smirnov distance between the stroboscopic slider_y over $periods"
  echo "  periods (after 10 periods of transient) and the same from RK4 at h = 2.5e-7 s; the 5% critical"
  echo "  value for two independent samples of this size is $(awk -v n="$periods" 'BEGIN { printf "%.3f", 1.36 * sqrt(2 / n) }')."
  echo
  echo "RK4 steps above 2.5 us are refused with this scene: the LuGre bristle state relaxes at up to"
  echo "1 / bristle_time_floor = 1e6 1/s and explicit RK4 is unstable on it beyond 2.78 us"
  echo "(docs/reference/mechanism/model.md)."
} > "$work/doc.md"

for f in $variants; do
for c in $clearances; do
  read -r -a extra <<< "$(variant_args "$f")"
  scene=(--set "joint.slider.clearance=$c" "${extra[@]}" -q)
  echo "references: $f c=$c" >&2
  # Short-horizon reference and long-run reference (no time limit).
  "$m" simulate "${scene[@]}" --set run.duration=0.024 --set run.output_interval=1e-5 --signals slider_y \
    --set integrator.step=3.125e-8 2> /dev/null | grep -v '^#' > "$work/ref_short"
  "$m" simulate "${scene[@]}" --stroboscopic --signals slider_y --set run.transient=$(awk -v p=$period 'BEGIN { print 10 * p }') \
    --set run.duration=$(awk -v p=$period -v n="$periods" 'BEGIN { print (n - 0.5) * p }') --set integrator.step=2.5e-7 \
    2> /dev/null | grep -v '^#' | cut -f2 > "$work/ref_long"
  {
    echo
    echo "## Clearance $(awk -v c="$c" 'BEGIN { print c * 1e3 }') mm, scene $f ${extra[*]:-(as printed)}"
    echo
    echo "| setting | wall s / sim s | error over 2 periods (m) | / clearance | KS distance | status |"
    echo "|---|---|---|---|---|---|"
  } >> "$work/doc.md"
  settings=()
  for h in "${rk4_steps[@]}"; do settings+=("rk4:$h"); done
  for t in "${dopri_tolerances[@]}"; do settings+=("dopri:$t"); done
  for s in "${settings[@]}"; do
    read -r -a a <<< "$(args_of "$s")"
    best=""
    refused=$("$m" simulate "${scene[@]}" "${a[@]}" --json --set run.duration=1e-4 2>&1 > /dev/null | grep 'invalid scene' || true)
    for ((i = 0; i < repeats && ${#refused} == 0; i++)); do
      w=$(sim "${scene[@]}" "${a[@]}" --json --set run.duration="$timed" --set run.output_interval=0 2> /dev/null | jq -r '.wall_seconds') || w=""
      [[ -n $w ]] || { best=""; break; }
      if [[ -z $best ]] || awk -v x="$w" -v y="$best" 'BEGIN { exit !(x < y) }'; then best=$w; fi
    done
    label=${s/rk4:/RK4 h = }
    label=${label/dopri:/dopri5 rtol = }
    if [[ -n $refused ]]; then
      echo "| $label | refused | - | - | - | ${refused#mechanism: invalid scene: } |" >> "$work/doc.md"
      continue
    fi
    if [[ -z $best ]]; then
      echo "| $label | over the limit | - | - | - | timing run over ${limit} s |" >> "$work/doc.md"
      continue
    fi
    status=$(sim "${scene[@]}" "${a[@]}" --json --set run.duration=0.024 --set run.output_interval=0 2> /dev/null | jq -r .status) || status="over ${limit} s"
    sim "${scene[@]}" "${a[@]}" --set run.duration=0.024 --set run.output_interval=1e-5 --signals slider_y \
      2> /dev/null | grep -v '^#' > "$work/short" || true
    # The long run only when the timing run says it fits in the limit.
    projected=$(awk -v w="$best" -v t="$timed" -v n="$periods" -v p=$period 'BEGIN { printf "%.0f", w / t * (n + 10) * p }')
    : > "$work/long"
    long_rc=skipped
    if ((projected <= limit)); then
      long_rc=0
      sim "${scene[@]}" "${a[@]}" --stroboscopic --signals slider_y --set run.transient=$(awk -v p=$period 'BEGIN { print 10 * p }') \
        --set run.duration=$(awk -v p=$period -v n="$periods" 'BEGIN { print (n - 0.5) * p }') > "$work/long.raw" 2> "$work/long.err" || long_rc=$?
      grep -v '^#' "$work/long.raw" | cut -f2 > "$work/long" || true
    fi
    err=$(max_difference "$work/ref_short" "$work/short")
    rel=$(awk -v e="$err" -v c="$c" 'BEGIN { printf "%.3g", e / c }')
    if [[ $long_rc == 0 && $(wc -l < "$work/long") -ge $periods ]]; then
      ks=$(ks_distance "$work/ref_long" "$work/long")
    elif [[ $long_rc == skipped ]]; then
      ks="not run: needs ~${projected} s (limit ${limit} s)"
    elif [[ $long_rc == 124 ]]; then
      ks="cut at the ${limit} s limit"
    else
      ks="stopped: $(grep -o 'stopped: .*' "$work/long.err" | head -1 | sed 's/^stopped: //')"
    fi
    per=$(awk -v w="$best" -v t="$timed" 'BEGIN { printf "%.3f", w / t }')
    echo "| $label | $per | $err | $rel | $ks | $status |" >> "$work/doc.md"
    echo "$f $c $s $per $err $ks" >> "$work/points"
    echo "done: $f c=$c $s ($per s/s, error $err, KS $ks)" >&2
  done
done
done

if command -v gnuplot > /dev/null; then
  plots=""
  for f in $variants; do
    for c in $clearances; do
      for kind in rk4 dopri; do
        awk -v f="$f" -v c="$c" -v k="$kind" '$1 == f && $2 == c && index($3, k) == 1 { print $4, $5 }' "$work/points" > "$work/$kind-$f-$c"
        plots+="${plots:+, }'$work/$kind-$f-$c' w lp t '$kind, $f, c = $c'"
      done
    done
  done
  gnuplot <<GNUPLOT
set terminal svg size 1000,600 dynamic font 'sans,11'
set output 'docs/validation/mechanism/performance.svg'
set logscale xy
set xlabel 'wall seconds per simulated second (one core)'
set ylabel 'max |slider_y error| over two periods (m)'
set key outside
plot $plots
GNUPLOT
  echo -e "\n![wall time against short-horizon error](performance.svg)" >> "$work/doc.md"
fi
cp "$work/doc.md" "$out"
echo "wrote $out" >&2
