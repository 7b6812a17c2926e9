#!/usr/bin/env bash
# Runs every libFuzzer target of fuzz/ (one per parser) for a fixed time, one per core at a time,
# starting from seed corpora made of the shipped files and with a dictionary of the config keys.
# Corpora grow in <build>/fuzz/corpus/<target> from run to run; findings (crashes, sanitizer
# reports, leaks, inputs slower than 5 s, more than 2 GB) are written to <build>/fuzz/findings.
# Prints the executions per target; exits 1 on any finding.
#
# Usage: scripts/fuzz.sh <build dir> <seconds per target> [target ...]
#   The seconds are spent where the parsers are: each target runs its weight times them (the binary
#   log containers 2, CDR, the ROS map, map image and rosbag2 metadata readers 1, the YAML files
#   and --set overrides 0.5, the line formats CSV, TUM, path and route 0.25; at least 1 s).
#   The build dir must be configured with Clang and -DRETRACE_FUZZ=ON (scripts/test.sh builds
#   build-asan so); targets default to all of them.
# Environment: FUZZ_RUNS=N stops a target after N executions (before its time is up);
#   FUZZ_TIMEOUT (s, default 5) is the time one input may take before it counts as a hang;
#   FUZZ_JOBS (default: the number of cores) targets run at once; FUZZ_FORK=N runs each target in
#   libFuzzer's fork mode with N worker processes (one run whose executions add up; a crash, a
#   hang or an out-of-memory input still ends it and is a finding).
set -euo pipefail
cd "$(dirname "$0")/.."
build="$1"
seconds="$2"
shift 2
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  for f in "$build"/fuzz/fuzz_*; do targets+=("$(basename "$f" | sed 's/^fuzz_//')"); done
fi
work="$build/fuzz"
rm -rf "$work/seeds" "$work/findings" "$work/unconfirmed" "$work/logs"
mkdir -p "$work/seeds" "$work/findings" "$work/logs" "$work/corpus"

