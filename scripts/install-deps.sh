#!/usr/bin/env bash
# Installs the Debian 12 packages the project builds with. Runs as root (or through sudo).
set -euo pipefail
packages=(
  g++ cmake make ninja-build pkg-config
  libeigen3-dev libfftw3-dev libboost-dev
  libcli11-dev nlohmann-json3-dev libtomlplusplus-dev libnanoflann-dev
  libgtest-dev libbenchmark-dev
  jq gnuplot-nox
  libopenmpi-dev openmpi-bin
  pybind11-dev python3-dev python3-numpy python3-pytest python3-matplotlib
  python3-setuptools python3-wheel python3-venv python3-pip
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [[ ${#missing[@]} -eq 0 ]]; then exit 0; fi
sudo_cmd=()
[[ $(id -u) -eq 0 ]] || sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
