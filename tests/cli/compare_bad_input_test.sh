#!/usr/bin/env bash
# `retrace compare` on bad input: each case must print exactly one line on stderr that names the
# problem, exit with code 2 and leave no output folder (nor its staging folder) behind.
# Usage: compare_bad_input_test.sh <retrace binary> <source dir>
set -uo pipefail
retrace="$1"
src="$2"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
small="$src/scenarios/small.yaml"
pass=0
fail=0

expect_bad() {  # expect_bad <name> <expected substring> <compare args...>
  local name="$1" want="$2"
  shift 2
  "$retrace" compare "$@" --out "$tmp/study" >"$tmp/stdout" 2>"$tmp/stderr"
  local code=$?
  local lines
  lines=$(wc -l <"$tmp/stderr")
  if [ "$code" -eq 2 ] && [ "$lines" -eq 1 ] && grep -qF -- "$want" "$tmp/stderr" &&
    [ ! -e "$tmp/study" ] && [ ! -e "$tmp/study.tmp" ] && [ ! -s "$tmp/stdout" ]; then
    pass=$((pass + 1))
  else
    fail=$((fail + 1))
    echo "FAIL $name: exit $code, $lines stderr lines, wanted '$want':"
    cat "$tmp/stderr"
  fi
}

expect_bad unknown-mode "--modes: unknown mode 'perfect'" "$small" --modes partial,perfect --seeds 2
expect_bad one-mode "--modes: a comparison needs at least two modes" "$small" --modes partial --reference partial
expect_bad twice "--modes: mode 'partial' is given twice" "$small" --modes partial,partial,consistent
expect_bad all-in-a-list "--modes: all means every mode; give it alone" "$small" --modes partial,all --seeds 2
expect_bad reference-missing "--reference: mode 'consistent' is not among the compared modes" "$small" --modes partial,single
expect_bad reference-unknown "--reference: unknown mode 'slam'" "$small" --reference slam
expect_bad one-seed "--seeds: at least 2 seeds are needed for a confidence interval, got 1" "$small" --seeds 1
expect_bad seeds-not-a-number "--seeds" "$small" --seeds many
expect_bad zero-repeats "--repeats" "$small" --repeats 0
expect_bad unknown-set-key "particle" "$small" --set nav.localizer.particle=100
expect_bad bad-set-syntax "--set expects key.path=value" "$small" --set nonsense
expect_bad online-no-switching "\`online\` switching needs a map mode that switches maps" "$small" --modes single,consistent --set route.switch_points=online --seeds 2
expect_bad missing-scenario "missing.yaml" "$tmp/missing.yaml"

# An output folder that cannot be created fails before any run (the staging folder comes first).
"$retrace" compare "$small" --seeds 2 --out /proc/retrace/study >"$tmp/stdout" 2>"$tmp/stderr"
code=$?
if [ "$code" -eq 2 ] && [ "$(wc -l <"$tmp/stderr")" -eq 1 ] && grep -qF "/proc/retrace/study.tmp" "$tmp/stderr"; then
  pass=$((pass + 1))
else
  fail=$((fail + 1))
  echo "FAIL unwritable-output: exit $code:"
  cat "$tmp/stderr"
fi

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
