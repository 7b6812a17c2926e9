#!/usr/bin/env bash
# `retrace calibrate-lidar` on a recorded simulated drive: it writes a sim.lidar.noise block, the
# unknown cells' free path and the clutter's density, which log-simulate's --config takes as they
# are, with the figure beside them; and each bad input (a partial
# teach folder, a log the map does not cover, a fit that does not converge, no reference) prints
# exactly one line on stderr, exits with code 2 and writes neither the YAML nor the figure.
# Usage: calibrate_lidar_test.sh <retrace binary> <source dir>
. "$(dirname "$0")/lib.sh" || exit 1

# Every bad case: `retrace calibrate-lidar <args> --out $tmp/bad.yaml` (and nothing written: no
# bad.yaml, no bad.png).
bad_command=(calibrate-lidar)
bad_suffix=(--out "$tmp/bad.yaml")

# A recorded drive of the small scenario, shortened to 12 m, and its consistent and partial maps.
run record "${short_teach[@]}" --mode consistent,partial --out "$tmp/sim" --record-log "$tmp/logs"
mcap="$tmp/logs/teach.mcap"
consistent="$tmp/sim/consistent/teach"

# The good case: the block loads as log-simulate's --config.
if "$retrace" calibrate-lidar "$mcap" --teach "$consistent" --out "$tmp/noise.yaml" >"$tmp/stdout" 2>&1 &&
  grep -q '^      random_probability: ' "$tmp/noise.yaml" && [ -s "$tmp/noise.png" ] &&
  grep -q '^  unknown_free_path: ' "$tmp/noise.yaml" && grep -q '^  density: ' "$tmp/noise.yaml" &&
  grep -q '^simulated world: ' "$tmp/stdout" &&
  "$retrace" log-simulate "$mcap" --teach "$consistent" --config "$tmp/noise.yaml" \
    --out "$tmp/simulated.mcap" >/dev/null 2>&1; then
  passed
else
  failed "calibrate: the fit or its use by log-simulate --config failed:" "$tmp/stdout"
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

finish calibrate-lidar
