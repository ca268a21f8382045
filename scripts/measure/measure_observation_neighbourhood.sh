#!/usr/bin/env bash
# The automatic pipeline on the zoo's series read through a nonlinear sensor: for every chaotic
# system of docs/validation/zoo.md that the pipeline analyses, the zoo's series at N = 10^5, standardised
# (z = (x - mean) / std, population std) and passed through each response of SENSORS, then
# `chaos analyze` with every choice automatic. A recording is rarely the state variable itself: a
# photodiode, a strain gauge or an amplifier near its rails responds smoothly but not linearly.
#
# Responses (each a smooth map of the real line with a positive derivative, so a diffeomorphism
# onto its image):
#   exp   y = exp(z)        a response that grows faster than linearly (stretches one side and
#                           squeezes the other by e^(z_max - z_min))
#   tanh  y = tanh(z)       a saturating sensor (derivative 1 at the mean, 0.07 at 2.5 std)
#   cubic y = z + z^3       stretches both tails (derivative 1 + 3 z^2 >= 1)
#   affine y = 1000 x + 10^6  units and offset only: every choice and estimate must stand as it
#                           was, to rounding (a check of the scale invariance of the rules)
#
# Bands, fixed before the run: the system's own, read from the same docs/validation/zoo.md row. D2 and the
# Lyapunov exponents are invariants of the attractor under a smooth invertible change of
# coordinates, and a generic smooth observable of the state has the same ones (Takens 1981; Sauer,
# Yorke & Casdagli 1991). A response that is not linear changes only the scales at which the
# invariants show, so a confident D2 (saturated) must lie in the row's D2 band and a confident
# lambda_1 (Rosenstein and Kantz: linear_region, local maps: consistent) within 10% of lambda_1
# from the equations, or the row is wrong. Any other status is unsure.
#
# Usage: scripts/measure/measure_observation_neighbourhood.sh [build-dir] > table.md
# Environment: JOBS (2) parallel cases; ONLY=name,name to restrict the systems; SENSORS
# ("exp tanh"; any of exp, tanh, cubic, affine).
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/measure/zoo_neighbourhood_common.sh "$@"
sensors=${SENSORS:-exp tanh}
for s in $sensors; do
  [[ $s == exp || $s == tanh || $s == cubic || $s == affine ]] || { echo "unknown sensor response '$s' (exp, tanh, cubic, affine)" >&2; exit 2; }
done

zoo_systems > "$work/systems"
[[ -s $work/systems ]] || { echo "no automatic-choice rows at N = 10^5 found in docs/validation/zoo.md" >&2; exit 3; }

# sense RESPONSE IN OUT: OUT = the response of the standardised IN, sample by sample, 17 digits.
sense() {
  awk -v f="$1" 'NR == FNR { x[NR] = $1; s += $1; n = NR; next }
    FNR == 1 { mean = s / n; for (i = 1; i <= n; ++i) q += (x[i] - mean)^2; sd = sqrt(q / n) }
    FNR <= n {
      z = (x[FNR] - mean) / sd
      if (f == "exp") y = exp(z)
      else if (f == "tanh") { e = exp(-2 * (z < 0 ? -z : z)); y = (1 - e) / (1 + e); if (z < 0) y = -y }
      else if (f == "cubic") y = z + z * z * z
      else y = 1000 * x[FNR] + 1e6
      printf "%.17g\n", y }' "$2" "$2" > "$3"
}

case_rows() {  # name d2_low d2_high lambda_1 -> $work/rows.name
  local name=$1 lo=$2 hi=$3 lam=$4 dt s json out="$work/rows.$1"
  dt=$(zoo_series "$name")
  : > "$out"
  for s in $sensors; do
    sense "$s" "$work/$name.dat" "$work/$name.$s.dat"
    json=$("$chaos" analyze "$work/$name.$s.dat" ${dt:+--dt $dt} --json -q 2> /dev/null) || json='{}'
    jq -r --arg name "$name" --arg s "$s" --arg lo "$lo" --arg hi "$hi" --arg lam "$lam" "$zoo_verdicts"'
      [$name, $s, automatic_columns, lambda_columns, $lam] | join("\t")' <<< "$json" >> "$out"
  done
  echo "done $name" >&2
}
export -f case_rows sense
export sensors

zoo_run_cases < <(zoo_band_cases)

echo "# The automatic pipeline through a nonlinear sensor (written by scripts/measure/measure_observation_neighbourhood.sh)"
echo
echo "Commit $(git rev-parse --short HEAD 2> /dev/null || echo unknown), responses $sensors; $(zoo_machine); $elapsed s."
echo
echo "| system | response | tau | m (Cao) | w | D2 | D2 band | D2 verdict | lambda Rosenstein | verdict | lambda Kantz | verdict | lambda local maps | verdict | lambda_1 (equations) |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
zoo_table_rows
echo
zoo_keyed_summary "Response %s"
