# shellcheck shell=bash
# Shared by the scripts/measure/measure_*.sh that run the command on the zoo's series away from the zoo's own
# choices (delay, noise, length, sensor, ...) and judge every confident estimate against the bands of
# the same system's row in docs/validation/zoo.md. Sourced from the repository root with the build directory as
# $1 (default build).
#
# Sets chaos (the command), jobs (JOBS, default 2) and work (a scratch directory, removed on exit),
# and defines:
#   zoo_columns     (scripts/measure/zoo_columns.sh) columns of docs/validation/zoo.md by their names
#   zoo_systems     one line "name tau w d2_low d2_high lambda_1" per automatic-choice row of
#                   docs/validation/zoo.md at N = 10^5 that got an embedding dimension, in the file's order
#   zoo_series N    the case's series (N = 10^5) into $work/N.dat; prints its sampling step (empty
#                   for a map)
#   zoo_verdicts    jq definitions: num (4 decimals, "-" for none), d2v (a D2 against $lo and $hi)
#                   and lv(status; value; confident status) (a lambda_1 within 10% of $lam); a
#                   confident estimate outside its band is WRONG, anything not confident is unsure;
#                   automatic_columns (analyze's own delay, m and w, then D2 with its status, the
#                   band and the verdict) and lambda_columns (the six lambda_1 columns: value and status, verdict, for
#                   Rosenstein, Kantz and local maps, from analyze's JSON)
#   zoo_choices     one line "name tau m w" per such row (the zoo's delay, Cao's m and window)
#   zoo_saturated_cases
#                   one line "name tau m w band" per row of docs/validation/zoo.md at N = 10^5 whose automatic D2
#                   is saturated (band as "[low,high]"); ONLY (name,name; empty: all) selects
#   zoo_only        the lines of standard input whose first word ONLY (name,name; empty: all) selects
#   zoo_band_cases  one line "name d2_low d2_high lambda_1" per system of $work/systems that ONLY
#                   selects
#   zoo_table_rows  the Markdown rows of $work/rows.NAME (tab-separated), systems in zoo order
#   zoo_run_cases   runs case_rows (defined by the script) on each line of standard input, JOBS at
#                   a time, and sets elapsed to the seconds it took; with RESUME_FROM=DIR, the
#                   cases whose rows file DIR/rows.NAME exists are taken from DIR instead of run
#   zoo_machine     "CPU model, N cores, J jobs", for the report's header
#   zoo_keyed_summary FORMAT
#                   the verdict counts per value of the rows' second column (noise level, sensor
#                   response), each line headed by FORMAT with that value
#   (stopped by Ctrl-C, i.e. SIGINT to the process group, which ends the running cases too, a
#   script prints the rows of the cases begun so far and keeps the rows of the cases it finished in
#   a directory it names, for RESUME_FROM, so that a long measurement stopped for lack of time keeps
#   what it measured; a signal to the script's own process alone waits, as bash does, for the
#   running cases to end first)
#   add_noise SNR IN NOISE OUT
#                   OUT = IN + sigma * NOISE sample by sample, sigma = std(IN) / 10^(SNR / 20)
#                   (population std, as chaos::add_noise; NOISE holds unit-variance values)

source scripts/measure/zoo_columns.sh

zoo_build=${1:-build}
chaos="$PWD/$zoo_build/chaos/chaos"
[[ -x $chaos ]] || { echo "build the chaos command first: cmake --build $zoo_build --target chaos_cli" >&2; exit 2; }
command -v jq > /dev/null || { echo "jq is needed" >&2; exit 2; }
# shellcheck disable=SC2034  # read by the scripts that source this file
jobs=${JOBS:-2}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

zoo_systems() {
  zoo_columns "system	N	tau	w	D2 band	lambda_1 eq.	m" | awk '$2 == 100000 && $7 + 0 > 0 {
      band = $5; gsub(/[][]/, "", band); split(band, b, ",")
      print $1, $3, $4, b[1], b[2], $6 + 0 }'
}

zoo_series() {
  "$chaos" zoo --series "$1" --json > "$work/$1.json"
  jq -r '.x[]' "$work/$1.json" > "$work/$1.dat"
  jq -r '.parameters.dt // empty' "$work/$1.json"
}

