#!/usr/bin/env bash
# `study` as a user runs it: exit codes, messages naming the rule, the result directory's files,
# resume after a kill, and (when built with MPI) two ranks writing the same files as one process.
# Expected values come from the documented protocol (docs/reference/study.md) and from the tool's own
# single-process run.
set -uo pipefail
STUDY=${STUDY:?set STUDY to the study binary}
CHAOS=${CHAOS:?set CHAOS to the chaos binary}
MPI_ENABLED=${MPI_ENABLED:-0}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
expect_code() {  # expected_code description command...
  local want=$1 what=$2; shift 2
  "$@" >"$work/out" 2>"$work/err"; local got=$?
  [[ $got == "$want" ]] || fail "$what: exit $got, expected $want ($(head -c 300 "$work/err"))"
}
expect_message() {  # pattern description
  grep -q -- "$1" "$work/err" || fail "$2: message lacks '$1' ($(head -c 300 "$work/err"))"
}
fast=(--set 'joint.slider.friction.sigma1_velocity=1e-3' --set 'integrator.method="dopri5"' --set integrator.relative_tolerance=1e-5)

# Bad requests: the rule named, exit 2 (usage) or 3 (refused sweep).
expect_code 2 "no output directory" "$STUDY" sweep --axis joint.slider.clearance=1e-4:2e-4:2
expect_code 3 "malformed axis" "$STUDY" sweep --axis joint.slider.clearance=1e-4:2e-4 -o "$work/x"
expect_message "from:to:count" "malformed axis"
expect_code 3 "keep above periods" "$STUDY" sweep --periods 5 --keep 6 -o "$work/x"
expect_message "must be 1 .. --periods" "keep above periods"
expect_code 3 "impossible clearance" "$STUDY" sweep --axis joint.slider.clearance=0,1e-4 -o "$work/x"
expect_message "clearance" "impossible clearance"
expect_code 3 "unknown signal" "$STUDY" sweep --signals slider_height -o "$work/x"
expect_message "is not a signal" "unknown signal"
expect_code 3 "missing scene file" "$STUDY" sweep "$work/none.toml" -o "$work/x"
expect_message "cannot be opened" "missing scene file"
# More exponents than the phase space has (the seed scene's: 6) ran for minutes writing empty columns;
# a scene with every joint ideal and the crank driven has no phase space at all.
expect_code 3 "exponents beyond the phase space" "$STUDY" sweep --lyapunov --lyapunov-exponents 2000000000 -o "$work/x"
expect_message "at most the scene's phase-space dimension, 6" "exponents beyond the phase space"
expect_code 3 "no phase space" "$STUDY" sweep --set joint.slider.type=ideal --lyapunov -o "$work/x"
expect_message "no phase space" "no phase space"
expect_code 3 "unknown initial conditions" "$STUDY" sweep --initial restart -o "$work/x"
expect_message "must be fresh or continuation" "unknown initial conditions"
# An unknown command is named (exit 2), also with --help after it.
expect_code 2 "unknown command" "$STUDY" foo --help
expect_message "unknown command 'foo'; the commands are: sweep, pipeline, plot" "unknown command"
# A directory as the scene ran the built-in scene and spec.txt recorded the
# directory; --max-delay 0 failed every point's analysis with exit 0. Both are refused up front.
expect_code 3 "directory as scene" "$STUDY" sweep "$work" -o "$work/x"
expect_message "is a directory, not a scene file" "directory as scene"
expect_code 3 "max-delay 0" "$STUDY" sweep --analysis --max-delay 0 -o "$work/x"
expect_message "max-delay = 0: must be at least 1 sample" "max-delay 0"
# --max-dimension 1000 failed every point's analysis with exit 0; the range is
# 2 .. 33 (study/sweep.hpp: Eckmann-Ruelle and Takens on the mechanism's 1e8-row limit), checked
# before the run by sweep and pipeline alike.
expect_code 3 "max-dimension 1000" "$STUDY" sweep --analysis --max-dimension 1000 -o "$work/x"
expect_message "max-dimension = 1000: must be 2 .. 33" "max-dimension 1000"
expect_code 3 "pipeline max-dimension 34" "$STUDY" pipeline --max-dimension 34
expect_message "max-dimension = 34: must be 2 .. 33" "pipeline max-dimension 34"
expect_code 3 "pipeline max-delay 0" "$STUDY" pipeline --max-delay 0
expect_message "max-delay = 0: must be at least 1 sample" "pipeline max-delay 0"
# ... and when the analysis fails at every point (here 2 samples per revolution over 1 revolution:
# 3 samples, too short for any estimator) the sweep exits 5 (docs/reference/study.md) and says so.
expect_code 5 "every analysis failed" "$STUDY" sweep -q "${fast[@]}" --axis joint.slider.clearance=1e-4,2e-4 --periods 4 --keep 1 \
  --analysis --analysis-periods 1 --analysis-samples-per-period 2 -o "$work/no_analysis"
