#!/usr/bin/env bash
# Issue 16, item 7: a results folder is replaced atomically. `retrace teach` replaces an old
# results folder with new results while a preloaded library (tests/support/kill_shim.cpp) kills
# it with SIGKILL just before its k-th rename or removal under the results folder, for every k
# the command makes. After each kill the results folder must be either the old one, byte for
# byte, or the new one, complete: every results file of an uninterrupted run. Figures are drawn
# from the published results after the swap (a rendering failure must not cost the numbers), so
# a kill while drawing leaves some missing; `retrace render` draws them again.
# Usage: commit_kill_test.sh <retrace binary> <source dir> <kill_shim.so>
set -uo pipefail
retrace="$1"
src="$2"
shim="$3"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

teach() {  # teach <seed> <out>: a 12 m teaching drive of the small scenario, partial maps
  "$retrace" teach "$src/scenarios/small.yaml" --mode partial --seed "$1" --out "$2" \
    --set 'route.points=[[1, 1], [9, 1], [9, 5]]' --set 'route.switch_points=[6]' >/dev/null 2>&1
}
listing() { (cd "$1" && find . -type f -not -path './figures/*' | sort); }
digest() { (cd "$1" && find . -type f -print0 | sort -z | xargs -0 md5sum); }

teach 1 "$tmp/old" || { echo "FAIL: the old results could not be written"; exit 1; }
teach 2 "$tmp/new" || { echo "FAIL: the new results could not be written"; exit 1; }
old_digest=$(digest "$tmp/old/partial")
new_listing=$(listing "$tmp/new/partial")

# How many renames and removals the replacement makes.
rm -rf "$tmp/res" && cp -a "$tmp/old" "$tmp/res"
RETRACE_KILL_MATCH="$tmp/res/" RETRACE_KILL_COUNT_FILE="$tmp/count" LD_PRELOAD="$shim" \
  teach 2 "$tmp/res" || { echo "FAIL: the replacing run failed"; exit 1; }
calls=$(cat "$tmp/count")
[ "$calls" -gt 2 ] || { echo "FAIL: only $calls renames and removals seen: is the shim preloaded?"; exit 1; }

pass=0 fail=0 old_seen=0 new_seen=0
for k in $(seq 1 "$calls"); do
  rm -rf "$tmp/res" && cp -a "$tmp/old" "$tmp/res"
  RETRACE_KILL_MATCH="$tmp/res/" RETRACE_KILL_AT="$k" LD_PRELOAD="$shim" teach 2 "$tmp/res"
  code=$?
  if [ "$code" -ne 137 ]; then
    fail=$((fail + 1)); echo "FAIL k=$k: exit $code, not killed"; continue
  fi
  if [ -d "$tmp/res/partial" ] && [ "$(digest "$tmp/res/partial")" = "$old_digest" ]; then
    old_seen=$((old_seen + 1)); pass=$((pass + 1))
  elif [ -d "$tmp/res/partial" ] && [ "$(listing "$tmp/res/partial")" = "$new_listing" ]; then
    new_seen=$((new_seen + 1)); pass=$((pass + 1))
  else
    fail=$((fail + 1))
    echo "FAIL k=$k: the results folder is neither the old nor the new one:"
    ls -R "$tmp/res" | head -20
  fi
done
echo "$calls kill points: $pass passed ($old_seen left the old folder, $new_seen the new one), $fail failed"
[ "$fail" -eq 0 ] && [ "$old_seen" -gt 0 ] && [ "$new_seen" -gt 0 ]
