#!/usr/bin/env bash
# Checks the dependency rules of docs/DESIGN.md §1 on the #includes: which library may include
# which (internal/ folders included), that third-party types stay out of the public headers of
# sim, nav and viz, and that CLI11 lives only in the command line. The layers, bottom up:
#
#   core → io → sim, nav, viz, logs → bench/engine → bench/metrics → bench/output, bench/suite
#   → bench/sweep, bench/compare, bench/replay, bench/worldgen (on output) → bench/calibration,
#   bench/run → bench/cli (bench/crowd: on core, io, sim and viz; logs: only bench/replay,
#   bench/calibration, bench/cli and python read logs; only bench/cli and python include
#   bench/calibration). python/ (the Python module) binds the library calls beside bench/cli:
#   it includes what bench/cli's commands call, never bench/cli itself, and only it includes
#   pybind11.
#
# The table of docs/DESIGN.md §1 checks every library's CMake links (parsed from the document
# itself, below), so that a link cannot quietly allow what the includes may not do.
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
harness='bench/(engine|metrics|output|suite|sweep|compare|replay|calibration|run|cli|worldgen|crowd)/'
above_engine='bench/(metrics|output|suite|sweep|compare|replay|calibration|run|cli|worldgen|crowd)/'
check core '*' 'io/|sim/|nav/|viz/|bench/|yaml-cpp|box2d|opencv2|nlohmann|CLI/' "core depends on Eigen and std only"
check io '*' 'sim/|nav/|logs/|viz/|bench/|box2d|CLI/' "io depends on core only"
check sim '*' 'nav/|logs/|viz/|bench/|CLI/' "sim must not see nav, viz or bench"
check nav '*' 'sim/|logs/|viz/|bench/|box2d|CLI/' "nav must never see the simulator or logs"
check logs '*' 'sim/|nav/|viz/|bench/|box2d|opencv2|CLI/' "logs depend on core and io only"
check viz '*' 'sim/|nav/|logs/|bench/|box2d|CLI/' "viz depends on core and io only"
for lib in sim nav viz logs; do
  check "$lib" '*.hpp' 'box2d|opencv2|yaml-cpp|io/config_yaml|sqlite3|zstd|lz4|zlib|bzlib' \
    "third-party types stay out of $lib's public headers" '/internal/'
done
check bench/stack '*' 'io/|sim/|nav/|logs/|viz/|bench/(engine|metrics|output|suite|sweep|compare|replay|calibration|run|cli|worldgen|crowd)/|yaml-cpp|box2d|opencv2|nlohmann|CLI/' \
  "the stack interface speaks core types only"
check bench/engine '*' "$above_engine|viz/|logs/|CLI/" \
  "the episode engine sees core, io, sim and nav only"
check bench/metrics '*' 'bench/(output|suite|sweep|compare|replay|calibration|run|cli|worldgen|crowd)/|viz/|logs/|CLI/' \
  "metrics depend on the engine only"
check bench/output '*' 'bench/(suite|sweep|compare|replay|calibration|run|cli|worldgen|crowd)/|logs/|CLI/' \
  "output depends on the engine, metrics and viz only"
check bench/suite '*' 'bench/(output|sweep|compare|replay|calibration|run|cli|worldgen|crowd)/|viz/|logs/|CLI/' \
  "suites depend on the engine and metrics only"
check bench/sweep '*' 'bench/(suite|compare|replay|calibration|run|cli|worldgen|crowd)/|logs/|CLI/' \
  "sweeps depend on output, the engine, metrics and viz only"
check bench/compare '*' 'bench/(suite|sweep|replay|calibration|run|cli|worldgen|crowd)/|logs/|CLI/' \
  "the comparison study depends on output, metrics and viz only"
check bench/worldgen '*' "bench/(metrics|suite|sweep|compare|replay|calibration|run|cli|crowd)/|nav/|viz/|logs/|CLI/" "world generation depends on core, io, sim, the engine (clutter) and output (staged folders) only"
check bench/crowd '*' "bench/(engine|metrics|output|suite|sweep|compare|replay|calibration|run|cli|worldgen)/|nav/|logs/|CLI/" "the crowd check depends on core, io, sim and viz only"
check bench/replay '*' 'bench/(suite|sweep|compare|calibration|run|cli|worldgen|crowd)/|CLI/' \
  "replay depends on the engine, metrics, output, logs and viz only"
