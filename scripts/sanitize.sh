#!/usr/bin/env bash
# Builds the whole project with AddressSanitizer + UndefinedBehaviorSanitizer (preset
# `sanitize`, build/sanitize: RelWithDebInfo, no benchmarks, no Python module) and runs the
# whole test suite under them; any report fails the test that caused it. Extra arguments go to
# ctest (e.g. `-L scene` or `-R Resume` for a part). docs/robustness.md says how long it takes.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake --preset sanitize >/dev/null
cmake --build --preset sanitize -j "$(nproc)"
ctest --preset sanitize -j "$(nproc)" "$@"
