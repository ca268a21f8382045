#!/usr/bin/env bash
# Regenerates docs/mechanism/section-d2.md: the correlation dimension of the slider-crank's
# stroboscopic section (one slider_y sample per crank revolution, issue 13) at three clearances of
# the Lyapunov sweep's grid (docs/mechanism/lyapunov-sweep.md), with the slider's rotation free and
# locked, beside the Kaplan-Yorke dimension of the same scene from that sweep. For a periodically
# forced system the section's dimension is the attractor's minus 1, so D_KY - 1 is what a section
# D2 should not exceed (Kaplan-Yorke conjecture: D2 <= D1 = D_KY).
# Usage: scripts/measure_section_d2.sh [build-dir]
# Environment: CLEARANCES (comma list, m), KEEP (10000 section points), TRANSIENT (500 revolutions
#   dropped first), MAX_M (10), THREADS (2).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/printed_reading.sh
build=${1:-build}
study="$build/study/study"
chaos="$build/chaos/chaos"
for tool in "$study" "$chaos"; do
  [[ -x $tool ]] || { echo "build $tool first: cmake --build $build" >&2; exit 2; }
done
command -v jq > /dev/null || { echo "jq is needed" >&2; exit 2; }
clearances=${CLEARANCES:-1.172727e-4,3.318182e-4,5.463636e-4}
keep=${KEEP:-10000}
transient=${TRANSIENT:-500}
max_m=${MAX_M:-10}
threads=${THREADS:-2}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
out=docs/mechanism/section-d2.md

variants=(printed printed_locked)
# Each variant starts from the printed reading.
variant_args() { echo "$printed_reading $(variant_sets "$1")"; }
variant_sets() {
  case $1 in
    printed) ;;
    printed_locked) echo "--set joint.slider.rotation=locked" ;;
  esac
}
variant_label() {
  case $1 in
    printed) echo "the scene as printed, rotation free" ;;
    printed_locked) echo "joint.slider.rotation=locked" ;;
  esac
}
# D_KY at a clearance from docs/mechanism/lyapunov-sweep.md (its table for the variant, the row whose
# clearance in mm matches to 3 significant digits), or "-".
dky() {
  awk -v section="## $1 " -v c="$2" '
    index($0, section) == 1 { inside = 1; next }
    /^## / { inside = 0 }
    inside && /^\| [0-9]/ { split($0, f, "|"); gsub(/ /, "", f[2]); gsub(/ /, "", f[8])
      if (sprintf("%.3g", f[2]) == sprintf("%.3g", c * 1000)) { print f[8]; exit } }' docs/mechanism/lyapunov-sweep.md
}

declare -A wall
for v in "${variants[@]}"; do
  start=$(date +%s.%N)
  # shellcheck disable=SC2046
  "$study" sweep -q $(variant_args "$v") --axis "joint.slider.clearance=$clearances" --periods $((keep + transient)) \
    --keep "$keep" --signals slider_y --threads "$threads" -o "$work/$v" > /dev/null
  wall[$v]=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.0f", b - a }')
done

{
  echo "# The stroboscopic section's correlation dimension"
  echo
  echo "Made by \`scripts/measure_section_d2.sh\` on $(date -u +%Y-%m-%d) ($(nproc) cores, Release). For each clearance:"
  echo
  echo "    study sweep [--set joint.slider.rotation=locked] --axis joint.slider.clearance=C \\"
  echo "      --periods $((keep + transient)) --keep $keep --signals slider_y -o DIR"
  echo "    chaos d2 SECTION -d 1 -M $max_m --halves --json"
  echo
  echo "SECTION is the point's $keep slider_y samples, one per crank revolution at the same crank angle, after"
  echo "$transient revolutions from the seed's Eq. 29 (\`samples.tsv\`, column 5). The section of a periodically forced"
  echo "system has the attractor's dimension minus 1, so the bound to compare with is D_KY - 1, D_KY from the"
  echo "equations at the same clearance ([lyapunov-sweep.md](lyapunov-sweep.md), its 4 leading exponents)."
  echo "\`--halves\`: a saturated D2 must be reproduced by both halves of the section (docs/correlation_dimension.md)."
  echo
  for v in "${variants[@]}"; do
    echo "## $v ($(variant_label "$v"); ${wall[$v]} s on $threads threads)"
    echo
    echo "| clearance (mm) | section: range, interquartile range (µm) | status | D2 | interval | scaling region | D_KY - 1 | D2(m) per dimension, m = 1..$max_m (- : no region) |"
    echo "|---|---|---|---|---|---|---|---|"
    for point in $(grep -v '^#' "$work/$v/points.tsv" | cut -f1 | sort -un); do
      c=$(awk -F'\t' -v p="$point" '!/^#/ && $1 == p { print $2; exit }' "$work/$v/samples.tsv")
      awk -F'\t' -v p="$point" '!/^#/ && $1 == p { print $5 }' "$work/$v/samples.tsv" > "$work/section.dat"
      d=$(dky "$v" "$c")
      spread=$(sort -g "$work/section.dat" | awk '{ v[NR] = $1 } END {
        printf "%.1f, %.1f", (v[NR] - v[1]) * 1e6, (v[int(0.75 * NR + 0.5)] - v[int(0.25 * NR + 0.5)]) * 1e6 }')
      bound=$(awk -v d="$d" 'BEGIN { if (d == "-" || d == "") print "-"; else printf "%.2f", d - 1 }')
      "$chaos" d2 "$work/section.dat" -d 1 -M "$max_m" --halves -q --json |
        jq -r --arg c "$(awk -v c="$c" 'BEGIN { printf "%.3g", c * 1000 }')" --arg bound "$bound" --arg spread "$spread" '
          "| \($c) | \($spread) | \(.status) | \(if .d2 == null then "-" else (.d2 * 1000 | round / 1000 | tostring) end) | \(if .d2_interval == null then "-" else "[\(.d2_interval[0] * 100 | round / 100), \(.d2_interval[1] * 100 | round / 100)]" end) | \(if .scaling_region == null then "-" else "[\(.scaling_region[0] | tostring | .[0:8]), \(.scaling_region[1] | tostring | .[0:8])]" end) | \($bound) | \(.d2_by_dimension | map(if . == null then "-" else (. * 100 | round / 100 | tostring) end) | join(", ")) |"'
    done
    echo
  done
} > "$out"
cat "$out"
