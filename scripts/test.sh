#!/usr/bin/env bash
# Installs what is missing, checks the include rules, then:
#  - a Release build (GCC, what users run) of the program, the micro benchmarks, the system
#    tests and the Python module; runs the system tests, the CI regression suite against its
#    committed baseline (navigation metrics gated, timing reported) and the Python module's tests;
#  - an AddressSanitizer + UndefinedBehaviorSanitizer build (Clang) of the program, the unit
#    and integration tests and the fuzz targets; runs the tests, then every fuzz target for
#    RETRACE_FUZZ_SECONDS (default 6) seconds, weighted by parser (scripts/fuzz.sh).
# Each test runs once, in the build where it pays. Prints how long each stage took.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)
start=$SECONDS
stage_start=$SECONDS
stage_names=()
stage_seconds=()
stage() {  # stage <title>: closes the previous stage's timing, opens the next
  if [ -n "${stage_name:-}" ]; then
    echo "== ${stage_name}: $((SECONDS - stage_start)) s"
    stage_names+=("$stage_name")
    stage_seconds+=("$((SECONDS - stage_start))")
  fi
  stage_name="$1"
  stage_start=$SECONDS
  [ -n "$1" ] && echo "== $1"
  return 0
}

stage "Packages and include rules"
scripts/install_deps.sh --test
scripts/check_includes.sh
scripts/check_function_length.py core io sim nav viz logs bench fuzz python

stage "Release build (program, micro benchmarks, system tests, Python module)"
# Unity builds (CMake batches of 8 files per translation unit): the heavy headers (GoogleTest,
# CLI11, Eigen, nlohmann-json, yaml-cpp) are parsed once per batch, not once per file.
# The Python module is built here only (docs/PYTHON.md): not under the sanitizers.
scripts/build.sh build -DRETRACE_WERROR=ON -DCMAKE_UNITY_BUILD=ON -DRETRACE_TEST_TIERS=system \
  -DRETRACE_PYTHON=ON

stage "System tests (Release)"
ctest --test-dir build --output-on-failure -j "$jobs" -L system

stage "Regression suite bench/suites/ci.yaml against results/baselines/ci.json; the docs' tables"
./build/retrace bench bench/suites/ci.yaml --jobs "$jobs"
# The docs' tables: every block names its command, and the suite's table equals this run of it.
scripts/results.py check --output ci-suite=results/bench/ci

stage "Python module tests (Release: pytest tests/python)"
# What ctest runs as python.pytest where the integration tier is built with the module.
PYTHONPATH=build/python /usr/bin/python3 -m pytest -q -p no:cacheprovider tests/python

stage "AddressSanitizer + UBSan build (Clang: program, unit and integration tests)"
# Clang, so that a second compiler's warnings are errors too, and because it builds the
# instrumented code 2.5 times faster than GCC; -O2, where the slow tests run a quarter faster
# than at -O1 for 7 % more build time; -g1 (line tables: what sanitizer stack traces print).
CC=clang CXX=clang++ scripts/build.sh build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" -DRETRACE_SANITIZE=ON \
  -DRETRACE_WERROR=ON -DRETRACE_BUILD_BENCHMARKS=OFF -DCMAKE_UNITY_BUILD=ON \
  -DRETRACE_TEST_TIERS="unit;integration" -DRETRACE_FUZZ=ON

stage "Unit and integration tests (AddressSanitizer + UBSan)"
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build-asan --output-on-failure -j "$jobs" -L 'unit|integration'

stage "Fuzzing: every parser's fuzz target, ${RETRACE_FUZZ_SECONDS:-6} s weighted by parser"
scripts/fuzz.sh build-asan "${RETRACE_FUZZ_SECONDS:-6}"

stage ""
# The stage table, as docs/BENCHMARKS.md "CI stages" keeps its history.
echo
echo "| stage | s |"
echo "|---|---|"
for i in "${!stage_names[@]}"; do echo "| ${stage_names[$i]} | ${stage_seconds[$i]} |"; done
echo "| **total** | **$((SECONDS - start))** |"
