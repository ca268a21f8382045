#!/usr/bin/env bash
# Hostile values for every numeric option of every `chaos` command: -1, 0, huge (2^63,
# 1e300), nan and inf. Each run must end within its time limit with an exit code below 128 that
# is not 1 (README.md: 1 is an internal error, a bug; >= 128 is a signal, a crash), a message on
# stderr when it refuses, and no NaN in what it writes. The options are read from each command's
# --help (CLI11 prints UINT, INT or FLOAT after a numeric option), so a new option is covered too.
# `chaos zoo` and `chaos validate` run whole catalogues and are left out.
# Usage: run_hostile_options.sh [SHARD COUNT]: only the (command, option) pairs whose place in the
# sorted list, modulo COUNT, is SHARD (CTest runs the shards side by side); all without arguments.
# HOSTILE_SAMPLE=S (default 1, all): each pair runs only the values whose place in its list plus
# the pair's place is a multiple of S, so every pair still runs at least one value and every value
# runs on about one pair in S (the sanitizer build samples: tests/CMakeLists.txt).
set -u
shard=${1:-0}
count=${2:-1}
sample=${HOSTILE_SAMPLE:-1}
if ! [[ $shard =~ ^[0-9]+$ && $count =~ ^[1-9][0-9]*$ && $shard -lt $count && $sample =~ ^[1-9][0-9]*$ ]]; then
  echo "usage: $0 [SHARD COUNT] with 0 <= SHARD < COUNT and HOSTILE_SAMPLE >= 1 (got '$shard' '$count' '$sample')" >&2
  exit 2
fi
: "${CHAOS:?set CHAOS to the chaos executable}"
# The time one run may take before it counts as a hang: 20 s, longer where the build runs slower
# (tests/CMakeLists.txt sets HANG_LIMIT for the sanitizer and debug builds).
hang_limit=${HANG_LIMIT:-20}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
passed=0
failed=0
fail() { failed=$((failed + 1)); echo "FAIL: $*" >&2; }

"$CHAOS" generate lorenz -l 1500 --components x > "$work/x.dat" || fail "generate lorenz x"
"$CHAOS" generate lorenz -l 1500 --components all > "$work/xyz.dat" || fail "generate lorenz xyz"
# density reads (parameter, value) rows: three parameter values of 200 values each.
for p in 1 2 3; do awk -v p="$p" 'NR <= 200 { print p, $1 }' "$work/x.dat"; done > "$work/pv.dat"

# try CMD ARGS...: one run, checked as above.
try() {
  local out="$work/out" err="$work/err" rc
  timeout "$hang_limit" "$CHAOS" "$@" > "$out" 2> "$err"
  rc=$?
  if [[ $rc -eq 124 ]]; then fail "chaos $* ran past ${hang_limit} s"; return; fi
  if [[ $rc -ge 128 ]]; then fail "chaos $* crashed (exit $rc)"; return; fi
  if [[ $rc -eq 1 ]]; then fail "chaos $* exited 1 (internal error): $(head -c 300 "$err")"; return; fi
  if [[ $rc -ne 0 && ! -s $err ]]; then fail "chaos $* exited $rc without a message"; return; fi
  if grep -Eqiw -- '-?nan' "$out"; then fail "chaos $* printed NaN"; return; fi
  passed=$((passed + 1))
}

# Numeric options of a command: "short,long TYPE" per line (short may be empty), from its --help.
numeric_options() {
  "$CHAOS" "$1" --help | sed -nE 's/^ +(-[^ ,]+)?,?(--?[^ ]+) +(UINT|INT|FLOAT)\b.*/\1,\2 \3/p'
}

# without NAMES -- ARGS...: ARGS less any "option value" pair whose option is one of NAMES
# (comma-separated), so the hostile value is the only one given.
without() {
  local names=",$1,"
  shift 2
  local kept=()
  while [[ $# -gt 0 ]]; do
    if [[ $1 == -* && $names == *",$1,"* ]]; then shift 2; continue; fi
    kept+=("$1")
    shift
  done
  echo "${kept[@]}"
}

declare -A base=(
  [mutual]="$work/x.dat" [autocorrelation]="$work/x.dat" [cao]="$work/x.dat -M 4" [fnn]="$work/x.dat -M 4"
  [d2]="$work/x.dat -M 3 --reference-points 300" [analyze]="$work/x.dat --surrogates 3 -M 4"
  [lyapunov]="$work/x.dat -m 3 --reference-points 200" [lyapunov-maps]="$work/x.dat -m 3 -d 5" [surrogates]="$work/x.dat -n 2"
  [nonlinearity]="$work/x.dat -n 3" [density]="$work/pv.dat -v 2" [section]="$work/xyz.dat --hyperplane 1"
  [neighbors]="$work/x.dat -r 1 -k 2 --check-points 100 --norm euclidean"
  [generate]="henon -l 100" [spectrum]="henon --iterations 2000"
)
mapfile -t commands < <(printf '%s\n' "${!base[@]}" | sort)
k=0  # (command, option) pairs are dealt to the shards in turn, which balances them within a few runs
for command in "${commands[@]}"; do
  options=$(numeric_options "$command")
  [[ -n $options ]] || fail "chaos $command --help lists no numeric option"
  while read -r names type; do
    pair=$k
    (( k++ % count == shard )) || continue
    option=${names##*,}
    # shellcheck disable=SC2086  # the base arguments are words
    args=$(without "$names" -- ${base[$command]})
    values=(-1 0 1e300 nan inf)
    [[ $type == FLOAT ]] || values+=(9223372036854775808 18446744073709551615)
    for j in "${!values[@]}"; do
      (( (pair + j) % sample == 0 )) || continue
      # shellcheck disable=SC2086
      try "$command" $args "$option" "${values[j]}"
    done
  done <<<"$options"
done

echo "hostile options (shard $shard of $count, one value in $sample): $passed passed, $failed failed"
[[ $failed -eq 0 ]]