# shellcheck disable=SC2016,SC2089,SC2090  # a jq program: its $ names are jq's, passed as one word
zoo_verdicts='
  def num: if . == null then "-" else (. * 10000 | round / 10000 | tostring) end;
  def d2v: if .d2_status != "saturated" then "unsure"
           elif .d2 >= ($lo | tonumber) and .d2 <= ($hi | tonumber) then "in_band" else "WRONG" end;
  def lv(s; v; ok): if s != ok then "unsure"
           elif v >= 0.9 * ($lam | tonumber) and v <= 1.1 * ($lam | tonumber) then "in_band" else "WRONG" end;
  def automatic_columns:
    (.delay // "-" | tostring), (.embedding_dimension // "-" | tostring), (.theiler // "-" | tostring),
    "\(.d2 | num) \(.d2_status // .stopped // "error")", "[\($lo), \($hi)]", d2v;
  def lambda_columns:
    "\(.lambda | num) \(.lambda_status // "error")", lv(.lambda_status; .lambda; "linear_region"),
    "\(.lambda_kantz | num) \(.lambda_kantz_status // "error")", lv(.lambda_kantz_status; .lambda_kantz; "linear_region"),
    "\(.lambda_local_maps | num) \(.lambda_local_maps_status // "error")",
    lv(.lambda_local_maps_status; .lambda_local_maps; "consistent");'

# zoo_choices: one line "name tau m w" per automatic-choice row of docs/validation/zoo.md at N = 10^5 that got an
# embedding dimension (the delay, Cao's m and the Theiler window the zoo used), in the file's order.
zoo_choices() {
  zoo_columns "system	N	tau	m	w" | awk '$2 == 100000 && $4 + 0 > 0 { print $1, $3, $4, $5 }'
}

zoo_saturated_cases() {
  zoo_columns "system	N	tau	m	w	D2 band	D2" | awk '$2 == 100000 && $7 ~ /\]saturated$/ { print $1, $3, $4, $5, $6 }' | zoo_only
}

# zoo_only: the lines of standard input whose first word is a system ONLY (name,name; empty: all) selects.
zoo_only() {
  local name rest
  while read -r name rest; do
    if [[ -z ${ONLY:-} || ,$ONLY, == *,$name,* ]]; then echo "$name $rest"; fi
  done
}

zoo_band_cases() {
  local name
  while read -r name _ _ lo hi lam; do echo "$name $lo $hi $lam"; done < <(zoo_only < "$work/systems")
}

zoo_table_rows() {
  local name
  while read -r name _; do
    if [[ -f $work/rows.$name ]]; then sed 's/\t/ | /g; s/^/| /; s/$/ |/' "$work/rows.$name"; fi
  done < "$work/systems"
}

zoo_run_cases() {
  local start name rest
  start=$(date +%s)
  if [[ -n ${RESUME_FROM:-} && ! -d $RESUME_FROM ]]; then
    echo "RESUME_FROM=$RESUME_FROM is not a directory" >&2
    exit 2
  fi
  # The trap ends a case on Ctrl-C even where its loop would go on after a command that died of it.
  # shellcheck disable=SC2016  # expanded by the inner bash
  while read -r name rest; do
    if [[ -n ${RESUME_FROM:-} && -f $RESUME_FROM/rows.$name ]]; then
      cp "$RESUME_FROM/rows.$name" "$work/" && echo "$name" >> "$work/finished"
    else
      echo "$name $rest"
    fi
  done | xargs -r -P "$jobs" -L 1 bash -c 'trap "exit 130" INT TERM; case_rows "$@" && echo "$1" >> "$work/finished"' _
  # shellcheck disable=SC2034  # read by the scripts that source this file
  elapsed=$(($(date +%s) - start))
}

# zoo_keyed_summary FORMAT: one line per value of the rows' second column (a noise level, a sensor
# response), FORMAT (a printf format with one %s for that value) then the verdict counts of D2 and
# of the three lambda_1 estimators, and the systems with a wrong row.
zoo_keyed_summary() {
  cat "$work"/rows.* | awk -F'\t' -v format="$1" '{
      key = $2; rows[key]++; d[key, $8]++; r[key, $10]++; k[key, $12]++; l[key, $14]++
      if ($8 == "WRONG" || $10 == "WRONG" || $12 == "WRONG" || $14 == "WRONG") wrong[key] = wrong[key] " " $1
    } END {
      for (key in rows)
        printf format ": %d rows. D2: %d in band, %d unsure, %d wrong. lambda_1 by Rosenstein: %d / %d / %d; Kantz: %d / %d / %d; local maps: %d / %d / %d (in band / unsure / wrong). Systems with a wrong row:%s.\n",
          key, rows[key], d[key, "in_band"], d[key, "unsure"], d[key, "WRONG"], r[key, "in_band"], r[key, "unsure"], r[key, "WRONG"],
          k[key, "in_band"], k[key, "unsure"], k[key, "WRONG"], l[key, "in_band"], l[key, "unsure"], l[key, "WRONG"],
          (key in wrong ? wrong[key] : " none")
    }'
}

zoo_machine() {
  echo "$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores, $jobs jobs"
}

zoo_interrupted() {
  trap - INT TERM
  if [[ -s $work/systems ]]; then
    echo
    echo "Stopped before the end: the rows of the cases begun so far (a case that was running has only the rows it finished)."
    echo
    zoo_table_rows
    # The cases that finished (listed in $work/finished) are worth keeping; a running case's
    # partial rows file is left out, so that a resumed run measures it again.
    local kept name
    kept=$(mktemp -d)
    if [[ -f $work/finished ]]; then
      while read -r name; do cp "$work/rows.$name" "$kept"/; done < "$work/finished"
    fi
    echo "rows of the finished cases kept in $kept (RESUME_FROM=$kept goes on from there)" >&2
  fi
  exit 130
}
trap zoo_interrupted INT TERM

add_noise() {
  awk -v snr="$1" 'NR == FNR { x[NR] = $1; s += $1; n = NR; next }
    FNR == 1 { mean = s / n; for (i = 1; i <= n; ++i) q += (x[i] - mean)^2; sigma = sqrt(q / n) / 10^(snr / 20) }
    FNR <= n { printf "%.17g\n", x[FNR] + sigma * $1 }' "$2" "$3" > "$4"
}

export -f zoo_series add_noise
# shellcheck disable=SC2090
export chaos work zoo_verdicts
