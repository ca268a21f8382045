#!/usr/bin/env bash
# Regenerates docs/notes/mechanism/lyapunov-sweep.md and lyapunov-sweep.png: the leading Lyapunov
# exponents and the Kaplan-Yorke dimension from the equations (study sweep --lyapunov) across the
# seed's clearance range at 5000 rpm, with the slider's rotation free and locked, for the printed
# reading, for it with sigma1 fading, and for the built-in scene (docs/reference/mechanism/scene.md).
# Usage: scripts/measure/measure_sweep_lyapunov.sh [build-dir]
# Environment: CLEARANCES ("1e-5:6e-4:12", a study axis), PERIODS (100, averaged per point),
#   RUN (50: revolutions simulated before the exponents start), THREADS (2), VARIANTS (default all
#   six, in the order below), OUT (docs/notes/mechanism/lyapunov-sweep.md; the figure is OUT with .png).
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/printed_reading.sh
build=${1:-build}
study="$build/study/study"
[[ -x $study ]] || { echo "build the study command first: cmake --build $build --target study_cli" >&2; exit 2; }
command -v gnuplot > /dev/null || { echo "gnuplot is needed" >&2; exit 2; }
clearances=${CLEARANCES:-1e-5:6e-4:12}
periods=${PERIODS:-100}
run=${RUN:-50}
threads=${THREADS:-2}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
out=${OUT:-docs/notes/mechanism/lyapunov-sweep.md}
png=${out%.md}.png

read -r -a variants <<<"${VARIANTS:-printed printed_locked sigma1_fading sigma1_fading_locked built_in built_in_locked}"
# The first four start from the printed reading, the last two from the built-in scene.
variant_args() {
  case $1 in
    built_in*) variant_sets "$1" ;;
    *) echo "$printed_reading $(variant_sets "$1")" ;;
  esac
}
variant_sets() {
  case $1 in
    printed | built_in) ;;
    printed_locked | built_in_locked) echo "--set joint.slider.rotation=locked" ;;
    sigma1_fading) echo "--set joint.slider.friction.sigma1_velocity=1e-3" ;;
    sigma1_fading_locked) echo "--set joint.slider.friction.sigma1_velocity=1e-3 --set joint.slider.rotation=locked" ;;
  esac
}
variant_title() {
  case $1 in
    built_in*) echo "the built-in scene${2:+, $2}" ;;
    *) echo "the printed reading${2:+, $2}" ;;
  esac
}

declare -A wall
for v in "${variants[@]}"; do
  start=$(date +%s.%N)
  # shellcheck disable=SC2046
  "$study" sweep -q $(variant_args "$v") --axis "joint.slider.clearance=$clearances" --periods "$run" --keep 1 \
    --lyapunov --lyapunov-periods "$periods" --lyapunov-exponents 4 --threads "$threads" -o "$work/$v" > /dev/null || true
  wall[$v]=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.0f", b - a }')
done

# columns of lyapunov.tsv: point, clearance, status, periods, lambda_1..4, se_1..4, kaplan_yorke, ...
# The gnuplot clauses of one curve per variant, for column $1.
curves() {
  local column=$1 v clauses=()
  for v in "${variants[@]}"; do
    clauses+=("\"$work/$v/lyapunov.tsv\" using (\$2*1e3):$column with linespoints title \"${v//_/ }\"")
  done
  local IFS=,
  echo "${clauses[*]}"
}
gnuplot <<EOF
set terminal pngcairo size 1100,450
set output "$png"
set multiplot layout 1,2
set grid
set key top left
set xlabel "clearance (mm)"
set datafile missing "-"
set title "largest Lyapunov exponent from the equations, 5000 rpm"
set ylabel "lambda_1 (1/s)"
set logscale y
plot $(curves 5)
unset logscale y
set title "Kaplan-Yorke dimension of the attractor"
set ylabel "D_KY"
set yrange [0:*]
plot $(curves 13), 2.24 with lines dt 2 lc rgb "black" title "the seed's D2"
unset multiplot
EOF

{
  echo "# Lyapunov exponents across the clearance range"
  echo
  settings=""
  for name in CLEARANCES VARIANTS OUT; do [[ -n ${!name:-} ]] && settings+="$name=\"${!name}\" "; done
  echo "Made by \`${settings}scripts/measure/measure_sweep_lyapunov.sh\` on $(date -u +%Y-%m-%d) ($(nproc) cores, Release): \`study sweep"
  echo "--lyapunov\` at 5000 rpm over joint.slider.clearance = $clearances m, each point simulated for $run"
  echo "revolutions from the seed's Eq. 29, then its 4 leading exponents averaged over $periods periods"
  echo "(after 20 that align the directions). Method and validation: [lyapunov.md](lyapunov.md). λ in 1/s with"
  echo "standard errors; D_KY is the attractor's; \`-\`: none (the 4 exponents do not bound it, or the run failed)."
  echo
  echo "![lambda_1 and D_KY against the clearance]($(basename "$png"))"
  echo
  for v in "${variants[@]}"; do
    sets=$(variant_sets "$v" | sed 's/--set //g')
    echo "## $v ($(variant_title "$v" "$sets"); ${wall[$v]} s on $threads threads)"
    echo
    echo "| clearance (mm) | status | λ1 | λ2 | λ3 | λ4 | D_KY |"
    echo "|---|---|---|---|---|---|---|"
    awk -F'\t' '!/^#/ {
      printf "| %.3g | %s |", $2 * 1e3, $3
      for (k = 0; k < 4; ++k) {
        l = $(5 + k); e = $(9 + k)
        if (l == "-") printf " - |"; else printf " %.0f ± %.0f |", l, e
      }
      printf " %s |\n", ($13 == "-" ? "-" : sprintf("%.2f", $13))
    }' "$work/$v/lyapunov.tsv"
    echo
  done
} > "$out"
echo "wrote $out and $png"
