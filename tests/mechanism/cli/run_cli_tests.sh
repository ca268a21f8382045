#!/usr/bin/env bash
# The `mechanism` command as a user runs it: exit codes, messages naming the key and the rule,
# the printed scene reading back, and the JSON summary's keys. MECHANISM names the binary.
set -uo pipefail
m=${MECHANISM:?set MECHANISM to the mechanism binary}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }

# expect CODE PATTERN -- ARGS: runs the command, checks the exit code and that stderr matches.
expect() {
  local code=$1 pattern=$2
  shift 3
  "$m" "$@" > "$work/out" 2> "$work/err"
  local got=$?
  [[ $got -eq $code ]] || fail "mechanism $* exited $got, expected $code ($(head -c 300 "$work/err"))"
  [[ -z $pattern ]] || grep -q -- "$pattern" "$work/err" || fail "mechanism $*: stderr lacks '$pattern': $(head -c 300 "$work/err")"
}

# The commented default scene is valid TOML that reads back to the default scene.
"$m" scene --default > "$work/default.toml" || fail "scene --default"
"$m" scene "$work/default.toml" > "$work/resolved.toml" 2> /dev/null || fail "scene default.toml"
"$m" scene > "$work/plain.toml" 2> /dev/null || fail "scene"
cmp -s "$work/resolved.toml" "$work/plain.toml" || fail "the commented default does not read back to the default scene"
grep -q '^clearance = 5e-04$' "$work/plain.toml" || fail "the seed's clearance is not in the resolved scene"

# Refusals: exit 3 with the key, the value and the rule.
expect 3 "joint.slider.clearence" -- scene --set joint.slider.clearence=1e-4
expect 3 "crank.mass = -1.0: must be a finite number > 0" -- scene --set crank.mass=-1.0
expect 3 "conrod.length" -- scene --set conrod.length=0.04
expect 3 "cannot be opened" -- scene "$work/missing.toml"
printf 'crank = [1,\n' > "$work/bad.toml"
expect 3 "not valid TOML" -- scene "$work/bad.toml"
expect 3 "is not a signal" -- simulate -q --set run.duration=0.001 --signals t,nonsense
expect 2 "" -- simulate --no-such-flag
# The built-in scene (the seed's printed mu_s = 0.1 < mu_k = 0.11, kept on purpose: scene.md) runs
# without a warning; every run printed one about it.
expect 0 "" -- scene
[[ ! -s $work/err ]] || fail "the built-in scene warns: $(head -c 300 "$work/err")"
expect 0 "" -- simulate --set run.duration=0.001 -o /dev/null
[[ ! -s $work/err ]] || fail "a run of the built-in scene warns: $(head -c 300 "$work/err")"
# Another pair with mu_s < mu_k warns on every run; simulate -q silences it.
expect 0 "no stiction peak" -- simulate --set run.duration=0.001 --set joint.slider.friction.static_coefficient=0.05 -o /dev/null
expect 0 "" -- simulate -q --set run.duration=0.001 --set joint.slider.friction.static_coefficient=0.05 -o /dev/null
[[ ! -s $work/err ]] || fail "simulate -q still warns: $(head -c 300 "$work/err")"

# A short run: the table's header holds the resolved scene; the JSON summary has its keys.
# The header gives the scene as the keys that differ from the built-in one, each a line, and stays
# short (it held all 180 lines of the resolved scene).
"$m" simulate -q --set run.duration=0.002 --set joint.slider.clearance=2e-4 --signals t,slider_y > "$work/run.tsv" 2> /dev/null || fail "simulate"
grep -q '^#   joint.slider.clearance = 2e-04$' "$work/run.tsv" || fail "the table header lacks the changed clearance"
grep -q '^#   run.duration = ' "$work/run.tsv" || fail "the table header lacks the changed duration"
grep -q 'young_modulus' "$work/run.tsv" && fail "the table header lists keys that kept their built-in values"
(( $(grep -c '^#' "$work/run.tsv") <= 6 )) || fail "the table header has $(grep -c '^#' "$work/run.tsv") lines, expected at most 6"
rows=$(grep -vc '^#' "$work/run.tsv")
[[ $rows -eq 201 ]] || fail "expected 201 rows (0 to 2 ms every 10 us), got $rows"
"$m" simulate -q --json --set run.duration=0.002 > "$work/run.json" 2> /dev/null || fail "simulate --json"
for key in status steps rejected_steps wall_seconds max_penetration contact_events located_switches energy_balance_error; do
  jq -e "has(\"$key\")" "$work/run.json" > /dev/null || fail "JSON summary lacks $key"