expect_message "the analysis failed at all 2 analysed points (the first: series too short: 3 samples)" "every analysis failed"
[[ $(jq -r .analysis_failed "$work/out") == 2 ]] || fail "every analysis failed: the summary's analysis_failed is $(jq -r .analysis_failed "$work/out"), expected 2"
# --lyapunov: lyapunov.tsv, one row per point, K = 2 exponent columns and their errors; the spec
# records the settings; --lyapunov-periods below 10 is refused before the run.
expect_code 0 "sweep --lyapunov" "$STUDY" sweep -q "${fast[@]}" --axis joint.slider.clearance=3e-4,5e-4 --periods 4 --keep 1 \
  --lyapunov --lyapunov-periods 10 --lyapunov-exponents 2 --lyapunov-intervals 10 -o "$work/lyap"
[[ $(grep -vc '^#' "$work/lyap/lyapunov.tsv") == 2 ]] || fail "sweep --lyapunov: lyapunov.tsv lacks its 2 rows"
grep -q $'\tlambda_1\tlambda_2\tse_1\tse_2\tkaplan_yorke' "$work/lyap/lyapunov.tsv" || fail "sweep --lyapunov: lyapunov.tsv header"
grep -q '^lyapunov.periods = 10$' "$work/lyap/spec.txt" || fail "sweep --lyapunov: spec.txt lacks lyapunov.periods"
[[ $(jq -r .lyapunov_failed "$work/out") == 0 ]] || fail "sweep --lyapunov: lyapunov_failed is not 0"
expect_code 3 "lyapunov periods 5" "$STUDY" sweep --lyapunov --lyapunov-periods 5 -o "$work/x"
expect_message "lyapunov-periods = 5: must be >= 10" "lyapunov periods 5"
# --periods -1 was read as 2^64-1 and "completed" with nothing done. A
# negative count is a usage error (exit 2); a run too large to finish is refused (exit 3).
expect_code 2 "negative periods" "$STUDY" sweep --periods -1 -o "$work/x"
expect_message "'-1' is negative" "negative periods"
expect_code 3 "periods beyond any run" "$STUDY" sweep --periods 9223372036854775808 --keep 3 -o "$work/x"
expect_message "point 0's run is too large" "periods beyond any run"
[[ ! -e "$work/x/points" ]] || fail "a refused sweep left a result directory"

# At 1e-6 m clearance and 50 rpm (the scene as printed: face contact, exponent
# 1.5, absolute LuGre with a constant sigma1, no longer the built-in reading)
# energy_balance_relative was 0.53 with status "completed" and 0 failed points. One revolution
# measures 0.18, above the limit of 0.03 per revolution (mechanism/simulate.hpp): the point is
# energy_defect, counted as failed, exit 5 (docs/reference/study.md); the 5000 rpm point of the same sweep
# (0.004) stays completed.
printed=(--set joint.slider.model=face --set joint.slider.contact.exponent=1.5 --set joint.slider.friction.law=lugre_absolute --set joint.slider.friction.sigma1_velocity=0)
expect_code 5 "energy defect" "$STUDY" sweep -q --threads 1 "${printed[@]}" --set joint.slider.clearance=1e-6 \
  --axis driver.speed_rpm=50,5000 --periods 1 --keep 1 -o "$work/energy"
[[ $(jq -r .failed "$work/out") == 1 ]] || fail "energy defect: the summary counts $(jq -r .failed "$work/out") failed points, expected 1"
expect_message "1 of 2 points did not complete (the first: point 0, energy_defect)" "energy defect"
statuses=$(grep -v '^#' "$work/energy/points.tsv" | cut -f3 | tr '\n' ' ')
[[ $statuses == "energy_defect completed " ]] || fail "energy defect: points.tsv statuses are '$statuses'"

