#!/usr/bin/env bash
# Builds the project with AddressSanitizer + UndefinedBehaviorSanitizer (preset `sanitize`,
# build/sanitize: RelWithDebInfo, no benchmarks, no Python module) and runs the test suite under
# them; any report fails the test that caused it. docs/robustness.md says how long it takes.
#   bash scripts/sanitize.sh [ctest args]   the whole suite (e.g. `-L scene` or `-R Resume` for a part)
#   bash scripts/sanitize.sh --fast         only the abd and fem libraries and their tests (CI: ~10 min)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake --preset sanitize >/dev/null
if [ "${1:-}" = "--fast" ]; then
  cmake --build --preset sanitize -j "$(nproc)" --target abd_tests --target fem_tests
  ctest --preset sanitize -j "$(nproc)" -L '^(abd|fem)$'
  exit
fi
cmake --build --preset sanitize -j "$(nproc)"
ctest --preset sanitize -j "$(nproc)" "$@"
