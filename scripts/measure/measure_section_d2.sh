#!/usr/bin/env bash
# Regenerates docs/notes/mechanism/section-d2.md: the correlation dimension of the slider-crank's
# stroboscopic section (one slider_y sample per crank revolution) at three clearances of
# the Lyapunov sweep's grid (docs/notes/mechanism/lyapunov-sweep.md), with the slider's rotation free and
# locked, beside the Kaplan-Yorke dimension of the same scene from that sweep. For a periodically
# forced system the section's dimension is the attractor's minus 1, so D_KY - 1 is what a section
# D2 should not exceed (Kaplan-Yorke conjecture: D2 <= D1 = D_KY). With ANALYSIS_PERIODS, the same
# sweep also gives each point's continuous-series D2 (study sweep --analysis), against D_KY itself.
# Usage: scripts/measure/measure_section_d2.sh [build-dir]
# Environment: CLEARANCES (comma list or study axis, m), KEEP (10000 section points), TRANSIENT (500
#   revolutions dropped first), MAX_M (10), THREADS (2), VARIANTS ("printed printed_locked"; also
#   built_in, built_in_locked: the built-in scene), SETS (more --set arguments for every variant,
#   e.g. an integrator), DKY_FROM (the Lyapunov table to read D_KY from,
#   docs/notes/mechanism/lyapunov-sweep.md), ANALYSIS_PERIODS (0: no continuous D2) and ANALYSIS_INTERVAL
#   (1e-4 s), OUT (docs/notes/mechanism/section-d2.md; with gnuplot and ANALYSIS_PERIODS, a figure OUT.png).
set -euo pipefail
cd "$(dirname "$0")/../.."
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
sets=${SETS:-}
dky_from=${DKY_FROM:-docs/notes/mechanism/lyapunov-sweep.md}
analysis_periods=${ANALYSIS_PERIODS:-0}
analysis_interval=${ANALYSIS_INTERVAL:-1e-4}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
out=${OUT:-docs/notes/mechanism/section-d2.md}
png=${out%.md}.png
analysis=()
if ((analysis_periods > 0)); then
  analysis=(--analysis --analysis-periods "$analysis_periods" --analysis-interval "$analysis_interval"
            --max-dimension "$max_m")
fi

read -r -a variants <<<"${VARIANTS:-printed printed_locked}"
# The printed variants start from the printed reading, the built-in ones from the built-in scene.
variant_args() {
  case $1 in
    built_in*) echo "$(variant_sets "$1") $sets" ;;
    *) echo "$printed_reading $(variant_sets "$1") $sets" ;;
  esac
}
variant_sets() {
  case $1 in
    printed | built_in) ;;
    printed_locked | built_in_locked) echo "--set joint.slider.rotation=locked" ;;
  esac
}
variant_label() {
  case $1 in
    printed) echo "the scene as printed, rotation free" ;;
    printed_locked) echo "the scene as printed, joint.slider.rotation=locked" ;;
    built_in) echo "the built-in scene, rotation free" ;;
    built_in_locked) echo "the built-in scene, joint.slider.rotation=locked" ;;
  esac
}
# D_KY at a clearance from docs/notes/mechanism/lyapunov-sweep.md (its table for the variant, the row whose
# clearance in mm matches to 3 significant digits), or "-".
dky() {
  awk -v section="## $1 " -v c="$2" '
    index($0, section) == 1 { inside = 1; next }
    /^## / { inside = 0 }
    inside && /^\| [0-9]/ { split($0, f, "|"); gsub(/ /, "", f[2]); gsub(/ /, "", f[8])
      if (sprintf("%.3g", f[2]) == sprintf("%.3g", c * 1000)) { print f[8]; exit } }' "$dky_from"
}

round2() { awk -v x="$1" 'BEGIN { if (x == "-" || x == "") print "-"; else printf "%.2f", x }'; }

