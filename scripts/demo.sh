#!/usr/bin/env bash
# Quick start 1: install what is missing, build (Release), run the default scene into out/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
build/release/apps/stiffsoft run scenes/default.json -o out
build/release/apps/stiffsoft check out/default.pvd
