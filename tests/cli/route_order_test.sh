#!/usr/bin/env bash
# The route as a graph of maps, end to end (docs/RESULTS.md, "A drive in another order"):
#  - route A (scenarios/bypass/teach.yaml) is taught in three maps: corridor, bypass, corridor;
#  - a drive along route B over the same world (scenarios/bypass/drive.yaml), recorded as a log,
#    starts mid-A in A's last map, goes back along A, skips A's bypass map and rejoins A's first
#    map; log-localize puts it in A's maps, seeds 1-3: it must start in map 2, switch 2 -> 1 -> 0,
#    and stay under 0.5 m on-route RMS in every mode and seed;
#  - an operator takeover (scenarios/bypass/takeover.yaml) drives the robot past the bypass and
#    hands it back on A's last map: every mode reaches the goal.
# Usage: route_order_test.sh <retrace binary> <source dir>
. "$(dirname "$0")/lib.sh" || exit 1
json() {  # json <file> <python expression over m>
  /usr/bin/python3 -c "import json,sys; m=json.load(open(sys.argv[1])); print($2)" "$1"
}

run teach teach "$src/scenarios/bypass/teach.yaml" --out "$tmp/a"
run drive teach "$src/scenarios/bypass/drive.yaml" --out "$tmp/b" --record-log "$tmp/log"
for mode in partial scan_matched consistent; do
  for seed in 1 2 3; do
    out="$tmp/loc_${mode}_$seed"
    run "localize_${mode}_$seed" log-localize "$tmp/log/teach.mcap" --teach "$tmp/a/$mode/teach" \
      --seed "$seed" --no-figures --out "$out"
    rms=$(json "$out/metrics.json" 'm["localization_error_on_route_m"]["rms"]')
    echo "$mode seed $seed: on-route RMS $rms m"
    check "$mode-$seed-rms" /usr/bin/python3 -c "import sys; sys.exit(0 if $rms < 0.5 else 1)"
    if [ "$mode" != consistent ]; then
      first=$(awk -F, 'NR == 2 {print $2}' "$out/est_map.csv")
      switches=$(grep -c map_switch "$out/events.csv")
      check "$mode-$seed-starts-in-map-2" [ "$first" = 2 ]
      check "$mode-$seed-switches" grep -q '2->1' "$out/events.csv"
      check "$mode-$seed-back-in-map-0" grep -q '1->0' "$out/events.csv"
      check "$mode-$seed-two-switches" [ "$switches" = 2 ]
    fi
  done
done

run takeover run "$src/scenarios/bypass/takeover.yaml" --repeats 1 --no-figures --no-report \
  --out "$tmp/takeover"
for mode in partial scan_matched consistent; do
  ok=$(json "$tmp/takeover/$mode/metrics.json" 'm["aggregate"]["success_rate"]')
  echo "takeover, $mode: success rate $ok"
  check "takeover-$mode" [ "$ok" = 1.0 ]
done
finish
