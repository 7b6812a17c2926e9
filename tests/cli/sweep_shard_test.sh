#!/usr/bin/env bash
# `retrace sweep --shard i/N` and `retrace merge`: the merged shards give a results.csv
# byte-identical to the unsharded run's; merge refuses a missing, duplicated or incomplete
# shard and a shard of another sweep (exit 2, one line, nothing written).
# Usage: sweep_shard_test.sh <retrace binary> <source dir>
. "$(dirname "$0")/lib.sh" || exit 1
sweep="$src/tests/data/sweep_small.yaml"  # 8 short cases

run whole sweep "$sweep" --jobs 2 --out "$tmp/whole" --no-plot
for i in 1 2 3; do run "shard$i" sweep "$sweep" --jobs 1 --shard "$i/3" --out "$tmp/shard$i" --no-plot; done
[ "$(wc -l <"$tmp/shard3/results.csv")" -eq 3 ] || failed "shard 3/3 should hold cases 2 and 5"
run merge merge "$tmp/shard3" "$tmp/shard1" "$tmp/shard2" --out "$tmp/merged"
cmp "$tmp/whole/results.csv" "$tmp/merged/results.csv" || failed "merged shards differ from the unsharded run"
[ "$(wc -l <"$tmp/merged/timings.csv")" -eq 9 ] || failed "merged timings.csv has not 8 rows"
# The plot is made, or its absence explained (no off-screen context on this machine).
[ -s "$tmp/merged/sweep.png" ] || grep -q "no sweep.png" "$tmp/merge.err" || failed "no sweep.png and no warning"
# The merged folder is the unsharded sweep's: running it there finds every case done.
run again sweep "$sweep" --out "$tmp/merged" --no-plot
grep -q "(0 now, 8 before)" "$tmp/again.out" || failed "the merged folder was not taken as complete: $(cat "$tmp/again.out")"
cmp "$tmp/whole/results.csv" "$tmp/merged/results.csv" || failed "results.csv changed"

# Refused merges write nothing under $tmp: not their --out folder (nor its staging folder), not
# into a shard (into-shard's --out is one).
expect_bad missing "missing shard 2/3" merge "$tmp/shard1" "$tmp/shard3" --out "$tmp/m1"
cp -r "$tmp/shard2" "$tmp/shard2b"
expect_bad duplicated "shard 2/3 is given twice" merge "$tmp/shard1" "$tmp/shard2" "$tmp/shard2b" "$tmp/shard3" --out "$tmp/m2"
# A shard whose last case is missing (interrupted before it finished).
cp -r "$tmp/shard1" "$tmp/shard1cut"
head -n 2 "$tmp/shard1/results.csv" >"$tmp/shard1cut/results.csv"
expect_bad incomplete "shard 1/3 is incomplete: 1 of 3 cases done" merge "$tmp/shard1cut" "$tmp/shard2" "$tmp/shard3" --out "$tmp/m3"
run other sweep "$sweep" --jobs 1 --shard 2/3 --out "$tmp/other2" --no-plot --set limits.stall_time=30
expect_bad another "holds another sweep" merge "$tmp/shard1" "$tmp/other2" "$tmp/shard3" --out "$tmp/m4"
expect_bad split "the shards of one merge must split the sweep the same way" merge "$tmp/shard1" "$tmp/whole" --out "$tmp/m5"
expect_bad not-a-sweep "not a sweep results folder" merge "$tmp/shard1" "$src/scenarios" --out "$tmp/m6"
expect_bad into-shard "is one of the shard folders" merge "$tmp/shard1" "$tmp/shard2" "$tmp/shard3" --out "$tmp/shard2"

finish
