#!/usr/bin/env bash
# Eq. 11 read both ways (docs/reference/mechanism/contact-and-friction.md, "Eq. 11's exponent"): the seed's
# face stiffness has units N/m, which fits F = K delta^1 (exponent 1); the seed uses it as K delta^1.5.
# For each friction law, clearance and exponent: the seed scene, 5 crank periods of transient, then
# 10 periods written every 10 us; prints the largest |slider_y| over the clearance, the largest
# corner penetration, and the share of samples with the slider's centre beyond its clearance.
# Usage: scripts/measure/measure_stiffness_exponent.sh [build-dir]
# Environment: CLEARANCES ("0.01e-3 0.05e-3 0.1e-3 0.5e-3"), LAWS ("lugre_absolute none")
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/printed_reading.sh
build=${1:-build}
mech="$build/mechanism/mechanism"
[[ -x $mech ]] || { echo "no $mech: build first (cmake --build $build)" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "| friction | clearance (m) | exponent | max abs slider_y / clearance | max penetration (um) | samples beyond the clearance |"
echo "|---|---|---|---|---|---|"
for law in ${LAWS:-lugre_absolute none}; do
  for c in ${CLEARANCES:-0.01e-3 0.05e-3 0.1e-3 0.5e-3}; do
    for n in 1 1.5; do
      # shellcheck disable=SC2086  # the printed reading is words
      "$mech" simulate -q $printed_reading --set joint.slider.clearance="$c" --set joint.slider.contact.exponent="$n" \
        --set joint.slider.friction.law="$law" --set run.transient=0.06 --set run.duration=0.12 \
        --set run.output_interval=1e-5 --signals t,slider_y,slider_penetration -o "$tmp/run.tsv"
      awk -v c="$c" -v n="$n" -v law="$law" '
        $1 ~ /^[-+0-9.]/ { a = $2 < 0 ? -$2 : $2; if (a > m) m = a; if ($3 > p) p = $3; if (a > c) o++; k++ }
        END { printf "| %s | %s | %s | %.3g | %.3g | %.1f%% |\n", law, c, n, m / c, p * 1e6, 100 * o / k }' "$tmp/run.tsv"
    done
  done
done
