#!/usr/bin/env bash
# ROS 1 bags against the reference, Debian's python3-rosbag (tests/cli/ros1_bags.py):
#   1. bags rosbag writes (LaserScan, Odometry, tf and PoseStamped in uncompressed, bz2 and lz4
#      chunks; MultiEchoLaserScan, tf/tfMessage and PoseWithCovarianceStamped; chunks stored out
#      of time order; a recording cut off) are read by retrace field for field as rosbag reads
#      them (retrace_log_dump's decoded messages against rosbag's; the cut recording against what
#      rosbag reads of it once reindexed, and with retrace's note);
#   2. a bag retrace writes (`retrace run --record-log`) is read by rosbag field for field as
#      retrace reads it, every connection's md5sum that of its definition and of the installed
#      type;
#   3. the log commands take the bag: log-info describes a bag without scans (topics, types,
#      counts) and refuses another definition of LaserScan in one line; log-teach, log-localize,
#      log-simulate and calibrate-lidar run on the recorded drive's bag as on its MCAP file, and
#      log-localize gives the same metrics on both.
# Each reader is first shown a broken file, to prove it refuses one. The missing packages are a
# failure, not a skip: CI installs them (scripts/install_deps.sh --test).
# Usage: ros1_bag_test.sh <retrace binary> <source dir> <retrace_log_dump binary>
cli_more_args=("<retrace_log_dump binary>")
. "$(dirname "$0")/lib.sh" || exit 1
dump="$3"
# The system's Python, where Debian's packages are (a `python3` on PATH may be another one).
py=/usr/bin/python3
ref="$src/tests/cli/ros1_bags.py"
"$py" -c 'import rosbag, sensor_msgs.msg, nav_msgs.msg, tf2_msgs.msg, geometry_msgs.msg' 2>/dev/null ||
  die "python3-rosbag and the message packages are not installed (scripts/install_deps.sh --test installs them)"

mkdir "$tmp/ref"
"$py" "$ref" write "$tmp/ref" || die "ros1_bags.py write failed"
# Each reader is first shown a broken file: bags cut short (their index gone), and garbage.
run record "${short_teach[@]}" --mode partial --out "$tmp/sim" --record-log "$tmp/logs"
bag="$tmp/logs/teach.bag"
head -c 30000 "$tmp/ref/drive_none.bag" >"$tmp/broken.bag"
head -c $(($(stat -c %s "$bag") / 2)) "$bag" >"$tmp/half.bag"
printf '#ROSBAG V2.0\n\x10\x00\x00\x00garbage' >"$tmp/garbage.bag"
check "rosbag refuses broken bags" "$py" "$ref" refuses "$tmp/broken.bag" "$tmp/half.bag" "$tmp/garbage.bag"
for broken in broken half garbage; do
  if "$dump" "$tmp/$broken.bag" >/dev/null 2>"$tmp/err" || [ "$(grep -c '' "$tmp/err")" -ne 1 ]; then
    failed "retrace reads $broken.bag, or not in one line:" "$tmp/err"
  else
    passed
  fi
done

# 1. Bags rosbag writes, read by retrace; 2. the bag retrace wrote, read by rosbag. Each
# retrace_log_dump output is compared with rosbag's reading of the bag (the cut recording with
# what rosbag reads of it once reindexed), in one Python process.
pairs=()
for name in drive_none drive_bz2 drive_lz4 other_types out_of_order no_scan cut; do
  "$dump" "$tmp/ref/$name.bag" >"$tmp/$name.jsonl" 2>"$tmp/$name.err" ||
    die "retrace_log_dump $name.bag: $(cat "$tmp/$name.err")"
  pairs+=("$tmp/ref/$name.bag" "$tmp/$name.jsonl")
