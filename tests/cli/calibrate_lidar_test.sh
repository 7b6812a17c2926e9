#!/usr/bin/env bash
# `retrace calibrate-lidar` on a recorded simulated drive: it writes a sim.lidar.noise block, the
# unknown cells' free path and the clutter's density, which log-simulate's --config takes as they
# are, with the figure beside them; and each bad input (a partial
# teach folder, a log the map does not cover, a fit that does not converge, no reference) prints
# exactly one line on stderr, exits with code 2 and writes neither the YAML nor the figure.
# Usage: calibrate_lidar_test.sh <retrace binary> <source dir>
set -uo pipefail
retrace="$1"
src="$2"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0
fail=0

expect_bad() {  # expect_bad <name> <expected substring> <args...>
  local name="$1" want="$2"
  shift 2
  "$retrace" calibrate-lidar "$@" --out "$tmp/bad.yaml" >"$tmp/stdout" 2>"$tmp/stderr"
  local code=$?
  local lines
  lines=$(wc -l <"$tmp/stderr")
  if [ "$code" -eq 2 ] && [ "$lines" -eq 1 ] && grep -qF -- "$want" "$tmp/stderr" &&
    [ ! -e "$tmp/bad.yaml" ] && [ ! -e "$tmp/bad.png" ]; then
    pass=$((pass + 1))
  else
    fail=$((fail + 1))
    echo "FAIL $name: exit $code, $lines stderr lines, wanted '$want':"
    cat "$tmp/stderr"
  fi
}

# A recorded drive of the small scenario, shortened to 12 m, and its consistent and partial maps.
"$retrace" teach "$src/scenarios/small.yaml" --mode consistent,partial --out "$tmp/sim" \
  --set 'route.points=[[1, 1], [9, 1], [9, 5]]' --set 'route.switch_points=[6]' \
  --record-log "$tmp/logs" >/dev/null 2>&1 || { echo "FAIL: could not record a log"; exit 1; }
mcap="$tmp/logs/teach.mcap"
consistent="$tmp/sim/consistent/teach"

# The good case: the block loads as log-simulate's --config.
if "$retrace" calibrate-lidar "$mcap" --teach "$consistent" --out "$tmp/noise.yaml" >"$tmp/stdout" 2>&1 &&
  grep -q '^      random_probability: ' "$tmp/noise.yaml" && [ -s "$tmp/noise.png" ] &&
  grep -q '^  unknown_free_path: ' "$tmp/noise.yaml" && grep -q '^  density: ' "$tmp/noise.yaml" &&
  grep -q '^simulated world: ' "$tmp/stdout" &&
  "$retrace" log-simulate "$mcap" --teach "$consistent" --config "$tmp/noise.yaml" \
    --out "$tmp/simulated.mcap" >/dev/null 2>&1; then
  pass=$((pass + 1))
else
  fail=$((fail + 1))
  echo "FAIL calibrate: the fit or its use by log-simulate --config failed:"
  cat "$tmp/stdout"
fi

# The reference moved 1 km away: no beam of the log has an expected range in the map.
awk '{ $2 = $2 + 1000; print }' "$consistent/gt.tum" >"$tmp/far.tum"
# The CARMEN log without its TRUEPOS lines: no reference.
gzip -dc "$tmp/logs/teach.log.gz" | grep -v '^TRUEPOS' >"$tmp/no_reference.log"
expect_bad partial "calibration needs a map that is the world" "$mcap" --teach "$tmp/sim/partial/teach"
expect_bad no_overlap "the map does not cover this part of the log" "$mcap" --teach "$consistent" \
  --reference "$tmp/far.tum"
expect_bad no_convergence "did not converge in 2 iterations" "$mcap" --teach "$consistent" \
  --max-iterations 2
expect_bad no_reference "no reference trajectory" "$tmp/no_reference.log" --teach "$consistent"
expect_bad window "--to: must be later than --from" "$mcap" --teach "$consistent" --from 5 --to 2
expect_bad band "clutter.band: must be wider than the corridor" "$mcap" --teach "$consistent" \
  --set clutter.band=0.2

echo "calibrate-lidar: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
