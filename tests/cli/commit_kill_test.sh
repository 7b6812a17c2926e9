#!/usr/bin/env bash
# Issue 16, item 7: a results folder is replaced atomically. `retrace teach` replaces an old
# results folder with new results while a preloaded library (tests/support/kill_shim.cpp) kills
# it with SIGKILL just before its k-th rename or removal under the results folder, for every k
# the command makes. After each kill the results folder must be either the old one, byte for
# byte, or the new one, complete: every results file of an uninterrupted run. Figures are drawn
# from the published results after the swap (a rendering failure must not cost the numbers), so
# a kill while drawing leaves some missing; `retrace render` draws them again.
# Usage: commit_kill_test.sh <retrace binary> <source dir> <kill_shim.so>
cli_more_args=("<kill_shim.so>")
. "$(dirname "$0")/lib.sh" || exit 1
shim="$3"

teach() {  # teach <seed> <out>: a 12 m teaching drive of the small scenario, partial maps
  "$retrace" "${short_teach[@]}" --mode partial --seed "$1" --out "$2" >/dev/null 2>&1
}
listing() { (cd "$1" && find . -type f -not -path './figures/*' | sort); }
digest() { (cd "$1" && find . -type f -print0 | sort -z | xargs -0 md5sum); }

teach 1 "$tmp/old" || die "the old results could not be written"
teach 2 "$tmp/new" || die "the new results could not be written"
old_digest=$(digest "$tmp/old/partial")
new_listing=$(listing "$tmp/new/partial")

# How many renames and removals the replacement makes.
rm -rf "$tmp/res" && cp -a "$tmp/old" "$tmp/res"
RETRACE_KILL_MATCH="$tmp/res/" RETRACE_KILL_COUNT_FILE="$tmp/count" LD_PRELOAD="$shim" \
  teach 2 "$tmp/res" || die "the replacing run failed"
calls=$(cat "$tmp/count")
[ "$calls" -gt 2 ] || die "only $calls renames and removals seen: is the shim preloaded?"

old_seen=0 new_seen=0
for k in $(seq 1 "$calls"); do
  rm -rf "$tmp/res" && cp -a "$tmp/old" "$tmp/res"
  RETRACE_KILL_MATCH="$tmp/res/" RETRACE_KILL_AT="$k" LD_PRELOAD="$shim" teach 2 "$tmp/res"
  code=$?
  if [ "$code" -ne 137 ]; then
    failed "k=$k: exit $code, not killed"; continue
  fi
  if [ -d "$tmp/res/partial" ] && [ "$(digest "$tmp/res/partial")" = "$old_digest" ]; then
    old_seen=$((old_seen + 1)); passed
  elif [ -d "$tmp/res/partial" ] && [ "$(listing "$tmp/res/partial")" = "$new_listing" ]; then
    new_seen=$((new_seen + 1)); passed
  else
    failed "k=$k: the results folder is neither the old nor the new one:"
    ls -R "$tmp/res" | head -20
  fi
done
echo "$calls kill points: $old_seen left the old folder, $new_seen the new one"
[ "$old_seen" -gt 0 ] || failed "no kill point left the old folder"
[ "$new_seen" -gt 0 ] || failed "no kill point left the new folder"
finish "$calls kill points"
