#!/usr/bin/env bash
# Runs every scene in scenes/ to its end into out/<scene>/ and checks its frames with
# `stiffsoft check`; prints one summary line per scene. A long study, not a test.
# Usage: bash scripts/run_all_scenes.sh [scene ...]   (needs a Release build: scripts/build.sh)
set -uo pipefail
cd "$(dirname "$0")/.."
bin=build/release/apps/stiffsoft
[ -x "$bin" ] || { echo "run_all_scenes: build first (bash scripts/build.sh)" >&2; exit 2; }
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=($(ls scenes/*.json | xargs -n1 basename | sed 's/\.json$//'))
status=0
mkdir -p out
printf '| scene | steps | unconverged steps | mean Newton it. | wall s | check |\n|---|---|---|---|---|---|\n'
for s in "${scenes[@]}"; do
  start=$(date +%s)
  "$bin" run "scenes/$s.json" -o "out/$s" > "out/$s.log" 2>&1 || true
  wall=$(( $(date +%s) - start ))
  if "$bin" check "out/$s/$s.pvd" >> "out/$s.log" 2>&1; then check=clean; else check=INTERSECTING; status=1; fi
  summary=$(awk -F, 'NR==1{for(i=1;i<=NF;i++) c[$i]=i; next} {n++; it+=$c["newton_iterations"]; if ($c["converged"]!=1) bad++} END{printf "%d | %d | %.2f", n, bad, it/n}' "out/$s/stats.csv")
  printf '| %s | %s | %d | %s |\n' "$s" "$summary" "$wall" "$check"
done
exit $status
