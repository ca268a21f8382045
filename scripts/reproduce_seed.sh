#!/usr/bin/env bash
# Reproduces the seed paper's figures 3-13 with `study` and `mechanism` (docs/validation/reproduction.md).
#   scripts/reproduce_seed.sh [figure...]      figures: fig3 fig4 fig5 fig6 fig7 fig9 fig12 fig13
# (fig8 comes out of fig4's sweep.) With no figure, all of them. Sweep results go to
# $RUNS (default build/reproduction-runs), figures to $FIGURES (default docs/validation/reproduction), and
# the wall time of every command is appended to $FIGURES/timing.tsv.
#
# Sizes: the seed's where this 2-core machine can afford them, else reduced (the variables below,
# each overridable from the environment; SIZE=seed sets every one to the seed's value).
# The integrator is the one docs/validation/mechanism/performance.md shows to keep the long-run statistics:
# dopri5 at relative tolerance RTOL (1e-4), or INTEGRATOR=rk4 at STEP (1e-6 s, the seed's).
set -euo pipefail
cd "$(dirname "$0")/.."
STUDY=${STUDY:-build/study/study}
MECHANISM=${MECHANISM:-build/mechanism/mechanism}
RUNS=${RUNS:-build/reproduction-runs}
FIGURES=${FIGURES:-docs/validation/reproduction}
THREADS=${THREADS:-$(nproc 2>/dev/null || echo 2)}
RTOL=${RTOL:-1e-4}
SCENE_SETS=(${SCENE_SETS:-})  # extra --set arguments for every run, e.g. "--set joint.slider.rotation=locked"
# READING=printed starts every run from the seed's slider joint as printed (scripts/printed_reading.sh)
# instead of the built-in reading; SCENE_SETS still come after it.
if [[ ${READING:-built_in} == printed ]]; then
  source scripts/printed_reading.sh
  SCENE_SETS=($printed_reading "${SCENE_SETS[@]}")
elif [[ ${READING:-built_in} != built_in ]]; then
  echo "READING must be built_in or printed (got '$READING')" >&2
  exit 2
fi

if [[ ${SIZE:-docs} == seed ]]; then
  : "${FIG4_CLEARANCES:=120}" "${FIG4_PERIODS:=1000}" "${FIG5_SPEEDS:=150}" "${FIG5_PERIODS:=1000}"
  : "${FIG6_POINTS:=10000}" "${FIG9_CLEARANCES:=120}" "${FIG9_SPEEDS:=150}" "${FIG9_PERIODS:=1000}"
  : "${FIG12_CLEARANCES:=120}" "${FIG12_PERIODS:=1000}"
fi
FIG4_CLEARANCES=${FIG4_CLEARANCES:-120}  # 0.01 .. 0.6 mm at 5000 rpm
FIG4_PERIODS=${FIG4_PERIODS:-1000}
FIG5_SPEEDS=${FIG5_SPEEDS:-46}           # 500 .. 5000 rpm, for c_t = 0.1, 0.2, 0.3, 0.5 mm
FIG5_PERIODS=${FIG5_PERIODS:-300}
FIG6_POINTS=${FIG6_POINTS:-10000}        # stroboscopic points per portrait
FIG9_CLEARANCES=${FIG9_CLEARANCES:-12}
FIG9_SPEEDS=${FIG9_SPEEDS:-10}
FIG9_PERIODS=${FIG9_PERIODS:-200}
FIG12_CLEARANCES=${FIG12_CLEARANCES:-12}
FIG12_PERIODS=${FIG12_PERIODS:-200}

mkdir -p "$RUNS" "$FIGURES"
if [[ ${INTEGRATOR:-dopri5} == rk4 ]]; then  # the seed's method: RK4 at STEP (default 1e-6 s)
  integrator=(--set 'integrator.method="rk4"' --set "integrator.step=${STEP:-1e-6}" "${SCENE_SETS[@]}")
else
  integrator=(--set 'integrator.method="dopri5"' --set "integrator.relative_tolerance=$RTOL" "${SCENE_SETS[@]}")
fi
mm=(--x-scale 1e3)

# timed NAME COMMAND...: runs it and appends "NAME<TAB>seconds<TAB>command" to timing.tsv.
timed() {
  local name=$1; shift
  local t0 t1
  t0=$(date +%s.%N)
  # Exit 5: finished, but some points' simulations did not complete; their rows say why and the
  # figures leave them out, so the script goes on (docs/validation/reproduction.md counts them).
  "$@" || { local code=$?; [[ $code == 5 ]] || exit "$code"; echo "$name: some points did not complete (exit 5)" >&2; }
  t1=$(date +%s.%N)
  printf '%s\t%.1f\t%s\n' "$name" "$(echo "$t1 - $t0" | bc)" "$*" >> "$FIGURES/timing.tsv"
}

