#!/usr/bin/env bash
# `retrace sweep --shard i/N` and `retrace merge`: the merged shards give a results.csv
# byte-identical to the unsharded run's; merge refuses a missing, duplicated or incomplete
# shard and a shard of another sweep (exit 2, one line, nothing written).
# Usage: sweep_shard_test.sh <retrace binary> <source dir>
set -uo pipefail
retrace="$1"
src="$2"
sweep="$src/tests/data/sweep_small.yaml"  # 8 short cases
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}
run() {  # run <name> <args...>: must exit 0
  local name="$1"
  shift
  "$retrace" "$@" >"$tmp/$name.out" 2>"$tmp/$name.err" || { echo "FAIL: $name: $(cat "$tmp/$name.err")"; exit 1; }
}
expect_bad() {  # expect_bad <name> <expected substring> <folder that must not appear> <args...>
  local name="$1" want="$2" absent="$3"
  shift 3
  "$retrace" "$@" >"$tmp/$name.out" 2>"$tmp/$name.err"
  local code=$?
  local lines
  lines=$(wc -l <"$tmp/$name.err")
  if [ "$code" -ne 2 ] || [ "$lines" -ne 1 ] || ! grep -qF -- "$want" "$tmp/$name.err" || [ -e "$absent" ]; then
    fail "$name: exit $code, $lines stderr lines, wanted '$want': $(cat "$tmp/$name.err")"
  fi
}

run whole sweep "$sweep" --jobs 2 --out "$tmp/whole" --no-plot
for i in 1 2 3; do run "shard$i" sweep "$sweep" --jobs 1 --shard "$i/3" --out "$tmp/shard$i" --no-plot; done
[ "$(wc -l <"$tmp/shard3/results.csv")" -eq 3 ] || fail "shard 3/3 should hold cases 2 and 5"
run merge merge "$tmp/shard3" "$tmp/shard1" "$tmp/shard2" --out "$tmp/merged"
cmp "$tmp/whole/results.csv" "$tmp/merged/results.csv" || fail "merged shards differ from the unsharded run"
[ "$(wc -l <"$tmp/merged/timings.csv")" -eq 9 ] || fail "merged timings.csv has not 8 rows"
# The plot is made, or its absence explained (no off-screen context on this machine).
[ -s "$tmp/merged/sweep.png" ] || grep -q "no sweep.png" "$tmp/merge.err" || fail "no sweep.png and no warning"
# The merged folder is the unsharded sweep's: running it there finds every case done.
run again sweep "$sweep" --out "$tmp/merged" --no-plot
grep -q "(0 now, 8 before)" "$tmp/again.out" || fail "the merged folder was not taken as complete: $(cat "$tmp/again.out")"
cmp "$tmp/whole/results.csv" "$tmp/merged/results.csv" || fail "results.csv changed"

expect_bad missing "missing shard 2/3" "$tmp/m1" merge "$tmp/shard1" "$tmp/shard3" --out "$tmp/m1"
cp -r "$tmp/shard2" "$tmp/shard2b"
expect_bad duplicated "shard 2/3 is given twice" "$tmp/m2" merge "$tmp/shard1" "$tmp/shard2" "$tmp/shard2b" "$tmp/shard3" --out "$tmp/m2"
# A shard whose last case is missing (interrupted before it finished).
cp -r "$tmp/shard1" "$tmp/shard1cut"
head -n 2 "$tmp/shard1/results.csv" >"$tmp/shard1cut/results.csv"
expect_bad incomplete "shard 1/3 is incomplete: 1 of 3 cases done" "$tmp/m3" merge "$tmp/shard1cut" "$tmp/shard2" "$tmp/shard3" --out "$tmp/m3"
run other sweep "$sweep" --jobs 1 --shard 2/3 --out "$tmp/other2" --no-plot --set limits.stall_time=30
expect_bad another "holds another sweep" "$tmp/m4" merge "$tmp/shard1" "$tmp/other2" "$tmp/shard3" --out "$tmp/m4"
expect_bad split "the shards of one merge must split the sweep the same way" "$tmp/m5" merge "$tmp/shard1" "$tmp/whole" --out "$tmp/m5"
expect_bad not-a-sweep "not a sweep results folder" "$tmp/m6" merge "$tmp/shard1" "$src/scenarios" --out "$tmp/m6"
expect_bad into-shard "is one of the shard folders" "$tmp/none" merge "$tmp/shard1" "$tmp/shard2" "$tmp/shard3" --out "$tmp/shard2"

if [ "$failures" -ne 0 ]; then
  echo "$failures failures"
  exit 1
fi
echo "PASS"
