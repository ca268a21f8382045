#!/usr/bin/env bash
# Write failures (support/safe_output.hpp): every command family (chaos, mechanism, study) writing to
# a full file system and to /dev/full, through standard output, -o and --plot. Each run must exit
# non-zero (chaos and mechanism 3, study 4) with a message naming the path and the system's reason,
# and leave no file under the target's name (an existing file keeps its contents) and no temporary
# file beside it. An unwritable -o is refused before the work, with the system's reason.
#
# The full file system is a 64 KiB tmpfs filled up to FREE_KB where this process may mount one (as
# root with CAP_SYS_ADMIN); elsewhere each command runs under `ulimit -f FREE_KB` with SIGXFSZ
# ignored, so that a write past the limit fails with EFBIG ("File too large") instead: the same
# failure from the command's side (a short write, then an error). The test says which it used.
set -u
: "${CHAOS:?set CHAOS to the chaos executable}"
: "${MECHANISM:?set MECHANISM to the mechanism executable}"
: "${STUDY:?set STUDY to the study executable}"
free_kb=8
work=$(mktemp -d)
full=$work/full
mkdir -p "$full"
mounted=0
cleanup() {
  [[ $mounted == 1 ]] && umount "$full" 2> /dev/null
  rm -rf "$work"
}
trap cleanup EXIT
passed=0
failed=0
pass() { passed=$((passed + 1)); }
fail() { failed=$((failed + 1)); echo "FAIL: $*" >&2; }
export LC_ALL=C
trap '' XFSZ  # inherited: a write past ulimit -f fails with EFBIG instead of killing the command

if mount -t tmpfs -o size=64k tmpfs "$full" 2> /dev/null; then
  mounted=1
  # All but FREE_KB of it taken, so that any output larger than that is cut mid-write.
  dd if=/dev/zero of="$full/filler" bs=1k count=$((64 - free_kb)) status=none 2> /dev/null
  limit=()
  reason="No space left on device"
  echo "full file system: a 64 KiB tmpfs with ${free_kb} KiB free"
else
  limit=(ulimit -f "$free_kb")
  reason="File too large"
  echo "full file system: no tmpfs could be mounted here; ulimit -f ${free_kb} (KiB) with SIGXFSZ ignored"
fi