done
[[ $(jq -r .status "$work/run.json") == completed ]] || fail "status is not completed"
# Stroboscopic rows: one per revolution, the first at t = 0.
"$m" simulate -q --stroboscopic --set run.duration=0.036 --signals t,slider_y > "$work/strobe.tsv" 2> /dev/null || fail "simulate --stroboscopic"
[[ $(grep -vc '^#' "$work/strobe.tsv") -eq 4 ]] || fail "expected 4 stroboscopic rows over 3 periods"
# --plot draws the slider's trajectory and, with a revolute clearance joint, the journal's path.
"$m" simulate -q --json --set run.duration=0.006 --set joint.crank_conrod.type=clearance --plot "$work/trajectory.png" > /dev/null 2>&1 \
  || fail "simulate --plot"
[[ -s $work/trajectory.png ]] && [[ $(head -c 4 "$work/trajectory.png" | tail -c 3) == PNG ]] || fail "--plot wrote no PNG file"
expect 3 "must end in .png or .svg" -- simulate -q --json --set run.duration=0.001 --plot "$work/trajectory.pdf"

# A run that cannot continue exits 5 with the time.
expect 5 "step limit" -- simulate -q --set integrator.max_steps=10 --set run.duration=0.001
# ... and with --plot, when it stopped before the transient ended, says there is nothing to draw.
expect 5 "no plot: the run wrote no samples" -- simulate -q -o /dev/null --set integrator.max_steps=10 \
  --set run.transient=0.001 --set run.duration=0.001 --plot "$work/none.png"
[[ ! -e $work/none.png ]] || fail "a run with no samples still drew $work/none.png"

# 1e-6 m clearance at 50 rpm on the scene as printed (face contact, exponent 1.5,
# absolute LuGre with a constant sigma1; the built-in scene's reading completes it)
# reported "completed" with energy_balance_relative 0.53 (3 revolutions). Half a revolution
# measures 0.075, above the limit of 0.03 per revolution (mechanism/simulate.hpp): status
# energy_defect, exit 5, the numbers named.
printed=(--set joint.slider.model=face --set joint.slider.contact.exponent=1.5 --set joint.slider.friction.law=lugre_absolute --set joint.slider.friction.sigma1_velocity=0)
expect 5 "above the limit 0.03" -- simulate -q --json "${printed[@]}" --set joint.slider.clearance=1e-6 \
  --set driver.speed_rpm=50 --set run.duration=0.6 --set run.output_interval=0
[[ $(jq -r .status "$work/out") == energy_defect ]] || fail "the issue's case has status $(jq -r .status "$work/out"), expected energy_defect"

# Runs that did nothing or never ended. A duration of 1.9e13 s wrapped the RK4
# step count to 0 and "completed"; an output interval of 1e-300 s wrote rows until the disk was
# full. Both are refused before the run (exit 3, README.md) with the numbers and the limit
# (mechanism/scene.hpp: 1e12 steps, 1e8 rows).
expect 3 "run.duration = 1.9e+13: with run.transient 0.0 s and integrator.step = 1e-06 s needs 1.9e+19 RK4 steps, more than the limit of 1e+12 steps" \
  -- simulate -q --set run.duration=1.9e13 --set run.output_interval=0
expect 3 "run.output_interval = 1e-300: gives 6e+298 rows over run.duration 0.06 s, more than the limit of 1e+08 rows" \
  -- simulate -q --set run.output_interval=1e-300
expect 3 "integrator.max_steps = 1e+30: must be at most 1e+12" -- simulate -q --set integrator.max_steps=1e30
[[ ! -s $work/out ]] || fail "a refused run wrote rows"

# A scene file after --set k=v was read as another --set value ("must be
# KEY=VALUE"). Each --set takes one value; the file is the scene, the override applies.
"$m" scene --set joint.slider.clearance=2e-4 "$work/default.toml" > "$work/order.toml" 2> "$work/err" || fail "scene --set k=v FILE: $(head -c 300 "$work/err")"
grep -A12 '^\[joint.slider\]' "$work/order.toml" | grep -q '^clearance = 2e-04$' || fail "scene --set k=v FILE did not apply the override"

