#!/usr/bin/env bash
# `chaos lyapunov` on its own, as a user runs it, at the zoo's choices: for every chaotic system of
# docs/validation/zoo.md that the pipeline analyses, the zoo's series at N = 10^5, clean and with white Gaussian
# measurement noise at each SNR of NOISE_DB (default 40 dB; the noise of
# scripts/measure/measure_noise_neighbourhood.sh, same seed), and `chaos lyapunov --dt DT -m M -d TAU -t W`
# with the delay and the window of the system's automatic row, at m from its Cao dimension to that
# plus M_EXTRA (default 2: the zoo's grid of m, whose fits use m, m + 1 and m + 2; measurement noise
# raises the m a user would pick). With BASELINE=/path/to/chaos
# the same runs of another build are listed beside, so a change of the command's defaults can be
# judged on the same series.
#
# Band, fixed before the run: lambda_1 from the equations (the row's), +-10%. A `linear_region`
# outside it is WRONG; any other status is unsure.
#
# Usage: scripts/measure/measure_lyapunov_command.sh [build-dir] > table.md
# Environment: BASELINE (another chaos executable), JOBS (2), ONLY=name,name, NOISE_DB ("40";
# "" for the clean series only), SEED (1), M_EXTRA (2).
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/measure/zoo_neighbourhood_common.sh "$@"
levels=${NOISE_DB-40}
seed=${SEED:-1}
m_extra=${M_EXTRA:-2}
baseline=${BASELINE:-}
[[ -z $baseline || -x $baseline ]] || { echo "BASELINE=$baseline is not an executable" >&2; exit 2; }

zoo_systems > "$work/systems"
zoo_choices > "$work/choices"
[[ -s $work/choices ]] || { echo "no automatic-choice rows at N = 10^5 found in docs/validation/zoo.md" >&2; exit 3; }
"$chaos" generate white_noise -l 100000 --seed "$seed" | grep -v '^#' > "$work/noise"

# verdict JSON: "value status verdict" of the command's answer against lambda_1 = $lam
verdict() {
  jq -r --arg lam "$2" '
    def num: if . == null then "-" else (. * 10000 | round / 10000 | tostring) end;
    "\(.lambda | num) \(.status // "error")\t" +
    (if .status != "linear_region" then "unsure"
     elif .lambda >= 0.9 * ($lam | tonumber) and .lambda <= 1.1 * ($lam | tonumber) then "in_band" else "WRONG" end)' "$1"
}

case_rows() {  # name tau m0 w -> $work/rows.name
  local name=$1 tau=$2 m0=$3 w=$4 lam dt snr file out="$work/rows.$1" args m
  lam=$(awk -v n="$name" '$1 == n { print $6 }' "$work/systems")
  dt=$(zoo_series "$name")
  : > "$out"
  for snr in clean $levels; do
    file="$work/$name.dat"
    if [[ $snr != clean ]]; then
      file="$work/$name.$snr.dat"
      add_noise "$snr" "$work/$name.dat" "$work/noise" "$file"
    fi
    for ((m = m0; m <= m0 + m_extra; ++m)); do
      args=(lyapunov "$file" ${dt:+--dt "$dt"} -m "$m" -d "$tau" -t "$w" --json -q)
      local row="$name	$snr	$tau	$m	$w" json="$work/$name.$snr.$m"
      if [[ -n $baseline ]]; then
        "$baseline" "${args[@]}" > "$json.base.json" 2> /dev/null || echo '{}' > "$json.base.json"
        row="$row	$(verdict "$json.base.json" "$lam")"
      fi
      "$chaos" "${args[@]}" > "$json.json" 2> /dev/null || echo '{}' > "$json.json"
      row="$row	$(verdict "$json.json" "$lam")	$(jq -r '.local_maps.status // "-"' "$json.json")	$lam"
      echo "$row" >> "$out"
    done
  done
  echo "done $name" >&2
}
export -f case_rows verdict zoo_series
export levels baseline chaos work m_extra

zoo_run_cases < <(zoo_only < "$work/choices")

echo "# \`chaos lyapunov\` on its own at the zoo's choices (written by scripts/measure/measure_lyapunov_command.sh)"
echo
echo "Commit $(git rev-parse --short HEAD 2> /dev/null || echo unknown)${baseline:+, baseline $baseline}; noise ${levels:-none} dB, seed $seed; $(zoo_machine); $elapsed s."
echo
if [[ -n $baseline ]]; then
  echo "| system | SNR dB | tau | m | w | baseline lambda | verdict | this build lambda | verdict | local maps | lambda_1 (equations) |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|"
else
  echo "| system | SNR dB | tau | m | w | lambda | verdict | local maps | lambda_1 (equations) |"
  echo "|---|---|---|---|---|---|---|---|---|"
fi
zoo_table_rows
echo
# Totals per noise level: in band / unsure / WRONG, for the baseline (if any) and this build.
cat "$work"/rows.* | awk -F'\t' -v base="${baseline:+1}" '
  { key = $2; if (base) { b[key, $7]++; t[key, $9]++ } else t[key, $7]++; seen[key] = 1 }
  END {
    for (k in seen) {
      if (base) printf "- %s: baseline %d in band / %d unsure / %d wrong; this build %d / %d / %d\n", k,
        b[k, "in_band"], b[k, "unsure"], b[k, "WRONG"], t[k, "in_band"], t[k, "unsure"], t[k, "WRONG"]
      else printf "- %s: %d in band / %d unsure / %d wrong\n", k, t[k, "in_band"], t[k, "unsure"], t[k, "WRONG"]
    }
  }' | sort
