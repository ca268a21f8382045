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
expect_json_keys analyze "$work/henon.dat" -d 1 -M 5 -- delay theiler embedding_dimension fnn_embedding_dimension

expect_json_keys d2 "$work/henon.dat" -d 1 -M 4 -- dimension radius correlation_sum local_slope d2_by_dimension d2 d2_interval scaling_region saturated
r=$("$CHAOS" d2 "$work/henon.dat" -d 1 -M 2 --radius-list 0.01,0.02,0.05,0.1 --json | jq -c '.radius')
[[ $r == "[0.01,0.02,0.05,0.1]" ]] && pass || fail "--radius-list gave radius $r"
expect_error 3 "increasing" -- d2 "$work/henon.dat" -M 2 --radius-list 0.1,0.05
expect_error 3 "search must be" -- d2 --search fast "$work/henon.dat"
expect_error 3 "png or .svg" -- d2 "$work/henon.dat" -M 3 --plot "$work/plot.gif"

# --plot draws a file (PNG and SVG) with gnuplot.
for ext in png svg; do
  "$CHAOS" d2 "$work/henon.dat" -d 1 -M 4 --plot "$work/d2.$ext" > /dev/null
  [[ -s $work/d2.$ext ]] && pass || fail "d2 --plot $ext produced no file"
done
head -c 8 "$work/d2.png" | od -An -c | grep -q "P   N   G" && pass || fail "d2.png is not a PNG"

# A null, not a guess, when there is no minimum: a monotone ramp has no MI minimum.
seq 1 500 > "$work/ramp.dat"
fm=$("$CHAOS" mutual "$work/ramp.dat" -D 5 --json | jq '.first_minimum')
[[ $fm == null ]] && pass || fail "ramp first_minimum = $fm, expected null"

# The header records every parameter, defaults included, and N.
header=$("$CHAOS" cao "$work/henon.dat" -M 4 | grep '^#')
for key in delay min_dimension max_dimension theiler norm N; do
  grep -q "# $key = " <<<"$header" && pass || fail "cao header lacks $key"
done

# Every command has --help.
for cmd in generate mutual autocorrelation cao fnn d2 analyze validate; do
  "$CHAOS" "$cmd" --help >/dev/null && pass || fail "chaos $cmd --help"
done

# validate lists the compiled-in reference table.
"$CHAOS" validate --list | grep -q "henon.x.cao.embedding_dimension" && pass || fail "validate --list"

echo "$passed passed, $failed failed"
[[ $failed -eq 0 ]]
