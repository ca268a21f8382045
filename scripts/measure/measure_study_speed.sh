#!/usr/bin/env bash
# The study's speed goals, measured (docs/validation/performance-study.md): the seed's 120-clearance bifurcation
# diagram (0.01 .. 0.6 mm at 5000 rpm, 1000 periods each, the last 50 kept) and a 10 000-point
# Poincare portrait (c_t = 0.5 mm, 100 periods of transient), for these settings:
#   built_in            the built-in scene (the audited reading), dopri5 rtol 1e-4, max_step 1e-5
#                       (the defaults of docs/validation/reproduction.md)
#   built_in_fast       the same scene, dopri5 rtol 1e-3, max_step 1e-4 (scripts/demo.sh)
#   sigma1_fading       the printed reading (scripts/printed_reading.sh) with
#                       joint.slider.friction.sigma1_velocity = 1e-3, dopri5 rtol 1e-4, max_step 1e-5
#   sigma1_fading_fast  the same scene, dopri5 rtol 1e-3, max_step 1e-4: the cheapest setting that
#                       scripts/measure/measure_study_tradeoff.sh finds to keep the long-run statistics
#   printed             the seed scene as printed, dopri5 rtol 1e-4 (it stops at many clearances)
# Prints one tab-separated row per run: case, scene, wall seconds, threads, points failed.
# Environment: THREADS (default: all cores), CLEARANCES (120), PERIODS (1000), PORTRAIT (10000),
# SCENES (default: all five).
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/printed_reading.sh
STUDY=${STUDY:-build/study/study}
THREADS=${THREADS:-$(nproc 2>/dev/null || echo 2)}
CLEARANCES=${CLEARANCES:-120}
PERIODS=${PERIODS:-1000}
PORTRAIT=${PORTRAIT:-10000}
SCENES=${SCENES:-built_in built_in_fast sigma1_fading sigma1_fading_fast printed}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "# $(date -u +%Y-%m-%dT%H:%MZ) $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"
printf '# case\tscene\twall_s\tthreads\tfailed\n'
for scene in $SCENES; do
  integrator=(--set 'integrator.method="dopri5"' --set integrator.relative_tolerance=1e-4)
  sets=()
  [[ $scene == built_in* ]] || read -r -a sets <<< "$printed_reading"
  [[ $scene == sigma1_fading* ]] && sets+=(--set joint.slider.friction.sigma1_velocity=1e-3)
  [[ $scene == *_fast ]] && integrator=(--set 'integrator.method="dopri5"' --set integrator.relative_tolerance=1e-3 --set integrator.max_step=1e-4)
  "$STUDY" sweep "${integrator[@]}" "${sets[@]}" --axis "joint.slider.clearance=1e-5:6e-4:$CLEARANCES" \
    --periods "$PERIODS" --keep 50 --threads "$THREADS" -q -o "$work/bif_$scene" > "$work/bif.json" 2>/dev/null || [[ $? == 5 ]]
  printf 'bifurcation %sx%s\t%s\t%.1f\t%s\t%s\n' "$CLEARANCES" "$PERIODS" "$scene" "$(jq .wall_seconds "$work/bif.json")" "$THREADS" "$(jq .failed "$work/bif.json")"
  "$STUDY" sweep "${integrator[@]}" "${sets[@]}" --set joint.slider.clearance=5e-4 \
    --periods $((PORTRAIT + 100)) --keep "$PORTRAIT" --threads 1 -q -o "$work/portrait_$scene" > "$work/portrait.json" 2>/dev/null || [[ $? == 5 ]]
  printf 'portrait %s points\t%s\t%.1f\t1\t%s\n' "$PORTRAIT" "$scene" "$(jq .wall_seconds "$work/portrait.json")" "$(jq .failed "$work/portrait.json")"
done
