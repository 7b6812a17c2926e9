#!/usr/bin/env bash
# The inputs that fuzzing and hand-made bad input found (issue 16), with their exact bytes: each
# must exit 2 with exactly one stderr line naming the file and key, write nothing, and answer
# within a second (checked here at 2 s: test machines are shared).
# Usage: hardening_test.sh <retrace binary> <source dir>
. "$(dirname "$0")/lib.sh" || exit 1

# Each case answers within 2 s (a hang is killed at 10 s) and writes nothing under $tmp: not the
# output $tmp/out (nor its staging folder $tmp/out.tmp) or $tmp/out.png the cases ask for.
bad_timeout=10
bad_max_ms=2000

scenario() {  # scenario <file> <world file>: a short route in that world
  make_file "$1" "name: s\nworld: $2\nroute:\n  points: [[1, 1], [9, 1]]\nseed: 1\nmodes: [partial]\n"
}
out=(--out "$tmp/out")

# 1. A binary PPM declaring 25554 x 25425 pixels, then 64 zero bytes: OpenCV allocated 3.9 GB.
pnm_file huge.ppm 'P6\n25554 25425\n65535\n' 64
ros_map huge.yaml huge.ppm '[0, 0, 0]'
make_file w_huge.yaml 'name: w\nmaps:\n  - {file: huge.yaml}\n'
scenario s_huge.yaml w_huge.yaml
expect_bad huge-ppm "huge.ppm: PPM header declares 25554 x 25425 pixels; retrace's limit" teach "$tmp/s_huge.yaml" "${out[@]}"
# A small PPM whose data is cut short, and a PNG cut in the middle (libpng printed a line).
pnm_file short.ppm 'P6\n40 40\n255\n' 100
ros_map short.yaml short.ppm '[0, 0, 0]'
make_file w_short.yaml 'name: w\nmaps:\n  - {file: short.yaml}\n'
expect_bad short-ppm "short.ppm: PPM has the wrong size" world "$tmp/w_short.yaml" --png "$tmp/out.png"
png="$src/docs/campus_maps.png"
head -c $(($(stat -c %s "$png") / 2)) "$png" >"$tmp/cut.png"
ros_map cut.yaml cut.png '[0, 0, 0]'
make_file w_cut.yaml 'name: w\nmaps:\n  - {file: cut.yaml}\n'
expect_bad truncated-png "cut.png: truncated PNG" world "$tmp/w_cut.yaml" --png "$tmp/out.png"
# Found by fuzz_map_image: OpenCV's PBM/PPM decoder and libpng printed their own lines.
for f in "$src"/tests/data/fuzz_findings/map-image-print-*; do
  name=$(basename "$f")
  cp "$f" "$tmp/$name"
  ros_map "m_$name.yaml" "$name" '[0, 0, 0]'
  make_file "w_$name.yaml" "name: w\nmaps:\n  - {file: m_$name.yaml}\n"
  expect_bad "$name" "$name: " world "$tmp/w_$name.yaml" --png "$tmp/out.png"
done

# 2. A world far from the origin: a bucket per metre of 1e9 m (std::length_error), or 10 GB.
make_file w_far.yaml 'name: w\nboxes: [{center: [1e9, 1e9], size: [1, 1]}, {center: [0, 0], size: [1, 1]}]\n'
scenario s_far.yaml w_far.yaml
expect_bad far-box "w_far.yaml:2: boxes[0].center: must be a finite coordinate within ±10000 m" teach "$tmp/s_far.yaml" "${out[@]}"
make_file w_far2.yaml 'name: w\nboxes: [{center: [20000, 20000], size: [1, 1]}, {center: [0, 0], size: [1, 1]}]\n'
expect_bad far-box-20km "boxes[0].center: must be a finite coordinate within ±10000 m" world "$tmp/w_far2.yaml" --png "$tmp/out.png"
pnm_file ok.pgm 'P5\n20 20\n255\n' 400
ros_map far_map.yaml ok.pgm '[1e9, 1e9, 0]'
make_file w_far_map.yaml 'name: w\nmaps:\n  - {file: far_map.yaml}\n'
expect_bad far-map-origin "far_map.yaml:3: origin: must be a finite coordinate within ±10000 m" world "$tmp/w_far_map.yaml" --png "$tmp/out.png"

# 3. Huge sizes: a float-to-int overflow in the geometry index, then Box2D's assertions.
make_file w_wall.yaml 'name: w\nwalls: [{points: [[0, 0], [1e300, 0]], thickness: 0.2}]\n'
scenario s_wall.yaml w_wall.yaml
expect_bad wall-1e300 "w_wall.yaml:2: walls[0].points[1]: must be a finite coordinate" teach "$tmp/s_wall.yaml" "${out[@]}"
make_file w_box.yaml 'name: w\nboxes: [{center: [0, 0], size: [1e308, 1]}]\n'
scenario s_box.yaml w_box.yaml
expect_bad box-size-1e308 "w_box.yaml:2: boxes[0].size: must be at most 20000 m" teach "$tmp/s_box.yaml" "${out[@]}"
make_file w_circle.yaml 'name: w\ncircles: [{center: [0, 0], radius: 1e308}]\n'
expect_bad circle-radius-1e308 "w_circle.yaml:2: circles[0].radius: must be at most 20000 m" world "$tmp/w_circle.yaml" --png "$tmp/out.png"

# 4. Long routes: a clearance query every 2 cm over 1e7 m hung; 1e10 overflowed first.
expect_bad route-1e7 "route[1]: must be a finite coordinate within ±10000 m" teach "$src/scenarios/small.yaml" --set 'route.points=[[-100, -100], [-1e7, -100]]' "${out[@]}"
expect_bad route-1e10 "route[1]: must be a finite coordinate within ±10000 m" teach "$src/scenarios/small.yaml" --set 'route.points=[[-100, -100], [-1e10, -100]]' "${out[@]}"
expect_bad route-too-long "m long; retrace's limit is 100000 m" teach "$src/scenarios/small.yaml" --set 'route.points=[[0, -100], [9000, -100], [0, -100], [9000, -100], [0, -100], [9000, -100], [0, -100], [9000, -100], [0, -100], [9000, -100], [0, -100], [9000, -100], [0, -100]]' "${out[@]}"

# 5. A list index beyond any integer: std::stoul threw, "internal error", exit 3.
expect_bad set-index-overflow "--set route.points.99999999999999999999=[1,1]: list index 99999999999999999999 out of range" run "$src/scenarios/small.yaml" --set 'route.points.99999999999999999999=[1,1]' "${out[@]}"

# 6. Quaternions whose squares overflow read as heading NaN: tests/io/tum_test.cpp and
# tests/io/route_file_test.cpp (HugeQuaternionComponentsGiveTheirHeadingNotNan).

# 7. The atomic swap of a results folder: tests/cli/commit_kill_test.sh.

# 8. Smaller ones.
expect_bad repeats-0 "--repeats: must be a number > 0, got '0'" run "$src/scenarios/small.yaml" --repeats 0 "${out[@]}"
expect_bad seed-minus-1 "--seed: must be an integer from 0 to 9223372036854775807, got '-1'" run "$src/scenarios/small.yaml" --seed -1 "${out[@]}"
expect_bad seed-2-63 "--seed: must be an integer from 0 to 9223372036854775807" run "$src/scenarios/small.yaml" --seed 9223372036854775808 "${out[@]}"
: >"$tmp/afile"
expect_bad out-is-a-file "afile: exists and is not a folder" run "$src/scenarios/small.yaml" --mode partial --out "$tmp/afile"

finish