sweep() {  # name, then study sweep arguments; resumes a sweep already in $RUNS/name
  local name=$1; shift
  local resume=()
  [[ -e "$RUNS/$name/spec.txt" ]] && resume=(--resume)
  timed "$name" "$STUDY" sweep "${integrator[@]}" "$@" --threads "$THREADS" -q -o "$RUNS/$name" "${resume[@]}" > "$RUNS/$name.json"
}

fig3() {  # slider trajectories over 5 periods after 100 for five clearances
  for c in 0.5 0.3 0.2 0.1 0.01; do
    timed "fig3_$c" "$MECHANISM" simulate "${integrator[@]}" --set "joint.slider.clearance=${c}e-3" \
      --set run.transient=1.2 --set run.duration=0.06 --signals t -q -o /dev/null --plot "$FIGURES/fig3_ct${c}mm.png"
  done
}

# A saturated-D2 figure with no saturated point is refused (exit 3, the statuses counted): the run
# goes on to the next figure, the message left on stderr.
d2_plot() {
  local code=0
  "$STUDY" plot "$@" || code=$?
  [[ $code == 0 || $code == 3 ]] || return "$code"
}

fig4() {  # bifurcation diagram and PDF over clearance at 5000 rpm, with the D2 analysis (Fig. 8)
  sweep fig4 --axis "joint.slider.clearance=1e-5:6e-4:$FIG4_CLEARANCES" --periods "$FIG4_PERIODS" \
    --keep $((FIG4_PERIODS / 2)) --analysis
  "$STUDY" plot "$RUNS/fig4" --figure bifurcation --last 50 "${mm[@]}" --y-scale 1e3 \
    --x-label 'clearance c_t (mm)' --y-label 'slider y (mm)' --title 'Fig. 4a: last 50 periods, 5000 rpm' -o "$FIGURES/fig4a_bifurcation.png"
  "$STUDY" plot "$RUNS/fig4" --figure density "${mm[@]}" --y-scale 1e3 \
    --x-label 'clearance c_t (mm)' --y-label 'slider y (mm)' --title 'Fig. 4b: PDF of the last 500 periods' --log -o "$FIGURES/fig4b_density.png"
  "$STUDY" plot "$RUNS/fig4" --figure e2 "${mm[@]}" --x-label 'clearance c_t (mm)' --title "Fig. 8a: Cao's E2" -o "$FIGURES/fig8a_e2.png"
  d2_plot "$RUNS/fig4" --figure d2 "${mm[@]}" --x-label 'clearance c_t (mm)' --title 'Fig. 8b: D2' -o "$FIGURES/fig8b_d2.png"
  "$STUDY" plot "$RUNS/fig4" --figure d2 --dimension 6 "${mm[@]}" --x-label 'clearance c_t (mm)' \
    --title 'Fig. 8b at m = 6 (the seed: tau = 18, m = 6): D2(6), not saturated' -o "$FIGURES/fig8b_d2_m6.png"
}

fig5() {  # PDFs over crank speed for four clearances
  sweep fig5 --axis "driver.speed_rpm=500:5000:$FIG5_SPEEDS" --axis joint.slider.clearance=1e-4,2e-4,3e-4,5e-4 \
    --periods "$FIG5_PERIODS" --keep $((FIG5_PERIODS / 2))
  "$STUDY" plot "$RUNS/fig5" --figure density --y-scale 1e3 --x-label 'crank speed (rpm)' --y-label 'slider y (mm)' \
    --title 'Fig. 5' --log -o "$FIGURES/fig5_density.png"
}

fig6() {  # Poincare portraits (slider_vy against slider_y once per revolution) for four clearances
  sweep fig6 --axis joint.slider.clearance=1e-4,2e-4,3e-4,5e-4 --periods $((FIG6_POINTS + 100)) --keep "$FIG6_POINTS"
  "$STUDY" plot "$RUNS/fig6" --figure portrait "${mm[@]}" --x-label 'slider y (mm)' --y-label 'slider v_y (m/s)' \
    --title 'Fig. 6' -o "$FIGURES/fig6_portraits.png"
}

