#!/usr/bin/env bash
# Friction against its bound mu * F_N (docs/validation/mechanism/friction-measured.md, "Friction against
# mu F_N"). The seed scene with each LuGre reading and Coulomb's law as a reference: 5 crank periods
# of transient, then 10 written at every RK4 step (1e-6 s). At every sample where the slider's faces
# carry a normal force, r = |slider_friction| / (mu_max (slider_normal_upper + slider_normal_lower)),
# with mu_max = max(mu_s, mu_k) = 0.11. A law bounded by mu F_N has r <= 1 (LuGre's sigma1 term may
# add its allowance). Prints a Markdown table: the share of contact samples with r > 1.01, the 99th
# percentile and the largest r.
# Usage: scripts/measure/measure_friction_bound.sh [build-dir]
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/printed_reading.sh
build=${1:-build}
mech="$build/mechanism/mechanism"
[[ -x $mech ]] || { echo "no $mech: build first (cmake --build $build)" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
f=joint.slider.friction
variants=(
  "lugre_absolute, sigma1 = 400 (as printed)|"
  "lugre_absolute, sigma1 fading (v_d = 1e-3)|--set $f.sigma1_velocity=1e-3"
  "lugre_absolute, sigma1 = 0|--set $f.sigma1=0"
  "lugre_normalised, sigma1 = 400|--set $f.law=lugre_normalised"
  "lugre_normalised, sigma1 fading (v_d = 1e-3)|--set $f.law=lugre_normalised --set $f.sigma1_velocity=1e-3"
  "lugre_normalised, sigma1 = 0|--set $f.law=lugre_normalised --set $f.sigma1=0"
  "coulomb|--set $f.law=coulomb"
)
echo "| friction | contact samples | share with r > 1.01 | 99th percentile of r | largest r | run |"
echo "|---|---|---|---|---|---|"
for v in "${variants[@]}"; do
  name=${v%%|*}
  read -r -a sets <<< "$printed_reading ${v#*|}"
  status=$("$mech" simulate -q "${sets[@]}" --set run.transient=0.06 --set run.duration=0.12 \
    --set run.output_interval=1e-6 --signals t,slider_normal_upper,slider_normal_lower,slider_friction \
    -o "$tmp/run.tsv" --json | sed -n 's/.*"status": *"\([a-z_]*\)".*/\1/p' | head -1)
  awk '$1 ~ /^[-+0-9.]/ && $2 + $3 > 0 { f = $4 < 0 ? -$4 : $4; print f / (0.11 * ($2 + $3)) }' "$tmp/run.tsv" |
    sort -g > "$tmp/r.txt"
  awk -v name="$name" -v status="${status:-?}" '{ r[NR] = $1; if ($1 > 1.01) over++ }
    END { n = NR; if (n == 0) { printf "| %s | 0 | - | - | - | %s |\n", name, status; exit }
          p = r[int(0.99 * (n - 1)) + 1];
          printf "| %s | %d | %.1f%% | %.3g | %.3g | %s |\n", name, n, 100 * over / n, p, r[n], status }' "$tmp/r.txt"
done