# -o naming the input overwrote it, and an unwritable -o or --plot failed only
# after the whole run. Both are refused while the command line is read (exit 3, README.md), with
# the option and the path named; a run of 1e13 s would be refused too, so the message shows the
# output was checked first.
cp "$work/default.toml" "$work/scene.toml"
expect 3 "-o .*scene.toml is the input file" -- simulate -q "$work/scene.toml" -o "$work/scene.toml"
cmp -s "$work/default.toml" "$work/scene.toml" || fail "-o naming the scene file changed it"
expect 3 "-o .*/no_such_dir/out.tsv: the directory .*no_such_dir does not exist" -- simulate -q -o "$work/no_such_dir/out.tsv" \
  --set run.duration=1e13
expect 3 "-o $work is a directory" -- simulate -q -o "$work" --set run.duration=1e13
expect 3 "--plot .*/no_such_dir/p.png: the directory .*no_such_dir does not exist" -- simulate -q --json \
  --plot "$work/no_such_dir/p.png" --set run.duration=1e13
expect 3 "--plot: the file must end in .png or .svg" -- simulate -q --json --plot "$work/p.pdf" --set run.duration=1e13

# A directory given as the scene ran the built-in scene; it is refused (exit 3).
expect 3 "is a directory, not a scene file" -- simulate -q "$work"

# An unknown command is named (exit 2), also with --help after it.
expect 2 "unknown command 'foo'; the commands are: scene, simulate" -- foo
expect 2 "unknown command 'foo'" -- foo --help

# A free crank (the Flores-Leine-Glocker scene file) has no period: no stroboscopic rows, no period map.
flg="$(dirname "$0")/../../../mechanism/scenes/flores_leine_glocker_free.toml"
expect 3 "run.stroboscopic = true: needs a driven crank" -- simulate -q "$flg" --stroboscopic --set run.duration=0.001
expect 3 "driver.free = true: has no crank-period map" -- lyapunov -q "$flg" --periods 10
"$m" simulate -q "$flg" --set run.duration=0.01 --json -o /dev/null > "$work/flg.json" 2> "$work/err" ||
  fail "simulate the free Flores-Leine-Glocker scene: $(head -c 300 "$work/err")"
grep -q '"crank_angle"' "$work/flg.json" || fail "the free crank's angle is not a coordinate"

# mechanism lyapunov: the exponents from the equations (docs/reference/mechanism/lyapunov.md). A short run of
# the tilted, dissipative audit scene: JSON keys, one exponent per phase coordinate (conrod and
# slider angles and their rates), the table's rows (one per period averaged), and refusals.
tilted=(--set joint.slider.model=line --set joint.slider.friction.law=none --set joint.slider.contact.restitution=0.5
  --set initial.slider_angle=0.01 --set initial.slider_rate=20)
"$m" lyapunov -q "${tilted[@]}" --periods 10 --transient-periods 2 --json > "$work/lyap.json" 2> "$work/err" ||
  fail "lyapunov --json: $(head -c 300 "$work/err")"
for key in status exponents standard_error exponents_per_period resolution_limit kaplan_yorke kaplan_yorke_section collapsed coordinates \
  scale period periods perturbation perturbation_floor steps_per_interval largest_scaled_coordinate largest_separation wall_seconds; do
  grep -q "\"$key\":" "$work/lyap.json" || fail "lyapunov --json lacks $key"
done
grep -q '"status": "completed"' "$work/lyap.json" || fail "lyapunov: the tilted scene did not complete: $(head -c 300 "$work/lyap.json")"
n_exp=$(awk '/"exponents": \[/ { on = 1; next } on && /\]/ { print n; exit } on { n++ }' "$work/lyap.json")
[[ $n_exp -eq 4 ]] || fail "lyapunov: expected 4 exponents, got $n_exp"
"$m" lyapunov -q "${tilted[@]}" --periods 10 --transient-periods 2 -k 1 -o "$work/lyap.tsv" > "$work/out" 2> "$work/err" ||
  fail "lyapunov -o: $(head -c 300 "$work/err")"
