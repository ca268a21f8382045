#!/usr/bin/env bash
# The `chaos` command as a user meets it: every refusal of bad input exits non-zero with a message
# that names the rule and the numbers; JSON keys that scripts rely on are present.
# Expected values come from the documented exit codes (README.md) and the issue's JSON contract.
set -u
: "${CHAOS:?set CHAOS to the chaos executable}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
passed=0
failed=0

pass() { passed=$((passed + 1)); }
fail() { failed=$((failed + 1)); echo "FAIL: $*" >&2; }

# expect_error CODE PATTERN -- ARGS...: exit code CODE and stderr matching PATTERN (extended regex).
expect_error() {
  local code=$1 pattern=$2
  shift 3
  local err rc
  err=$("$CHAOS" "$@" 2>&1 >/dev/null)
  rc=$?
  if [[ $rc -ne $code ]]; then fail "chaos $* exited $rc, expected $code ($err)"; return; fi
  if ! grep -Eq -- "$pattern" <<<"$err"; then fail "chaos $*: message '$err' does not match /$pattern/"; return; fi
  pass
}

# expect_json_keys ARGS... -- KEY...: the JSON output has every key at top level.
expect_json_keys() {
  local args=() keys=()
  while [[ $1 != -- ]]; do args+=("$1"); shift; done
  shift
  keys=("$@")
  local json
  if ! json=$("$CHAOS" "${args[@]}" --json 2>&1); then fail "chaos ${args[*]} --json failed: $json"; return; fi
  for key in "${keys[@]}"; do
    if ! jq -e --arg k "$key" 'has($k)' <<<"$json" >/dev/null; then fail "chaos ${args[*]} --json lacks key $key"; return; fi
  done
  pass
}

"$CHAOS" generate henon -l 3000 --components x > "$work/henon.dat" || fail "generate henon"
"$CHAOS" generate lorenz -l 5000 --components x > "$work/lorenz.dat" || fail "generate lorenz"
printf '1\n2\nthree\n4\n' > "$work/word.dat"
printf '1\n2\nnan\n4\n' > "$work/nan.dat"
printf '1 2\n3 4\n5\n' > "$work/short_row.dat"
printf '# only a comment\n\n' > "$work/empty.dat"
for i in $(seq 1 200); do echo 3.5; done > "$work/constant.dat"
printf '1\n2\n3\n4\n5\n' > "$work/five.dat"

# Bad input: each rule, its exit code (3) and what the message must name.
expect_error 3 "missing.dat.*cannot open" -- mutual "$work/missing.dat"
expect_error 3 "empty.dat: no data rows" -- cao "$work/empty.dat"
expect_error 3 "word.dat:3: column 1: 'three' is not a number" -- mutual "$work/word.dat"
expect_error 3 "nan.dat:3: .*not finite" -- fnn "$work/nan.dat"
expect_error 3 "short_row.dat:3: column 2 requested but the line has only 1" -- mutual -c 2 "$work/short_row.dat"
expect_error 3 "constant.*200 samples" -- cao "$work/constant.dat"
expect_error 3 "constant" -- mutual "$work/constant.dat"
expect_error 3 "too short.*N = 5" -- cao -M 10 "$work/five.dat"
expect_error 3 "tau.*0|delay.*0" -- cao -d 0 "$work/henon.dat"
expect_error 3 "dimension.*0|m = 0" -- cao -m 0 "$work/henon.dat"
expect_error 3 "dimension.*0|m = 0" -- fnn -m 0 "$work/henon.dat"
expect_error 3 "boxes" -- mutual -b 1 "$work/henon.dat"
expect_error 3 "column numbers start at 1" -- mutual -c 0 "$work/henon.dat"
expect_error 3 "no parameter 'rh'" -- generate lorenz -p rh=28
expect_error 3 "unknown system" -- generate lorenzz
expect_error 3 "norm must be" -- cao --norm taxicab "$work/henon.dat"
expect_error 2 "" -- cao --no-such-option "$work/henon.dat"
expect_error 2 "" -- no-such-command

# Stdin and TISEAN's -x/-l select rows.
n=$(printf '# c\n1\n2\n3\n4\n5\n6\n7\n8\n9\n10\n' | "$CHAOS" autocorrelation -x 2 -l 6 -D 2 --json - | jq '.parameters.N')
[[ $n == 6 ]] && pass || fail "-x 2 -l 6 on stdin gave N = $n, expected 6"

# JSON contracts.
expect_json_keys mutual "$work/lorenz.dat" -D 30 -- delay mutual_information first_minimum
expect_json_keys cao "$work/henon.dat" -M 5 -- dimension E1 E2 embedding_dimension
expect_json_keys fnn "$work/henon.dat" -M 5 -- dimension false_fraction embedding_dimension
expect_json_keys autocorrelation "$work/lorenz.dat" -- lag autocorrelation first_zero_crossing decorrelation_time
expect_json_keys analyze "$work/henon.dat" -d 1 -M 5 -- delay theiler embedding_dimension fnn_embedding_dimension lambda lambda_interval lambda_status nonlinearity
l=$("$CHAOS" analyze "$work/henon.dat" -d 1 -M 5 --json | jq -c '[(.lambda > 0.35 and .lambda < 0.5), .lambda_per, .nonlinearity.rejected, .nonlinearity.ties]')
[[ $l == '[true,"sample",true,0]' ]] && pass || fail "analyze on Hénon gave $l"
# --threads shares the work and changes nothing else (each estimator's results are the same for any
# number of threads): the JSON of 1 and 2 threads differ in parameters.threads alone; 0 threads is refused.
one=$("$CHAOS" analyze "$work/henon.dat" -d 1 -M 5 --json | jq -S 'del(.parameters.threads)')
two=$("$CHAOS" analyze "$work/henon.dat" -d 1 -M 5 --threads 2 --json | jq -S 'del(.parameters.threads)')
[[ -n $one && $one == "$two" ]] && pass || fail "analyze --threads 2 changed the result"
expect_error 3 "threads must be at least 1" -- analyze "$work/henon.dat" --threads 0

