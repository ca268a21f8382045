#!/usr/bin/env bash
# The surrogate test for nonlinearity per clearance (docs/notes/mechanism/dynamics.md):
# `study sweep --analysis --surrogates K` on the slider's vertical displacement over the last
# ANALYSIS_PERIODS revolutions (after 500), sampled every ANALYSIS_INTERVAL s, with the slider's
# rotation free and locked. Writes a Markdown table to OUT (default: standard output).
# Environment: CLEARANCES (study's from:to:count, default 1e-5:6e-4:12), ANALYSIS_PERIODS (200),
# ANALYSIS_INTERVAL (1e-4), SURROGATES (19), TEST_LENGTH (4096), MAX_M (10), THREADS (2),
# SETS (--set arguments for every run; default: dopri5 rtol 1e-4, max_step 1e-5), STUDY (the binary).
set -euo pipefail
cd "$(dirname "$0")/../.."
STUDY=${STUDY:-build/study/study}
CLEARANCES=${CLEARANCES:-1e-5:6e-4:12}
ANALYSIS_PERIODS=${ANALYSIS_PERIODS:-200}
ANALYSIS_INTERVAL=${ANALYSIS_INTERVAL:-1e-4}
SURROGATES=${SURROGATES:-19}
TEST_LENGTH=${TEST_LENGTH:-4096}
MAX_M=${MAX_M:-10}
THREADS=${THREADS:-2}
read -r -a sets <<<"${SETS:---set integrator.method=\"dopri5\" --set integrator.relative_tolerance=1e-4 --set integrator.max_step=1e-5}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
out=${OUT:-/dev/stdout}
periods=$((500 + ANALYSIS_PERIODS))
{
  echo "# The surrogate test for nonlinearity over the clearance"
  echo
  echo "Made by \`scripts/measure/measure_surrogate_test.sh\` on $(date -u +%Y-%m-%d) ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $THREADS threads). For each rotation case:"
  echo
  echo "    study sweep ${sets[*]} [--set joint.slider.rotation=locked] --axis joint.slider.clearance=$CLEARANCES \\"
  echo "      --periods $periods --keep 1 --analysis --analysis-periods $ANALYSIS_PERIODS --analysis-interval $ANALYSIS_INTERVAL \\"
  echo "      --max-dimension $MAX_M --surrogates $SURROGATES --test-length $TEST_LENGTH -o DIR"
  echo
  echo "The test (docs/reference/study.md, docs/reference/nonlinearity_test.md): $SURROGATES IAAFT surrogates of the first $TEST_LENGTH samples of"
  echo "slider_y, the zeroth-order prediction error in the point's Cao embedding, delay and Theiler window, one-sided"
  echo "at 1/($SURROGATES + 1). Rank 1: the series is predicted better than every surrogate."
  echo
  echo "| clearance (mm) | rotation | delay (samples) | Theiler | Cao m | nonlinearity | rank of $((SURROGATES + 1)) | D2 status |"
  echo "|---|---|---|---|---|---|---|---|"
} > "$work/table"
for rotation in free locked; do
  extra=()
  [[ $rotation == locked ]] && extra=(--set joint.slider.rotation=locked)
  start=$(date +%s)
  "$STUDY" sweep "${sets[@]}" "${extra[@]}" --axis "joint.slider.clearance=$CLEARANCES" --periods "$periods" --keep 1 \
    --analysis --analysis-periods "$ANALYSIS_PERIODS" --analysis-interval "$ANALYSIS_INTERVAL" --max-dimension "$MAX_M" \
    --surrogates "$SURROGATES" --test-length "$TEST_LENGTH" --threads "$THREADS" -q -o "$work/$rotation" > /dev/null
  echo "$rotation $(( $(date +%s) - start )) s" >> "$work/times"
  awk -F'\t' -v rot="$rotation" '
    /^# point/ { sub(/^# /, ""); for (i = 1; i <= NF; ++i) col[$i] = i; next }
    !/^#/ { printf "| %.3g | %s | %s | %s | %s | %s | %s | %s |\n", $col["joint.slider.clearance"] * 1e3, rot,
              $col["delay_samples"], $col["theiler"], $col["cao_dimension"], $col["nonlinearity"],
              $col["nonlinearity_rank"], $col["d2_status"] }' "$work/$rotation/analysis.tsv" >> "$work/table"
done
{
  cat "$work/table"
  echo
  echo "Wall time on $THREADS threads: $(paste -sd, "$work/times" | sed 's/,/, /g')."
} > "$out"
