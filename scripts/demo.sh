#!/usr/bin/env bash
# Quick start 1, from nothing to a picture: install what is missing, build only what the run
# needs (the library and the `stiffsoft` program, Release, build/release), run the hybrid
# default scene into out/default, check every frame for intersections, render pictures, and say
# where to look. `bash scripts/demo.sh --python` then also builds and installs the Python module
# (docs/python.md; a few more minutes).
set -euo pipefail
cd "$(dirname "$0")/.."
python=0
for arg in "$@"; do
  case "$arg" in
    --python) python=1 ;;
    *) echo "usage: bash scripts/demo.sh [--python]" >&2; exit 2 ;;
  esac
done
start=$(date +%s)
stage() {
  local now
  now=$(date +%s)
  printf '\n== [%s] %s  (%d min %02d s so far)\n' "$1" "$2" $(((now - start) / 60)) $(((now - start) % 60))
}

stage "1/5" "Debian packages (scripts/setup.sh; on a fresh Debian 12 a few hundred packages, minutes)"
bash scripts/setup.sh
stage "2/5" "building the library and the stiffsoft program (151 steps cold, about 6 minutes on 2 cores, the longest stage; [done/total] counts them)"
bash scripts/build.sh stiffsoft
stiffsoft=build/release/apps/stiffsoft
out=out/default
stage "3/5" "running scenes/default.json into $out (soft ball and block, affine boxes, a ramp; seconds)"
$stiffsoft run scenes/default.json -o "$out"
stage "4/5" "checking every frame for intersecting triangles"
$stiffsoft check "$out/default.pvd"
stage "5/5" "rendering the frames to pictures (off screen, under a minute)"
$stiffsoft render "$out/default.pvd" -o "$out/png" --mp4
if [ "$python" = 1 ]; then
  stage "+" "building and installing the Python module (docs/python.md)"
  bash scripts/build.sh stiffsoft_python
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo cmake --install build/release --component python   # `import stiffsoft` in Debian's python3
fi
end=$(date +%s)
cat <<DONE

Done in $(((end - start) / 60)) min $(((end - start) % 60)) s. Where to look:
  $out/png/default_sheet.png        six frames side by side (open it in any image viewer)
  $out/png/default_NNNNNN.png       every frame$(command -v ffmpeg > /dev/null && echo "; $out/png/default.mp4, the movie")
  $out/default.paraview.py          ParaView, coloured and ready: paraview --script=$out/default.paraview.py
                                    (soft bodies by von Mises stress, affine bodies by speed, contact forces as arrows)
  $out/default.pvd                  the frames themselves (VTK), for ParaView or VTK
  $out/stats.csv                    one row per step: Newton iterations, contacts, energies, timings
Next: build/release/apps/stiffsoft run scenes/mixed_pile.json -o out/mixed_pile (README "Scenes"),
      then stiffsoft render out/mixed_pile/mixed_pile.pvd -o out/mixed_pile/png.
DONE
[ "$python" = 1 ] && echo "Python: python3 examples/python/ball_on_boxes.py (docs/python.md)" || echo "Python: bash scripts/demo.sh --python builds and installs the module (docs/python.md)"
