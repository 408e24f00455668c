#!/usr/bin/env bash
# Quick start 2: install what is missing, build (Release), run the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
ctest --preset release -j "$(nproc)"
