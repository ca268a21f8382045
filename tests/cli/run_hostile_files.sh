#!/usr/bin/env bash
# Corrupt files: series files to every `chaos` command that reads one, scene files to
# `mechanism simulate` and `scene`, `study sweep` and `study pipeline`, and result files (a point file,
# spec.txt and the lock of a `study sweep` directory, then --resume; the assembled tables, then
# `study plot`). Each run must end within its time limit with an exit code below 128 that is not 1
# (README.md and docs/reference/study.md: 1 is an internal error, >= 128 a crash), a message on stderr that
# names the file (and the line or the key where there is one) when it refuses, and no NaN or
# infinity in what it writes. A line-end or byte-order-mark variant of a good file must give the
# good file's output. The cases come from a fixed seed (HOSTILE_SEED, default 16); the scene
# mutations are a sample of HOSTILE_SCENES (default 120) drawn from every key and hostile value.
# HOSTILE_SAMPLE=S (default 1, all): each command reads only the corrupt variants whose place in the
# list plus the command's place is a multiple of S, so every variant is read by about one command
# in S (the sanitizer build samples: tests/CMakeLists.txt).
set -u
: "${CHAOS:?set CHAOS to the chaos executable}"
: "${MECHANISM:?set MECHANISM to the mechanism executable}"
: "${STUDY:?set STUDY to the study executable}"
seed=${HOSTILE_SEED:-16}
scenes=${HOSTILE_SCENES:-120}
sample=${HOSTILE_SAMPLE:-1}
# The time one run may take before it counts as a hang: 20 s, longer where the build runs slower
# (tests/CMakeLists.txt sets HANG_LIMIT for the sanitizer and debug builds).
hang_limit=${HANG_LIMIT:-20}
# rnd N: R = a number in [0, N) from a generator of its own (bash reseeds $RANDOM in every
# subshell, so it is not reproducible; no function that draws runs in one).
state=$seed
rnd() {
  state=$(((state * 1103515245 + 12345) % 2147483648))
  R=$(((state / 256) % $1))
}
work=$(mktemp -d)
trap 'chmod -R u+rwx "$work"; rm -rf "$work"' EXIT
passed=0
failed=0
fail() { failed=$((failed + 1)); echo "FAIL: $*" >&2; }
export LC_ALL=C

# check TOOL ALLOWED NAMES -- ARGS...: one run of TOOL (chaos, mechanism, study) with a HANG_LIMIT s guard;
# its exit code must be one of ALLOWED (e.g. "0 3"), a refusal (exit 3) must say on stderr the
# extended regex NAMES ("" names nothing; any other non-zero exit needs a message only: mechanism's
# 5 is a run that could not continue, not a refusal of the file), and stdout must hold no NaN or
# infinity. Leaves the output in $work/out and $work/err.
check() {
  local tool=$1 allowed=" $2 " names=$3 rc
  shift 4
  local exe
  case $tool in chaos) exe=$CHAOS ;; mechanism) exe=$MECHANISM ;; study) exe=$STUDY ;; esac
  timeout "$hang_limit" "$exe" "$@" > "$work/out" 2> "$work/err"
  rc=$?
  local what="$tool $*"
  what=${what:0:240}
  if [[ $rc -eq 124 ]]; then fail "$what ran past ${hang_limit} s"; return 1; fi
  if [[ $rc -ge 128 ]]; then fail "$what crashed (exit $rc)"; return 1; fi
  if [[ $rc -eq 1 ]]; then fail "$what exited 1 (internal error): $(head -c 300 "$work/err")"; return 1; fi
  if [[ $allowed != *" $rc "* ]]; then fail "$what exited $rc, expected one of$allowed: $(head -c 300 "$work/err")"; return 1; fi
  if grep -Eqiw -- '-?(nan|inf|infinity)' "$work/out"; then fail "$what printed NaN or infinity"; return 1; fi
  if [[ $rc -ne 0 && ! -s $work/err ]]; then fail "$what exited $rc without a message"; return 1; fi
  if [[ $rc -eq 3 && -n $names ]] && ! grep -Eq -- "$names" "$work/err"; then
    fail "$what: message does not name /$names/: $(head -c 300 "$work/err")"
    return 1
  fi
  passed=$((passed + 1))
  return 0
}

