#!/usr/bin/env bash
# The main job on its built-in default: install dependencies, build, and choose the delay, Theiler
# window and embedding dimension of a Lorenz x series, with the evidence for each choice.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j"$(nproc 2>/dev/null || echo 2)" --target chaos_cli > /dev/null
build/chaos/chaos analyze "$@"
