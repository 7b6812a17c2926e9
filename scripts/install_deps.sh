#!/usr/bin/env bash
# Installs the Debian 12 packages retrace needs, only if some are missing.
# Usage: install_deps.sh [--test]   (--test: also what the tests need beyond the build: pytest and
# matplotlib for the Python module's tests and the examples of docs/PYTHON.md; Chromium,
# which the system test tests/cli/report_browser_test.sh loads report.html in; junitparser and
# jsonschema for the system's Python, with which tests/cli/bench_ci_files_test.sh reads
# `retrace bench`'s JUnit and trend files; ROS 1's rosbag and message packages for the system's
# Python, the reference that tests/cli/ros1_bag_test.sh checks ROS 1 bags against and that
# scripts/fuzz.sh writes the ROS 1 bag seeds with)
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libbox2d-dev libeigen3-dev libyaml-cpp-dev libopencv-dev libpng-dev
  nlohmann-json3-dev libcli11-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libosmesa6-dev
  zlib1g-dev liblz4-dev libzstd-dev libbz2-dev libsqlite3-dev
  clang libclang-rt-dev lld
  pybind11-dev python3-dev python3-numpy
)
for arg in "$@"; do
  case "$arg" in
    --test)
      packages+=(python3-pytest python3-matplotlib
                 chromium python3-junitparser python3-jsonschema python3-rosbag python3-sensor-msgs
                 python3-nav-msgs python3-tf2-msgs python3-geometry-msgs)
      ;;
    *) echo "install_deps.sh: unknown argument '$arg' (usage: install_deps.sh [--test])" >&2; exit 2 ;;
  esac
done

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "Installing: ${missing[*]}"
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
