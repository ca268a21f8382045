#!/usr/bin/env bash
# Wall time of one simulated second (docs/validation/mechanism/performance.md, "The audited scene on dopri5"):
# each setting ROUNDS times, the settings interleaved round by round so that a slow spell of a
# shared machine touches all of them alike; prints the minimum and the median per setting.
# Environment: SETTINGS (rtol:max_step pairs, default "1e-4:1e-5 1e-3:1e-4 1e-2:1e-4"), ROUNDS (7),
# DURATION (1, simulated seconds per run), SCENE_SETS (default: the audited scene of
# docs/reference/mechanism/contact-and-friction.md: line contact, Eq. 11 with exponent 1, normalised LuGre
# with sigma1 fading), MECHANISM (the binary), BASELINE (a second binary, e.g. an older build,
# timed in the same rounds).
set -euo pipefail
cd "$(dirname "$0")/../.."
M=${MECHANISM:-build/mechanism/mechanism}
SETTINGS=${SETTINGS:-1e-4:1e-5 1e-3:1e-4 1e-2:1e-4}
ROUNDS=${ROUNDS:-7}
DURATION=${DURATION:-1}
SCENE_SETS=(${SCENE_SETS:---set joint.slider.model=line --set joint.slider.contact.exponent=1 --set joint.slider.friction.law=lugre_normalised --set joint.slider.friction.sigma1_velocity=1e-3})
binaries=("$M")
[[ -n ${BASELINE:-} ]] && binaries+=("$BASELINE")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

echo "# $(date -u +%Y-%m-%dT%H:%MZ) $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), load $(cut -d' ' -f1-3 /proc/loadavg), scene sets: ${SCENE_SETS[*]}"
for ((r = 1; r <= ROUNDS; ++r)); do
  for b in "${binaries[@]}"; do
    for s in $SETTINGS; do
      rtol=${s%%:*} max_step=${s##*:}
      "$b" simulate -q "${SCENE_SETS[@]}" --set "run.duration=$DURATION" --stroboscopic \
        --set 'integrator.method="dopri5"' --set "integrator.relative_tolerance=$rtol" \
        --set "integrator.max_step=$max_step" -o /dev/null --json |
        jq -r --arg b "$b" --arg s "$s" "[\$b, \$s, .wall_seconds / $DURATION, .status] | @tsv" >> "$work/times"
    done
  done
done
printf '# binary\trtol:max_step\tmin_wall_s_per_sim_s\tmedian\truns\tstatuses\n'
sort -k1,1 -k2,2 -k3,3g "$work/times" | awk -F'\t' '
  function flush() { if (n) printf "%s\t%s\t%.4f\t%.4f\t%d\t%s\n", key1, key2, v[1], (n % 2 ? v[(n + 1) / 2] : (v[n / 2] + v[n / 2 + 1]) / 2), n, st }
  $1 != key1 || $2 != key2 { flush(); key1 = $1; key2 = $2; n = 0; st = "" }
  { v[++n] = $3; if (index(st, $4) == 0) st = st (st ? "," : "") $4 }
  END { flush() }'
