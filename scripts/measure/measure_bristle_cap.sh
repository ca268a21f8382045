#!/usr/bin/env bash
# What the LuGre bristle-rate cap (joint.slider.friction.bristle_time_floor, 1 us) and the exact
# bristle update (integrator.bristles = "exponential") change (docs/validation/mechanism/friction-measured.md,
# "The bristle-rate cap, measured", and docs/reference/mechanism/contact-and-friction.md, "The exact bristle update"). The audited scene at 0.5 mm: runs
# with the cap at 1 us and with a floor of 10 ns, which the normalised form never reaches (its rate
# sigma0 |v| / mu(v) stays below 1e8 1/s up to 110 m/s), so the cap is off; then the exponential
# update, which has no cap, on dopri5 and on RK4. Each run is one draw of the chaotic trajectory
# (initial crank angles 0, 1e-9, 2e-9 rad). Printed: wall s per simulated s, the deepest
# penetration, and the Kolmogorov-Smirnov distances of the stroboscopic slider_y and slider_vy over
# 1000 periods (after 10) against the uncapped integrated run at phase 0 (5% critical value for two
# samples of 1000: 0.061).
# Environment: SCENE_SETS (default: the audited scene), CLEARANCE (5e-4), PERIODS (1000).
set -euo pipefail
cd "$(dirname "$0")/../.."
M=${MECHANISM:-build/mechanism/mechanism}
SCENE_SETS=(${SCENE_SETS:---set joint.slider.model=line --set joint.slider.contact.exponent=1 --set joint.slider.friction.law=lugre_normalised --set joint.slider.friction.sigma1_velocity=1e-3})
CLEARANCE=${CLEARANCE:-5e-4}
PERIODS=${PERIODS:-1000}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

source scripts/measure/ks_distance.sh  # ks FILE_A FILE_B COLUMN

duration=$(awk -v p="$PERIODS" 'BEGIN {printf "%.10g", (p + 10) * 60 / 5000}')
common=(simulate -q "${SCENE_SETS[@]}" --set "joint.slider.clearance=$CLEARANCE" --set "run.duration=$duration"
  --stroboscopic --signals slider_y,slider_vy)
echo "# $(date -u +%Y-%m-%dT%H:%MZ) $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), clearance $CLEARANCE, scene sets: ${SCENE_SETS[*]}"
printf '# bristles\tbristle_time_floor\tintegrator\tphase\twall_s_per_sim_s\tmax_penetration_m\tKS_y\tKS_vy\tstatus\n'
# bristles, floor, integrator (dopri5:rtol with max_step 1e-4, or rk4:step), phase
runs=("integrated 1e-8 dopri5:1e-4 0" "integrated 1e-8 dopri5:1e-4 1e-9" "integrated 1e-8 dopri5:1e-4 2e-9"
  "integrated 1e-6 dopri5:1e-4 0" "integrated 1e-6 dopri5:1e-4 1e-9" "integrated 1e-6 dopri5:1e-4 2e-9"
  "integrated 1e-6 dopri5:1e-2 0" "integrated 1e-6 dopri5:1e-2 1e-9"
  "exponential - dopri5:1e-4 0" "exponential - dopri5:1e-4 1e-9" "exponential - dopri5:1e-4 2e-9"
  "exponential - dopri5:1e-2 0" "exponential - dopri5:1e-2 1e-9"
  "integrated 1e-6 rk4:1e-6 0" "exponential - rk4:1e-6 0" "exponential - rk4:1e-6 1e-9")
for spec in "${runs[@]}"; do
  read -r bristles floor integrator phase <<< "$spec"
  method=${integrator%%:*} setting=${integrator#*:}
  sets=(--set "integrator.bristles=$bristles" --set "driver.initial_angle=$phase" --set "integrator.method=$method")
  [[ $floor != - ]] && sets+=(--set "joint.slider.friction.bristle_time_floor=$floor")
  if [[ $method == dopri5 ]]; then
    sets+=(--set integrator.max_step=1e-4 --set "integrator.relative_tolerance=$setting")
  else
    sets+=(--set "integrator.step=$setting")
  fi
  out="$work/run_${bristles}_${floor}_${integrator}_${phase}.tsv"
  "$M" "${common[@]}" "${sets[@]}" -o "$out" --json > "$work/run.json"
  ref="$work/run_integrated_1e-8_dopri5:1e-4_0.tsv"
  if [[ $out == "$ref" ]]; then ks_y=reference ks_vy=reference; else ks_y=$(ks "$out" "$ref" 2) ks_vy=$(ks "$out" "$ref" 3); fi
  printf '%s\t%s\t%s\t%s\t%.3f\t%.3g\t%s\t%s\t%s\n' "$bristles" "$floor" "$integrator" "$phase" \
    "$(jq ".wall_seconds / $duration" "$work/run.json")" "$(jq .max_penetration "$work/run.json")" "$ks_y" "$ks_vy" \
    "$(jq -r .status "$work/run.json")"
done
