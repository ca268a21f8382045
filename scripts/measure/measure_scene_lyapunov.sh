#!/usr/bin/env bash
# Regenerates docs/notes/mechanism/lyapunov-convergence.md: the Lyapunov exponents of the slider-crank
# from its equations (`mechanism lyapunov`, docs/reference/mechanism/lyapunov.md) for the scene's readings,
# and their convergence in the averaging length, the perturbation, the renormalisations per period
# and the RK4 step. Every run starts from the scene's initial state (seed Eq. 29), 0.5 mm, 5000 rpm.
# Usage: scripts/measure/measure_scene_lyapunov.sh [build-dir]
# Environment: PERIODS (200) periods averaged in the base runs; LONG (800) in the length check.
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/printed_reading.sh
build=${1:-build}
m="$build/mechanism/mechanism"
[[ -x $m ]] || { echo "build the mechanism command first: cmake --build $build --target mechanism_cli" >&2; exit 2; }
command -v jq > /dev/null || { echo "jq is needed" >&2; exit 2; }
periods=${PERIODS:-200}
long=${LONG:-800}
out=docs/notes/mechanism/lyapunov-convergence.md

# The scene's readings (docs/reference/mechanism/contact-and-friction.md), each from the printed one.
reading_args() { echo "$printed_reading $(reading_sets "$1")"; }
reading_sets() {
  case $1 in
    printed) ;;
    sigma1_fading) echo "--set joint.slider.friction.sigma1_velocity=1e-3" ;;
    candidate) echo "--set joint.slider.model=line --set joint.slider.contact.exponent=1" \
      "--set joint.slider.friction.law=lugre_normalised --set joint.slider.friction.sigma1_velocity=1e-3" ;;
    frictionless) echo "--set joint.slider.friction.law=none" ;;
    frictionless_tilted) echo "--set joint.slider.friction.law=none --set initial.slider_angle=0.01 --set initial.slider_rate=20" ;;
    printed_locked) echo "--set joint.slider.rotation=locked" ;;
    sigma1_fading_locked) echo "--set joint.slider.rotation=locked --set joint.slider.friction.sigma1_velocity=1e-3" ;;
    candidate_locked) echo "--set joint.slider.rotation=locked $(reading_sets candidate)" ;;
    frictionless_locked) echo "--set joint.slider.rotation=locked --set joint.slider.friction.law=none" ;;
    *) echo "unknown reading $1" >&2; exit 2 ;;
  esac
}

# row LABEL ARGS...: one run, one table row.
row() {
  local label=$1
  shift
  local json
  json=$("$m" lyapunov -q --json "$@" 2> /dev/null) || { echo "| $label | run failed | | | | | |"; return; }
  jq -r --arg name "$label" '
    def f: if . == null then "-inf" else (. * 10 | round / 10 | tostring) end;
    def e: if . == null then "-" else (. * 10 | round / 10 | tostring) end;
    "| \($name) | \(.status) | \([.exponents[] | f] | join(", ")) | \([.standard_error[] | e] | join(", ")) | " +
    "\(if .kaplan_yorke == null then "-" else (.kaplan_yorke * 100 | round / 100 | tostring) end) | " +
    "\(.largest_separation | tostring) | \(.wall_seconds * 10 | round / 10) |"' <<< "$json"
}

header() {
  echo "| $1 | status | exponents (1/s) | standard errors (1/s) | D_KY | largest separation | wall s |"
  echo "|---|---|---|---|---|---|---|"
}

{
  echo "# Lyapunov exponents of the slider-crank: the measurements"
  echo
  echo "Made by \`scripts/measure/measure_scene_lyapunov.sh\` on $(date -u +%Y-%m-%d) ($(nproc) cores, $(uname -m), Release)."
  echo "The method and how to read these tables: docs/reference/mechanism/lyapunov.md. Every run: 0.5 mm clearance,"
  echo "5000 rpm, from the seed's initial state, 20 periods to align the directions, then the stated"
  echo "number of periods averaged; all exponents (one per phase coordinate), 50 renormalisations per"
  echo "period, perturbation 1e-8 of each coordinate's scale, RK4 at 1e-6 s, unless the row says otherwise."
  echo "D_KY is the attractor's (the section's plus 1). Standard errors come from 10 block means."
  echo
  echo "## The scene's readings ($periods periods)"
  echo
  header reading
  for r in printed sigma1_fading candidate frictionless frictionless_tilted; do
    # shellcheck disable=SC2046
    row "$r" $(reading_args "$r") --periods "$periods"
  done
  echo
  echo "## The same with the slider's rotation locked (joint.slider.rotation = locked, $periods periods)"
  echo
  header reading
  for r in printed_locked sigma1_fading_locked candidate_locked frictionless_locked; do
    # shellcheck disable=SC2046
    row "$r" $(reading_args "$r") --periods "$periods"
  done
  echo
  echo "## Convergence, the printed scene"
  echo
  header setting
  row "base ($periods periods)" --periods "$periods"
  row "$long periods" --periods "$long"
  row "perturbation 1e-6" --periods "$periods" --perturbation 1e-6
  row "perturbation 1e-10" --periods "$periods" --perturbation 1e-10
  row "25 renormalisations per period" --periods "$periods" --intervals-per-period 25
  row "100 renormalisations per period" --periods "$periods" --intervals-per-period 100
  row "RK4 5e-7 s" --periods "$periods" --set integrator.step=5e-7
  row "seed 2 (other initial directions)" --periods "$periods" --seed 2
} > "$out"
echo "wrote $out"
