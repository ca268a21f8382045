#!/usr/bin/env bash
# The automatic pipeline on mildly noisy records: for every chaotic system of docs/validation/zoo.md that the
# pipeline analyses, the zoo's series at N = 10^5 plus white Gaussian measurement noise at each SNR
# of NOISE_DB (default 40 and 30 dB), then `chaos analyze` with every choice automatic (delay,
# Theiler window, m), as a user with a real recording would run it. The zoo itself has noisy
# records only for Lorenz and Henon (20 and 10 dB, docs/validation/zoo.md); this is the noise neighbourhood of
# every system.
#
# Noise: y = x + sigma e, sigma = std(x) / 10^(SNR / 20) (population std, as chaos::add_noise), e
# from `chaos generate white_noise --seed S` (unit variance; S = SEED, default 1, the same for every
# system and level).
#
# Bands, fixed before the run: the clean system's, read from the same docs/validation/zoo.md row. Noise
# cannot change the attractor's D2 or lambda_1; it hides the small scales. So a confident D2
# (saturated) must lie in the row's D2 band and a confident lambda_1 (Rosenstein and Kantz:
# linear_region, local maps: consistent) within 10% of lambda_1 from the equations, or the row is
# wrong. Any other status is unsure, which is the honest answer where the noise reaches the scales
# the estimate needs.
#
# Usage: scripts/measure/measure_noise_neighbourhood.sh [build-dir] > table.md
# Environment: JOBS (2) parallel cases; ONLY=name,name to restrict the systems; NOISE_DB ("40 30");
# SEED (1).
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/measure/zoo_neighbourhood_common.sh "$@"
levels=${NOISE_DB:-40 30}
seed=${SEED:-1}

zoo_systems > "$work/systems"
[[ -s $work/systems ]] || { echo "no automatic-choice rows at N = 10^5 found in docs/validation/zoo.md" >&2; exit 3; }

"$chaos" generate white_noise -l 100000 --seed "$seed" | grep -v '^#' > "$work/noise"

case_rows() {  # name d2_low d2_high lambda_1 -> $work/rows.name
  local name=$1 lo=$2 hi=$3 lam=$4 dt snr json out="$work/rows.$1"
  dt=$(zoo_series "$name")
  : > "$out"
  for snr in $levels; do
    add_noise "$snr" "$work/$name.dat" "$work/noise" "$work/$name.$snr.dat"
    json=$("$chaos" analyze "$work/$name.$snr.dat" ${dt:+--dt $dt} --json -q 2> /dev/null) || json='{}'
    jq -r --arg name "$name" --arg snr "$snr" --arg lo "$lo" --arg hi "$hi" --arg lam "$lam" "$zoo_verdicts"'
      [$name, $snr, automatic_columns, lambda_columns, $lam] | join("\t")' <<< "$json" >> "$out"
  done
  echo "done $name" >&2
}
export -f case_rows
export levels

zoo_run_cases < <(zoo_band_cases)

echo "# The automatic pipeline on noisy records (written by scripts/measure/measure_noise_neighbourhood.sh)"
echo
echo "Commit $(git rev-parse --short HEAD 2> /dev/null || echo unknown), SNR $levels dB, noise seed $seed; $(zoo_machine); $elapsed s."
echo
echo "| system | SNR dB | tau | m (Cao) | w | D2 | D2 band (clean) | D2 verdict | lambda Rosenstein | verdict | lambda Kantz | verdict | lambda local maps | verdict | lambda_1 (equations) |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
zoo_table_rows
echo
zoo_keyed_summary "SNR %s dB"