# A small sweep: four points, the files of docs/reference/study.md, the kept revolutions.
expect_code 0 "small sweep" "$STUDY" sweep "${fast[@]}" --axis joint.slider.clearance=1e-4:4e-4:4 --periods 8 --keep 3 -o "$work/a" -q --threads 2
grep -q "warning" "$work/err" && fail "sweep -q still warns about the scene: $(head -c 300 "$work/err")"
for f in spec.txt samples.tsv points.tsv timing.tsv points/000003.tsv; do [[ -s "$work/a/$f" ]] || fail "missing $f"; done
rows=$(grep -vc '^#' "$work/a/samples.tsv")
[[ $rows == 12 ]] || fail "samples.tsv has $rows rows, expected 4 points x 3 revolutions"
revs=$(grep -v '^#' "$work/a/samples.tsv" | cut -f3 | sort -un | tr '\n' ' ')
[[ $revs == "6 7 8 " ]] || fail "kept revolutions are '$revs', expected the last three of 8"
[[ $(jq -r .computed "$work/out") == 4 ]] || fail "summary does not report 4 computed points"
# The tables open with a short header: the settings, the base scene as the keys that differ from the
# built-in scene (the --set lines of this sweep), then the column names; spec.txt keeps the whole
# resolved scene. They opened with all of spec.txt, some 190 '#' lines.
for f in samples.tsv points.tsv; do
  head_lines=$(grep -c '^#' "$work/a/$f")
  (( head_lines <= 20 )) || fail "$f opens with $head_lines '#' lines, expected at most 20"
  grep -q '^#   integrator.method = "dopri5"$' "$work/a/$f" || fail "$f: the header lacks the changed key integrator.method"
  grep -q 'spec.txt' "$work/a/$f" || fail "$f: the header does not point at spec.txt"
done
grep -q '^young_modulus = ' "$work/a/spec.txt" || fail "spec.txt lacks the whole resolved scene"

# The same sweep on one thread writes the same files.
expect_code 0 "one thread" "$STUDY" sweep "${fast[@]}" --axis joint.slider.clearance=1e-4:4e-4:4 --periods 8 --keep 3 -o "$work/b" -q --threads 1
cmp -s "$work/a/samples.tsv" "$work/b/samples.tsv" || fail "1 and 2 threads give different samples.tsv"

# An existing directory is refused without --resume; a killed sweep (a point file missing, a
# temporary file left behind) resumes, recomputes that point only and gives the same table.
expect_code 3 "existing directory" "$STUDY" sweep "${fast[@]}" --axis joint.slider.clearance=1e-4:4e-4:4 --periods 8 --keep 3 -o "$work/b" -q
expect_message "--resume" "existing directory"
rm "$work/b/points/000002.tsv"; echo partial > "$work/b/points/000002.tsv.tmp.99999"
expect_code 0 "resume" "$STUDY" sweep "${fast[@]}" --axis joint.slider.clearance=1e-4:4e-4:4 --periods 8 --keep 3 -o "$work/b" -q --resume
[[ $(jq -r .computed "$work/out") == 1 && $(jq -r .resumed_from_disk "$work/out") == 3 ]] || fail "resume did not recompute exactly one point: $(cat "$work/out")"
cmp -s "$work/a/samples.tsv" "$work/b/samples.tsv" || fail "a resumed sweep differs from an uninterrupted one"
[[ ! -e "$work/b/points/000002.tsv.tmp.99999" ]] || fail "resume left a killed run's temporary file"
expect_code 3 "resume with another spec" "$STUDY" sweep "${fast[@]}" --axis joint.slider.clearance=1e-4:4e-4:4 --periods 9 --keep 3 -o "$work/b" -q --resume
expect_message "first difference" "resume with another spec"

# A real kill: SIGKILL part-way through a sweep of about 2 s (whatever had finished stays; a point
# being written is at most a temporary file), then --resume computes only the rest and gives the
# uninterrupted run's table.
long=("${fast[@]}" --axis joint.slider.clearance=1e-4:4e-4:4 --periods 200 --keep 3 -q --threads 1)
expect_code 0 "uninterrupted long sweep" "$STUDY" sweep "${long[@]}" -o "$work/u"
"$STUDY" sweep "${long[@]}" -o "$work/k" >/dev/null 2>&1 &
victim=$!
for _ in $(seq 100); do  # until the first point is written, then kill
  compgen -G "$work/k/points/*.tsv" >/dev/null && break
  sleep 0.05
