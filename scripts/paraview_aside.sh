#!/usr/bin/env bash
# Unpacks Debian's ParaView 5.11 (paraview + python3-paraview) into build/paraview-aside without
# installing it: python3-paraview conflicts with python3-vtk9, which libvtk9-dev (a build
# dependency) needs. Gives build/paraview-aside/pvbatch and pvpython, wrappers that run the
# unpacked programs with their own Python modules, e.g.
#   build/paraview-aside/pvbatch out/default/default.paraview.py --screenshot last.png
# (under `xvfb-run -a` where there is no display). The tests use it when it is there
# (tests/apps/paraview_script_test.cpp). About 73 MB downloaded, 400 MB unpacked.
set -euo pipefail
cd "$(dirname "$0")/.."
dest=build/paraview-aside
if [ -x "$dest/pvbatch" ] && [ -x "$dest/root/usr/bin/pvbatch" ]; then
  echo "paraview-aside: already in $dest"
  exit 0
fi
mkdir -p "$dest/debs"
(cd "$dest/debs" && apt-get download paraview python3-paraview)
rm -rf "$dest/root"
for deb in "$dest"/debs/*.deb; do dpkg -x "$deb" "$dest/root"; done
for tool in pvbatch pvpython; do
  cat > "$dest/$tool" <<WRAP
#!/bin/sh
# $tool of Debian's ParaView 5.11, unpacked aside by scripts/paraview_aside.sh.
here=\$(dirname "\$(readlink -f "\$0")")
PYTHONPATH="\$here/root/usr/lib/python3/dist-packages\${PYTHONPATH:+:\$PYTHONPATH}" exec "\$here/root/usr/bin/$tool" "\$@"
WRAP
  chmod +x "$dest/$tool"
done
rm -rf "$dest/debs"
echo "paraview-aside: $dest/pvbatch and $dest/pvpython ($("$dest/root/usr/bin/pvbatch" --version 2>/dev/null | head -1 || true))"