expect_json_keys d2 "$work/henon.dat" -d 1 -M 4 -- dimension radius correlation_sum local_slope d2_by_dimension d2 d2_interval scaling_region saturated
r=$("$CHAOS" d2 "$work/henon.dat" -d 1 -M 2 --radius-list 0.01,0.02,0.05,0.1 --json | jq -c '.radius')
[[ $r == "[0.01,0.02,0.05,0.1]" ]] && pass || fail "--radius-list gave radius $r"
# The halves check, on by default (--halves says so explicitly): both halves are reported, and the
# verdict follows from them (saturated only when both halves saturate within the allowance of each
# other; otherwise not_reproduced and no D2).
h=$("$CHAOS" d2 "$work/henon.dat" -d 1 -M 4 --json | jq -c '
  (.first_half.d2 // null) as $a | (.second_half.d2 // null) as $b |
  [(.plateaus | length > 0), .parameters.halves,
   (if .status == "saturated" then ($a != null and $b != null and (($a - $b) | fabs) <= 0.05 * ($a + $b))
    elif .status == "not_reproduced" then (.d2 == null and (.explanation | test("halves")))
    else false end)]')
[[ $h == '[true,true,true]' ]] && pass || fail "d2 (halves by default) on Hénon gave $h"
[[ $("$CHAOS" d2 "$work/henon.dat" -d 1 -M 4 --halves --json | jq -c 'del(.parameters)') == \
   "$("$CHAOS" d2 "$work/henon.dat" -d 1 -M 4 --json | jq -c 'del(.parameters)')" ]] && pass || fail "d2 --halves differs from the default"
# --no-halves: the plain estimate, no halves in the result.
h=$("$CHAOS" d2 "$work/henon.dat" -d 1 -M 4 --no-halves --json | jq -c '[.parameters.halves, has("first_half"), .status, .parameters.halves_reference_points]')
[[ $h == '[false,false,"saturated",null]' ]] && pass || fail "d2 --no-halves on Hénon gave $h"
# Measurement noise (1% of the standard deviation) hides Hénon's small scales: below the plateau
# every dimension fills its space, so the status is noise_limited with the noise floor below the
# plateau and no D2; --noise-fill-fraction inf turns the check off (and inf is accepted, as for
# --projection-tolerance), which leaves the plateau as the saturated D2 (with --no-halves: the
# halves of the noisy record do not reproduce that large-scale plateau).
"$CHAOS" generate henon -l 20000 --components x | grep -v '^#' > "$work/henon20k.dat" || fail "generate henon 20000"
"$CHAOS" generate white_noise -l 20000 --seed 1 | grep -v '^#' > "$work/gauss20k.dat" || fail "generate white_noise"
awk 'NR == FNR { x[NR] = $1; s += $1; n = NR; next }
  FNR == 1 { m = s / n; for (i = 1; i <= n; ++i) q += (x[i] - m)^2; sd = sqrt(q / n) / 100 }
  { printf "%.17g\n", x[FNR] + sd * $1 }' "$work/henon20k.dat" "$work/gauss20k.dat" > "$work/henon_noisy.dat"
h=$("$CHAOS" d2 "$work/henon_noisy.dat" -d 1 -t 1 -M 5 --json | jq -c '
  [.status, .d2, (.noise_floor.radius < .plateaus[0].radii[0]), (.explanation | test("noise"))]')
[[ $h == '["noise_limited",null,true,true]' ]] && pass || fail "d2 on Hénon with 1% noise gave $h"
h=$("$CHAOS" d2 "$work/henon_noisy.dat" -d 1 -t 1 -M 5 --noise-fill-fraction inf --projection-tolerance inf --no-halves --json |
  jq -c '[.status, .noise_floor, (.d2 > 1.1 and .d2 < 1.3)]')
[[ $h == '["saturated",null,true]' ]] && pass || fail "d2 --noise-fill-fraction inf on noisy Hénon gave $h"
# --delay-check: the D2 at twice the delay is reported, and the verdict follows from it (saturated
# only within --delay-tolerance of it; otherwise not_reproduced and no D2).
h=$("$CHAOS" d2 "$work/henon.dat" -d 1 -M 4 --delay-check --json | jq -c '
  [(.delay_variant.delay == 2),
   (if .status == "saturated" then (.delay_variant.d2 != null and ((.delay_variant.d2 - .d2) | fabs) <= 0.05)
    elif .status == "not_reproduced" then (.d2 == null and (.explanation | test("at delay 2")))
    else false end)]')
[[ $h == '[true,true]' ]] && pass || fail "d2 --delay-check on Hénon gave $h"
# --inclusive counts pairs at distance <= eps (TISEAN's d2), the default < eps. Expected
# counts: every pair of a 12-sample integer series enumerated here by awk (ties at both radii).
printf '%s\n' 0 1 2 3 1 0 2 2 3 1 0 1 > "$work/ties.dat"
want=$(awk '{ x[NR] = $1 } END {
  for (i = 1; i <= NR; i++) for (j = i + 1; j <= NR; j++) { d = x[i] - x[j]; if (d < 0) d = -d; a += d < 1; b += d < 2; c += d <= 1; e += d <= 2 }
  printf "[[[%d,%d]],false] [[[%d,%d]],true]", a, b, c, e }' "$work/ties.dat")
got="$("$CHAOS" d2 "$work/ties.dat" -M 1 -t 0 --radius-list 1,2 --json | jq -c '[.pairs, .parameters.inclusive]') $("$CHAOS" d2 "$work/ties.dat" -M 1 -t 0 --radius-list 1,2 --inclusive --json | jq -c '[.pairs, .parameters.inclusive]')"
[[ $got == "$want" ]] && pass || fail "d2 pairs without and with --inclusive: $got, expected $want"
expect_error 3 "increasing" -- d2 "$work/henon.dat" -M 2 --radius-list 0.1,0.05
# One radius gives no slope: the rule named is D2's, not the radius grid's (whose r_min = r_max
# condition would name the automatic radii the user did not give).
expect_error 3 "at least 2 radii for a slope \\(got -# 1\\)" -- d2 "$work/henon.dat" -# 1
# --fast (adaptive_d2.hpp): on 3000 points the first round would count more than an eighth of
# them, so the exact counts are used and said so; with a small first round the rounds are reported.
f=$("$CHAOS" d2 "$work/henon.dat" -d 1 -M 4 --fast --json | jq -c '[.fast.exact, .fast.reference_points, (.fast.explanation | test("exact counts")), .parameters.fast, .parameters.halves_reference_points]')
[[ $f == '[true,"exact",true,true,0]' ]] && pass || fail "d2 --fast on 3000 Hénon points gave $f"
f=$("$CHAOS" d2 "$work/lorenz.dat" -d 17 -t 100 -M 5 --fast --fast-start 50 --json | jq -c '
  [(.fast.rounds | length > 0), (.fast.exact or (.fast.reference_points == 2 * .fast.rounds[-1].reference_points)),
   (.fast.exact or .fast.rounds[-1].stable or (.fast.settled | not) and .estimate.status != "confident"), (.fast.exact or (.d2_standard_error != null) or (.status != "saturated")),
   (.parameters.halves_reference_points == (if .fast.exact then 0 else .fast.reference_points / 2 end)),
   (.fast.exact or (.fast.halves and (if .first_half then .first_half.status == .fast.rounds[-1].status_a
                                       else .fast.rounds[-1].status_merged != "saturated" end)))]')
[[ $f == '[true,true,true,true,true,true]' ]] && pass || fail "d2 --fast --fast-start 50 on Lorenz gave $f (the rounds' subsets are the halves, half the budget each)"
# Without a budget the rounds draw from the whole record and each half is counted after them with
# the budget they chose (the form validated in docs/validation/fast-d2-zoo.md).
f=$("$CHAOS" d2 "$work/lorenz.dat" -d 17 -t 100 -M 5 --fast --fast-start 50 --fast-budget 0 --json | jq -c '
  [.fast.halves, (.fast.exact or (.parameters.halves_reference_points == .fast.reference_points))]')
[[ $f == '[false,true]' ]] && pass || fail "d2 --fast --fast-budget 0 on Lorenz gave $f (subsets of the whole record, the halves after)"
expect_error 3 "cannot be combined with --reference-points or -N \\(got --reference-points 100, -N 0\\)" -- d2 --fast --reference-points 100 "$work/henon.dat"
expect_error 3 "target agreement must be positive" -- d2 --fast --fast-target 0 "$work/lorenz.dat"
f=$("$CHAOS" d2 "$work/henon.dat" -d 1 -M 3 --fast --fast-start 4611686018427387904 --json | jq -c '[.fast.exact, (.fast.rounds | length)]')
[[ $f == '[true,0]' ]] && pass || fail "d2 --fast with a first round of 2^62 points gave $f (expected the exact counts at once)"
expect_error 3 "search must be" -- d2 --search fast "$work/henon.dat"
expect_error 3 "png or .svg" -- d2 "$work/henon.dat" -M 3 --plot "$work/plot.gif"

# --plot draws a file (PNG and SVG) with gnuplot.
for ext in png svg; do
  "$CHAOS" d2 "$work/henon.dat" -d 1 -M 4 --plot "$work/d2.$ext" > /dev/null
  [[ -s $work/d2.$ext ]] && pass || fail "d2 --plot $ext produced no file"
done
head -c 8 "$work/d2.png" | od -An -c | grep -q "P   N   G" && pass || fail "d2.png is not a PNG"

# chaos lyapunov: the JSON contract, per sample or per time unit, null for noise, refusals, plot.
"$CHAOS" generate white_noise -l 3000 > "$work/noise.dat" || fail "generate white_noise"
expect_json_keys lyapunov "$work/henon.dat" -- lambda lambda_interval per status divergence step local_slope terms
l=$("$CHAOS" lyapunov "$work/henon.dat" --json | jq -c '[.status, .per, (.lambda > 0.3 and .lambda < 0.5), (.divergence | length), .parameters.steps]')
# Default steps: 20 correlation times (Henon x: Theiler window 2 samples), so 40 steps and 41 curve values.
[[ $l == '["linear_region","sample",true,41,40]' ]] && pass || fail "lyapunov henon gave $l"
l=$("$CHAOS" lyapunov "$work/henon.dat" --method kantz --json | jq -c '[.status, .parameters.method, (.parameters.radius > 0)]')
[[ $l == '["linear_region","kantz",true]' ]] && pass || fail "lyapunov --method kantz gave $l"
# The other method checks the first (cross_check): on Henon both agree; --no-cross-check skips it.
l=$("$CHAOS" lyapunov "$work/henon.dat" --json | jq -c '[.cross_check.method, .cross_check.status, (.cross_check.lambda > 0.3 and .cross_check.lambda < 0.5), .parameters.cross_check]')
[[ $l == '["kantz","linear_region",true,true]' ]] && pass || fail "lyapunov cross-check on henon gave $l"
l=$("$CHAOS" lyapunov "$work/henon.dat" --method kantz --no-cross-check --json | jq -c '[.status, .cross_check, .local_maps, .parameters.cross_check]')
[[ $l == '["linear_region",null,null,false]' ]] && pass || fail "lyapunov --no-cross-check gave $l"
# Settings the curve of N samples cannot satisfy are refused with the rule and the numbers, as d2
# refuses its reference points, instead of being answered as a property of the data.
expect_error 3 "period must not exceed the curve's steps: period <= K = 500 \\(.*N = 5000\\) \\(got period = 100000\\)" -- lyapunov --period 100000 -q "$work/lorenz.dat"
expect_error 3 "min_steps <= K \\+ 1 with K = 50 \\(given \\(-s\\), N = 5000\\) \\(got min_steps = 1000\\)" -- lyapunov --min-steps 1000 -s 50 -q "$work/lorenz.dat"
expect_error 3 "2 half_width <= K with K = 50 .*\\(got half_width = 40\\)" -- lyapunov --half-width 40 -s 50 -q "$work/lorenz.dat"
expect_error 3 "reference_points must not exceed the [0-9]+ points .*P = N - \\(m-1\\)\\*tau - K = 5000 - .*\\(got reference_points = 6000\\)" -- lyapunov --reference-points 6000 -q "$work/lorenz.dat"
expect_error 3 "reference_points must not exceed the 2942 points .*P = N - \\(m-1\\)\\*tau - K = 3000 - 3\\*1 - 55 \\(got reference_points = 2943\\)" -- lyapunov -m 2 -d 1 -s 55 --reference-points 2943 -q "$work/henon.dat"
# A random walk with the automatic choices is refused as analyze stops on it (its correlation time
# grows with the record, and the curves followed N/10 steps with neighbourhoods of hundreds of
# points: minutes for no answer); with every choice given the estimator runs.
awk 'BEGIN { srand(7); s = 0; for (i = 0; i < 20000; i++) { s += rand() - 0.5; print s } }' > "$work/walk.dat"
expect_error 3 "automatic choices: .*fewer than 50 of its own correlation times.*give -d, -t, -m and -s" -- lyapunov -q "$work/walk.dat"
"$CHAOS" lyapunov -m 3 -d 1 -t 10 -s 20 -q "$work/walk.dat" > /dev/null && pass || fail "lyapunov with every choice given refused a random walk"
# The answers: one lambda_1 with an interval and a status, and the method's own estimate.
l=$("$CHAOS" lyapunov "$work/henon.dat" --json | jq -c '[.lambda_1.status, (.lambda_1.value > 0.38 and .lambda_1.value < 0.46), (.lambda_1.interval[0] <= .lambda_1.value and .lambda_1.value <= .lambda_1.interval[1]), .estimate.status]')
[[ $l == '["confident",true,true,"confident"]' ]] && pass || fail "lyapunov answers on henon gave $l"
# The third estimator, as in chaos analyze: on clean Hénon x (3000 iterations) the local maps are
# inconsistent at m = 2 and consistent at m + 1 = 3, within 10% of lambda_1 = 0.4195 per iteration (from
# the equations), and agree with the fit, so the value stands.
l=$("$CHAOS" lyapunov "$work/henon.dat" --json | jq -c '[.status, .local_maps.status, .local_maps.dimension, (.local_maps.lambda > 0.3776 and .local_maps.lambda < 0.4615)]')
[[ $l == '["linear_region","consistent",3,true]' ]] && pass || fail "lyapunov's local-map check on henon gave $l"
# With 1% measurement noise both divergence curves read low alike (docs/notes/zoo-noise.md): at m = 3 Rosenstein
# 0.362 and Kantz 0.382 agree within 10%, so their mutual check alone would pass and answer 0.362 with
# confidence (lambda_1 = 0.4195). The local maps find no deterministic structure at the
# neighbours' scale (not_deterministic), which leaves both unconfirmed; --no-cross-check gives the plain fit.
l=$("$CHAOS" lyapunov "$work/henon_noisy.dat" -m 3 --json | jq -c '[.status, .lambda, .local_maps.status, (.explanation | test("local"))]')
[[ $l == '["unconfirmed",null,"not_deterministic",true]' ]] && pass || fail "lyapunov on noisy Hénon gave $l"
l=$("$CHAOS" lyapunov "$work/henon_noisy.dat" -m 3 --no-cross-check --json | jq -c '[.status, .lambda < 0.4195 * 0.9]')
[[ $l == '["linear_region",true]' ]] && pass || fail "lyapunov --no-cross-check on noisy Hénon gave $l"
# --reference-points bounds every part (docs/reference/lyapunov.md, "Cost"): the local maps follow at most
# 10 maps per reference point, recorded as max_maps. On a drifting record with every choice given, a
# Kantz radius of the whole range puts every admissible point (all but the 2w + 1 of the window) in
# every neighbourhood, far above --max-neighbours 50, so every reference point used is capped; with
# --max-neighbours 0 none is.
l=$("$CHAOS" lyapunov "$work/henon.dat" --reference-points 30 --json | jq -c '[.parameters.max_maps, .parameters.max_neighbours, .capped_neighbourhoods]')
[[ $l == '[300,1000,0]' ]] && pass || fail "lyapunov --reference-points 30 gave $l"
awk -v seed=7 'BEGIN { srand(seed); x = 0; for (i = 0; i < 3000; ++i) { x += rand() - 0.5; print x } }' > "$work/walk.dat"
range=$(awk 'NR == 1 { lo = $1; hi = $1 } { if ($1 < lo) lo = $1; if ($1 > hi) hi = $1 } END { printf "%.17g", hi - lo }' "$work/walk.dat")
walk=(lyapunov "$work/walk.dat" --method kantz -m 2 -d 1 -t 5 -s 20 -r "$range" --reference-points 200 --no-cross-check --no-halves --json)
l=$("$CHAOS" "${walk[@]}" --max-neighbours 50 | jq -c '[.capped_neighbourhoods == .references_used, .references_used > 0, .parameters.max_neighbours]')
[[ $l == '[true,true,50]' ]] && pass || fail "lyapunov --max-neighbours 50 on a random walk gave $l"
l=$("$CHAOS" "${walk[@]}" --max-neighbours 0 | jq -c '[.capped_neighbourhoods, .mean_neighbours > 50]')
[[ $l == '[0,true]' ]] && pass || fail "lyapunov --max-neighbours 0 on a random walk gave $l"
"$CHAOS" lyapunov "$work/henon_noisy.dat" -m 3 | grep -q "^# local_maps = not_deterministic at m = 3" && pass || fail "lyapunov text output lacks the local_maps line"
"$CHAOS" lyapunov "$work/henon.dat" | grep -q "^# cross_check = kantz: linear_region" && pass || fail "lyapunov text output lacks the cross-check line"
l=$("$CHAOS" lyapunov "$work/henon.dat" --dt 0.5 --json | jq -c '[.per, (.lambda == .lambda_per_sample / 0.5)]')
[[ $l == '["time",true]' ]] && pass || fail "lyapunov --dt gave $l"
l=$("$CHAOS" lyapunov "$work/noise.dat" --json | jq -c '[.lambda, .lambda_interval, .status]')
[[ $l == '[null,null,"no_linear_region"]' ]] && pass || fail "lyapunov on white noise gave $l"
"$CHAOS" lyapunov "$work/noise.dat" | grep -q "^# lambda = none" && pass || fail "lyapunov text output for noise lacks 'lambda = none'"
# lyapunov --halves: Henon x (3000 iterations) diverges at one rate in each half, so both methods keep their values.
l=$("$CHAOS" lyapunov "$work/henon.dat" --halves --json | jq -c '[.status, .cross_check.status, .parameters.halves]')
[[ $l == '["linear_region","linear_region",true]' ]] && pass || fail "lyapunov --halves on henon gave $l"
# The zoo's Genesio-Tesi x, its first 10^4 samples, at m = 6, tau = 31, w = 63: a confident-wrong grid row of
# docs/validation/zoo.md before the halves rule (Rosenstein 0.0858 per time unit, Kantz agreeing within 10%, lambda_1 = 0.1019
# from the equations). Neither half of 5000 samples has a linear region, so with the halves check (the default)
# both are not_reproduced. Without the halves, the local maps at m = 6 and
# 7 are inconsistent, so they confirm neither slope, and only
# --no-cross-check gives the plain 0.0858.
"$CHAOS" zoo --series genesio_tesi -o "$work/genesio_tesi.dat" || fail "zoo --series genesio_tesi"
l=$("$CHAOS" lyapunov "$work/genesio_tesi.dat" -l 10000 --dt 0.05 -m 6 -d 31 -t 63 --no-halves -q --json | jq -c '[.status, .cross_check.status, .local_maps.status, .lambda]')
[[ $l == '["unconfirmed","unconfirmed","inconsistent",null]' ]] && pass || fail "lyapunov on the short Genesio-Tesi record gave $l"
l=$("$CHAOS" lyapunov "$work/genesio_tesi.dat" -l 10000 --dt 0.05 -m 6 -d 31 -t 63 --no-halves --no-cross-check -q --json | jq -c '[.status, .lambda < 0.1019 * 0.9]')
[[ $l == '["linear_region",true]' ]] && pass || fail "lyapunov --no-cross-check --no-halves on the short Genesio-Tesi record gave $l"
l=$("$CHAOS" lyapunov "$work/genesio_tesi.dat" -l 10000 --dt 0.05 -m 6 -d 31 -t 63 -q --json | jq -c '[.status, .cross_check.status, .lambda, .parameters.halves]')
[[ $l == '["not_reproduced","not_reproduced",null,true]' ]] && pass || fail "lyapunov (halves by default) on the short Genesio-Tesi record gave $l"
expect_error 3 "method must be rosenstein or kantz" -- lyapunov --method wolf "$work/henon.dat"
expect_error 3 "too short.*N = 5.*steps = 20" -- lyapunov "$work/five.dat"
expect_error 3 "eps must be positive.*-1" -- lyapunov --method kantz -r -1 "$work/henon.dat"
expect_error 3 "m = 0" -- lyapunov -m 0 "$work/henon.dat"
expect_error 3 "constant" -- lyapunov "$work/constant.dat"
# chaos lyapunov-maps: the JSON contract; a value only when every variant agrees (Henon at N = 2 10^4,
# lambda_1 = 0.4192, Sprott 2003), none for white noise (not_deterministic) or for 3000 Henon points,
# whose variants disagree; per time unit with --dt; refusals name the rule and the numbers.
"$CHAOS" generate henon -l 20000 --components x > "$work/henon20k.dat" || fail "generate henon 20000"
expect_json_keys lyapunov-maps "$work/henon20k.dat" -m 2 -- lambda lambda_interval per status explanation variants median_residual poor_fits
l=$("$CHAOS" lyapunov-maps "$work/henon20k.dat" -m 2 --json | jq -c '[.status, .per, (.lambda > 0.3983 and .lambda < 0.4402), (.variants | length), .variants[0].name, .parameters.step, .parameters.neighbours]')
[[ $l == '["consistent","sample",true,9,"base",1,10]' ]] && pass || fail "lyapunov-maps henon gave $l"
l=$("$CHAOS" lyapunov-maps "$work/henon20k.dat" -m 2 --dt 0.5 --json | jq -c '[.per, (.lambda == .lambda_per_sample / 0.5)]')
[[ $l == '["time",true]' ]] && pass || fail "lyapunov-maps --dt gave $l"
l=$("$CHAOS" lyapunov-maps "$work/henon.dat" -m 2 --json | jq -c '[.status, .lambda]')
[[ $l == '["inconsistent",null]' ]] && pass || fail "lyapunov-maps on 3000 henon points gave $l"
l=$("$CHAOS" lyapunov-maps "$work/noise.dat" -m 2 --json | jq -c '[.status, .lambda, .lambda_interval]')
[[ $l == '["not_deterministic",null,null]' ]] && pass || fail "lyapunov-maps on white noise gave $l"
"$CHAOS" lyapunov-maps "$work/noise.dat" | grep -q "^# lambda = none" && pass || fail "lyapunov-maps text output for noise lacks 'lambda = none'"
expect_error 3 "too short.*N = 5.*k = 10" -- lyapunov-maps "$work/five.dat"
expect_error 3 "needs at least m \+ 1 = 3 neighbours \(got k = 2\)" -- lyapunov-maps -k 2 "$work/henon.dat"
expect_error 3 "cutoff must lie in \(0, 1\) \(got 1\)" -- lyapunov-maps --cutoff 1 "$work/henon.dat"
expect_error 3 "constant" -- lyapunov-maps "$work/constant.dat"
expect_error 3 "m = 0" -- lyapunov-maps -m 0 "$work/henon.dat"
"$CHAOS" lyapunov "$work/henon.dat" --plot "$work/lyap.png" > /dev/null
head -c 8 "$work/lyap.png" | od -An -c | grep -q "P   N   G" && pass || fail "lyapunov --plot made no PNG"
expect_error 3 "png or .svg" -- lyapunov "$work/henon.dat" --plot "$work/lyap.pdf"

# chaos neighbors: every structure's answers equal brute force's (the definition, run by
# the command on the same points); the rows follow the structures and queries asked for.
l=$("$CHAOS" neighbors "$work/lorenz.dat" -m 3 -d 10 -t 50 -k 3 -r 2 --norm euclidean --json | jq -c '
  [.all_equal, (.rows | length), ([.rows[] | select(.structure != "brute_force") | .equal] | unique),
   ([.rows[] | .structure] | unique), ([.rows[] | select(.equal == "yes") | .checked == .points] | all),
   ([.rows[] | .query] | unique), .parameters.k, .parameters.radius]')
[[ $l == '[true,8,["yes"],["box_grid","brute_force","kd_tree","nanoflann"],true,["count","knn"],3,2]' ]] && pass ||
  fail "neighbors euclidean -k 3 -r 2 gave $l"
# Maximum norm (the default) and k = 1 (the default): nanoflann is skipped and says why.
l=$("$CHAOS" neighbors "$work/henon.dat" -m 2 -t 5 --json | jq -c '
  [.all_equal, .parameters.k, .parameters.norm, (.rows[] | select(.structure == "nanoflann") | [.ran, .equal, (.note | test("maximum norm"))])]')
[[ $l == '[true,1,"max",[false,"skipped",true]]' ]] && pass || fail "neighbors max norm gave $l"
# The table: the '#' header, then one row per structure.
t=$("$CHAOS" neighbors "$work/henon.dat" -m 2 -k 2)
[[ $(grep -c '^# chaos neighbors' <<<"$t") == 1 && $(grep -c '^# all_equal = yes' <<<"$t") == 1 && $(grep -vc '^#' <<<"$t") == 4 ]] &&
  pass || fail "neighbors table: $t"
# --sizes: the first N samples for each size; --check-points K: brute force at K points only.
l=$("$CHAOS" neighbors "$work/lorenz.dat" -d 10 -t 20 --sizes 4000,1000 --check-points 50 --json | jq -c '
  [.all_equal, ([.rows[] | .N] | unique), ([.rows[] | select(.structure == "brute_force") | .queries] | unique),
   ([.rows[] | select(.structure == "kd_tree") | .queries]), ([.rows[] | select(.equal == "yes") | .checked] | unique)]')
[[ $l == '[true,[1000,4000],[50],[980,3980],[50]]' ]] && pass || fail "neighbors --sizes --check-points gave $l"
l=$("$CHAOS" neighbors "$work/henon.dat" --no-brute --json | jq -c '[([.rows[] | .structure] | index("brute_force")), ([.rows[] | select(.ran) | .equal] | unique)]')
[[ $l == '[null,["unchecked"]]' ]] && pass || fail "neighbors --no-brute gave $l"
"$CHAOS" neighbors "$work/henon.dat" --sizes 1000,3000 --norm euclidean --plot "$work/neighbors.svg" > /dev/null
grep -q "<svg" "$work/neighbors.svg" && pass || fail "neighbors --plot made no SVG"
expect_error 3 "k = 0.*at least 1" -- neighbors -k 0 "$work/henon.dat"
expect_error 3 "radius r = 0.*positive and finite" -- neighbors -r 0 "$work/henon.dat"
expect_error 3 "radius r = -1.*positive and finite" -- neighbors -r -1 "$work/henon.dat"
expect_error 2 "nan" -- neighbors -r nan "$work/henon.dat"
expect_error 3 "too short: N = 5 samples give 3 embedded points \(m = 3, tau = 1\).*k \+ 2w \+ 1 = 4" -- neighbors -t 1 "$work/five.dat"
expect_error 3 "too short: N = 3000 .*w = 2000.*= 4002" -- neighbors -t 2000 "$work/henon.dat"
expect_error 3 "sizes 9000 asks for more samples than the series has \(N = 3000\)" -- neighbors --sizes 1000,9000 "$work/henon.dat"
expect_error 3 "check-points 0" -- neighbors --check-points 0 "$work/henon.dat"
expect_error 2 "excludes" -- neighbors --check-points 10 --no-brute "$work/henon.dat"
expect_error 3 "norm must be" -- neighbors --norm taxicab "$work/henon.dat"

# Mutual, autocorrelation, cao and fnn draw their curves with --plot (PNG and
# SVG, non-empty, the PNG a PNG); a wrong suffix is refused (exit 3) before any work, like d2's.
for cmd in mutual autocorrelation cao fnn; do
  for ext in png svg; do
    rm -f "$work/$cmd.$ext"
    "$CHAOS" "$cmd" "$work/lorenz.dat" --plot "$work/$cmd.$ext" > /dev/null
    [[ -s $work/$cmd.$ext ]] && pass || fail "$cmd --plot $ext produced no file"
  done
  head -c 8 "$work/$cmd.png" | od -An -c | grep -q "P   N   G" && pass || fail "$cmd --plot made no PNG"
  grep -q "<svg" "$work/$cmd.svg" && pass || fail "$cmd --plot made no SVG"
  expect_error 3 "^chaos: error \[invalid_parameter\]: .*png or .svg" -- "$cmd" "$work/no_such_file.dat" --plot "$work/$cmd.gif"
  [[ ! -e $work/$cmd.gif ]] && pass || fail "$cmd --plot with a wrong suffix wrote a file"
done
# With --dt the time axis is in time units, and the plot still comes out.
"$CHAOS" mutual "$work/lorenz.dat" --dt 0.01 -D 30 --plot "$work/mutual_dt.svg" > /dev/null
grep -q "delay tau (time units)" "$work/mutual_dt.svg" && pass || fail "mutual --dt --plot has no time axis"

# chaos spectrum SYSTEM: exponents and the Kaplan-Yorke dimension; refusals name the rule.
expect_json_keys spectrum henon --iterations 10000 -- exponents kaplan_yorke_dimension sum
l=$("$CHAOS" spectrum lorenz --time 100 --json | jq -c '[(.exponents | length), (.exponents[0] > 0.7 and .exponents[0] < 1.1), (.kaplan_yorke_dimension > 2 and .kaplan_yorke_dimension < 2.2)]')
[[ $l == '[3,true,true]' ]] && pass || fail "spectrum lorenz gave $l"
l=$("$CHAOS" spectrum henon -p b=0.2 --iterations 10000 --json | jq '.sum - (0.2 | log) | fabs < 1e-9')
[[ $l == true ]] && pass || fail "spectrum henon -p b=0.2: sum is not ln 0.2"
expect_error 3 "no spectrum for system 'sine'" -- spectrum sine
expect_error 3 "no model parameter 'rh'" -- spectrum lorenz -p rh=28
expect_error 3 "is a flow" -- spectrum lorenz --iterations 100
expect_error 3 "is a map" -- spectrum henon --time 100
expect_error 2 "" -- spectrum

# chaos surrogates: one column per surrogate; a seed fixes them; IAAFT keeps the values exactly.
grep -v '^#' "$work/henon.dat" | head -n 1000 > "$work/henon1000.dat"
cols=$("$CHAOS" surrogates "$work/henon1000.dat" -n 3 | grep -v '^#' | awk -F'\t' '{print NF}' | sort -u)
[[ $cols == 3 ]] && pass || fail "surrogates -n 3 wrote $cols columns"
rows=$("$CHAOS" surrogates "$work/henon1000.dat" -n 2 | grep -vc '^#')
[[ $rows == 1000 ]] && pass || fail "surrogates wrote $rows rows, expected 1000"
a=$("$CHAOS" surrogates "$work/henon1000.dat" -n 2 --seed 7 | md5sum)
b=$("$CHAOS" surrogates "$work/henon1000.dat" -n 2 --seed 7 | md5sum)
c=$("$CHAOS" surrogates "$work/henon1000.dat" -n 2 --seed 8 | md5sum)
[[ $a == "$b" && $a != "$c" ]] && pass || fail "surrogates: the same seed must repeat and another seed differ"
if cmp -s <("$CHAOS" surrogates "$work/henon1000.dat" | grep -v '^#' | sort -g) <(sort -g "$work/henon1000.dat"); then pass
else fail "IAAFT surrogate is not a permutation of the data"; fi
for method in ft aaft iaaft; do
  expect_json_keys surrogates "$work/henon1000.dat" --method $method -n 2 -- surrogates status iterations spectral_deviation
done
l=$("$CHAOS" surrogates "$work/henon1000.dat" --end-match --json | jq -c '[(.length < 1000), (.surrogates[0] | length) == .length]')
[[ $l == '[true,true]' ]] && pass || fail "surrogates --end-match gave $l"
expect_error 3 "method must be ft, aaft or iaaft" -- surrogates --method phase "$work/henon.dat"
expect_error 3 "count must be at least 1" -- surrogates -n 0 "$work/henon.dat"
expect_error 3 "constant" -- surrogates "$work/constant.dat"

# chaos nonlinearity: the JSON contract; Hénon is rejected, white noise is not.
expect_json_keys nonlinearity "$work/henon1000.dat" -n 19 -- statistic rank count ties rejected significance
l=$("$CHAOS" nonlinearity "$work/henon1000.dat" --json | jq -c '[.rejected, .rank, .count, .ties, .significance, .statistic_name]')
[[ $l == '[true,1,39,0,0.05,"prediction_error"]' ]] && pass || fail "nonlinearity on Hénon gave $l"
# 4,999 ones then one 2: every surrogate is a permutation of it, and its prediction error equals the
# data's up to rounding (13 digits), so all 19 tie with the data and the test cannot reject; compared
# exactly it answered rejected = true.
awk 'BEGIN { for (i = 0; i < 4999; i++) print 1; print 2 }' > "$work/spike.dat"
out=$("$CHAOS" nonlinearity "$work/spike.dat" -n 19 -q)
grep -q "^# ties = 19 " <<<"$out" && grep -q "^# rejected = false: the data's statistic ties with 19 of 19 surrogates: a tie cannot reject" <<<"$out" \
  && pass || fail "nonlinearity on the spike series: $(grep -E '^# (rank|ties|rejected)' <<<"$out")"
l=$("$CHAOS" nonlinearity "$work/noise.dat" -l 1024 --statistic time_reversal_asymmetry --method ft --json | jq -c '[.rejected, .parameters.statistic]')
[[ $l == '[false,"time_reversal_asymmetry"]' ]] && pass || fail "nonlinearity on white noise gave $l"
expect_error 3 "statistic must be prediction_error or time_reversal_asymmetry" -- nonlinearity --statistic skew "$work/henon.dat"
expect_error 3 "alternative must be" -- nonlinearity --alternative up "$work/henon.dat"
expect_error 3 "at least 1 surrogate" -- nonlinearity -n 0 "$work/henon.dat"
expect_error 3 "two-sided test needs at least 2 surrogates \\(got 1\\)" -- nonlinearity -n 1 "$work/henon.dat"
expect_error 3 "too short" -- nonlinearity -m 10 -d 10 "$work/five.dat"

# A null, not a guess, when there is no minimum: a monotone ramp has no MI minimum.
seq 1 500 > "$work/ramp.dat"
fm=$("$CHAOS" mutual "$work/ramp.dat" -D 5 --json | jq '.first_minimum')
[[ $fm == null ]] && pass || fail "ramp first_minimum = $fm, expected null"

# The header records every parameter, defaults included, and N.
header=$("$CHAOS" cao "$work/henon.dat" -M 4 | grep '^#')
for key in delay min_dimension max_dimension theiler norm N; do
  grep -q "# $key = " <<<"$header" && pass || fail "cao header lacks $key"
done

# chaos section: a cubic x(t) = (t - 1.3)(t - 2.6)(t - 4.1) with y = t^2, sampled every 0.1 by awk.
# The section's cubic through four rows reproduces a cubic exactly, so the crossings are the roots
# (analytic): up at 1.3 and 4.1, down at 2.6, with y = t^2 there and return times their differences.
awk 'BEGIN { for (i = 0; i <= 60; i++) { t = i * 0.1; printf "%.12g\t%.12g\t%.12g\n", t, (t - 1.3) * (t - 2.6) * (t - 4.1), t * t } }' > "$work/cubic.dat"
got=$("$CHAOS" section "$work/cubic.dat" --time-column 1 --hyperplane 2 --level 0 --direction both | grep -v '^#')
ok=$(awk -F'\t' 'BEGIN { split("1.3 2.6 4.1", r, " "); split("none 1.3 1.5", d, " "); bad = 0 }
  { n++; e = (($1 - r[n]) ^ 2 < 1e-18) && ($2 == 0) && (($3 - r[n] * r[n]) ^ 2 < 1e-18);
    if (n == 1) e = e && $4 == "none"; else e = e && (($4 - d[n]) ^ 2 < 1e-18);
    if (!e) bad = 1 }
  END { print (n == 3 && !bad) ? "yes" : "no" }' <<<"$got")
[[ $ok == yes ]] && pass || fail "section --hyperplane on the cubic gave: $got"
t=$("$CHAOS" section "$work/cubic.dat" --time-column 1 --hyperplane 2 --level 0 --direction down --json | jq -c '[(.time | length), (.time[0] - 2.6 | fabs < 1e-9), .return_time[0]]')
[[ $t == '[1,true,null]' ]] && pass || fail "section --direction down gave $t, expected the one root 2.6"
# Stroboscopic: every 20th row from row 5 (0-based) is awk's rows 6, 26, 46; the time is row x dt.
if cmp -s <("$CHAOS" section "$work/cubic.dat" -c 2,3 --stroboscopic 20 --phase 5 | grep -v '^#' | cut -f2-) \
          <(awk -F'\t' 'NR % 20 == 6 { printf "%s\t%s\n", $2, $3 }' "$work/cubic.dat"); then pass
else fail "section --stroboscopic 20 --phase 5 is not every 20th row from row 5"; fi
t=$("$CHAOS" section "$work/cubic.dat" -c 2 --stroboscopic 20 --phase 5 --dt 0.5 | grep -v '^#' | cut -f1 | paste -sd' ')
[[ $t == "2.5 12.5 22.5" ]] && pass || fail "section stroboscopic times with --dt 0.5: $t"
expect_json_keys section "$work/cubic.dat" --hyperplane 2 --level 0 -- time points return_time
expect_error 3 "period must be >= 1" -- section "$work/cubic.dat" --stroboscopic 0
expect_error 3 "phase \(3\) must be below the period \(3" -- section "$work/cubic.dat" --stroboscopic 3 --phase 3
expect_error 3 "choose one section" -- section "$work/cubic.dat"
expect_error 2 "" -- section "$work/cubic.dat" --stroboscopic 3 --hyperplane 2 --level 0
expect_error 3 "hyperplane column 2 is not among the columns" -- section "$work/cubic.dat" -c 1,3 --hyperplane 2 --level 0
expect_error 3 "needs --level" -- section "$work/cubic.dat" --hyperplane 2
expect_error 3 "direction must be up, down or both" -- section "$work/cubic.dat" --hyperplane 2 --level 0 --direction sideways
printf '0 1\n1 -1\n1 1\n2 -1\n' > "$work/stuck_time.dat"
expect_error 3 "times must increase" -- section "$work/stuck_time.dat" --time-column 1 --hyperplane 2 --level 0
expect_error 3 "word.dat:3: column 1: 'three' is not a number" -- section "$work/word.dat" --stroboscopic 2

# chaos density: rows (parameter, value) -> (parameter, bin centre, density). With 4 fixed bins on
# [0, 1] the density is count / (n x 0.25), counted here by awk from the same rows.
printf '1 0.1\n1 0.2\n1 0.3\n1 0.9\n2 0.55\n# a comment\n2 0.6\n2 0.05\n' > "$work/pv.dat"
expected=$(awk '!/^#/ && NF { n[$1]++; c[$1, int($2 / 0.25)]++ }
  END { for (p = 1; p <= 2; p++) for (b = 0; b < 4; b++) printf "%d %.6f %.6f\n", p, 0.125 + 0.25 * b, c[p, b] / (n[p] * 0.25) }' "$work/pv.dat")
got=$("$CHAOS" density "$work/pv.dat" --bins 4 --low 0 --high 1 | grep -v '^#' | awk 'NF { printf "%d %.6f %.6f\n", $1, $2, $3 }')
[[ $got == "$expected" ]] && pass || fail "density --bins 4 gave
$got
expected
$expected"
"$CHAOS" density "$work/pv.dat" | grep -q '^# bin_rule = freedman-diaconis' && pass || fail "density: the default rule is not named in the header"
"$CHAOS" density "$work/pv.dat" --bins 4 | grep -q '^# bin_rule = fixed: 4 bins' && pass || fail "density --bins: the rule is not named"
# The kernel estimate integrates to 1 per parameter value (sum of density x bin width).
s=$("$CHAOS" density "$work/pv.dat" --kde --bins 50 --json | jq -c '[(.edges[1] - .edges[0]) as $w | .density[] | (add * $w - 1 | fabs < 1e-9)]')
[[ $s == '[true,true]' ]] && pass || fail "density --kde does not integrate to 1: $s"
expect_json_keys density "$work/pv.dat" --kde -- parameter bin_centre edges density bandwidth kernel_mass
expect_error 3 "bins must be >= 1" -- density "$work/pv.dat" --bins 0
expect_error 3 "both --low and --high" -- density "$work/pv.dat" --low 0
expect_error 3 "range \[1, 0\] must be finite with low < high" -- density "$work/pv.dat" --low 1 --high 0
expect_error 3 "none of the 4 samples at parameter 1 lies in the range" -- density "$work/pv.dat" --low 5 --high 6
expect_error 3 "bandwidth .* must be finite and > 0" -- density "$work/pv.dat" --kde --bandwidth 0
expect_error 3 "add --kde" -- density "$work/pv.dat" --bandwidth 0.1
printf '1 0.1\n1 0.2\n2 nan\n' > "$work/pv_nan.dat"
expect_error 3 "pv_nan.dat:3: column 2: 'nan' is not finite" -- density "$work/pv_nan.dat"
"$CHAOS" density "$work/pv.dat" --plot "$work/density.png" > /dev/null
head -c 8 "$work/density.png" | od -An -c | grep -q "P   N   G" && pass || fail "density --plot made no PNG"
expect_error 3 "png or .svg" -- density "$work/pv.dat" --plot "$work/density.gif"

# chaos zoo --fast: the CI sample of the out-of-sample suite (4 systems, 5 controls, N = 10^4). It
# exits 4 if any estimate is confident and outside the band fixed in zoo_suite.hpp; the report says 0.
"$CHAOS" zoo --fast --threads 2 -q -o "$work/zoo.md" && pass || fail "chaos zoo --fast found a confident wrong estimate (exit $?)"
grep -q "Confident and wrong: \*\*0\*\*" "$work/zoo.md" && pass || fail "zoo.md does not report 0 confident-wrong"
grep -q "^| random_walk | random_walk |.*not_run" "$work/zoo.md" && pass || fail "zoo: the random walk was analysed"
expect_error 3 "no case matches --only" -- zoo --only no_such_case -q
expect_error 3 "grid-points must be 1 to 12, the points of the grid \(got 13\)" -- zoo --grid-points 13 --only lorenz -q
# zoo --checkpoint: the second run reads the case the first one appended instead of running it, and
# says so; a run with other options (the full suite) refuses the file (exit 3) and leaves it as it was.
"$CHAOS" zoo --fast --only random_walk --checkpoint "$work/zoo.ckpt" -o "$work/zoo1.md" 2>/dev/null \
  && pass || fail "zoo --checkpoint: the first run failed"
"$CHAOS" zoo --fast --only random_walk --checkpoint "$work/zoo.ckpt" -o "$work/zoo2.md" 2>"$work/zoo2.err" \
  && pass || fail "zoo --checkpoint: the resumed run failed"
grep -q "1 case(s) read from $work/zoo.ckpt" "$work/zoo2.err" && grep -q "the other 1 were read from a checkpoint" "$work/zoo2.md" \
  && pass || fail "zoo --checkpoint: the resumed run did not read the stored case"
[[ $(wc -l < "$work/zoo.ckpt") == 2 ]] && pass || fail "zoo --checkpoint: not one first line and one case"
cp "$work/zoo.ckpt" "$work/zoo.ckpt.before"
expect_error 3 "another build or with other options" -- zoo --only random_walk --checkpoint "$work/zoo.ckpt" -q
cmp -s "$work/zoo.ckpt" "$work/zoo.ckpt.before" && pass || fail "zoo --checkpoint: a refused file was changed"
expect_error 3 "threads must be at least 1" -- zoo --fast --threads 0 -q
# zoo --series writes a case's exact series: the sine at a period of 317/3 samples has exactly 317
# distinct values (control_signals.hpp: odd p, pure sine) in the full 10^5-sample record.
"$CHAOS" zoo --series periodic_rational -o "$work/rational.dat" && pass || fail "zoo --series periodic_rational"
[[ $(grep -vc '^#' "$work/rational.dat") == 100000 ]] && pass || fail "zoo --series: not 10^5 samples"
[[ $(grep -v '^#' "$work/rational.dat" | sort -u | wc -l) == 317 ]] && pass || fail "zoo --series: not 317 distinct values"
expect_error 3 "no case is named 'no_such_case'" -- zoo --series no_such_case
# zoo --series --json: the same series, every value (%.17g text and JSON both read back exactly),
# under the case's parameters; --json without --series is refused.
"$CHAOS" zoo --series periodic_rational --json -o "$work/rational.json" && pass || fail "zoo --series --json"
[[ $(jq -r '[.parameters.case, .parameters.N, (.x | length)] | @tsv' "$work/rational.json") == $'periodic_rational\t100000\t100000' ]] \
  && pass || fail "zoo --series --json: not the case's 10^5 samples"
cmp -s <(jq -r '.x[] | tostring' "$work/rational.json" | awk '{ printf "%.17g\n", $1 }') \
  <(grep -v '^#' "$work/rational.dat" | awk '{ printf "%.17g\n", $1 }') && pass || fail "zoo --series: --json and text differ"
expect_error 3 "--json writes a case's series: give --series NAME" -- zoo --fast --json -q

# analyze on a random walk: non-stationary, said with advice, nothing estimated, exit 0.
"$CHAOS" generate white_noise -l 5000 --seed 3 | awk '{ if ($1 !~ /^#/) { s += $1; print s } }' > "$work/walk.dat"
l=$("$CHAOS" analyze "$work/walk.dat" --json | jq -c '[.stationary, .d2_status, .lambda_status, (.stationarity_explanation | test("increments"))]')
[[ $l == '[false,"not_run","not_run",true]' ]] && pass || fail "analyze on a random walk gave $l"
# Analyze --plot draws the evidence in one figure (mutual information, Cao, false
# neighbours, D2 local slopes); a step that did not run is an empty panel that says so, not a failure.
"$CHAOS" analyze --builtin-length 20000 --surrogates 4 --plot "$work/analyze.png" > /dev/null
head -c 8 "$work/analyze.png" | od -An -c | grep -q "P   N   G" && pass || fail "analyze --plot made no PNG"
# The figure has a lambda_1 panel (the answer in its title, the two estimators' local slopes), and
# with --dt the mutual information against the delay in time units: it had neither. The built-in
# series' dt is 0.01 (docs/guide/getting-started.md), so the delay's time is shown too.
"$CHAOS" analyze --builtin-length 20000 --surrogates 4 -q --plot "$work/analyze.svg" > /dev/null
grep -q "lambda_1 = [0-9.]* per time unit" "$work/analyze.svg" && grep -q ">Rosenstein<" "$work/analyze.svg" && grep -q ">Kantz<" "$work/analyze.svg" \
  && pass || fail "analyze --plot: no lambda_1 panel with both estimators' local slopes"
grep -q "delay tau (time units)" "$work/analyze.svg" && grep -q "time units)" "$work/analyze.svg" \
  && pass || fail "analyze --plot with dt: the mutual information is not against time"
"$CHAOS" analyze "$work/walk.dat" --plot "$work/analyze_walk.svg" > /dev/null
grep -q "not run: " "$work/analyze_walk.svg" && pass || fail "analyze --plot on a random walk: no 'not run' panel"
expect_error 3 "^chaos: error \[invalid_parameter\]: .*png or .svg" -- analyze --plot "$work/analyze.jpg"
expect_error 3 "^chaos: error \[io\]: --plot .*/no_such_dir/p.png: the directory .*no_such_dir does not exist" -- \
  analyze --plot "$work/no_such_dir/p.png"

# On the logistic map analyze took delay 17, a noise-floor minimum of the mutual
# information, and called the series stochastic. A map decorrelates within one sample (its
# autocorrelation is below 1/e at lag 1), so the delay is 1 (chaos/automatic_analysis.hpp), and
# then the r = 4 map's known values come out: D2 = 1 (an absolutely continuous invariant density)
# and lambda = ln 2 = 0.693 per sample (Ott, Chaos in Dynamical Systems, 2002), within 15% and 10%.
"$CHAOS" generate logistic -l 10000 > "$work/logistic.dat"
l=$("$CHAOS" analyze "$work/logistic.dat" --json | jq -c '[.delay, (.delay_source | test("lag 1")), .stochastic, .d2_status, (.d2 > 0.85 and .d2 < 1.15), (.lambda > 0.62 and .lambda < 0.76)]')
[[ $l == '[1,true,false,"saturated",true,true]' ]] && pass || fail "analyze on the logistic map gave $l"
# The local-maps exponent in analyze: ln 2 for the logistic map at r = 4 (within the zoo's 10%); not run
# on a random walk, with the pipeline's reason.
# Consistent at Cao's m, so reported at that m (the pipeline tries m + 1 only after an inconsistent run).
l=$("$CHAOS" analyze "$work/logistic.dat" --json | jq -c '[.lambda_local_maps_status, (.lambda_local_maps > 0.6238 and .lambda_local_maps < 0.7625), .lambda_local_maps_dimension == .embedding_dimension]')
[[ $l == '["consistent",true,true]' ]] && pass || fail "analyze local maps on the logistic map gave $l"
# Henon x at N = 10^4: inconsistent at Cao's m = 2, consistent at m = 3 (measured), which analyze
# reports with both reasons; lambda_1 = 0.41922 (Sprott 2003, App. A) within the zoo's 10%.
"$CHAOS" generate henon -l 10000 --components x > "$work/henon10k.dat" || fail "generate henon 10000"
l=$("$CHAOS" analyze "$work/henon10k.dat" --json | jq -c '[.embedding_dimension, .lambda_local_maps_dimension, .lambda_local_maps_status, (.lambda_local_maps > 0.3773 and .lambda_local_maps < 0.4611), (.lambda_local_maps_explanation | test("^at m = 3: .*; at m = 2, inconsistent: "))]')
[[ $l == '[2,3,"consistent",true,true]' ]] && pass || fail "analyze local maps on Henon x 10^4 gave $l"
l=$("$CHAOS" analyze "$work/walk.dat" --json | jq -c '[.lambda_local_maps, .lambda_local_maps_status, .lambda_local_maps_dimension]')
[[ $l == '[null,"not_run",null]' ]] && pass || fail "analyze local maps on a random walk gave $l"
"$CHAOS" analyze "$work/logistic.dat" | grep -q "^largest_lyapunov_exponent_local_maps	0.6" && pass || fail "analyze text lacks the local-maps line"

# Negative whole numbers: CLI11 read "-1" into a count as 2^64-1 (segfaults in mutual and
# autocorrelation, "internal error: vector::..." in d2, surrogates and analyze, 6.7 GB in density).
# A value the option's type cannot hold is a usage error, exit 2 (docs/reference/input.md), naming the option.
expect_error 2 "^--max-delay: '-1' is negative" -- mutual -D -1 "$work/henon.dat"
expect_error 2 "^--max-lag: '-1' is negative" -- autocorrelation -D -1 "$work/henon.dat"
expect_error 2 "^--max-delay: '-2' is negative" -- mutual -D -2 "$work/henon.dat"
expect_error 2 "^--radii: '-1' is negative" -- d2 -# -1 "$work/henon.dat"
expect_error 2 "^--count: '-1' is negative" -- surrogates -n -1 "$work/henon.dat"
expect_error 2 "^--surrogates: '-1' is negative" -- analyze --surrogates -1 "$work/henon.dat"
expect_error 2 "^--bins: '-1' is negative" -- density -b -1 "$work/pv.dat"
expect_error 2 "^--max-delay: '99999999999999999999' is larger than 18446744073709551615" -- mutual -D 99999999999999999999 "$work/henon.dat"
expect_error 2 "^--level: 'nan' is not a finite number" -- cao --level nan "$work/henon.dat"
expect_error 2 "^--min-radius: 'inf' is not a finite number" -- d2 -r inf "$work/henon.dat"
# The largest whole number is a number, so each command bounds it before it allocates (exit 3).
expect_error 3 "N = 3000 samples, but at least 18446744073709551615.*max_lag = 18446744073709551615" -- autocorrelation -D 18446744073709551615 "$work/henon.dat"
expect_error 3 "N = 3000 samples, but at least 18446744073709551615.*max_delay = 18446744073709551615" -- mutual -D 18446744073709551615 "$work/henon.dat"
expect_error 3 "bins must be at most 100000 \(got 18446744073709551615\)" -- density -b 18446744073709551615 "$work/pv.dat"
expect_error 3 "number of radii must be at most 10000 \(got 9223372036854775808\)" -- d2 -# 9223372036854775808 "$work/henon.dat"
expect_error 3 "at most 10000 surrogates \(got 9223372036854775808\)" -- surrogates -n 9223372036854775808 "$work/henon.dat"
expect_error 3 "at most 10000 surrogates \(got 9223372036854775808\)" -- analyze --surrogates 9223372036854775808 "$work/henon.dat"
expect_error 3 "length -l must be in 1..100000000 \(got 9223372036854775808\)" -- generate henon -l 9223372036854775808
expect_error 3 "iterations \+ transient = 9223372036854775808 is more than 1e15" -- spectrum henon --iterations 9223372036854775808
expect_error 3 "highest of the 9223372036854775808 dimensions" -- lyapunov --dimensions 9223372036854775808 "$work/henon.dat"

# Extreme scales. A Lorenz series times 1e150 gave -nan autocorrelation rows, d2
# asked for "at least 9223372036854775814" samples, and times 1e306 d2 and lyapunov fell back to
# a wrong Theiler window and gave wrong numbers, all with exit 0; then such series were refused
# beyond 1e+-120. Every estimator now works on the series divided by a power of two where its
# magnitude needs it (series.hpp), so every estimate is independent of the scale: times a power
# of two (exact) the autocorrelation, the Theiler windows and lyapunov are identical, and times a
# power of ten (rounded) Cao's E1 and E2 and D2 agree to 1e-6 relative, out to 1e+-300. Only values
# beyond 2^1022 (max - min can overflow) or spanning less than 2^-1021 (subnormal doubles, bits
# lost) are refused, with exit 3 (docs/reference/input.md) and the numbers, never answered with NaN.
scaled() { awk -v f="$1" '!/^#/ { printf "%.17g\n", $1 * f }' "$work/lorenz.dat" > "$work/scaled.dat"; }
invariants() {
  {
    "$CHAOS" autocorrelation "$1" --json | jq -c '[.first_zero_crossing, .decorrelation_time, .autocorrelation]'
    "$CHAOS" d2 "$1" --json | jq -c '[.status, .parameters.theiler]'
    "$CHAOS" lyapunov "$1" --json | jq -c '[.status, .lambda, .points, .mean_neighbours, .parameters.theiler]'
  } 2>&1
}
d2_of() { "$CHAOS" d2 "$1" --no-halves --json | jq -r '"\(.d2) \(.takens_theiler)"'; }  # 5000 samples: the halves do not reproduce D2
cao_of() { "$CHAOS" cao "$1" --json | jq -r '(.["E1"] + .["E2"]) | map(tostring) | join(" ")'; }
close() { awk -v a="$1" -v b="$2" 'BEGIN { split(a, x, " "); split(b, y, " "); exit !((x[1] - y[1]) ^ 2 < 1e-18 && (x[2] - y[2]) ^ 2 < 1e-18) }'; }
# Every number of b within 1e-6 relative of a's, and as many of them.
relative() { awk -v a="$1" -v b="$2" 'BEGIN { n = split(a, x, " "); if (split(b, y, " ") != n || n == 0) exit 1
  for (i = 1; i <= n; i++) { d = x[i] - y[i]; if (d < 0) d = -d; s = x[i] < 0 ? -x[i] : x[i]; if (d > 1e-6 * s) exit 1 } }'; }
reference=$(invariants "$work/lorenz.dat")
ref_d2=$(d2_of "$work/lorenz.dat")
ref_cao=$(cao_of "$work/lorenz.dat")
[[ $ref_d2 == *null* ]] && fail "the reference d2 has no answer to compare: $ref_d2"
[[ -n $ref_cao && $ref_cao != *null* ]] || fail "the reference cao has no E1 and E2 to compare: $ref_cao"
for f in 2^-390 2^-200 2^-1 2^7 2^200 2^390 1e-100 1e100 1e-150 1e150 1e-300 1e300; do
  if [[ $f == 2^* ]]; then scaled "$(awk -v e="${f#2^}" 'BEGIN { printf "%.17g", 2 ^ e }')"; else scaled "$f"; fi
  if [[ $f == 2^* ]]; then
    [[ $(invariants "$work/scaled.dat") == "$reference" ]] && pass || fail "x $f changes the scale-free results"
  fi
  d2=$(d2_of "$work/scaled.dat")
  close "$d2" "$ref_d2" && pass || fail "x $f: d2 and Takens-Theiler $d2, expected $ref_d2"
  if [[ $f == 1e* ]]; then
    d2_value=$(d2_of "$work/scaled.dat" | cut -d' ' -f1)
    relative "${ref_d2%% *}" "$d2_value" && pass || fail "x $f: D2 $d2_value, expected ${ref_d2%% *} to 1e-6 relative"
    cao=$(cao_of "$work/scaled.dat")
    relative "$ref_cao" "$cao" && pass || fail "x $f: Cao's E1 and E2 differ from the unscaled series' beyond 1e-6: $cao"
  fi
done
for f in 5e306 -5e306 1e-310 4.9e-324; do
  scaled "$f"
  for cmd in autocorrelation d2 lyapunov; do
    expect_error 3 "\\[scale\\]: .*scaled.dat: the values (reach .* beyond the 4.49423e\\+307 \\(2\\^1022\\)|span only .* below the 4.45015e-308 \\(2\\^-1021\\))" -- "$cmd" "$work/scaled.dat"
  done
done

# A spreadsheet's CSV with a UTF-8 byte-order mark and a "time,value" header
# failed with "'time' is not a number". It is read (docs/reference/input.md), the column chosen by number or
# by name; a name not in the header is refused with the names; a huge bad token is cut.
{ printf '\xEF\xBB\xBFtime,value\n'; awk '!/^#/ { printf "%d,%s\n", NR, $1 }' "$work/henon.dat"; } > "$work/henon.csv"
by_number=$("$CHAOS" mutual "$work/henon.dat" | grep -v '^#')
[[ $("$CHAOS" mutual "$work/henon.csv" -c value | grep -v '^#') == "$by_number" ]] && pass || fail "mutual -c value on the CSV differs from the plain file"
[[ $("$CHAOS" mutual "$work/henon.csv" -c 2 | grep -v '^#') == "$by_number" ]] && pass || fail "mutual -c 2 on the CSV differs from the plain file"
expect_error 3 "henon.csv:1: no column named 'valeur' in the header \(time, value\)" -- mutual "$work/henon.csv" -c valeur
expect_error 2 "^--column: '-1' is neither a column number" -- mutual "$work/henon.csv" -c -1
{ echo 1; echo 2; head -c 1000000 /dev/zero | tr '\0' x; echo; } > "$work/huge_token.dat"
err=$("$CHAOS" mutual "$work/huge_token.dat" 2>&1)
[[ ${#err} -lt 300 && $err == *"... (1000000 bytes)' is not a number"* ]] && pass || fail "a 1 MB token is echoed: ${err:0:300}"

# Chaos d2 on 10^6 points ran for over 15 minutes with no word. Above 2e5 points
# (exact sums) it says so with the option that shortens it, and on a terminal it draws a progress
# line after 2 s (util-linux `script` gives it one); -q silences both. Each run is cut after 4 s.
# -M 3: m <= 2 alone takes under 2 s at this N (m = 2 is counted without
# enumerating pairs), too short for a progress line; m = 3 takes about 30 s.
"$CHAOS" generate lorenz -l 250000 --components x > "$work/long.dat"
err=$(timeout 4 "$CHAOS" d2 "$work/long.dat" -M 3 -o /dev/null 2>&1 >/dev/null)
[[ $err == *"N = 250000 samples"*"--reference-points"* ]] && pass || fail "d2 on 250000 points gave no hint: ${err:0:300}"
err=$(timeout 4 "$CHAOS" d2 "$work/long.dat" -M 3 -q -o /dev/null 2>&1 >/dev/null)
[[ -z $err ]] && pass || fail "d2 -q still writes to stderr: ${err:0:300}"
if command -v script >/dev/null; then
  tty_err=$(timeout 10 script -qec "timeout 4 '$CHAOS' d2 '$work/long.dat' -M 3 -o /dev/null" /dev/null | tr '\r' '\n')
  grep -q '^\[#* *\] correlation sums .* s left' <<<"$tty_err" && pass || fail "d2 drew no progress line on a terminal: ${tty_err:0:300}"
fi
# The other long commands (lyapunov, cao, fnn, surrogates, nonlinearity,
# analyze) share d2's progress line and hint (common.hpp: Progress); -q silences both. Each run is
# cut after 1 s (the hint comes before the work), two draw on a terminal for 3.5 s. There a larger
# -M: Cao's method over the default m = 1..10 takes under 2 s at this N (its searches run in the tree's
# leaf order), too short for a progress line; over m = 1..16 it takes longer than the run. analyze's
# Cao's method reads the first 10^5 samples (choose.hpp): over m = 1..16 1.8 s there, over m = 1..24 3.9 s.
for cmd in lyapunov cao fnn surrogates nonlinearity analyze; do
  err=$(timeout 1 "$CHAOS" "$cmd" "$work/long.dat" -o /dev/null 2>&1 >/dev/null)
  [[ $err == "chaos $cmd: N = 250000 samples: "*"(-q silences this)"* ]] && pass || fail "$cmd on 250000 points gave no hint: ${err:0:300}"
  [[ $cmd != lyapunov || $err == *"bounded by --reference-points"* ]] && pass || fail "lyapunov's hint does not name the bound: ${err:0:300}"
  err=$(timeout 1 "$CHAOS" "$cmd" "$work/long.dat" -q -o /dev/null 2>&1 >/dev/null)
  [[ -z $err ]] && pass || fail "$cmd -q still writes to stderr: ${err:0:300}"
done
if command -v script >/dev/null; then
  for run in "cao:16:Cao's method" "analyze:24:Cao's method"; do
    cmd=${run%%:*} rest=${run#*:}
    tty_err=$(timeout 10 script -qec "timeout 3.5 '$CHAOS' $cmd '$work/long.dat' -M ${rest%%:*} -o /dev/null" /dev/null | tr '\r' '\n')
    grep -q "^\[#* *\] ${rest#*:} .* s left" <<<"$tty_err" && pass || fail "$cmd drew no progress line on a terminal: ${tty_err:0:300}"
    tty_err=$(timeout 10 script -qec "timeout 3.5 '$CHAOS' $cmd '$work/long.dat' -M ${rest%%:*} -q -o /dev/null" /dev/null | tr '\r' '\n')
    [[ -z ${tty_err//$'\n'/} ]] && pass || fail "$cmd -q drew on a terminal: ${tty_err:0:300}"
  done
fi

# The README's order, options first and the file last, read the file as another
# value of a list option (d2 --radius-list a,b FILE, section -c 1 FILE). Each list option takes
# one argument per occurrence (comma-separated), so the file is the file.
a=$("$CHAOS" d2 --radius-list 0.05,0.1,0.2 "$work/henon.dat" -d 1 -M 3 --json | jq -c "[.parameters.min_radius, .parameters.max_radius, .parameters.radii]")
b=$("$CHAOS" d2 "$work/henon.dat" -d 1 -M 3 --radius-list 0.05,0.1,0.2 --json | jq -c "[.parameters.min_radius, .parameters.max_radius, .parameters.radii]")
[[ -n $a && $a == "$b" ]] && pass || fail "d2 --radius-list a,b FILE: '$a', expected '$b'"
"$CHAOS" generate lorenz -l 2000 --components all > "$work/xyz.dat"
a=$("$CHAOS" section -c 1,2 "$work/xyz.dat" --stroboscopic 10 | grep -vc '^#')
[[ $a == 200 ]] && pass || fail "section -c 1,2 FILE gave $a rows, expected 2000 / 10"

# "chaos foo" said only "A subcommand is required", and "chaos foo --help" printed
# the main help with exit 0; -o naming the input file overwrote the data; an unwritable -o failed
# only after the work. An unknown command is a usage error (2) naming it; a bad -o is refused
# before any work with exit 3 (docs/reference/input.md: invalid input), the data untouched.
expect_error 2 "^chaos: unknown command 'foo'; the commands are: generate, mutual" -- foo
expect_error 2 "^chaos: unknown command 'foo'" -- foo --help
cp "$work/henon.dat" "$work/data.dat"
expect_error 3 "-o .*data.dat is the input file" -- mutual "$work/data.dat" -o "$work/data.dat"
expect_error 3 "-o .*data.dat is the input file" -- mutual -o "$work/data.dat" "$work/data.dat"
cmp -s "$work/henon.dat" "$work/data.dat" && pass || fail "-o naming the input file changed the data"
expect_error 3 "-o .*/no_such_dir/out.tsv: the directory .*no_such_dir does not exist" -- d2 "$work/henon.dat" -o "$work/no_such_dir/out.tsv"
# An unwritable --plot failed only after the work. Every command with --plot
# (d2, lyapunov, density; since item 8 also mutual, autocorrelation, cao, fnn) refuses it with
# -o's rules while reading the command line: exit 3 and the message naming --plot and the path,
# before the series is read (a missing series file is not what the message names).
for cmd in d2 lyapunov mutual autocorrelation cao fnn; do
  expect_error 3 "^chaos: error \[io\]: --plot .*/no_such_dir/p.png: the directory .*no_such_dir does not exist" -- \
    "$cmd" "$work/henon.dat" --plot "$work/no_such_dir/p.png"
  expect_error 3 "^chaos: error \[io\]: --plot .*/no_such_dir/p.png" -- "$cmd" "$work/no_such_file.dat" --plot "$work/no_such_dir/p.png"
done
expect_error 3 "--plot .*/d2_dir.png is a directory" -- d2 "$work/henon.dat" --plot "$(mkdir -p "$work/d2_dir.png" && echo "$work/d2_dir.png")"
cp "$work/pv.dat" "$work/pv.svg"
expect_error 3 "--plot .*pv.svg is the input file" -- density "$work/pv.svg" --plot "$work/pv.svg"
cmp -s "$work/pv.dat" "$work/pv.svg" && pass || fail "density --plot naming the input file changed the data"

# Every command has --help.
for cmd in generate mutual autocorrelation cao fnn d2 analyze lyapunov spectrum surrogates nonlinearity section density validate zoo; do
  "$CHAOS" "$cmd" --help >/dev/null && pass || fail "chaos $cmd --help"
done

# A typo in --filter ran nothing and exited 0; it is refused (exit 3) by name.
expect_error 3 "--filter 'henon.x.caoo' matches no case id" -- validate --filter henon.x.caoo

# validate lists the compiled-in reference table.
"$CHAOS" validate --list | grep -q "henon.x.cao.embedding_dimension" && pass || fail "validate --list"

# -q is accepted by every command, so a script can pass it to all alike (commands with nothing to
# silence say so in their help).
for c in generate mutual autocorrelation cao fnn d2 analyze lyapunov lyapunov-maps neighbors spectrum surrogates \
         nonlinearity section density validate zoo; do
  "$CHAOS" "$c" --help 2>&1 | grep -q -- "-q,--quiet" && pass || fail "chaos $c does not accept -q"
done

echo "$passed passed, $failed failed"
[[ $failed -eq 0 ]]
