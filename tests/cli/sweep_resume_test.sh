#!/usr/bin/env bash
# `retrace sweep` killed with SIGKILL mid-sweep and started again with the same command loses no
# finished case and ends with a results.csv byte-identical to an uninterrupted run's (which
# uses one job where the interrupted one uses two).
# Usage: sweep_resume_test.sh <retrace binary> <source dir>
. "$(dirname "$0")/lib.sh" || exit 1
sweep="$src/tests/data/sweep_small.yaml"  # 8 short cases
rows() {  # complete data rows of the interrupted run's results.csv
  if [ -f "$tmp/run/results.csv" ]; then echo $(($(wc -l <"$tmp/run/results.csv") - 1)); else echo 0; fi
}

run ref sweep "$sweep" --jobs 1 --out "$tmp/ref" --no-plot
[ "$(wc -l <"$tmp/ref/results.csv")" -eq 9 ] || die "the reference has not 8 rows"

# (lib.sh's exit trap kills $bg_pid, should the test end while it runs)
"$retrace" sweep "$sweep" --jobs 2 --out "$tmp/run" --no-plot >/dev/null 2>&1 &
bg_pid=$!
while kill -0 "$bg_pid" 2>/dev/null && [ "$(rows)" -lt 2 ]; do sleep 0.01; done
kill -9 "$bg_pid" 2>/dev/null
wait "$bg_pid" 2>/dev/null
bg_pid=""
at_kill=$(rows)
[ "$at_kill" -ge 2 ] || die "only $at_kill rows before the kill"
echo "killed with $at_kill of 8 rows written"
# What a kill in the middle of an append leaves: half a row without its line break.
printf '7,3,1,2,120,fa' >>"$tmp/run/results.csv"

run resume sweep "$sweep" --jobs 2 --out "$tmp/run" --no-plot
grep -q "dropped a half-written last row" "$tmp/resume.err" || die "no warning about the partial row: $(cat "$tmp/resume.err")"
cmp "$tmp/ref/results.csv" "$tmp/run/results.csv" || die "the resumed results.csv differs from the uninterrupted one"
# Finished cases were kept, not run again.
before=$(sed -n 's/.* now, \([0-9]*\) before).*/\1/p' "$tmp/resume.out")
[ -n "$before" ] && [ "$before" -ge "$at_kill" ] || die "resume reran finished cases: $(cat "$tmp/resume.out")"
grep -q '"complete": true' "$tmp/run/sweep.json" || die "sweep.json does not say complete"
[ "$(wc -l <"$tmp/run/timings.csv")" -ge 7 ] || die "timings.csv lost rows"
echo "PASS (resumed with $before of 8 cases done)"