# Seeds: the shipped files each parser reads, and a few written here.
seed() {  # seed <target> <files...>
  mkdir -p "$work/seeds/$1"
  local t="$1"
  shift
  for f in "$@"; do [ -f "$f" ] && cp "$f" "$work/seeds/$t/$(echo "$f" | tr / _)"; done
  return 0
}
seed world worlds/*.yaml
seed scenario scenarios/*.yaml
seed suite bench/suites/*.yaml
seed sweep bench/sweeps/*.yaml tests/data/sweep_small.yaml
seed map_image tests/data/*.png
seed route worlds/routes/*.txt
seed mcap $(find tests/data/rosbag2 -name '*.mcap')
seed db3 $(find tests/data/rosbag2 -name '*.db3')
seed rosbag2_metadata $(find tests/data/rosbag2 -name metadata.yaml)
# ROS 1 bags: the test bags of tests/cli/ros1_bag_test.sh, a tenth as long, as Debian's
# python3-rosbag writes them (scripts/install_deps.sh --test installs it).
if printf '%s\n' "${targets[@]}" | grep -qx bag; then
  mkdir -p "$work/seeds/bag"
  /usr/bin/python3 tests/cli/ros1_bags.py seeds "$work/seeds/bag"
fi
mkdir -p "$work/seeds/set_override" "$work/seeds/ros_map" "$work/seeds/path" "$work/seeds/tum" \
  "$work/seeds/csv" "$work/seeds/carmen" "$work/seeds/cdr" "$work/seeds/map_image"
printf 'nav.localizer.particles=300\nroute.points=[[1, 1], [9, 1], [9, 5]]\nroute.points.1=[8, 1]\nsim.lidar={beams: 181}\n' >"$work/seeds/set_override/a"
printf 'image: map.pgm\nresolution: 0.05\norigin: [-1, -2, 0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\nmode: trinary\n' >"$work/seeds/ros_map/a"
printf 'P5\n4 3\n255\n\x00\x10\xfe\xff\xcd\xcd\x00\x00\xfe\xfe\xfe\x00' >"$work/seeds/map_image/a.pgm"
printf 'P6\n2 2\n255\n\x00\x00\x00\xff\xff\xff\x10\x20\x30\xfe\xfe\xfe' >"$work/seeds/map_image/b.ppm"
printf '0 0 0 0 0 0 1\n1 0 0 0 0 0.38 0.92\n2 1 0 0 0 0.7 0.7\n' >"$work/seeds/path/a"
printf '# t x y z qx qy qz qw\n0.05 0 0 0 0 0 0 1\n0.10 0.1 0 0 0 0 0.1 0.99\n' >"$work/seeds/tum/a"
printf 'case,seed,"label, quoted",value\n0,1,a,0.5\n1,2,"b ""c""",nan\n' >"$work/seeds/csv/a"
printf 'PARAM robot_front_laser_max 50.0 nohost 0.0\nODOM 0 0 0 0 0 0 1.0 h 1.0\nFLASER 3 1.0 2.0 3.0 0 0 0 0 0 0 1.1 h 1.1\nROBOTLASER1 0 -1.57 3.14 1.57 30 0.01 0 3 1.0 2.0 3.0 0 0 0 0 0 0 0 0 0 0 1.2 h 1.2\nTRUEPOS 0 0 0 0 0 0 1.3 h 1.3\nODOM 1 0 0 0 0 0 2.0 h 2.0\n' >"$work/seeds/carmen/a"
printf '\x00\x00\x01\x00\x00' >"$work/seeds/cdr/a"

# The dictionary: every config key (the names reflected in the sources) and YAML's punctuation.
dict="$work/keys.dict"
{
  grep -rhoE 'v\("[a-z_0-9]+"' --include='*.hpp' core io logs sim nav viz bench | sed -E 's/v\("(.*)"/"\1:"/'
  printf '"[" \n"]"\n"{"\n"}"\n": "\n"- "\n"true"\n"false"\n"null"\n".nan"\n".inf"\n"-1e308"\n"1e308"\n'
  # The field names of ROS 1 bag records and connection headers.
  for f in op conn time topic type md5sum message_definition compression size index_pos \
    conn_count chunk_count ver count chunk_pos start_time end_time; do printf '"%s="\n' "$f"; done
  printf '"none"\n"bz2"\n"lz4"\n"#ROSBAG V2.0\\x0a"\n'
} | sort -u >"$dict"

weight() {  # weight <target>: its share of the seconds per target
  case "$1" in
    carmen | mcap | db3 | bag) echo 2 ;;
    cdr | ros_map | map_image | rosbag2_metadata) echo 1 ;;
    world | scenario | suite | sweep | set_override) echo 0.5 ;;
    *) echo 0.25 ;;
  esac
}
export -f weight

run_one() {  # run_one <target>: one target for its seconds, its stats in logs/<target>.txt
  local t="$1"
  local time
  time=$(awk -v s="$seconds" -v w="$(weight "$t")" 'BEGIN {t = int(s * w + 0.5); print (t < 1 ? 1 : t)}')
  mkdir -p "$work/corpus/$t"
  local fork=()
  [ "$forks" -gt 0 ] && fork=(-fork="$forks" -ignore_crashes=0 -ignore_timeouts=0 -ignore_ooms=0)
  "$build/fuzz/fuzz_$t" "$work/corpus/$t" "$work/seeds/$t" -dict="$work/keys.dict" "${fork[@]}" \
    -max_total_time="$time" -runs="$runs" -timeout="$timeout" -report_slow_units="$timeout" -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$work/findings/$t-" >"$work/logs/$t.txt" 2>&1 || true
  local execs
  if [ "$forks" -gt 0 ]; then  # fork mode's parent prints the running total as "#N: cov: ..."
    execs=$(grep -oE '^#[0-9]+: cov' "$work/logs/$t.txt" | tail -1 | grep -oE '[0-9]+' || echo 0)
  else
    execs=$(grep -oE 'stat::number_of_executed_units: [0-9]+' "$work/logs/$t.txt" | grep -oE '[0-9]+$' || echo 0)
  fi
  echo "$t $execs"
}
export -f run_one
runs="${FUZZ_RUNS:--1}"
timeout="${FUZZ_TIMEOUT:-5}"
forks="${FUZZ_FORK:-0}"
export build work seconds runs timeout forks
# The longest first, so that the cores finish together.
for t in "${targets[@]}"; do echo "$(weight "$t") $t"; done | sort -rn | cut -d' ' -f2 | xargs -P "${FUZZ_JOBS:-$(nproc)}" -I{} bash -c 'run_one {}' | sort >"$work/execs.txt"

# A hang must reproduce: on a loaded machine an input can take longer than the timeout only
# because the fuzzer did not get the CPU. Each timeout or slow input runs again alone; one that
# now finishes within the timeout is kept in unconfirmed/ and reported, but is no finding.
mkdir -p "$work/unconfirmed"
for f in "$work"/findings/*-timeout-* "$work"/findings/*-slow-unit-*; do
  [ -f "$f" ] || continue
  t=$(basename "$f" | cut -d- -f1)
  start=$(date +%s%N)
  if timeout "$timeout" "$build/fuzz/fuzz_$t" "$f" >/dev/null 2>&1; then
    echo "unconfirmed: $(basename "$f") ran again in $((($(date +%s%N) - start) / 1000000)) ms"
    mv "$f" "$work/unconfirmed/"
  fi
done
findings=$(find "$work/findings" -type f | wc -l)
printf '%-18s %12s\n' target executions
while read -r t n; do printf '%-18s %12s\n' "$t" "$n"; done <"$work/execs.txt"
echo "fuzzing: ${#targets[@]} targets, ${seconds} s per target weighted by parser, $(awk '{s += $2} END {print s}' "$work/execs.txt") executions, $findings findings"
if [ "$findings" -gt 0 ]; then
  for f in "$work"/findings/*; do
    t=$(basename "$f" | cut -d- -f1)
    echo "== finding $f (target $t):"
    grep -E 'ERROR|SUMMARY|terminate|what\(\)|deadly' "$work/logs/$t.txt" | head -5
  done
  exit 1
fi