rows=$(grep -vc '^#' "$work/lyap.tsv")
[[ $rows -eq 10 ]] || fail "lyapunov: expected 10 rows (one per period), got $rows"
grep -q '^# lambda_1 = ' "$work/lyap.tsv" || fail "lyapunov: the table's header lacks lambda_1"
grep -q '^# lambda_2' "$work/lyap.tsv" && fail "lyapunov -k 1 wrote a second exponent"
# One positive exponent alone bounds no dimension: the header says so instead of printing NaN.
grep -q '^# Kaplan-Yorke dimension: none' "$work/lyap.tsv" || fail "lyapunov -k 1: the Kaplan-Yorke line is not 'none'"
grep -qiw 'nan' "$work/lyap.tsv" && fail "lyapunov -k 1 printed NaN"
expect 3 "mechanism: lyapunov: periods = 5: must be >= 10" -- lyapunov -q --periods 5
expect 3 "perturbation = 0: must be in (0, 1)" -- lyapunov -q --perturbation 0
# Below what the state resolves: refused with the floor named. 1e-16 used to complete with every
# exponent -inf; 1e-11 gave lambda_1 twice the default's. 1e3 epsilon bounds every floor (refused
# before any integration); the built-in scene's floor (240 RK4 steps per interval, the largest
# |coordinate| / scale about 4.5) is about 2.4e-10.
expect 3 "perturbation = .*: is below the floor 2.22e-13" -- lyapunov -q --perturbation 1e-16
expect 3 "perturbation = .*: is below this scene's floor 2.[0-9]*e-10: 1e3 x machine epsilon .* x 240 integrator steps per interval" -- \
  lyapunov -q --periods 10 --transient-periods 2 --perturbation 1e-11
expect 3 "rigid" -- lyapunov -q --set joint.slider.type=ideal
# --method saltation (docs/reference/mechanism/saltation.md): the same keys plus the method, and the
# scenes it refuses, each with the reason.
"$m" lyapunov -q "${tilted[@]}" --method saltation --periods 10 --transient-periods 2 -k 2 --json > "$work/salt.json" \
  2> "$work/err" || fail "lyapunov --method saltation: $(head -c 300 "$work/err")"
grep -q '"method": "saltation"' "$work/salt.json" || fail "lyapunov --method saltation: the JSON does not name the method"
grep -q '"latched_variations": "carried"' "$work/salt.json" || fail "lyapunov --method saltation: latched_variations not carried"
grep -q '"status": "completed"' "$work/salt.json" || fail "lyapunov --method saltation did not complete: $(head -c 300 "$work/salt.json")"
grep -q '"method": "benettin"' "$work/lyap.json" || fail "lyapunov: the JSON does not name the default method"
expect 2 "not in {benettin,saltation}" -- lyapunov -q --method newton
expect 2 "needs --method saltation" -- lyapunov -q --drop-latched-variations
expect 3 "method = saltation: does not apply to this scene: .*rk4" -- lyapunov -q --method saltation \
  --set integrator.method=dopri5
# Coulomb's law: the saltation method differentiates its located reversals; a contact that sticks
# (the Flores-Leine-Glocker slider on RK4's grid) has no saltation matrix, and the run says so.
"$m" lyapunov -q --method saltation --set joint.slider.friction.law=coulomb --periods 10 --transient-periods 0 -k 1 \
  --json > "$work/coulomb.json" 2> "$work/err" || fail "lyapunov --method saltation with Coulomb: $(head -c 300 "$work/err")"
grep -q '"status": "completed"' "$work/coulomb.json" || fail "saltation with Coulomb did not complete: $(head -c 300 "$work/coulomb.json")"
expect 5 "a Coulomb contact stuck at t = .*use --method benettin" -- lyapunov -q --method saltation --periods 10 \
  --transient-periods 0 -k 1 --set integrator.method=rk4 --set integrator.step=1e-6 "${flg%_free.toml}_driven.toml"
expect 3 "exponents = 9: must be between 1 and the phase-space dimension" -- lyapunov -q --periods 10 -k 9
"$m" lyapunov -q --periods -1 > /dev/null 2> "$work/err"
code=$?
[[ $code -eq 2 || $code -eq 3 ]] || fail "lyapunov --periods -1 exited $code: $(head -c 300 "$work/err")"

# The closed-form benchmark prints one row per method; its periodic orbit's exponents agree.
"$m" impact-oscillator --periods 200 > "$work/osc.tsv" 2> "$work/err" || fail "impact-oscillator: $(head -c 300 "$work/err")"
for row in closed_form saltation finite_differences; do
  grep -q "^$row	" "$work/osc.tsv" || fail "impact-oscillator: no $row row"
done
expect 3 "restitution = 0: must be in (0, 1]" -- impact-oscillator --restitution 0

if ((failures > 0)); then
  echo "$failures mechanism command check(s) failed" >&2
  exit 1
fi
echo "all mechanism command checks passed"
