#!/usr/bin/env bash
# `retrace log-info`, `log-teach` and `log-localize` on bad logs and options: each case must print
# exactly one line on stderr that names the file (and the record) or the option, exit with code 2
# and leave no output folder (nor its staging folder) behind. Among them the ROS 1 bag of a
# recorded drive cut at every chunk boundary: one line naming the offset, never a crash.
# Usage: log_bad_input_test.sh <retrace binary> <source dir>
. "$(dirname "$0")/lib.sh" || exit 1

# A real recorded drive to damage: the small scenario's teaching drive, shortened to 12 m.
run record "${short_teach[@]}" --mode partial --out "$tmp/sim" --record-log "$tmp/logs"
mcap="$tmp/logs/teach.mcap"
carmen="$tmp/logs/teach.log.gz"
run taught log-teach "$mcap" --mode partial --switch-points 6 --out "$tmp/taught"
teach="$tmp/taught/partial/teach"
run taught_c log-teach "$mcap" --mode consistent --switch-points auto --out "$tmp/taught_c"

size=$(stat -c %s "$mcap")
head -c $((size / 2)) "$mcap" >"$tmp/truncated.mcap"
# A byte flipped in the middle of the data: a chunk that fails to decompress or its CRC.
cp "$mcap" "$tmp/corrupt.mcap"
printf '\xff\xff\xff\xff' | dd of="$tmp/corrupt.mcap" bs=1 seek=$((size / 3)) conv=notrunc status=none
# The ROS 1 bag of the drive, cut at every chunk boundary (where each chunk record starts and
# where its data ends) and where its index starts, its first chunk's lz4 data corrupted, and an
# old format's version line. The boundaries from the bag's index, by Python's standard library.
bag="$tmp/logs/teach.bag"
boundaries=$(/usr/bin/python3 - "$bag" <<'EOF'
import struct, sys
data = open(sys.argv[1], 'rb').read()
def fields(header):
    out, i = {}, 0
    while i < len(header):
        (n,) = struct.unpack_from('<I', header, i)
        name, _, value = header[i + 4:i + 4 + n].partition(b'=')
        out[name.decode()], i = value, i + 4 + n
    return out
def record(pos):  # (header fields, data start, data end)
    (h,) = struct.unpack_from('<I', data, pos)
    (d,) = struct.unpack_from('<I', data, pos + 4 + h)
    return fields(data[pos + 4:pos + 4 + h]), pos + 8 + h, pos + 8 + h + d
(index_pos,) = struct.unpack('<Q', record(13)[0]['index_pos'])
pos, cuts = index_pos, []
while pos < len(data):
    header, _, end = record(pos)
    if header['op'] == b'\x06':
        (chunk,) = struct.unpack('<Q', header['chunk_pos'])
        cuts += [chunk, record(chunk)[2]]
    pos = end
print(' '.join(map(str, sorted(cuts) + [index_pos])), record(min(cuts))[1])
EOF
)
read -r -a cuts <<<"$boundaries"
first_chunk_data=${cuts[-1]}
unset 'cuts[-1]'
[ ${#cuts[@]} -ge 4 ] || die "teach.bag: no chunks found (${boundaries})"
for cut in "${cuts[@]}"; do head -c "$cut" "$bag" >"$tmp/cut_$cut.bag"; done
cp "$bag" "$tmp/corrupt.bag"
printf '\xff\xff\xff\xff' | dd of="$tmp/corrupt.bag" bs=1 seek=$((first_chunk_data + 4)) conv=notrunc status=none
{ printf '#ROSBAG V1.2\n'; tail -c +14 "$bag"; } >"$tmp/old.bag"
# CARMEN lines: time going backwards, a NaN range.
printf 'ODOM 0 0 0 0 0 0 1.0 h 1.0\nODOM 1 0 0 0 0 0 2.0 h 2.0\nODOM 2 0 0 0 0 0 1.5 h 1.5\nFLASER 3 1.0 1.0 1.0 0 0 0 0 0 0 2.0 h 2.0\n' >"$tmp/backwards.log"
printf 'ODOM 0 0 0 0 0 0 1.0 h 1.0\nFLASER 3 1.0 nan 1.0 0 0 0 0 0 0 1.0 h 1.0\n' >"$tmp/nan.log"
printf 'ODOM 0 0 0 0 0 0 1.0 h 1.0\nFLASER 3 1.0 1.0 1.0 0 0 0 0 0 0 1.0 h 1.0\nFLASER 3 1.0 1.0 1.0 0 0 0 0 0 0 2.0 h 2.0\nODOM 0 0 0 0 0 0 2.0 h 2.0\n' >"$tmp/noreference.log"
# CARMEN lines without odometry (RAWLASER1 carries no robot pose, no ODOM) but with TRUEPOS: the
# one line names the option that draws odometry from the reference. A PARAM retrace reads,
# malformed.
for k in 0 1 2 3 4; do
  printf 'RAWLASER1 0 -1.5 3.0 1.5 20.0 0.01 0 3 1.0 2.0 3.0 0 %s h %s\nTRUEPOS %s 0 0 0 0 0 %s h %s\n' \
    "$k.5" "$k.5" "$k" "$k.5" "$k.5"
done >"$tmp/noodometry.log"
printf 'PARAM robot_front_laser_max far nohost 0\nFLASER 3 1.0 1.0 1.0 0 0 0 0 0 0 1.0 h 1.0\nFLASER 3 1.0 1.0 1.0 0 0 0 0 0 0 2.0 h 2.0\n' >"$tmp/badparam.log"
printf '\x00\x01\x02binary' >"$tmp/binary.bin"
: >"$tmp/empty.log"

# log-info writes nothing, and takes no --out; the other commands write to $tmp/out. Nothing may
# be written under $tmp in any case (no $tmp/out, no staging folder $tmp/out.tmp).
expect_bad missing "$tmp/missing.mcap: no such file" log-info "$tmp/missing.mcap"
expect_bad empty "empty file" log-info "$tmp/empty.log"
expect_bad binary "not a log retrace reads" log-info "$tmp/binary.bin"
expect_bad nan-range "nan.log" log-info "$tmp/nan.log"
expect_bad bad-param "badparam.log: message 1 on 'PARAM': PARAM robot_front_laser_max: 'far' is not a finite number" log-info "$tmp/badparam.log"
bad_suffix=(--out "$tmp/out")
expect_bad truncated "truncated.mcap" log-teach "$tmp/truncated.mcap"
for cut in "${cuts[@]}"; do
  expect_bad "bag-cut-at-$cut" "cut_$cut.bag: truncated: " log-teach "$tmp/cut_$cut.bag"
done
expect_bad bag-corrupt-chunk "corrupt.bag: lz4 chunk (lz4 data corrupt" log-localize "$tmp/corrupt.bag" --teach "$teach"
expect_bad bag-old-format "old.bag: a ROS bag of format 1.2; retrace reads format 2.0" log-teach "$tmp/old.bag"
expect_bad corrupt-chunk "corrupt.mcap" log-teach "$tmp/corrupt.mcap"
expect_bad reference-topic "--reference-topic '/nope' is not in the log" log-teach "$mcap" --reference-topic /nope
expect_bad corrupt-chunk-data "corrupt.mcap" log-localize "$tmp/corrupt.mcap" --teach "$teach"
expect_bad no-scan-topic "no sensor_msgs/msg/LaserScan topic" log-teach "$src/tests/data/rosbag2/talker_mcap"
expect_bad not-a-scan-topic "--scan-topic '/odom' holds no laser scans" log-teach "$mcap" --scan-topic /odom
expect_bad unknown-topic "--scan-topic '/front' is not in the log" log-localize "$mcap" --teach "$teach" --scan-topic /front
expect_bad backwards "backwards.log: message 3 on 'ODOM'" log-teach "$tmp/backwards.log" --odometry-topic ODOM
expect_bad consistent-without-reference "consistent needs a reference" log-teach "$tmp/noreference.log" --mode consistent
expect_bad switch-beyond "beyond the driven path" log-teach "$mcap" --mode partial --switch-points 6,500
expect_bad switch-order "must be strictly increasing" log-teach "$mcap" --switch-points 8,6
expect_bad switch-word "route.switch_points" log-teach "$mcap" --switch-points sometimes
expect_bad from-negative "--from: must be a time >= 0 s" log-teach "$mcap" --from -1
expect_bad to-before-from "--to: must be later than --from" log-teach "$mcap" --from 50 --to 10
# The drive's CARMEN log written without time (every stamp 0): refused naming the way out, which
# then teaches, saying so in manifest.yaml.
zcat "$carmen" | awk '$1 != "PARAM" && $1 !~ /^#/ { $(NF-2) = 0; $NF = 0 } { print }' \
  >"$tmp/timeless.log"
expect_bad timeless "carry no time stamps" log-teach "$tmp/timeless.log" --mode partial
expect_bad scan-rate-zero "--scan-rate" log-teach "$tmp/timeless.log" --scan-rate 0
run timeless_rate log-teach "$tmp/timeless.log" --scan-rate 10 --mode partial --switch-points 6 \
  --out "$tmp/timeless"
check timeless-manifest grep -q "^stamps: nominal, --scan-rate 10 Hz" \
  "$tmp/timeless/partial/manifest.yaml"
expect_bad empty-window "no scan with odometry" log-localize "$mcap" --teach "$teach" --from 5000
expect_bad teach-missing "no such teach folder" log-localize "$mcap" --teach "$tmp/nothing"
expect_bad initial-pose "--initial-pose: must be x,y,yaw_deg" log-localize "$mcap" --teach "$teach" --initial-pose 1,2
expect_bad reference-file "missing.tum" log-localize "$mcap" --teach "$teach" --reference "$tmp/missing.tum"
expect_bad route-file "route.file: does not apply to a log" log-teach "$mcap" --set route.file=x.txt
expect_bad repeats "playback: only initial_sigma_xy" log-localize "$mcap" --teach "$teach" --set playback.repeats=3
expect_bad unknown-key "particle" log-localize "$mcap" --teach "$teach" --set nav.localizer.particle=100
expect_bad config-missing "missing.yaml" log-teach "$mcap" --config "$tmp/missing.yaml"
expect_bad compare-one "a comparison needs at least two log-localize folders" log-compare "$tmp/taught"
expect_bad compare-not-localize "metrics.json" log-compare "$tmp/taught" "$tmp/taught_c"
expect_bad compare-labels "--labels: gives 3 labels for 2 folders" log-compare "$tmp/taught" "$tmp/taught_c" --labels a,b,c
expect_bad simulate-partial-world "--teach: the world is the map of a teach folder of one map" log-simulate "$mcap" --teach "$teach"
expect_bad simulate-no-reference "no reference to drive" log-simulate "$tmp/noreference.log" --teach "$tmp/taught_c/consistent/teach"
expect_bad no-odometry "noodometry.log: no odometry (no ODOM lines, RAWLASER1 lines carry no robot pose); its reference 'TRUEPOS' can stand in: add --synthetic-odometry" log-teach "$tmp/noodometry.log"
expect_bad no-odometry-localize "noodometry.log: no odometry (no ODOM lines" log-localize "$tmp/noodometry.log" --teach "$teach"

# A log without odometry is described by log-info (exit 0), which names what would draw it.
if "$retrace" log-info "$tmp/noodometry.log" >"$tmp/stdout" 2>"$tmp/stderr" &&
  grep -qF "odometry:   none (no ODOM lines, RAWLASER1 lines carry no robot pose): log-teach and log-localize draw it from the reference 'TRUEPOS' with --synthetic-odometry" "$tmp/stdout"; then
  passed
else
  failed "no-odometry-info: log-info on a log without odometry:" "$tmp/stdout" "$tmp/stderr"
fi

# A PARAM retrace does not read never refuses a log, whatever its value.
printf 'PARAM laser_front_laser_flipped no nohost 0\nPARAM robot_name the blue pioneer nohost 0\n' >"$tmp/params.log"
cat "$tmp/noreference.log" >>"$tmp/params.log"
if "$retrace" log-info "$tmp/params.log" >"$tmp/stdout" 2>"$tmp/stderr"; then
  passed
else
  failed "unread-params: log-info on a log with PARAM laser_front_laser_flipped no:" "$tmp/stderr"
fi

# The default (online) switching fits the modes asked for: a consistent map alone is taught.
if "$retrace" log-teach "$mcap" --mode consistent --no-figures --out "$tmp/consistent_only" >/dev/null 2>"$tmp/stderr" &&
  [ -f "$tmp/consistent_only/consistent/teach/sub_map_num.txt" ]; then
  passed
else
  failed "consistent-only: log-teach --mode consistent under the default switching:" "$tmp/stderr"
fi

finish