done
kill -9 "$victim" 2>/dev/null
wait "$victim" 2>/dev/null
before=$(ls "$work/k/points" | grep -c '\.tsv$')
expect_code 0 "resume after SIGKILL" "$STUDY" sweep "${long[@]}" -o "$work/k" --resume
[[ $(jq -r .resumed_from_disk "$work/out") == "$before" ]] || fail "resume after SIGKILL did not keep the $before finished point(s): $(cat "$work/out")"
cmp -s "$work/u/samples.tsv" "$work/k/samples.tsv" || fail "a sweep killed and resumed differs from an uninterrupted one"

# A second sweep into a directory another sweep is writing is refused (exit 3,
# docs/reference/study.md: a refused request), naming the lock's holder; the first finishes untouched.
"$STUDY" sweep "${long[@]}" -o "$work/l" >/dev/null 2>&1 &
holder=$!
for _ in $(seq 100); do [[ -s "$work/l/lock" ]] && break; sleep 0.05; done
expect_code 3 "a second sweep into a held directory" "$STUDY" sweep "${fast[@]}" --axis joint.slider.clearance=1e-4:4e-4:4 --periods 20 --keep 3 -q -o "$work/l"
expect_message "is in use by another sweep (process $holder holds" "a second sweep into a held directory"
wait "$holder" || fail "the first sweep into the held directory failed"
cmp -s "$work/u/samples.tsv" "$work/l/samples.tsv" || fail "the held directory's sweep differs from an uninterrupted one"

# A point file cut short (there to 1000 bytes; here to half of its size) was
# kept on --resume. It is recomputed, said on stderr, and the table equals the uninterrupted run's.
size=$(stat -c %s "$work/u/points/000003.tsv")
head -c $((size / 2)) "$work/u/points/000003.tsv" > "$work/cut.tsv" && mv "$work/cut.tsv" "$work/u/points/000003.tsv"
expect_code 0 "resume over a truncated point file" "$STUDY" sweep "${long[@]}" -o "$work/u" --resume
expect_message "recomputing point 3 (.*000003.tsv): is incomplete" "resume over a truncated point file"
[[ $(jq -r .computed "$work/out") == 1 ]] || fail "resume over a truncated point file did not recompute one point: $(cat "$work/out")"
cmp -s "$work/k/samples.tsv" "$work/u/samples.tsv" || fail "a recomputed truncated point gives another table"

# Analysis columns, and plots of each kind.
expect_code 0 "analysis" "$STUDY" sweep "${fast[@]}" --axis joint.slider.clearance=2e-4,5e-4 --axis driver.speed_rpm=4000,5000 --periods 8 --keep 5 --analysis -o "$work/c" -q
[[ $(grep -vc '^#' "$work/c/analysis.tsv") == 4 ]] || fail "analysis.tsv should have one row per point"
grep -q 'delay_samples' "$work/c/analysis.tsv" || fail "analysis.tsv lacks its header"
# The surrogate test only tests an analysed series; asked for, every analysed row says what it found.
expect_code 3 "surrogates without analysis" "$STUDY" sweep "${fast[@]}" --periods 8 --keep 5 --surrogates 19 -o "$work/x" -q
expect_message "--surrogates = 19: tests the analysed series: it needs --analysis" "surrogates without analysis"
awk -F'\t' '/^# point/ {for (i = 1; i <= NF; ++i) if ($i == "nonlinearity") c = i; next} !/^#/ && $c != "not asked" {bad = 1}
  END {exit !(c && !bad)}' "$work/c/analysis.tsv" || fail "analysis.tsv without --surrogates should say 'not asked' in its nonlinearity column"
expect_code 0 "analysis with surrogates" "$STUDY" sweep "${fast[@]}" --axis joint.slider.clearance=5e-4 --periods 8 --keep 5 --analysis \
  --surrogates 19 --test-length 1024 -o "$work/s" -q
