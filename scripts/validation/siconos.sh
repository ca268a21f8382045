#!/usr/bin/env bash
# Our free Flores-Leine-Glocker scene beside the same mechanism in Siconos (validation tier: it
# installs Siconos's Python package, which nothing else in the project uses or links).
# Usage: scripts/validation/siconos.sh [build-dir] [out-dir] [--duration S] [--siconos-step H] [--cases a,b]
#        scripts/validation/siconos.sh [build-dir] [out-dir] --driven [--revolutions N] [--cases e0.9] [--crank-speed W] [--stiffness K]
#        scripts/validation/siconos.sh [build-dir] [out-dir] --contact-scan --duration 1
# Writes out-dir/summary.tsv and out-dir/siconos_comparison.png, or with --driven
# out-dir/driven_summary.tsv and driven_phases.tsv (docs/validation/mechanism/siconos.md).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build}
out=${2:-$build/siconos}
shift $(( $# > 2 ? 2 : $# ))
py=/usr/bin/python3
if ! "$py" -c 'import siconos.kernel' 2> /dev/null; then
  echo "siconos.sh: installing python3-siconos (Debian 12: Siconos 4.4)" >&2
  if [[ $(id -u) -eq 0 ]]; then
    DEBIAN_FRONTEND=noninteractive apt-get install -y python3-siconos > /dev/null
  elif command -v sudo > /dev/null; then
    sudo DEBIAN_FRONTEND=noninteractive apt-get install -y python3-siconos > /dev/null
  else
    echo "siconos.sh: python3-siconos is missing and this user cannot install it (root or sudo needed)" >&2
    exit 2
  fi
fi
"$py" -c 'import matplotlib, numpy' 2> /dev/null || {
  echo "siconos.sh: needs numpy and matplotlib for /usr/bin/python3 (apt-get install python3-matplotlib)" >&2
  exit 2
}
[[ -x $build/mechanism/mechanism ]] || { echo "siconos.sh: build the mechanism command first ($build/mechanism/mechanism)" >&2; exit 2; }
command -v cc > /dev/null || { echo "siconos.sh: needs a C compiler (cc) for the Siconos model's plugins" >&2; exit 2; }
"$py" "$root/scripts/validation/siconos_compare.py" "$build/mechanism/mechanism" "$out" "$@"
