#!/usr/bin/env bash
# Configures and builds the Release preset (build/release): every target, or only the targets
# given (e.g. `bash scripts/build.sh stiffsoft stiffsoft_python`).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --preset release >/dev/null
targets=()
for t in "$@"; do targets+=(--target "$t"); done
cmake --build --preset release -j "$(nproc)" "${targets[@]}"
