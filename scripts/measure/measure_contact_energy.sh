#!/usr/bin/env bash
# The energy audit of the slider's contact models (docs/reference/mechanism/model.md, "Energy from a tilted
# start"): restitution 1 and no friction, so a conservative contact returns everything it stores.
# Starts tilted and spinning (initial.slider_angle = 0.01 rad, initial.slider_rate = 20 rad/s, the
# seed scene otherwise), runs DURATION simulated seconds at the scene's RK4 step, and reads the work
# of the contact forces (signal work_contact) at every 10 us sample where no corner penetrates
# (slider_penetration <= 0). Prints a Markdown table: the largest |W_contact| at those instants,
# and its value at the last one. A second table does the same for the built-in reading (exponent 1,
# lugre_normalised; friction off here) with the conservative models, at RK4 steps 2e-6 to 2.5e-7 s,
# with and without steps ended at contact switches (integrator.locate_switches).
# Usage: scripts/measure/measure_contact_energy.sh [build-dir]     Environment: DURATION (1.2)
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/printed_reading.sh
build=${1:-build}
duration=${DURATION:-1.2}
mech="$build/mechanism/mechanism"
[[ -x $mech ]] || { echo "no $mech: build first (cmake --build $build)" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "| model | stiffness | contact-free samples | max abs W_contact there (J) | W_contact at the last (J) |"
echo "|---|---|---|---|---|"
for model in face corners line; do
  for stiffness in contact_length flat_face; do
    # shellcheck disable=SC2086  # the printed reading is words
    "$mech" simulate -q $printed_reading --set joint.slider.model="$model" --set joint.slider.stiffness_model="$stiffness" \
      --set joint.slider.contact.restitution=1 --set joint.slider.friction.law=none \
      --set initial.slider_angle=0.01 --set initial.slider_rate=20 --set run.duration="$duration" \
      --set run.output_interval=1e-5 --signals t,work_contact,slider_penetration -o "$tmp/run.tsv"
    awk -v model="$model" -v stiffness="$stiffness" '
      $1 ~ /^[-+0-9.]/ && $3 <= 0 { n++; w = $2 < 0 ? -$2 : $2; if (w > worst) worst = w; last = $2 }
      END { printf "| %s | %s | %d | %.3g | %.3g |\n", model, stiffness, n, worst, last }' "$tmp/run.tsv"
  done
done

echo
echo "| model | RK4 step (s) | locate_switches | contact-free samples | max abs W_contact there (J) |"
echo "|---|---|---|---|---|"
for model in line corners; do
  for locate in false true; do
    for step in 2e-6 1e-6 5e-7 2.5e-7; do
      "$mech" simulate -q --set joint.slider.model="$model" --set joint.slider.stiffness_model=contact_length \
        --set joint.slider.contact.restitution=1 --set joint.slider.friction.law=none \
        --set initial.slider_angle=0.01 --set initial.slider_rate=20 --set run.duration="$duration" \
        --set integrator.step="$step" --set integrator.locate_switches="$locate" \
        --set run.output_interval=1e-5 --signals t,work_contact,slider_penetration -o "$tmp/run.tsv"
      awk -v model="$model" -v step="$step" -v locate="$locate" '
        $1 ~ /^[-+0-9.]/ && $3 <= 0 { n++; w = $2 < 0 ? -$2 : $2; if (w > worst) worst = w }
        END { printf "| %s | %s | %s | %d | %.3g |\n", model, step, locate, n, worst }' "$tmp/run.tsv"
    done
  done
done
