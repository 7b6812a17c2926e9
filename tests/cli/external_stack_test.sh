#!/usr/bin/env bash
# The stack interface is public and enough (docs/DESIGN.md §6): retrace's build is installed
# (`cmake --install`), examples/external_stack is configured against the installed package alone
# (find_package(retrace)), built, and run:
#  - its stack, `pure_pursuit`, drives the small scenario through `run`, scored like any other;
#  - its options are checked with the scenario: a value that is not a number is one clear line;
#  - with the built-in stack, the program built outside the tree drives the same runs to the bit
#    as the tree's `retrace`.
# Usage: external_stack_test.sh <retrace binary> <source dir> <retrace's build dir>
cli_more_args=("<build dir>")
. "$(dirname "$0")/lib.sh" || exit 1
build="$3"
compiler=$(sed -n 's/^CMAKE_CXX_COMPILER:[A-Z]*=//p' "$build/CMakeCache.txt")

cmake --install "$build" --prefix "$tmp/install" >"$tmp/install.log" 2>&1 ||
  die "cmake --install: $(cat "$tmp/install.log")"
cmake -S "$src/examples/external_stack" -B "$tmp/example" -DCMAKE_PREFIX_PATH="$tmp/install" \
  -DCMAKE_CXX_COMPILER="$compiler" >"$tmp/configure.log" 2>&1 ||
  die "configuring the example: $(cat "$tmp/configure.log")"
cmake --build "$tmp/example" >"$tmp/build.log" 2>&1 || die "building the example: $(cat "$tmp/build.log")"
check installed-program [ -x "$tmp/install/bin/retrace" ]
tree_retrace="$retrace"
retrace="$tmp/example/retrace_pure_pursuit"

small=(run "$src/scenarios/small.yaml" --mode partial --repeats 1 --no-figures --no-report)
run pure_pursuit "${small[@]}" --set playback.stack=pure_pursuit --out "$tmp/pp"
check pure-pursuit-named grep -q "playback stack: pure_pursuit" "$tmp/pure_pursuit.out"
check pure-pursuit-scored /usr/bin/python3 -c "
import json, sys
m = json.load(open(sys.argv[1]))
a = m['aggregate']
sys.exit(0 if a['runs'] == 1 and a['localization_error_m']['pooled']['rms'] < 1.0 else 1)" \
  "$tmp/pp/partial/metrics.json"

expect_bad option-not-a-number "playback.stack_options.speed: 'fast' is not a number" \
  "${small[@]}" --set playback.stack=pure_pursuit --set playback.stack_options.speed=fast \
  --out "$tmp/bad"
expect_bad option-undeclared "stack 'pure_pursuit' takes no option 'sped'" \
  "${small[@]}" --set playback.stack=pure_pursuit --set playback.stack_options.sped=1 \
  --out "$tmp/bad"

run outside "${small[@]}" --seed 3 --out "$tmp/outside"
"$tree_retrace" "${small[@]}" --seed 3 --out "$tmp/tree" >/dev/null 2>&1 || die "the tree's retrace"
for f in est.tum est_map.csv gt.tum odom.tum events.csv errors.csv; do
  check "same-$f" cmp -s "$tmp/outside/partial/runs/0/$f" "$tmp/tree/partial/runs/0/$f"
done
finish external_stack
