#!/usr/bin/env bash
# Bad input to the retrace program: each case must print exactly one line on stderr that names
# the problem, exit with code 2, and leave no output file behind.
# Usage: bad_input_test.sh <retrace binary> <source dir>
. "$(dirname "$0")/lib.sh" || exit 1

make_file malformed.yaml 'name: x\nboxes: [{center: [1, 2}\n'
make_file unknown.yaml 'name: x\nbox: []\n'
make_file nan.yaml 'name: x\ncircles: [{center: [0, .nan], radius: 1}]\n'
make_file negative.yaml 'name: x\ncircles: [{center: [0, 0], radius: -1}]\n'
make_file empty.yaml 'name: nothing\n'
pnm_file short.pgm 'P5\n100 80\n255\n' 7000
ros_map short.yaml short.pgm '[0, 0, 0]'
make_file pgm_world.yaml 'name: x\nmaps: [{file: short.yaml}]\n'
ros_map yaw.yaml short.pgm '[0, 0, 0.3]'
make_file yaw_world.yaml 'name: x\nmaps: [{file: yaw.yaml}]\n'
printf '0 0\n20 0\n' >"$tmp/through_wall.txt"
printf '8 6.25\n9 abc\n' >"$tmp/garbage_route.txt"
make_file crowded.yaml 'name: x\nboxes: [{center: [0, 0], size: [1, 1]}]\npedestrians: [{count: 50, region_min: [2, 2], region_max: [3, 3]}]\n'

expect_bad missing-file "missing.yaml: cannot open file" world "$tmp/missing.yaml" --png "$tmp/out.png"
expect_bad malformed-yaml "malformed.yaml:2: invalid YAML" world "$tmp/malformed.yaml" --png "$tmp/out.png"
expect_bad unknown-key "unknown.yaml:2: box: unknown key; did you mean 'boxes'?" world "$tmp/unknown.yaml" --png "$tmp/out.png"
expect_bad nan "circles[0].center[1]: must be a finite number" world "$tmp/nan.yaml" --png "$tmp/out.png"
expect_bad negative-radius "circles[0].radius: must be > 0, got -1" world "$tmp/negative.yaml" --png "$tmp/out.png"
expect_bad empty-world "no static geometry" world "$tmp/empty.yaml" --png "$tmp/out.png"
expect_bad pgm-wrong-size "PGM has the wrong size" world "$tmp/pgm_world.yaml" --png "$tmp/out.png"
expect_bad origin-yaw "origin yaw 0.3 rad is not supported" world "$tmp/yaw_world.yaml" --png "$tmp/out.png"
expect_bad route-through-wall "route is not drivable" world "$src/worlds/office.yaml" --route "$tmp/through_wall.txt" --png "$tmp/out.png"
expect_bad route-garbage "garbage_route.txt:2" world "$src/worlds/office.yaml" --route "$tmp/garbage_route.txt" --png "$tmp/out.png"
expect_bad crowded-region "pedestrian" world "$tmp/crowded.yaml" --png "$tmp/out.png"
expect_bad bad-override "--set walls.0.thickness=-1" world "$src/worlds/office.yaml" --set walls.0.thickness=-1 --png "$tmp/out.png"
expect_bad bad-override-syntax "--set expects key.path=value" world "$src/worlds/office.yaml" --set nonsense --png "$tmp/out.png"
expect_bad unwritable-output "cannot create folder" world "$src/worlds/office.yaml" --png /proc/retrace/out.png
expect_bad no-subcommand "A subcommand is required" 
expect_bad unknown-option "--bogus" world "$src/worlds/office.yaml" --png "$tmp/out.png" --bogus

# Scenarios (`retrace run`, `teach`, `playback`): nothing may be written, as $tmp/results or
# anywhere else.
cp "$src/worlds/test_room.yaml" "$tmp/room.yaml"
scenario() {  # scenario <file> <route/extra yaml>
  make_file "$1" "name: bad\nworld: room.yaml\n$2"
}
scenario unknown_key.yaml 'route: {points: [[1, 1], [9, 1]]}\nplayback: {repeat: 2}\n'
scenario through_box.yaml 'route: {points: [[1, 3.8], [9, 3.8]]}\n'
scenario beyond_end.yaml 'route: {points: [[1, 1], [9, 1]], switch_points: [4, 12]}\n'
scenario inside.yaml 'route: {points: [[4, 2], [9, 1]]}\n'
scenario decreasing.yaml 'route: {points: [[1, 1], [9, 1]], switch_points: [5, 3]}\n'
scenario bad_mode.yaml 'route: {points: [[1, 1], [9, 1]]}\nmodes: [partial, slam]\n'
scenario missing_world.yaml 'route: {points: [[1, 1], [9, 1]]}\n'
scenario nav_mount.yaml 'route: {points: [[1, 1], [9, 1]]}\nnav: {localizer: {lidar_mount: [0.1, 0, 0]}}\n'
sed -i 's/room.yaml/nowhere.yaml/' "$tmp/missing_world.yaml"
mkdir -p "$tmp/teach_broken/maps"
echo 2 >"$tmp/teach_broken/sub_map_num.txt"

