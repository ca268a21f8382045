#!/usr/bin/env bash
# lambda_1 answers of `chaos lyapunov` (every default) on the zoo's controls: noise, surrogates,
# random walks, periodic and quasi-periodic signals, noisy, quantised and short chaos. Noise,
# surrogates and random walks must get no confident lambda_1; periodic and quasi-periodic signals
# none either (their lambda_1 is 0); noisy chaos is printed beside lambda_1 of its system.
# A case that takes over 5 min is reported as such: on a random walk at N = 10^5 Kantz's neighbourhoods
# grow with the drift and the curve runs for 10^4 steps (the time bound is still missing).
# Usage: scripts/measure/lyapunov_controls.sh CHAOS_BINARY
set -euo pipefail
chaos=${1:?usage: lyapunov_controls.sh CHAOS_BINARY}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
printf 'case\tN\tdt\tvalue\tlow\thigh\tstatus\n'
for c in white_noise pink_noise brown_noise ar1 random_walk lorenz_iaaft henon_iaaft periodic_integer \
         periodic_rational periodic_irrational torus2 torus2_rational_first torus3 lorenz_snr10 lorenz_snr20 \
         henon_snr20 lorenz_quantised henon_quantised lorenz_short henon_short; do
  "$chaos" zoo --series "$c" --json > "$work/$c.json"
  python3 - "$work/$c.json" "$work/$c.txt" > "$work/$c.dt" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
values = next(v for k, v in j.items() if isinstance(v, list))
open(sys.argv[2], "w").write("\n".join(repr(v) for v in values) + "\n")
print(j["parameters"].get("dt") or "", len(values))
PY
  read -r dt n < "$work/$c.dt" || true
  if [[ -z "${n:-}" ]]; then n=$dt; dt=; fi
  if ! timeout 300 "$chaos" lyapunov "$work/$c.txt" -q --json ${dt:+--dt "$dt"} > "$work/$c.out" 2> "$work/$c.err"; then
    [[ -s "$work/$c.err" ]] || echo "no answer within 300 s" > "$work/$c.err"
    printf '%s\t%s\t%s\trefused: %s\n' "$c" "$n" "${dt:--}" "$(head -c 120 "$work/$c.err")"
    continue
  fi
  python3 -c '
import json, sys
a = json.load(open(sys.argv[1]))["lambda_1"] or {}
f = lambda x: "-" if x is None else "%.4g" % x
iv = a.get("interval") or [None, None]
print("\t".join([sys.argv[2], sys.argv[3], sys.argv[4] or "-", f(a.get("value")), f(iv[0]), f(iv[1]), str(a.get("status"))]))' "$work/$c.out" "$c" "$n" "$dt"
done
