#!/usr/bin/env bash
# Installs, with apt, what the peer benchmark (bench/peers, scripts/compare_peers.sh) needs
# beyond scripts/setup.sh: Bullet and MuJoCo (both optional for the rest of the project) and
# matplotlib for the plot. Idempotent: a machine that has them all runs no apt command at all.
set -euo pipefail
packages=(libbullet-dev libmujoco-dev python3-matplotlib)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup_bench: all ${#packages[@]} packages present"
  exit 0
fi
echo "setup_bench: installing ${missing[*]}"
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