out=(--out "$tmp/results")
expect_bad run-unknown-key "playback.repeat: unknown key; did you mean 'repeats'?" run "$tmp/unknown_key.yaml" "${out[@]}"
expect_bad run-route-through-box "route is not drivable" run "$tmp/through_box.yaml" "${out[@]}"
expect_bad run-switch-beyond-end "beyond_end.yaml: route.switch_points: switch point 1 (12) must lie inside the route" run "$tmp/beyond_end.yaml" "${out[@]}"
expect_bad run-start-inside "route is not drivable" run "$tmp/inside.yaml" "${out[@]}"
expect_bad run-switch-decreasing "must be strictly increasing" run "$tmp/decreasing.yaml" "${out[@]}"
expect_bad run-video-odometry-stack "--video: the video shows the localizer's particles and maps, and playback.stack odometry has none to show" run "$src/scenarios/small.yaml" --video --set playback.stack=odometry "${out[@]}"
expect_bad run-unknown-stack "playback.stack: unknown stack 'foo'; registered: odometry, retrace" run "$src/scenarios/small.yaml" --set playback.stack=foo "${out[@]}"
expect_bad run-bad-mode "unknown value 'slam'" run "$tmp/bad_mode.yaml" "${out[@]}"
expect_bad run-missing-world "nowhere.yaml: cannot open file" run "$tmp/missing_world.yaml" "${out[@]}"
expect_bad run-bad-mode-flag "unknown mode 'slam'" run "$src/scenarios/small.yaml" --mode slam "${out[@]}"
expect_bad run-auto-in-list "route.switch_points: \`auto\` stands alone" run "$src/scenarios/small.yaml" --set 'route.switch_points=[auto, 10]' "${out[@]}"
expect_bad run-online-in-list "route.switch_points: \`online\` stands alone" run "$src/scenarios/small.yaml" --set 'route.switch_points=[online, 10]' "${out[@]}"
expect_bad run-online-consistent "route.switch_points: \`online\` switching needs a map mode that switches maps" run "$src/scenarios/small.yaml" --mode consistent --set route.switch_points=online "${out[@]}"
expect_bad teach-online-single "\`online\` switching needs a map mode" teach "$src/scenarios/small.yaml" --mode single --set route.switch_points=online "${out[@]}"
expect_bad run-online-drift "route.online_drift: must be" run "$src/scenarios/small.yaml" --set route.online_drift=2 "${out[@]}"
expect_bad run-matcher-range "nav.scan_matcher.sigma: must be > 0" run "$src/scenarios/small.yaml" --mode scan_matched --set nav.scan_matcher.sigma=0 "${out[@]}"
expect_bad run-bad-mode-in-list "unknown mode 'slam'" run "$src/scenarios/small.yaml" --mode partial,slam "${out[@]}"
expect_bad run-mode-twice "mode 'partial' is given twice" run "$src/scenarios/small.yaml" --mode partial,consistent,partial "${out[@]}"
expect_bad run-bad-set "--set nav.localizer.particles=-5" run "$src/scenarios/small.yaml" --set nav.localizer.particles=-5 "${out[@]}"
# The robot's geometry is stated once, under sim: nav keys that would repeat it name that key.
expect_bad run-robot-radius-in-nav "nav.avoidance.robot_radius: unknown key; the robot's geometry is stated once, for the simulator and the navigation stack alike: set sim.robot.radius" run "$src/scenarios/small.yaml" --set nav.avoidance.robot_radius=0.5 "${out[@]}"
expect_bad run-lidar-mount-in-nav "nav_mount.yaml:4: nav.localizer.lidar_mount: unknown key; the robot's geometry is stated once, for the simulator and the navigation stack alike: set sim.lidar.mount" run "$tmp/nav_mount.yaml" "${out[@]}"
expect_bad playback-two-modes "one mode" playback "$src/scenarios/small.yaml" --teach "$tmp/nothing" --mode partial,single "${out[@]}"
expect_bad playback-missing-bundle "no such teach folder" playback "$src/scenarios/small.yaml" --teach "$tmp/nothing" "${out[@]}"
expect_bad playback-broken-bundle "teach_broken" playback "$src/scenarios/small.yaml" --teach "$tmp/teach_broken" "${out[@]}"

# And the good case writes the image.
if "$retrace" world "$src/worlds/office.yaml" --route "$src/worlds/routes/office_loop.txt" --png "$tmp/ok.png" >/dev/null &&
   [ -s "$tmp/ok.png" ]; then
  passed
else
  failed "good-world: no image written"
fi

finish
