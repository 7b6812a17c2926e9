#!/usr/bin/env bash
# Installs what is missing, builds, and runs the main job: the campus scenario in all four map
# modes (partial maps, scan-matched partial maps, one odometry map, a ground-truth map), writing
# results/campus/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh
scripts/build.sh build
mkdir -p results/campus
./build/retrace world worlds/campus.yaml --route worlds/routes/campus.txt --png results/campus/world.png
# Exit code 1 means a required mode (partial, consistent) did not succeed in every run: the
# results are still written; the summary says which.
./build/retrace run scenarios/campus.yaml --mode all --out results/campus "$@"
echo "results: $(pwd)/results/campus (metrics.json, trajectories and teach bundles per mode; comparison.json)"
