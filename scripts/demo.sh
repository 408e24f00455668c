#!/usr/bin/env bash
# Quick start 1: install what is missing, build what the run needs (the `stiffsoft` program and
# the Python module, installed for Debian's python3), run the default scene into out/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh stiffsoft stiffsoft_python
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
$sudo cmake --install build/release --component python   # `import stiffsoft` (docs/python.md)
build/release/apps/stiffsoft run scenes/default.json -o out
build/release/apps/stiffsoft check out/default.pvd
echo
echo "Done. The frames are in out/: open out/default.pvd in ParaView (File > Open, Apply; colour by"
echo "velocity or contact_force); out/stats.csv has one row per step. From Python (docs/python.md):"
echo "  python3 examples/python/ball_on_boxes.py    # a soft ball on affine boxes: out/python/*.png and .pvd"
