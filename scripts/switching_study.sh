#!/usr/bin/env bash
# Online map switching against switch points planned from the route's geometry (`auto`) and, for
# the shipped scenarios, against the hand-picked ones: for every scenario, one teaching drive and
# playback per way of switching (mode partial), and one line each with the maps made, the fewest
# possible for that drive, the maps holding a place twice (judged on ground truth) and the
# playback successes. Random tours come from `retrace generate-tour`.
#
# Usage: scripts/switching_study.sh <retrace binary> <out dir> [tours (20)] [repeats (2)]
# Two scenarios run at a time. Prints the table and writes it to <out dir>/switching.txt.
set -euo pipefail
retrace=$(realpath "$1")
out=$2
tours=${3:-20}
repeats=${4:-2}
src=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out"
out=$(realpath "$out")

# One teaching drive and its playbacks; prints "<label> <switching> <maps> <fewest> <twice> <ok>/<runs>".
one() {
  local label=$1 scenario=$2 switching=$3
  local dir="$out/runs/$label-$switching"
  local set=()
  [ "$switching" = as_given ] || set=(--set "route.switch_points=$switching")
  # A failed playback run makes the exit code non-zero; only a missing summary is a failure here.
  "$retrace" run "$scenario" --mode partial --repeats "$repeats" --jobs 1 --no-figures \
    --out "$dir" "${set[@]}" >"$dir.log" 2>&1 || true
  local cut success
  cut=$(grep -E '^partial: [0-9]+ maps' "$dir.log") || { echo "$label $switching FAILED (see $dir.log)"; return; }
  success=$(awk '$1 == "partial" && $2 ~ /\// {print $2; exit}' "$dir.log")
  # "partial: 4 maps (fewest possible 4), 0 holding a place twice; ..."
  echo "$label $switching $(echo "$cut" | sed -E 's/^partial: ([0-9]+) maps \(fewest possible ([0-9]+)\), ([0-9]+) holding.*/\1 \2 \3/') $success"
}
export -f one
export retrace out repeats

jobs=()
for name in small office campus; do
  jobs+=("$name $src/scenarios/$name.yaml as_given" "$name $src/scenarios/$name.yaml online")
done
mkdir -p "$out/runs"
for seed in $(seq 1 "$tours"); do
  "$retrace" generate-tour --seed "$seed" --out "$out/tours/$seed" >/dev/null
  jobs+=("tour-$seed $out/tours/$seed/scenario.yaml auto" "tour-$seed $out/tours/$seed/scenario.yaml online")
done

{
  echo "scenario switching maps fewest twice success"
  printf '%s\n' "${jobs[@]}" | xargs -P 2 -I{} bash -c 'one {}' | sort -V
} | column -t | tee "$out/switching.txt"
