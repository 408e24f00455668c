#!/usr/bin/env bash
# Quick start 2: install what is missing, build (Release), run the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
# ParaView's pvbatch, unpacked aside, for the test of the ParaView script (it skips without one).
bash scripts/paraview_aside.sh || echo "test: no ParaView aside; ParaViewScript.OpensTheRunColouredInPvbatch will skip"
ctest --preset release -j "$(nproc)"
