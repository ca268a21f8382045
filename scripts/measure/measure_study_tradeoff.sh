#!/usr/bin/env bash
# The integrator knobs of a sweep against the long-run statistics they must keep (docs/validation/performance-study.md,
# "Speed against accuracy"). For each clearance and setting: wall time per simulated second, and
# the Kolmogorov-Smirnov distances of the stroboscopic slider_y and slider_vy over 1000 periods
# (after 10) against RK4 at h = 2.5e-7 s. The 5% critical value for two samples of 1000 is 0.061.
# Environment: CLEARANCES (default "5e-4 1e-4"), SETTINGS (rtol:max_step pairs), SCENE_SETS
# (default: sigma1 fading), PERIODS (1000), PHASES (default "0": initial crank angles in rad; each
# phase is a run of its own, e.g. "0 1e-9 2e-9" gives three draws of the chaotic trajectory, whose
# KS distances scatter: samples one period apart are correlated, so the 5% value is exceeded more
# often than 5% of the time by runs that agree).
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/printed_reading.sh
M=${MECHANISM:-build/mechanism/mechanism}
CLEARANCES=${CLEARANCES:-5e-4 1e-4}
SETTINGS=${SETTINGS:-1e-4:1e-5 1e-4:3e-5 1e-4:5e-5 1e-4:1e-4 1e-3:3e-5 1e-3:5e-5 1e-3:1e-4}
SCENE_SETS=(${SCENE_SETS:-$printed_reading --set joint.slider.friction.sigma1_velocity=1e-3})
PERIODS=${PERIODS:-1000}
PHASES=${PHASES:-0}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

source scripts/measure/ks_distance.sh  # ks FILE_A FILE_B COLUMN

echo "# $(date -u +%Y-%m-%dT%H:%MZ) $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), scene sets: ${SCENE_SETS[*]}"
printf '# clearance\trtol\tmax_step\tphase\twall_s_per_sim_s\tKS_y\tKS_vy\tstatus\n'
duration=$(awk -v p="$PERIODS" 'BEGIN {printf "%.10g", (p + 10) * 60 / 5000}')
for c in $CLEARANCES; do
  common=(simulate -q "${SCENE_SETS[@]}" --set "joint.slider.clearance=$c" --set "run.duration=$duration" --stroboscopic --signals slider_y,slider_vy)
  "$M" "${common[@]}" --set integrator.step=2.5e-7 -o "$work/ref.tsv" 2>/dev/null
  for s in $SETTINGS; do
    rtol=${s%%:*} max_step=${s##*:}
    for phase in $PHASES; do
      "$M" "${common[@]}" --set "driver.initial_angle=$phase" --set 'integrator.method="dopri5"' \
        --set "integrator.relative_tolerance=$rtol" --set "integrator.max_step=$max_step" -o "$work/run.tsv" \
        --json > "$work/run.json" 2>/dev/null || true
      printf '%s\t%s\t%s\t%s\t%.3f\t%s\t%s\t%s\n' "$c" "$rtol" "$max_step" "$phase" \
        "$(jq ".wall_seconds / $duration" "$work/run.json")" "$(ks "$work/run.tsv" "$work/ref.tsv" 2)" \
        "$(ks "$work/run.tsv" "$work/ref.tsv" 3)" "$(jq -r .status "$work/run.json")"
    done
  done
done
