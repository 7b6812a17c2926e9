#!/usr/bin/env bash
# Checks the dependency rules of docs/DESIGN.md §1 on the #includes: which library may include
# which (internal/ folders included), that third-party types stay out of the public headers of
# sim, nav and viz, and that CLI11 lives only in the command line. The layers, bottom up:
#
#   core → io → sim, nav, viz, logs → bench/engine → bench/metrics → bench/output, bench/suite,
#   bench/sweep, bench/compare, bench/replay → bench/cli   (bench/worldgen and bench/crowd: on
#   core, io and sim only; logs: only bench/replay and bench/cli read logs)
#
# The same table checks the harness's CMake links: each bench/<lib>/CMakeLists.txt may link
# only the retrace:: libraries its row allows, so that a link cannot quietly allow what the
# includes may not do.
set -uo pipefail
cd "$(dirname "$0")/.."
fail=0
check() {  # check <dir> <file-glob> <forbidden include regex> <reason> [exempt path regex]
  local hits
  hits=$(grep -rnE "#\s*include\s*[<\"]($3)" "$1" --include="$2" 2>/dev/null || true)
  if [ -n "${5:-}" ] && [ -n "$hits" ]; then hits=$(grep -vE "$5" <<<"$hits" || true); fi
  if [ -n "$hits" ]; then
    echo "include rule broken: $4"
    echo "$hits"
    fail=1
  fi
}
harness='bench/(engine|metrics|output|suite|sweep|compare|replay|cli|worldgen|crowd)/'
above_engine='bench/(metrics|output|suite|sweep|compare|replay|cli|worldgen|crowd)/'
check core '*' 'io/|sim/|nav/|viz/|bench/|yaml-cpp|box2d|opencv2|nlohmann|CLI/' "core depends on Eigen and std only"
check io '*' 'sim/|nav/|logs/|viz/|bench/|box2d|CLI/' "io depends on core only"
check sim '*' 'nav/|logs/|viz/|bench/|CLI/' "sim must not see nav, viz or bench"
check nav '*' 'sim/|logs/|viz/|bench/|box2d|CLI/' "nav must never see the simulator or logs"
check logs '*' 'sim/|nav/|viz/|bench/|box2d|opencv2|CLI/' "logs depend on core and io only"
check viz '*' 'sim/|nav/|logs/|bench/|box2d|CLI/' "viz depends on core and io only"
for lib in sim nav viz logs; do
  check "$lib" '*.hpp' 'box2d|opencv2|yaml-cpp|io/config_yaml|sqlite3|zstd|lz4|zlib' \
    "third-party types stay out of $lib's public headers" '/internal/'
done
check bench/engine '*' "$above_engine|viz/|logs/|CLI/" \
  "the episode engine sees core, io, sim and nav only"
check bench/metrics '*' 'bench/(output|suite|sweep|compare|replay|cli|worldgen|crowd)/|viz/|logs/|CLI/' \
  "metrics depend on the engine only"
check bench/output '*' 'bench/(suite|sweep|compare|replay|cli|worldgen|crowd)/|logs/|CLI/' \
  "output depends on the engine, metrics and viz only"
check bench/suite '*' 'bench/(output|sweep|compare|replay|cli|worldgen|crowd)/|viz/|logs/|CLI/' \
  "suites depend on the engine and metrics only"
check bench/sweep '*' 'bench/(output|suite|compare|replay|cli|worldgen|crowd)/|logs/|CLI/' \
  "sweeps depend on the engine, metrics and viz only"
check bench/compare '*' 'bench/(output|suite|sweep|replay|cli|worldgen|crowd)/|logs/|CLI/' \
  "the comparison study depends on metrics and viz only"
check bench/worldgen '*' "bench/(engine|metrics|output|suite|sweep|compare|replay|cli|crowd)/|nav/|viz/|logs/|CLI/" "world generation depends on core, io and sim only"
check bench/crowd '*' "bench/(engine|metrics|output|suite|sweep|compare|replay|cli|worldgen)/|nav/|viz/|logs/|CLI/" "the crowd check depends on core, io and sim only"
check bench/replay '*' 'bench/(output|suite|sweep|compare|cli|worldgen|crowd)/|CLI/' \
  "replay depends on the engine, metrics, logs and viz only"
check bench/micro '*' "$harness|CLI/" "the micro benchmarks measure sim, nav and logs kernels only"
# links <lib> <allowed retrace:: libraries, space separated>
links() {
  local file="bench/$1/CMakeLists.txt" dep
  for dep in $(grep -oE 'retrace::[a-z_]+' "$file" | sed 's/retrace:://' | sort -u); do
    case " $2 " in
      *" $dep "*) ;;
      *) echo "link rule broken: $file links retrace::$dep (allowed: $2)"; fail=1 ;;
    esac
  done
}
links engine "core io sim nav"
links metrics "core io sim nav engine"
links output "core io sim nav viz engine metrics"
links suite "core io sim nav engine metrics"
links sweep "core io sim nav viz engine metrics"
links compare "core io sim nav viz engine metrics"
links replay "core io sim nav viz logs engine metrics"
links worldgen "core io sim"
links crowd "core io sim"
links cli "core io sim nav viz logs engine metrics output suite sweep compare replay worldgen crowd cli"
[ $fail -eq 0 ] && echo "include rules: ok"
exit $fail