awk -F'\t' '/^# point/ {for (i = 1; i <= NF; ++i) {if ($i == "nonlinearity") c = i; if ($i == "surrogates") k = i}; next}
  !/^#/ {n++; if ($c !~ /^(rejected|not rejected|not run: .*)$/ || ($c ~ /rejected$/ && $k != 19)) bad = 1}
  END {exit !(n == 1 && !bad)}' "$work/s/analysis.tsv" || fail "the surrogate test's columns: $(grep -v '^#' "$work/s/analysis.tsv" | cut -f1-3)"
for fig in bifurcation density portrait e2; do
  expect_code 0 "plot $fig" "$STUDY" plot "$work/c" --figure "$fig" -o "$work/$fig.svg"
  [[ -s "$work/$fig.svg" ]] || fail "plot $fig wrote nothing"
done
# Eight revolutions give no saturated D2 at any point (d2_status not_saturated; the guide's
# parameter-study page shows the same): d2 and d2map drew an empty frame and exited 0. They are
# refused (exit 3) with the statuses counted and no file; --dimension 3 draws D2(3), which every
# point of this sweep has.
for fig in d2 d2map; do
  expect_code 3 "plot $fig with no saturated D2" "$STUDY" plot "$work/c" --figure "$fig" -o "$work/${fig}_empty.svg"
  expect_message "nothing to draw: none of the 4 points has a saturated D2 (analysis.tsv's d2_status column: 4 not_saturated)" \
    "plot $fig with no saturated D2"
  [[ ! -e "$work/${fig}_empty.svg" ]] || fail "plot $fig with nothing to draw still wrote a file"
  expect_code 0 "plot $fig --dimension 3" "$STUDY" plot "$work/c" --figure "$fig" --dimension 3 -o "$work/$fig.svg"
  [[ -s "$work/$fig.svg" ]] || fail "plot $fig --dimension 3 wrote nothing"
done
# Default axis labels carry the unit (the key's from the scene's documentation, the signal's from
# `mechanism simulate`'s header), and the scale when the values were multiplied: they showed the
# bare names.
expect_code 0 "plot units" "$STUDY" plot "$work/a" --figure bifurcation -o "$work/units.svg"
grep -q 'joint.slider.clearance (m)' "$work/units.svg" || fail "bifurcation: the x label lacks the clearance's unit m"
grep -q 'slider_y (m)' "$work/units.svg" || fail "bifurcation: the y label lacks slider_y's unit m"
expect_code 0 "plot units scaled" "$STUDY" plot "$work/a" --figure bifurcation --x-scale 1e3 -o "$work/units_mm.svg"
grep -q 'joint.slider.clearance (0.001 m)' "$work/units_mm.svg" || fail "bifurcation --x-scale 1e3: the x label lacks '(0.001 m)'"
expect_code 0 "plot density units" "$STUDY" plot "$work/a" --figure density -o "$work/density_units.svg"
grep -q 'probability density (per m)' "$work/density_units.svg" || fail "density: the colour bar lacks its unit"
expect_code 3 "plot without analysis" "$STUDY" plot "$work/a" --figure d2 -o "$work/none.svg"
expect_message "cannot be read" "plot without analysis"
expect_code 3 "bad plot extension" "$STUDY" plot "$work/a" --figure bifurcation -o "$work/fig.pdf"
# A samples table cut short after its header has nothing to draw: refused naming it (gnuplot given no
# data failed with only "is gnuplot-nox installed?").
cp -r "$work/a" "$work/header_only"
grep '^#' "$work/a/samples.tsv" > "$work/header_only/samples.tsv"
expect_code 3 "plot of a header-only table" "$STUDY" plot "$work/header_only" --figure density -o "$work/empty.svg"
expect_message "samples.tsv: has no data rows" "plot of a header-only table"