# Random bytes, from the seed: garbage FILE BYTES.
garbage() { rnd 1000000; awk -v s="$R" -v n="$2" 'BEGIN { srand(s); for (i = 0; i < n; i++) printf "%c", 1 + int(rand() * 255) }' > "$1"; }
# set_line SRC DST LINE TEXT: SRC with line LINE replaced by TEXT.
set_line() { awk -v k="$3" -v t="$4" 'NR == k { print t; next } { print }' "$1" > "$2"; }
# flip SRC DST COUNT: SRC with COUNT bytes at random offsets replaced by random printable ones.
flip() {
  cp "$1" "$2"
  local size i
  size=$(stat -c %s "$1")
  for ((i = 0; i < $3; i++)); do
    rnd 94
    local byte=$((33 + R))
    rnd "$size"
    printf "\\$(printf %03o "$byte")" | dd of="$2" bs=1 seek="$R" conv=notrunc status=none
  done
}

# ---- series files --------------------------------------------------------------------------------
"$CHAOS" generate lorenz -l 1500 --components x > "$work/x.dat" || fail "generate lorenz x"
"$CHAOS" generate lorenz -l 1500 --components all > "$work/xyz.dat" || fail "generate lorenz xyz"
for p in 1 2 3; do awk -v p="$p" '!/^#/ && n++ < 200 { print p, $1 }' "$work/x.dat"; done > "$work/pv.dat"
declare -A base=(
  [mutual]="x.dat" [autocorrelation]="x.dat" [cao]="x.dat -M 4" [fnn]="x.dat -M 4"
  [d2]="x.dat -M 3 --reference-points 300" [analyze]="x.dat --surrogates 3 -M 4"
  [lyapunov]="x.dat -m 3 --reference-points 200" [surrogates]="x.dat -n 2" [nonlinearity]="x.dat -n 3"
  [density]="pv.dat -v 2" [section]="xyz.dat --hyperplane 1 --level 0"
)
commands=(mutual autocorrelation cao fnn d2 analyze lyapunov surrogates nonlinearity density section)