done
"$py" "$ref" reindex "$tmp/ref/cut.bag" "$tmp/reindexed.bag" || die "rosbag reindex failed"
pairs[-2]="$tmp/reindexed.bag"
"$dump" "$bag" >"$tmp/recorded.jsonl" 2>"$tmp/recorded.err" || die "retrace_log_dump teach.bag: $(cat "$tmp/recorded.err")"
pairs+=("$bag" "$tmp/recorded.jsonl")
"$py" "$ref" compare "${pairs[@]}" >"$tmp/compare.txt" 2>&1
for ((i = 0; i < ${#pairs[@]}; i += 2)); do
  if grep -q "^${pairs[i]}: .* compared, 0 differences\$" "$tmp/compare.txt"; then
    passed
  else
    failed "retrace and rosbag read ${pairs[i]} differently:" "$tmp/compare.txt"
  fi
done
check "rosbag warns of no md5sum" bash -c "! grep -q WARNING '$tmp/compare.txt'"
grep ' compared, ' "$tmp/compare.txt"
check "no notes on an indexed bag" test ! -s "$tmp/drive_lz4.err"
check "cut.bag's note" grep -q "note: the bag has no index (a recording that was cut off" "$tmp/cut.err"
check "cut.bag's open chunk" grep -q "note: its last chunk, at byte .*, was never closed" "$tmp/cut.err"
check "the cut recording holds most of the drive" test "$(grep -c '' "$tmp/cut.jsonl")" -gt 100

# 3. The log commands. log-info on a bag without scans: described, then refused in one line.
"$retrace" log-info "$tmp/ref/no_scan.bag" >"$tmp/info.out" 2>"$tmp/info.err"
code=$?
if [ "$code" -eq 2 ] && [ "$(grep -c '' "$tmp/info.err")" -eq 1 ] &&
  grep -q "no_scan.bag: no sensor_msgs/LaserScan or MultiEchoLaserScan topic" "$tmp/info.err" &&
  grep -q "no_scan.bag: ROS 1 bag, 0.9 s, 20 messages" "$tmp/info.out" &&
  grep -qE '^  /odom +nav_msgs/Odometry +10 ' "$tmp/info.out" &&
  grep -qE '^  /chatter +std_msgs/String +10 ' "$tmp/info.out"; then
  passed
else
  failed "log-info on a bag without scans (exit $code):" "$tmp/info.out" "$tmp/info.err"
fi
expect_bad other-md5 "other_md5.bag: message 1 on '/scan': sensor_msgs/LaserScan: md5sum '0123456789abcdef0123456789abcdef' is not the md5sum of the sensor_msgs/LaserScan retrace reads" \
  log-info "$tmp/ref/other_md5.bag"
run info log-info "$tmp/ref/other_types.bag"
check "MultiEchoLaserScan noted" grep -q "note:       '/multi_scan' holds sensor_msgs/MultiEchoLaserScan" "$tmp/info.out"
check "PoseWithCovarianceStamped as the reference" grep -q "reference:  /amcl_pose (geometry_msgs/PoseWithCovarianceStamped): 20 poses" "$tmp/info.out"

# log-teach, log-localize, log-simulate and calibrate-lidar take the bag as they take the MCAP
# file: the same maps, the same metrics.
mcap="$tmp/logs/teach.mcap"
for f in bag mcap; do
  run "teach_$f" log-teach "$tmp/logs/teach.$f" --mode partial,consistent --switch-points 6 --no-figures --out "$tmp/taught_$f"
done
for f in bag mcap; do
  run "localize_$f" log-localize "$tmp/logs/teach.$f" --teach "$tmp/taught_mcap/partial/teach" --no-figures --out "$tmp/localized_$f"
done
if diff -r "$tmp/taught_bag/partial/teach" "$tmp/taught_mcap/partial/teach" >"$tmp/diff" 2>&1; then
  passed
else
  failed "log-teach: the bag's teach folder differs from the MCAP file's:" "$tmp/diff"
fi
"$py" - "$tmp/localized_bag/metrics.json" "$tmp/localized_mcap/metrics.json" >"$tmp/metrics.cmp" <<'EOF'
import json, sys
# All but the timings and the log's path.
apart = ('update_time_ms', 'real_time_factor', 'log')
def load(f):
    return {k: v for k, v in json.load(open(f)).items() if k not in apart}
a, b = load(sys.argv[1]), load(sys.argv[2])
for k in sorted(set(a) | set(b)):
    if a.get(k) != b.get(k):
        print(f'{k}: bag {a.get(k)}, mcap {b.get(k)}')
print(f"log-localize on teach.bag and teach.mcap: {len(a)} metrics {'identical' if a == b else 'differ'}"
      f" (localization error rms {a['localization_error_m']['rms']} m, {a['scans']} scans)")
sys.exit(0 if a == b else 1)
EOF
if [ $? -eq 0 ]; then passed; cat "$tmp/metrics.cmp"; else failed "log-localize metrics differ:" "$tmp/metrics.cmp"; fi
# (The first 5 s: they take the bag as any log, and the whole drive would cost seconds.)
run simulate log-simulate "$bag" --teach "$tmp/taught_bag/consistent/teach" --to 5 --out "$tmp/simulated.mcap"
run calibrate calibrate-lidar "$bag" --teach "$tmp/taught_bag/consistent/teach" --to 5 --out "$tmp/noise.yaml" --no-figures
check "calibrate-lidar on the bag" grep -q "z_hit" "$tmp/noise.yaml"

finish
