#!/usr/bin/env bash
# The main job on its built-in default: install dependencies, build, and run the seed paper's
# clearance study (its Figs. 4 and 8) at the seed's size on the built-in seed scene: 120
# clearances from 0.01 to 0.6 mm at 5000 rpm, 1000 crank periods each, the slider's stroboscopic
# height over the last 500, and the mutual-information delay, Cao's E1/E2 and D2 of its last 5
# periods. About two minutes on 2 cores once built (the sweep takes about 95 s).
#
# The built-in scene reads the seed's slider joint as the physics audit decided (line
# contact, Eq. 11 with exponent 1, the normalised LuGre with sigma1 fading: docs/reference/mechanism/scene.md).
# One setting differs from it, measured (docs/validation/mechanism/performance.md): Dormand-Prince at rtol 1e-3
# with steps up to 1e-4 s instead of RK4 at 1e-6 s, a setting that keeps the distribution of the
# stroboscopic samples. Extra arguments go to `study sweep`.
# Writes build/demo/ (the result directory, docs/reference/study.md) with four figures, then prints the
# analysis of every tenth clearance.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j"$(nproc 2>/dev/null || echo 2)" --target study_cli > /dev/null
out=build/demo
rm -rf "$out"
# Exit 5 (some points' simulations did not complete) still assembles the tables; they say which.
build/study/study sweep \
  --set 'integrator.method="dopri5"' --set integrator.relative_tolerance=1e-3 --set integrator.max_step=1e-4 \
  --axis joint.slider.clearance=1e-5:6e-4:120 --periods 1000 --keep 500 --analysis -o "$out" "$@" || [[ $? == 5 ]]
mm=(--x-scale 1e3 --x-label 'clearance c_t (mm)')
build/study/study plot "$out" --figure bifurcation --last 50 "${mm[@]}" --y-scale 1e3 --y-label 'slider y (mm)' -o "$out/bifurcation.png"
build/study/study plot "$out" --figure density --log "${mm[@]}" --y-scale 1e3 --y-label 'slider y (mm)' -o "$out/density.png"
build/study/study plot "$out" --figure e2 "${mm[@]}" -o "$out/e2.png"
build/study/study plot "$out" --figure d2 --dimension 6 "${mm[@]}" -o "$out/d2_m6.png"
echo "figures: $out/bifurcation.png $out/density.png $out/e2.png $out/d2_m6.png"
echo "every tenth clearance: c_t (m), delay (samples of 1e-5 s), Cao's dimension, max|E2-1|, D2 status, D2(m = 6):"
grep -v '^#' "$out/analysis.tsv" | awk -F'\t' 'NR % 10 == 1 {
  if ($3 != "ok") printf "%-9.3g %s\n", $2, $3
  else printf "%-9.3g %-4s %-3s %-7.4s %-14s %s\n", $2, $6, $9, $10, $11, $(14 + 24 + 6)}'