check bench/calibration '*' 'bench/(suite|sweep|compare|run|cli|worldgen|crowd)/|CLI/' \
  "calibration depends on replay, output, metrics, the engine, logs and viz only"
check bench/run '*' 'bench/(suite|sweep|compare|calibration|cli|worldgen|crowd)/|CLI/' \
  "a scenario run depends on replay, output, metrics, the engine and viz only"
check bench/micro '*' "$harness|CLI/" "the micro benchmarks measure sim, nav and logs kernels only"
check python '*' 'bench/(cli|worldgen|crowd|micro)/|sim/|nav/|viz/|CLI/' \
  "the Python module binds the library calls (run, sweep, compare, suite, replay, calibration, output, metrics, engine, logs, io, core), not the command line"
for dir in core io sim nav viz logs bench fuzz; do
  check "$dir" '*' 'python/|pybind11|Python\.h' "only python/ includes pybind11 and the module's headers"
done
# The CMake links against the table of docs/DESIGN.md §1 ("The dependency picture"): each
# row's target may link the targets its row lists, what those may use in turn, and core and io.
# The table is parsed here, so the check and the design cannot disagree.
design_rows=$(awk '
  /^ row  target/ { on = 1; next }
  on && /^ *-+ / { next }
  on && /^$/ { exit }
  on && /^ +[0-9] / {
    if ($2 == "retrace") next                      # the program: bench/cli, checked as cli
    line = $0; sub(/^ +[0-9] +[a-z_]+ +/, "", line)  # may use ... folder
    folder = $NF; sub(/ +[^ ]+$/, "", line)
    name = $2; uses[name] = line; dir[name] = folder; order[++n] = name; last = name; next
  }
  on && /^ +[a-z]/ { line = $0; sub(/^ +/, "", line); uses[last] = uses[last] ", " line; next }
  END {
    for (i = 1; i <= n; ++i) {
      u = uses[order[i]]; sub(/;.*/, "", u); gsub(/[ ,]+/, " ", u)
      print order[i], dir[order[i]], u
    }
  }' docs/DESIGN.md)
if [ -z "$design_rows" ]; then
  echo "link rule check: no dependency table found in docs/DESIGN.md §1"; fail=1
fi
declare -A row_uses row_dir
while read -r name folder uses; do
  row_dir[$name]=$folder
  row_uses[$name]=$uses
done <<<"$design_rows"
allowed_for() {  # the transitive closure of a row's targets, plus core and io
  local todo="$1" seen=" core io " t u
  while [ -n "$todo" ]; do
    t=${todo%% *}; todo=${todo#"$t"}; todo=${todo# }
    for u in ${row_uses[$t]:-}; do
      [ -n "${row_dir[$u]:-}" ] || continue  # a third-party library (Box2D, CLI11, ...)
      case "$seen" in *" $u "*) ;; *) seen="$seen$u "; todo="$todo $u"; todo=${todo# } ;; esac
    done
  done
  echo "$seen"
}
for name in "${!row_dir[@]}"; do
  file="${row_dir[$name]%/}/CMakeLists.txt"
  if [ ! -f "$file" ]; then
    echo "link rule check: docs/DESIGN.md §1 names $name in ${row_dir[$name]}, which has no CMakeLists.txt"
    fail=1; continue
  fi
  allowed="$(allowed_for "$name")$name "
  for dep in $(grep -oE 'retrace::[a-z_]+' "$file" | sed 's/retrace:://' | sort -u); do
    case "$allowed" in
      *" $dep "*) ;;
      *) echo "link rule broken: $file links retrace::$dep; docs/DESIGN.md §1 allows$allowed"; fail=1 ;;
    esac
  done
done
# Every library folder has its row.
for file in */CMakeLists.txt bench/*/CMakeLists.txt; do
  dir=${file%/CMakeLists.txt}
  # A library of sources (not bench/'s interface target of build facts).
  grep -qE '^add_library\(retrace_[a-z_]+ *$|^retrace_harness_library\(' "$file" || continue
  found=0
  for name in "${!row_dir[@]}"; do [ "${row_dir[$name]%/}" = "$dir" ] && found=1; done
  [ $found -eq 1 ] || { echo "link rule check: $dir builds a library but has no row in docs/DESIGN.md §1"; fail=1; }
done
[ $fail -eq 0 ] && echo "include rules: ok"
exit $fail