# corrupt KIND SRC DST: the corrupt variant KIND of SRC; sets `line` to the line it spoils (or empty).
corrupt() {
  local kind=$1 src=$2 dst=$3 rows
  rows=$(grep -c '' "$src")
  rnd $((rows - 1))
  line=$((2 + R))  # a data line (the generator writes no comment lines)
  case $kind in
    crlf) line=""; sed 's/$/\r/' "$src" > "$dst" ;;
    cr) line=""; tr '\n' '\r' < "$src" > "$dst" ;;
    mixed) rnd 1000000; awk -v s="$R" 'BEGIN { srand(s) } { r = rand(); printf "%s%s", $0, r < 0.33 ? "\r" : r < 0.66 ? "\r\n" : "\n" }' "$src" > "$dst" ;;
    bom) line=""; { printf '\xEF\xBB\xBF'; cat "$src"; } > "$dst" ;;
    blank_lines) line=""; { printf ' \t\n\n# a comment\n'; cat "$src"; printf '\n\t\n'; } > "$dst" ;;
    empty) line=""; : > "$dst" ;;
    header_only) line=""; printf '\xEF\xBB\xBFtime,value\n' > "$dst" ;;
    comments_only) line=""; printf '# nothing\n\n   \n' > "$dst" ;;
    binary) line=""; garbage "$dst" 4000 ;;
    nul) set_line "$src" "$dst" "$line" "$(sed -n "${line}p" "$src")"; printf '\0' | dd of="$dst" bs=1 seek=$(($(head -n $((line - 1)) "$src" | wc -c) + 1)) conv=notrunc status=none ;;
    nan) set_line "$src" "$dst" "$line" "NaN NaN NaN" ;;
    inf) set_line "$src" "$dst" "$line" "-inf -inf -inf" ;;
    e400) set_line "$src" "$dst" "$line" "1e400 1e400 1e400" ;;
    e-400) set_line "$src" "$dst" "$line" "-1e-400 -1e-400 -1e-400" ;;
    huge_token) { head -n $((line - 1)) "$src"; head -c 1000000 /dev/zero | tr '\0' 7; echo; tail -n +$((line + 1)) "$src"; } > "$dst" ;;
    two_dots) set_line "$src" "$dst" "$line" "1.2.3 1.2.3 1.2.3" ;;
    latin1) set_line "$src" "$dst" "$line" "$(printf '\xE9 \xE9 \xE9')" ;;
    short_line) set_line "$src" "$dst" "$line" ""; sed -i "${line}s/^/ , /" "$dst" ;;
    truncated) rnd "$(stat -c %s "$src")"; head -c "$R" "$src" > "$dst" ;;
    flipped) line=""; flip "$src" "$dst" 3 ;;
  esac
}
readable=(crlf cr mixed bom blank_lines)
refused=(empty header_only comments_only binary nul nan inf e400 e-400 huge_token two_dots latin1)
either=(short_line truncated truncated flipped flipped flipped)
for c in "${!commands[@]}"; do
  command=${commands[c]}
  read -r file args <<<"${base[$command]}"
  # shellcheck disable=SC2086  # the base arguments are words
  check chaos "0" "" -- "$command" "$work/$file" $args || continue
  grep -v '^# file' "$work/out" > "$work/clean.out"
  n=0
  for kind in "${readable[@]}" "${refused[@]}" "${either[@]}"; do
    n=$((n + 1))
    (( (c + n) % sample == 0 )) || continue
    case_file="$work/$command.$n.$kind.dat"
    corrupt "$kind" "$work/$file" "$case_file"
    name=$(basename "$case_file")
    if [[ " ${readable[*]} " == *" $kind "* ]]; then
      # shellcheck disable=SC2086
      check chaos "0" "" -- "$command" "$case_file" $args || continue
      grep -v '^# file' "$work/out" | cmp -s - "$work/clean.out" || fail "chaos $command on the $kind variant differs from the clean file"
    elif [[ " ${refused[*]} " == *" $kind "* ]]; then
      # shellcheck disable=SC2086
      check chaos "3" "$name${line:+:$line:}" -- "$command" "$case_file" $args
    else  # still a series, maybe a short one: an estimator may refuse it for that, by its own rule
      # shellcheck disable=SC2086
      check chaos "0 3" "" -- "$command" "$case_file" $args
    fi
  done
  mkdir -p "$work/dir.dat"
  # shellcheck disable=SC2086
  check chaos "3" "dir.dat: is a directory" -- "$command" "$work/dir.dat" $args
  if [[ $(id -u) -ne 0 ]]; then  # root reads any file: the unreadable case is skipped there
    cp "$work/$file" "$work/locked.dat" && chmod 000 "$work/locked.dat"
    # shellcheck disable=SC2086
    check chaos "3" "locked.dat" -- "$command" "$work/locked.dat" $args
  fi
done
echo "series files: $passed passed, $failed failed"