# The one-scene pipeline (seed Fig. 7): a JSON summary with every stage, and the six panels.
expect_code 3 "pipeline analysing more than it runs" "$STUDY" pipeline --periods 4 --analysis-periods 5
expect_message "must be 1 .. --periods" "pipeline analysing more than it runs"
expect_code 0 "pipeline" "$STUDY" pipeline "${fast[@]}" --periods 6 --analysis-periods 3 --plot "$work/fig7.svg" --series "$work/series.tsv"
[[ $(jq -r .simulation.status "$work/out") == completed ]] || fail "pipeline simulation status: $(head -c 300 "$work/out")"
[[ $(jq -r '.analysis["E1"] | length' "$work/out") == 12 ]] || fail "pipeline reports E1 for m = 1..12"
[[ $(jq -r .analysis.samples "$work/out") == $(grep -vc '^#' "$work/series.tsv") ]] || fail "pipeline analysed another series than it wrote"
[[ -s "$work/fig7.svg" ]] || fail "pipeline drew nothing"
# The pipeline's analysis is chaos analyze's: on the series it wrote (every digit), `chaos analyze`
# reports the same delay, Theiler window, embedding dimension and D2 (the property is equality).
cp "$work/out" "$work/pipeline.json"
"$CHAOS" analyze "$work/series.tsv" -c 2 --json >"$work/analyze.json" 2>/dev/null || fail "chaos analyze on the pipeline's series failed"
for pair in delay_samples:delay theiler_samples:theiler cao_dimension:embedding_dimension d2_status:d2_status d2:d2; do
  [[ $(jq -c ".analysis.${pair%%:*}" "$work/pipeline.json") == $(jq -c ".${pair##*:}" "$work/analyze.json") ]] ||
    fail "pipeline ${pair%%:*} $(jq -c ".analysis.${pair%%:*}" "$work/pipeline.json") differs from chaos analyze's ${pair##*:} $(jq -c ".${pair##*:}" "$work/analyze.json")"
done
# An unwritable --plot, --series or plot -o failed only after the work; all are
# refused while the command line is read, exit 4 (input/output, docs/reference/study.md), the file named;
# a plot that is not .png or .svg exits 3. The run of 10^12 periods would be refused too (exit 3),
# so exit 4 shows the file was checked first.
expect_code 4 "pipeline --plot into a missing directory" "$STUDY" pipeline --periods 1000000000000 --plot "$work/no_dir/fig7.png"
expect_message "--plot .*/no_dir/fig7.png: the directory .*no_dir does not exist" "pipeline --plot into a missing directory"
expect_code 3 "pipeline --plot not png or svg" "$STUDY" pipeline --periods 1000000000000 --plot "$work/fig7.pdf"
expect_message "--plot: the file must end in .png or .svg" "pipeline --plot not png or svg"
expect_code 4 "plot -o into a missing directory" "$STUDY" plot "$work/no_such_sweep" --figure bifurcation -o "$work/no_dir/b.png"
expect_message "-o .*/no_dir/b.png: the directory .*no_dir does not exist" "plot -o into a missing directory"
# An output that cannot be written exited 3; docs/reference/study.md says 4 (input/output).
expect_code 4 "unwritable --series" "$STUDY" pipeline "${fast[@]}" --periods 6 --analysis-periods 3 --series "$work/no_dir/series.tsv"
expect_message "--series .*/no_dir/series.tsv: the directory .*no_dir does not exist" "unwritable --series"
expect_code 0 "pipeline with a given delay" "$STUDY" pipeline "${fast[@]}" --periods 6 --analysis-periods 3 --delay 18
[[ $(jq -r .analysis.delay_samples "$work/out") == 18 ]] || fail "--delay 18 not used"

# Two MPI ranks write the same files as one process.
if [[ $MPI_ENABLED == 1 || $MPI_ENABLED == ON || $MPI_ENABLED == TRUE ]] && command -v mpirun >/dev/null; then
  mpi=(mpirun -n 2 --oversubscribe)
  [[ $(id -u) == 0 ]] && mpi+=(--allow-run-as-root)
  expect_code 0 "two MPI ranks" "${mpi[@]}" "$STUDY" sweep "${fast[@]}" --axis joint.slider.clearance=1e-4:4e-4:4 --periods 8 --keep 3 -o "$work/m" -q --threads 1
  [[ $(jq -r .ranks "$work/out") == 2 ]] || fail "mpirun -n 2 did not give two ranks: $(cat "$work/out")"
  cmp -s "$work/a/samples.tsv" "$work/m/samples.tsv" || fail "two MPI ranks give a different samples.tsv"
  cmp -s "$work/a/points.tsv" "$work/m/points.tsv" || fail "two MPI ranks give a different points.tsv"
else
  echo "note: built without MPI; the two-rank case is skipped"
fi

if (( failures )); then echo "$failures failure(s)"; exit 1; fi
echo "all study command tests passed"