# run CODE TARGET -- TOOL ARGS...: TOOL (chaos, mechanism or study), its standard output sent to
# $OUT (default a file of the work directory), exits CODE and says on stderr the TARGET and a
# system reason (REASON: the extended regex to find, default either full-disk reason). Leaves
# stderr in $work/err.
run() {
  local code=$1 target=$2 tool=$4 exe rc
  shift 4
  case $tool in chaos) exe=$CHAOS ;; mechanism) exe=$MECHANISM ;; study) exe=$STUDY ;; esac
  if [[ ${#limit[@]} -gt 0 && $target == "$full"/* ]]; then
    ("${limit[@]}" && exec "$exe" "$@") > "${OUT:-$work/out}" 2> "$work/err"
  else
    "$exe" "$@" > "${OUT:-$work/out}" 2> "$work/err"
  fi
  rc=$?
  local what="$tool $*"
  if [[ $rc -ne $code ]]; then fail "$what exited $rc, expected $code: $(head -c 300 "$work/err")"; return 1; fi
  if ! grep -qF -- "$target" "$work/err"; then fail "$what: message does not name $target: $(head -c 300 "$work/err")"; return 1; fi
  if ! grep -Eq -- "${REASON:-No space left on device|File too large}" "$work/err"; then
    fail "$what: message gives no system reason: $(head -c 300 "$work/err")"
    return 1
  fi
  pass
}

# no_file PATH: nothing under PATH's name and no temporary beside it.
no_file() {
  if [[ -e $1 ]]; then fail "$1 was left behind ($(stat -c %s "$1") bytes)"; return; fi
  if ls -A "$(dirname "$1")" | grep -q '\.tmp\.'; then fail "a temporary file was left beside $1: $(ls -A "$(dirname "$1")")"; return; fi
  pass
}

"$CHAOS" generate lorenz -l 3000 --components x > "$work/x.dat" || fail "generate lorenz"
ln -s /dev/full "$work/devfull.svg"  # --plot wants a .svg or .png name
ln -s /dev/full "$work/devfull.png"

# ---- chaos ---------------------------------------------------------------------------------------
OUT=/dev/full run 3 "standard output" -- chaos generate lorenz -l 100
# The table is written to standard output, the error said on standard error.
"$CHAOS" mutual "$work/x.dat" > /dev/full 2> "$work/err"
rc=$?
[[ $rc -eq 3 ]] && grep -q "standard output: writing failed (No space left on device)" "$work/err" && pass ||
  fail "chaos mutual > /dev/full exited $rc: $(cat "$work/err")"
REASON="No space left on device" run 3 /dev/full -- chaos generate lorenz -l 100 -o /dev/full
REASON="No space left on device" run 3 /dev/full -- chaos cao "$work/x.dat" -M 4 --json -o /dev/full
run 3 "$full/g.dat" -- chaos generate lorenz -l 20000 -o "$full/g.dat" && no_file "$full/g.dat"
run 3 "$full/s.dat" -- chaos surrogates "$work/x.dat" -o "$full/s.dat" && no_file "$full/s.dat"
run 3 "$full/g.json" -- chaos generate lorenz -l 20000 --json -o "$full/g.json" && no_file "$full/g.json"
# An existing file keeps its contents.
echo "the previous result" > "$full/keep.dat"
run 3 "$full/keep.dat" -- chaos generate lorenz -l 20000 -o "$full/keep.dat"
[[ $(cat "$full/keep.dat") == "the previous result" ]] && pass || fail "a failed -o changed the existing file"
rm -f "$full/keep.dat"
run 3 "$full/p.png" -- chaos mutual "$work/x.dat" --plot "$full/p.png" -o "$work/m.dat" && no_file "$full/p.png"
REASON="No space left on device" run 3 "$work/devfull.svg" -- chaos autocorrelation "$work/x.dat" --plot "$work/devfull.svg"
# A failed plot leaves the -o target untouched too: nothing is renamed into place after an error.
[[ ! -e $work/m.dat ]] && pass || fail "chaos mutual wrote -o although its --plot failed"

# ---- mechanism -----------------------------------------------------------------------------------
short=(--set run.duration=0.02 -q)
OUT=/dev/full run 3 "standard output" -- mechanism simulate "${short[@]}"
OUT=/dev/full run 3 "standard output" -- mechanism scene
REASON="No space left on device" run 3 /dev/full -- mechanism simulate "${short[@]}" -o /dev/full
run 3 "$full/sim.tsv" -- mechanism simulate "${short[@]}" -o "$full/sim.tsv" && no_file "$full/sim.tsv"
run 3 "$full/traj.png" -- mechanism simulate "${short[@]}" --plot "$full/traj.png" -o /dev/null && no_file "$full/traj.png"
! grep -q "invalid scene" "$work/err" && pass || fail "mechanism calls a write failure an invalid scene: $(cat "$work/err")"

# ---- study ---------------------------------------------------------------------------------------
fast=(--set 'joint.slider.friction.sigma1_velocity=1e-3' --set 'integrator.method="dopri5"' --set integrator.relative_tolerance=1e-5)
"$STUDY" sweep "${fast[@]}" --axis joint.slider.clearance=2e-4,5e-4 --periods 8 --keep 5 -o "$work/sweep" -q > /dev/null ||
  fail "study sweep"
OUT=/dev/full run 4 "standard output" -- study sweep "${fast[@]}" --axis joint.slider.clearance=2e-4,5e-4 \
  --periods 8 --keep 5 -o "$work/sweep" --resume -q
run 4 "$full/b.png" -- study plot "$work/sweep" --figure bifurcation -o "$full/b.png" && no_file "$full/b.png"
REASON="No space left on device" run 4 "$work/devfull.png" -- study plot "$work/sweep" --figure portrait -o "$work/devfull.png"
OUT=/dev/full run 4 "standard output" -- study pipeline "${fast[@]}" --periods 6 --analysis-periods 3
run 4 "$full/series.tsv" -- study pipeline "${fast[@]}" --periods 6 --analysis-periods 3 --series "$full/series.tsv" &&
  no_file "$full/series.tsv"
# The sweep's own files (point files, tables), each smaller than the limit a ulimit sets per file:
# into the full tmpfs it stops with the path and the reason, and leaves no temporary file behind.
if [[ $mounted == 1 ]]; then
  run 4 "$full/sw" -- study sweep "${fast[@]}" --axis joint.slider.clearance=2e-4:5e-4:12 --periods 8 --keep 5 -o "$full/sw" -q
  if [[ -d $full/sw ]] && find "$full/sw" -name '*.tmp.*' | grep -q .; then fail "study sweep left a temporary file"; else pass; fi
  rm -rf "$full/sw"
fi

# ---- refused before the work ---------------------------------------------------------------------
# /proc takes no new files, whoever runs the command (root included): refused while the command
# line is read, with the system's reason, before a computation that would take minutes.
"$CHAOS" generate lorenz -l 400000 --components x > "$work/long.dat" || fail "generate a long series"
check_early() {
  local code=$1 target=$2 tool=$3 exe start rc elapsed
  shift 3
  case $tool in chaos) exe=$CHAOS ;; mechanism) exe=$MECHANISM ;; study) exe=$STUDY ;; esac
  start=$(date +%s%N)
  timeout 60 "$exe" "$@" > /dev/null 2> "$work/err"
  rc=$?
  elapsed=$((($(date +%s%N) - start) / 1000000))
  if [[ $rc -ne $code ]]; then fail "$tool $* exited $rc, expected $code: $(cat "$work/err")"; return; fi
  if ! grep -qF -- "$target" "$work/err" || ! grep -Eq '\((No such file or directory|Permission denied|Read-only file system)\)' "$work/err"; then
    fail "$tool $*: the refusal names neither $target nor the reason: $(cat "$work/err")"
    return
  fi
  if ((elapsed > 2000)); then fail "$tool $*: refused after $elapsed ms, not before the work"; return; fi
  pass
}
check_early 3 /proc/x chaos d2 "$work/long.dat" -o /proc/x
check_early 3 /proc/x.svg chaos lyapunov "$work/long.dat" --plot /proc/x.svg
check_early 3 /proc/x chaos generate lorenz -l 10000000 -o /proc/x
check_early 3 /proc/x mechanism simulate --set run.duration=1000 -o /proc/x
! grep -q "invalid scene" "$work/err" && pass || fail "mechanism calls an unwritable -o an invalid scene: $(cat "$work/err")"
check_early 4 /proc/x.png study plot "$work/sweep" --figure bifurcation -o /proc/x.png
check_early 4 /proc/x.tsv study pipeline --periods 1000000 --series /proc/x.tsv

echo "write failures: $passed passed, $failed failed"
[[ $failed -eq 0 ]]