# ---- scene files ---------------------------------------------------------------------------------
"$MECHANISM" scene 2> /dev/null | sed 's/^duration = .*/duration = 0.002/' > "$work/scene.toml" || fail "mechanism scene"
# Every "key = value" line with its table: "LINE TABLE KEY KIND" (KIND: number or string).
awk '/^\[/ { t = substr($0, 2, length($0) - 2) "."; next }
     /^[a-z_0-9]+ = / { print NR, t $1, ($3 ~ /^"/ ? "string" : "number") }' "$work/scene.toml" > "$work/keys"
mapfile -t keys < "$work/keys"
numbers=(-1 0 nan inf -inf 1e300 1e-320 '"x"' true '[1, 2]' '{ a = 1 }' 9223372036854775808 1e400)
strings=('"bogus"' 1 '""' '"\u0000"')
# scene_case FILE: the next sampled mutation of the scene into FILE; sets `names` to the key it
# spoils, or the file's name for a file that is not valid TOML (empty: it may well be valid).
scene_case() {
  local f=$1 line key kind value table t
  rnd 10
  if ((R < 7)); then  # a value
    rnd ${#keys[@]}
    read -r line key kind <<<"${keys[R]}"
    if [[ $kind == number ]]; then rnd ${#numbers[@]}; value=${numbers[R]}; else rnd ${#strings[@]}; value=${strings[R]}; fi
    awk -v k="$line" -v v="$value" 'NR == k { sub(/=.*/, "= " v) } { print }' "$work/scene.toml" > "$f"
    # A number too large for TOML's integers or doubles is a syntax error, named by file and line.
    if [[ $value == 9223372036854775808 || $value == 1e400 ]]; then names="$(basename "$f").*line $line"; else names=${key#.}; fi
    return
  fi
  rnd ${#tables[@]}
  table=${tables[R]}
  t=${table#[}
  t=${t%]}
  rnd 9
  case $R in
    0) awk -v t="$table" '{ print } $0 == t { print "bogus_key = 1" }' "$work/scene.toml" > "$f"; names="$t.bogus_key" ;;
    1) { cat "$work/scene.toml"; echo "$table"; } > "$f"; names=$(basename "$f") ;;  # a table defined twice
    2) awk -v t="$table" '/^\[/ { skip = ($0 == t) } !skip' "$work/scene.toml" > "$f"; names="" ;;  # missing: defaults
    3) rnd "$(stat -c %s "$work/scene.toml")"; head -c "$R" "$work/scene.toml" > "$f"; names="" ;;  # cut short
    4) flip "$work/scene.toml" "$f" 2; names="" ;;
    5) garbage "$f" 2000; names=$(basename "$f") ;;
    6) { printf '\xEF\xBB\xBF'; cat "$work/scene.toml"; } > "$f"; names="" ;;
    7) sed 's/$/\r/' "$work/scene.toml" > "$f"; names="" ;;
    8) tr '\n' '\r' < "$work/scene.toml" > "$f"; names=$(basename "$f") ;;
  esac
}
mapfile -t tables < <(grep '^\[' "$work/scene.toml")
before=$passed
for ((n = 0; n < scenes; n++)); do
  f="$work/scene$n.toml"
  scene_case "$f"
  # mechanism: 0 ok, 3 invalid scene, 5 the integration could not continue (README.md).
  check mechanism "0 3 5" "$names" -- simulate -q "$f"
  ((n % 4 == 0)) && check mechanism "0 3" "$names" -- scene "$f"
done
mkdir -p "$work/scene_dir.toml"
check mechanism "3" "scene_dir.toml" -- simulate -q "$work/scene_dir.toml"
# study: scenes/8 more cases through a two-point sweep, one in three of them through the pipeline
# (docs/reference/study.md: 0 done, 3 refused, 5 some points failed).
for ((n = 0; n < scenes; n += 8)); do
  f="$work/study_scene$n.toml"
  scene_case "$f"
  rm -rf "$work/sweep"
  check study "0 3 5" "$names" -- sweep "$f" -q --threads 1 --axis joint.slider.clearance=2e-4,3e-4 --periods 2 --keep 1 -o "$work/sweep"
  if ((n % 24 == 0)); then
    check study "0 3 5" "$names" -- pipeline "$f" --periods 3 --analysis-periods 2
  fi
done
echo "scene files: $((passed - before)) passed"