fig7() {  # the correlation-dimension pipeline for c_t = 0.5 mm at 5000 rpm, then the local slopes
  timed fig7 "$STUDY" pipeline "${integrator[@]}" --periods 1000 --plot "$FIGURES/fig7_pipeline.png" \
    --series "$RUNS/fig7_series.tsv" > "$RUNS/fig7.json"
  timed fig7_tau18 "$STUDY" pipeline "${integrator[@]}" --periods 1000 --delay 18 --plot "$FIGURES/fig7_pipeline_tau18.png" > "$RUNS/fig7_tau18.json"
  # The evidence behind D2: log C and the local slopes d ln C / d ln eps for m = 1..12 with the
  # automatic scaling region, at the MI delay and at the seed's tau = 18.
  local tau theiler
  if ! jq -e .analysis > /dev/null "$RUNS/fig7.json"; then  # a run that did not complete has no analysis
    echo "fig7: no local slopes: the simulation ended with $(jq -r '.simulation.status + ": " + .simulation.message' "$RUNS/fig7.json")" >&2
    return 0
  fi
  tau=$(jq .analysis.delay_samples "$RUNS/fig7.json")
  theiler=$(jq .analysis.theiler_samples "$RUNS/fig7.json")
  if [[ $tau != null ]]; then
    build/chaos/chaos d2 "$RUNS/fig7_series.tsv" -c 2 --dt 1e-5 -d "$tau" -M 12 -t "$theiler" --json \
      --plot "$FIGURES/fig7_local_slopes.png" > "$RUNS/fig7_d2.json"
  fi
  build/chaos/chaos d2 "$RUNS/fig7_series.tsv" -c 2 --dt 1e-5 -d 18 -M 12 -t "$theiler" --json \
    --plot "$FIGURES/fig7_local_slopes_tau18.png" > "$RUNS/fig7_d2_tau18.json"
}

fig9() {  # D2 over clearance and speed
  sweep fig9 --axis "joint.slider.clearance=1e-5:6e-4:$FIG9_CLEARANCES" --axis "driver.speed_rpm=500:5000:$FIG9_SPEEDS" \
    --periods "$FIG9_PERIODS" --keep 10 --analysis --analysis-samples-per-period 1200 --max-delay 200
  d2_plot "$RUNS/fig9" --figure d2map "${mm[@]}" --x-label 'clearance c_t (mm)' --y-label 'crank speed (rpm)' \
    --title 'Fig. 9: D2' -o "$FIGURES/fig9_d2map.png"
  "$STUDY" plot "$RUNS/fig9" --figure d2map --dimension 6 "${mm[@]}" --x-label 'clearance c_t (mm)' --y-label 'crank speed (rpm)' \
    --title 'Fig. 9 at m = 6: D2(6), not saturated' -o "$FIGURES/fig9_d2map_m6.png"
}

fig12() {  # D2 over c_t with a revolute clearance at the conrod-slider pin, friction 0 and 0.05
  # (LuGre in the journal with sigma1 fading: with a constant sigma1 = 400 N s/m there, dopri5 stalls
  # in step_underflow within the first second; docs/validation/reproduction.md)
  local revolute=(--set 'joint.conrod_slider.type="clearance"')
  sweep fig12_mu0 "${revolute[@]}" --axis "joint.slider.clearance=1e-5:6e-4:$FIG12_CLEARANCES" \
    --axis joint.conrod_slider.clearance=1e-4,5e-4 --periods "$FIG12_PERIODS" --keep 10 --analysis
  sweep fig12_mu005 "${revolute[@]}" --set 'joint.conrod_slider.friction.law="lugre_absolute"' \
    --set joint.conrod_slider.friction.static_coefficient=0.05 --set joint.conrod_slider.friction.kinetic_coefficient=0.05 \
    --set joint.conrod_slider.friction.sigma1_velocity=1e-3 \
    --axis "joint.slider.clearance=1e-5:6e-4:$FIG12_CLEARANCES" --axis joint.conrod_slider.clearance=1e-4,5e-4 \
    --periods "$FIG12_PERIODS" --keep 10 --analysis
  for run in fig12_mu0 fig12_mu005; do
    local mu=${run#fig12_mu}
    d2_plot "$RUNS/$run" --figure d2 "${mm[@]}" --x-label 'clearance c_t (mm)' --title "Fig. 12: revolute mu_s = ${mu/005/0.05}" -o "$FIGURES/${run}_d2.png"
    "$STUDY" plot "$RUNS/$run" --figure d2 --dimension 6 "${mm[@]}" --x-label 'clearance c_t (mm)' --title "Fig. 12 at m = 6: revolute mu_s = ${mu/005/0.05}" -o "$FIGURES/${run}_d2_m6.png"
  done
}

fig13() {  # journal trajectories in the conrod-slider bearing, c_t = 0.5 mm, c_r = 0.1 and 0.5 mm
  for cr in 0.1 0.5; do
    timed "fig13_$cr" "$MECHANISM" simulate "${integrator[@]}" --set 'joint.conrod_slider.type="clearance"' \
      --set "joint.conrod_slider.clearance=${cr}e-3" --set run.transient=1.2 --set run.duration=0.12 --signals t -q \
      -o /dev/null --plot "$FIGURES/fig13_cr${cr}mm.png"
  done
}

figures=("$@")
[[ ${#figures[@]} -gt 0 ]] || figures=(fig3 fig4 fig5 fig6 fig7 fig9 fig12 fig13)
for f in "${figures[@]}"; do
  declare -F "$f" > /dev/null || { echo "unknown figure $f (fig3 fig4 fig5 fig6 fig7 fig9 fig12 fig13)" >&2; exit 2; }
  echo "== $f" >&2
  "$f"
done
