#!/usr/bin/env bash
# Installs what is missing, builds, and runs the main job: the default scenario.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh
scripts/build.sh build
mkdir -p results/office
./build/retrace world worlds/office.yaml --route worlds/routes/office_loop.txt \
  --png results/office/world.png