# ---- scenes beyond the bounds ----------------------------------------------------------------------
# scene.hpp's bounds, checked before the TOML parser reads the text (a key of 50,000 dotted parts
# overflowed its stack: exit 139): keys of at most 64 parts, in the file and in --set, scene files of
# at most 1 MiB, --set values of at most 4096 bytes. Each is refused with exit 3 by `mechanism scene`,
# `mechanism simulate` and `study sweep`, with the rule and the numbers, within 5 s (a Release
# build takes a few hundredths of a second; the limit leaves room for the sanitizer build). A key
# holding a NUL is named with the NUL escaped: the message was empty.
before=$passed
deep_key=$(printf 'a%.0s.' {1..49999})a
printf '%s = 1\n' "$deep_key" > "$work/deep_key.toml"
printf '[crank]\nmass = 0.3\n[%s]\n' "$deep_key" > "$work/deep_header.toml"
{ printf '[crank]\nmass = 0.3\n# '; head -c $((10 * 1024 * 1024)) /dev/zero | tr '\0' x; echo; } > "$work/big_scene.toml"
printf '"\\u0000x" = 1\n' > "$work/nul_key.toml"
long_value="crank.mass=0.3$(printf ' %.0s' {1..5000})"
bounded() {  # bounded NAMES ARGS...: refused with exit 3, naming NAMES, by all three commands
  local names=$1 start run
  shift
  local args="$*"
  for run in "mechanism scene" "mechanism simulate -q" "study sweep -q --threads 1 --periods 2 --keep 1 --axis joint.slider.clearance=2e-4,3e-4 -o $work/bounded_sweep"; do
    rm -rf "$work/bounded_sweep"
    start=$(date +%s%N)
    # shellcheck disable=SC2086  # the command's words
    check ${run%% *} "3" "$names" -- ${run#* } "$@" || continue
    (($(date +%s%N) - start < 5000000000)) || fail "${run%% -*} ${args:0:100}: the refusal took over 5 s"
  done
}
bounded "deep_key.toml.*line 1 has 50000 dotted parts; at most 64 are allowed" "$work/deep_key.toml"
bounded "deep_header.toml.*line 3 has 50000 dotted parts; at most 64 are allowed" "$work/deep_header.toml"
bounded "big_scene.toml.*is 10485782 bytes; a scene file may have at most 1048576 bytes" "$work/big_scene.toml"
bounded "has 60000 dotted parts; at most 64 are allowed" --set "$(printf 'a%.0s.' {1..59999})a=1"
bounded "the value is 5003 bytes; at most 4096 are allowed" --set "$long_value"
bounded '\\x00x = 1: is not a scene key' "$work/nul_key.toml"
echo "scenes beyond the bounds: $((passed - before)) passed"

# ---- result files --------------------------------------------------------------------------------
fast=(--set 'joint.slider.friction.sigma1_velocity=1e-3' --set 'integrator.method="dopri5"' --set integrator.relative_tolerance=1e-5)
sweep=("${fast[@]}" --axis joint.slider.clearance=1e-4:4e-4:3 --periods 4 --keep 2 --analysis --analysis-periods 2 -q --threads 1)
chain=("${fast[@]}" --axis joint.slider.clearance=1e-4:4e-4:3 --periods 4 --keep 2 -q --threads 1 --initial continuation)
before=$passed
check study "0" "" -- sweep "${sweep[@]}" -o "$work/good" || { echo "hostile files: $passed passed, $failed failed"; exit 1; }
check study "0" "" -- sweep "${chain[@]}" -o "$work/good_chain"
# resume_case NAME SETUP ALLOWED NAMES [chain]: a copy of the good directory spoilt by SETUP (run in
# it), resumed. A resume that succeeds must give the good directory's tables.
resume_case() {
  local good=$work/good args=("${sweep[@]}")
  [[ ${5:-} == chain ]] && good=$work/good_chain args=("${chain[@]}")
  rm -rf "$work/r" && cp -r "$good" "$work/r"
  pushd "$work/r" > /dev/null && eval "$2"
  popd > /dev/null
  check study "$3" "$4" -- sweep "${args[@]}" -o "$work/r" --resume || return
  if [[ $(tail -n 1 "$work/out") == "}" ]] && grep -q '"computed"' "$work/out"; then
    for t in samples.tsv points.tsv analysis.tsv; do
      [[ -e $good/$t ]] || continue
      cmp -s "$good/$t" "$work/r/$t" || fail "resume after '$1' gives another $t"
    done
  fi
}
point=points/000001.tsv
size=$(stat -c %s "$work/good/$point")
for ((k = 0; k < 6; k++)); do
  rnd "$size"
  resume_case "point file cut at byte $R" "head -c $R ../good/$point > $point" 0 "recomputing point 1"
  resume_case "point file flipped $k" "cp $point p && flip p $point 2 && rm p" 0 ""
done
for value in x nan 1e400 -1 ''; do
  # A field of each line edited in place; a garbled final_state in a continuation chain exited 1.
  resume_case "final_state = '$value'" "sed -i 's/^final_state\t[^\t]*/final_state\t$value/' points/000000.tsv; rm points/000001.tsv points/000002.tsv" 0 "recomputing point 0" chain
  resume_case "counters = '$value'" "sed -i 's/^counters\t[^\t]*/counters\t$value/' $point" 0 "recomputing point 1"
  resume_case "status = '$value'" "sed -i 's/^status\t[^\t]*/status\t$value/' $point" 0 "recomputing point 1"
  resume_case "a sample = '$value'" "sed -i '0,/^sample/s/^sample\t\([^\t]*\)\t[^\t]*/sample\t\1\t$value/' $point" 0 "recomputing point 1"
done
resume_case "point file empty" ": > $point" 0 "recomputing point 1"
resume_case "point file binary" "garbage $point 3000" 0 "recomputing point 1"
resume_case "point file with NUL" "printf '\\0' | dd of=$point bs=1 seek=40 conv=notrunc status=none" 0 "recomputing point 1"
resume_case "point file CRLF" "sed -i 's/\$/\\r/' $point" 0 "recomputing point 1"
resume_case "point file a directory" "rm $point && mkdir -p $point/x" 3 "000001.tsv: is a directory"
resume_case "spec.txt cut short" "head -c 200 ../good/spec.txt > spec.txt" 3 "holds another sweep"
resume_case "spec.txt empty" ": > spec.txt" 3 "holds another sweep"
resume_case "spec.txt binary" "garbage spec.txt 3000" 3 "holds another sweep"
resume_case "spec.txt a directory" "rm spec.txt && mkdir spec.txt" 3 "spec.txt: is a directory"
resume_case "lock file garbage" "garbage lock 500" 0 ""
resume_case "points a file" "rm -r points && echo x > points" 3 "points"
# The assembled tables through `study plot` (exit 3 names the table).
for ((k = 0; k < 8; k++)); do
  for t in samples analysis; do
    rm -rf "$work/p" && cp -r "$work/good" "$work/p"
    tsize=$(stat -c %s "$work/good/$t.tsv")
    case $((k % 4)) in
      0) rnd "$tsize"; head -c "$R" "$work/good/$t.tsv" > "$work/p/$t.tsv" ;;
      1) flip "$work/good/$t.tsv" "$work/p/$t.tsv" 3 ;;
      2) rnd 40; sed -i "$((R + 80))s/\t[^\t]*/\tnan/2" "$work/p/$t.tsv" ;;
      3) garbage "$work/p/$t.tsv" 2000 ;;
    esac
    if [[ $t == samples ]]; then figures=(bifurcation density portrait); else figures=(d2 e2); fi
    check study "0 3" "$t.tsv" -- plot "$work/p" --figure "${figures[k % ${#figures[@]}]}" -o "$work/p/figure.svg"
  done
done
echo "result files: $((passed - before)) passed"

echo "hostile files: $passed passed, $failed failed"
[[ $failed -eq 0 ]]