declare -A wall
for v in "${variants[@]}"; do
  start=$(date +%s.%N)
  # shellcheck disable=SC2046
  "$study" sweep -q $(variant_args "$v") --axis "joint.slider.clearance=$clearances" --periods $((keep + transient)) \
    --keep "$keep" --signals slider_y "${analysis[@]}" --threads "$threads" -o "$work/$v" > /dev/null
  wall[$v]=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.0f", b - a }')
done

{
  echo "# The stroboscopic section's correlation dimension"
  echo
  echo "Made by \`scripts/measure/measure_section_d2.sh\` on $(date -u +%Y-%m-%d) ($(nproc) cores, Release). For each clearance:"
  echo
  echo "    study sweep VARIANT${sets:+ $sets} --axis joint.slider.clearance=C \\"
  echo "      --periods $((keep + transient)) --keep $keep --signals slider_y${analysis[*]:+ ${analysis[*]}} -o DIR"
  echo "    chaos d2 SECTION -d 1 -M $max_m --halves --json"
  echo
  echo "SECTION is the point's $keep slider_y samples, one per crank revolution at the same crank angle, after"
  echo "$transient revolutions from the seed's Eq. 29 (\`samples.tsv\`, column 5). The section of a periodically forced"
  echo "system has the attractor's dimension minus 1, so the bound to compare with is D_KY - 1, D_KY from the"
  echo "equations at the same clearance ([$(basename "$dky_from")]($(basename "$dky_from")), its 4 leading exponents)."
  echo "\`--halves\`: a saturated D2 must be reproduced by both halves of the section (docs/reference/correlation_dimension.md)."
  if ((analysis_periods > 0)); then
    echo "The continuous D2 is the sweep's analysis of slider_y over the last $analysis_periods revolutions sampled every"
    echo "$analysis_interval s (\`analysis.tsv\`: MI delay, Cao, D2 up to m = $max_m with the record's halves; docs/reference/study.md),"
    echo "against D_KY itself."
    if command -v gnuplot > /dev/null; then
      echo
      echo "![section and continuous D2 against the clearance]($(basename "$png"))"
    fi
  fi
  echo
  for v in "${variants[@]}"; do
    echo "## $v ($(variant_label "$v"); ${wall[$v]} s on $threads threads)"
    echo
    if ((analysis_periods > 0)); then
      echo "| clearance (mm) | section: range, interquartile range (µm) | status | D2 | interval | scaling region | D_KY - 1 | D2(m) per dimension, m = 1..$max_m (- : no region) | continuous: status | D2 | D2(m) at m = 4, $max_m | D_KY |"
      echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
    else
      echo "| clearance (mm) | section: range, interquartile range (µm) | status | D2 | interval | scaling region | D_KY - 1 | D2(m) per dimension, m = 1..$max_m (- : no region) |"
      echo "|---|---|---|---|---|---|---|---|"
    fi
    for point in $(grep -v '^#' "$work/$v/points.tsv" | cut -f1 | sort -un); do
      c=$(awk -F'\t' -v p="$point" '!/^#/ && $1 == p { print $2; exit }' "$work/$v/samples.tsv")
      awk -F'\t' -v p="$point" '!/^#/ && $1 == p { print $5 }' "$work/$v/samples.tsv" > "$work/section.dat"
      d=$(dky "$v" "$c")
      spread=$(sort -g "$work/section.dat" | awk '{ v[NR] = $1 } END {
        printf "%.1f, %.1f", (v[NR] - v[1]) * 1e6, (v[int(0.75 * NR + 0.5)] - v[int(0.25 * NR + 0.5)]) * 1e6 }')
      bound=$(awk -v d="$d" 'BEGIN { if (d == "-" || d == "") print "-"; else printf "%.2f", d - 1 }')
      "$chaos" d2 "$work/section.dat" -d 1 -M "$max_m" --halves -q --json > "$work/section.json"
      row=$(jq -r --arg c "$(awk -v c="$c" 'BEGIN { printf "%.3g", c * 1000 }')" --arg bound "$bound" --arg spread "$spread" '
          "| \($c) | \($spread) | \(.status) | \(if .d2 == null then "-" else (.d2 * 1000 | round / 1000 | tostring) end) | \(if .d2_interval == null then "-" else "[\(.d2_interval[0] * 100 | round / 100), \(.d2_interval[1] * 100 | round / 100)]" end) | \(if .scaling_region == null then "-" else "[\(.scaling_region[0] | tostring | .[0:8]), \(.scaling_region[1] | tostring | .[0:8])]" end) | \($bound) | \(.d2_by_dimension | map(if . == null then "-" else (. * 100 | round / 100 | tostring) end) | join(", ")) |"' \
        "$work/section.json")
      if ((analysis_periods > 0)); then
        # The point's continuous-series analysis, its columns found by name in analysis.tsv's header.
        continuous=$(awk -F'\t' -v p="$point" -v top="D2_m$max_m" '
          /^# point/ { sub(/^# /, ""); for (i = 1; i <= NF; ++i) col[$i] = i; next }
          !/^#/ && $1 == p { printf "%s\t%s\t%s\t%s", $col["d2_status"], $col["d2"], $col["D2_m4"], $col[top]; exit }' \
          "$work/$v/analysis.tsv")
        IFS=$'\t' read -r c_status c_d2 c_m4 c_top <<<"$continuous"
        row="$row $c_status | $(round2 "$c_d2") | $(round2 "$c_m4"), $(round2 "$c_top") | ${d:--} |"
        # The figure's data: clearance (mm), D_KY, section D2 (saturated) and D2(m) at m = 4 and the
        # highest m, the same for the continuous series.
        jq -r --arg c "$c" --arg d "${d:--}" --arg cd "$c_d2" --arg c4 "$c_m4" --arg ct "$c_top" --argjson top "$max_m" '
          def v: if . == null then "-" else tostring end;
          [($c | tonumber * 1000 | tostring), $d, (.d2 | v), (.d2_by_dimension[3] | v), (.d2_by_dimension[$top - 1] | v),
           $cd, $c4, $ct] | join("\t")' "$work/section.json" >> "$work/$v.plot"
      fi
      echo "$row"
    done
    echo
  done
} > "$out"
cat "$out"

if ((analysis_periods > 0)) && command -v gnuplot > /dev/null; then
  # One panel per variant: D_KY and D_KY - 1 from the equations, the slopes at m = 4 and at the
  # highest m (far apart: no saturation), and a saturated D2 where there is one.
  panels=""
  for v in "${variants[@]}"; do
    panels+="set title \"$(variant_label "$v")\"
plot '$work/$v.plot' using 1:2 with lines lw 2 lc rgb 'black' title 'D_KY (equations)', \\
     '' using 1:(\$2 - 1) with lines lw 2 dt 2 lc rgb 'black' title 'D_KY - 1', \\
     '' using 1:7 with points pt 6 ps 0.6 lc rgb '#1f77b4' title 'continuous, slope at m = 4', \\
     '' using 1:8 with points pt 7 ps 0.6 lc rgb '#1f77b4' title 'continuous, slope at m = $max_m', \\
     '' using 1:4 with points pt 4 ps 0.6 lc rgb '#d62728' title 'section, slope at m = 4', \\
     '' using 1:5 with points pt 5 ps 0.6 lc rgb '#d62728' title 'section, slope at m = $max_m', \\
     '' using 1:6 with points pt 9 ps 1.2 lc rgb '#2ca02c' title 'continuous D2 (saturated)', \\
     '' using 1:3 with points pt 11 ps 1.2 lc rgb '#9467bd' title 'section D2 (saturated)', \\
     2.24 with lines lw 2 dt 3 lc rgb '#555555' title \"the seed's D2\"
"
  done
  gnuplot <<EOF
set terminal pngcairo size 1100,$((420 * ${#variants[@]}))
set output "$png"
set multiplot layout ${#variants[@]},1
set grid
set key outside right
set xlabel "clearance (mm)"
set ylabel "dimension"
set datafile missing "-"
set yrange [0:*]
$panels
unset multiplot
EOF
  echo "figure: $png"
fi
