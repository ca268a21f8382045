#!/usr/bin/env bash
# A measured rule, not adopted (docs/notes/zoo-notes.md section 4): lambda_1 on the zoo's chaotic series at
# N = 10^5 where the autocorrelation has no minimum (so `chaos lyapunov` uses no period), run again
# with the secant's period taken from the mean spacing of the series' local maxima
# (x[i-1] < x[i] >= x[i+1]; first to last maximum over their count minus one), when that is at least
# MIN_PERIOD samples. Both runs use the cross-check (Rosenstein and Kantz must agree within 10%), with
# each series' tau, m and w from the automatic-choice rows of docs/validation/zoo.md, as in the zoo.
#
# Prints two Markdown tables: the systems that get a period from the maxima, with lambda_1 without and
# with it against the band lambda_1 +- 10% from the equations, and totals over all systems; then, for
# every flow, how many e-folds of Rosenstein's divergence curve (with the period used) have a local
# slope within 10% of lambda_1 (the automatic fit needs a stretch rising by 2 e-folds whose slopes
# agree within 10%). The neighbourhood grid and the controls are not run here: the full zoo with the
# rule built in gave them (zoo-notes section 4).
# Usage: scripts/measure/measure_lyapunov_period.sh [build-dir]
# Environment: ONLY (comma list of zoo system names; default all), JOBS (2), MIN_PERIOD (10).
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
chaos="$build/chaos/chaos"
[[ -x $chaos ]] || { echo "build $chaos first: cmake --build $build" >&2; exit 2; }
command -v jq > /dev/null || { echo "jq is needed" >&2; exit 2; }
jobs=${JOBS:-2}
min_period=${MIN_PERIOD:-10}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# name tau m w lambda_1, from the chaotic rows at N = 10^5 that the pipeline analysed (m > 0)
source scripts/measure/zoo_columns.sh
zoo_columns "system	N	tau	m	w	lambda_1 eq." | awk '$2 == 100000 && $4 + 0 > 0 { print $1, $3, $4, $5, $6 }' > "$work/systems"
[[ -s $work/systems ]] || { echo "no automatic-choice rows found in docs/validation/zoo.md" >&2; exit 3; }

measure() {  # name tau m w lambda_1
  local name=$1 tau=$2 m=$3 w=$4 json dt
  json="$work/$name.json"
  "$chaos" zoo --series "$name" --json > "$json"
  jq -r '.x[]' "$json" > "$work/$name.dat"
  dt=$(jq -r '.parameters.dt // empty' "$json")
  local common=("$work/$name.dat" -d "$tau" -m "$m" -t "$w" ${dt:+--dt $dt} --reference-points 10000 -q --json)
  "$chaos" lyapunov "${common[@]}" > "$work/$name.none.json"
  local period
  period=$(awk 'NR > 2 && b > a && b >= $1 { if (count++ == 0) first = NR - 1; last = NR - 1 }
                { a = b; b = $1 }
                END { p = count >= 3 ? (last - first) / (count - 1) : 0; printf "%d", p + 0.5 }' "$work/$name.dat")
  if [[ $(jq -r '.parameters.period' "$work/$name.none.json") == 0 && $period -ge $min_period ]]; then
    "$chaos" lyapunov "${common[@]}" --period "$period" > "$work/$name.rule.json"
  else
    cp "$work/$name.none.json" "$work/$name.rule.json"
  fi
  echo "$*" > "$work/$name.row"
}
export -f measure
export chaos work min_period

while read -r name tau m w lam; do
  [[ -z ${ONLY:-} || ,$ONLY, == *,$name,* ]] && echo "$name $tau $m $w $lam"
done < "$work/systems" | xargs -P "$jobs" -L 1 bash -c 'measure "$@"' _

python3 - "$work" <<'EOF'
import glob, json, os, sys
work = sys.argv[1]
rows = [open(f).read().split() for f in sorted(glob.glob(os.path.join(work, '*.row')))]
def judge(d, lam):
    """Rosenstein's and Kantz's confident values, and whether one is in band / how many are not."""
    cc = d['cross_check']
    r = d['lambda'] if d['status'] == 'linear_region' else None
    k = cc.get('lambda') if cc['status'] == 'linear_region' and d['status'] == 'linear_region' else None
    values = [v for v in (r, k) if v is not None]
    inside = [v for v in values if abs(v - lam) <= 0.1 * lam]
    return r, k, bool(inside), len(values) - len(inside)
fmt = lambda v: '-' if v is None else f'{v:.4g}'
def cell(d, lam):
    r, k, covered, wrong = judge(d, lam)
    return (f"{fmt(r)} ({d['status']}), {fmt(k)} ({d['cross_check']['status']})"
            + (' in band' if covered else '') + (' **WRONG**' if wrong else ''))
print('| system | tau, m, w | period from the maxima | no period: Rosenstein, Kantz | with it: Rosenstein, Kantz | lambda_1 (eq.) |')
print('|---|---|---|---|---|---|')
totals = {'without': [0, 0], 'with': [0, 0]}
efolds = []
for name, tau, m, w, lam in rows:
    lam = float(lam)
    rule = json.load(open(os.path.join(work, name + '.rule.json')))
    none = json.load(open(os.path.join(work, name + '.none.json')))
    if rule['parameters']['period'] == none['parameters']['period']: rule = none
    for key, d in (('without', none), ('with', rule)):
        _, _, covered, wrong = judge(d, lam)
        totals[key][0] += covered; totals[key][1] += wrong
    if none is not rule:
        print(f"| {name} | {tau}, {m}, {w} | {rule['parameters']['period']} | {cell(none, lam)} | {cell(rule, lam)} | {lam:.4g} |")
    dt = rule['parameters'].get('dt')
    if dt:
        dv, ls = rule['divergence'], rule['local_slope']
        within = sum(dv[k] - dv[k - 1] for k in range(1, len(dv))
                     if ls[k] is not None and abs(ls[k] / dt / lam - 1) <= 0.1)
        efolds.append((name, rule['parameters']['period'], dv[0], max(dv), within))
print()
for key, (covered, wrong) in totals.items():
    print(f'- {key} the maxima period: {covered} of {len(rows)} systems with a confident lambda_1 in band, '
          f'{wrong} confident values out of band')
print()
print('| flow | period | ln d at step 0 | largest ln d | e-folds with a Rosenstein local slope within 10% of lambda_1 |')
print('|---|---|---|---|---|')
for name, period, d0, top, within in efolds:
    print(f'| {name} | {period or "-"} | {d0:.2f} | {top:.2f} | {within:.2f} |')
EOF
