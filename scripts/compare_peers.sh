#!/usr/bin/env bash
# stiffsoft side by side with Bullet and MuJoCo (docs/peers.md), in one command: builds
# peer_bench if needed, runs every scene at h = 1/100, 1/240, 1/1000 with each engine compiled
# in (stiffsoft, stiffsoft-coarse, stiffsoft-sleep, bullet_mesh: Bullet on triangle meshes,
# bullet_mesh-awake: the same with Bullet's sleeping off, bullet: Bullet on convex hulls, mujoco,
# mujoco-cg: MuJoCo with its CG solver; --engines picks some), and writes the CSV, the Markdown table and the
# plot (ms/step vs bodies at h = 1/240).
#
#   scripts/compare_peers.sh                      # everything, 2 s simulated per run
#   scripts/compare_peers.sh --duration 0.5       # shorter runs (any peer_bench option passes through)
#   scripts/compare_peers.sh --scenes light,medium --dt 1/240
#
# Environment: BUILD_DIR (default build/release, the Release preset), OUT (default out/peers),
# THREADS (stiffsoft's threads, default: all cores). Needs libbullet-dev and/or libmujoco-dev
# (scripts/setup_bench.sh); without python3-matplotlib the plot is skipped with a message.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${BUILD_DIR:-build/release}
OUT=${OUT:-out/peers}
THREADS=${THREADS:-0}
mkdir -p "$OUT"
if [ "$BUILD_DIR" = build/release ]; then
  cmake --preset release >/dev/null
else
  cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
cmake --build "$BUILD_DIR" --target peer_bench -j "$(nproc)"
bench="$BUILD_DIR/bench/peer_bench"
[ -x "$bench" ] || { echo "compare_peers: $bench was not built (are Bullet/MuJoCo installed? scripts/setup_bench.sh)" >&2; exit 1; }
"$bench" --verify --scenes light,house_of_cards,wrecking_ball,chain_net | tee "$OUT/verify.txt"
"$bench" --threads "$THREADS" --csv "$OUT/peers.csv" "$@" | tee "$OUT/peers.log"
# Debian's python3 has python3-matplotlib; a python3 earlier on PATH may not.
PY=python3
[ -x /usr/bin/python3 ] && PY=/usr/bin/python3
"$PY" bench/peers/report_peers.py "$OUT/peers.csv" --markdown "$OUT/peers.md" --plot "$OUT/peers_h240.png"
echo "compare_peers: results in $OUT (peers.csv, peers.md, peers_h240.png)"
