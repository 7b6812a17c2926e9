#!/usr/bin/env bash
# Checks the dependency rules of DESIGN.md §1: which library may include which, and that
# third-party types stay out of the public headers of sim, nav and viz.
set -uo pipefail
cd "$(dirname "$0")/.."
fail=0
check() {  # check <dir> <file-glob> <forbidden include regex> <reason>
  local hits
  hits=$(grep -rnE "#\s*include\s*[<\"]($3)" $1 --include="$2" 2>/dev/null | grep -v '/internal/' || true)
  if [ -n "$hits" ]; then
    echo "include rule broken: $4"
    echo "$hits"
    fail=1
  fi
}
check core '*' 'io/|sim/|nav/|viz/|bench/|yaml-cpp|box2d|opencv2|nlohmann' "core depends on Eigen and std only"
check io '*' 'sim/|nav/|viz/|bench/|box2d' "io depends on core only"
check sim '*' 'nav/|viz/|bench/' "sim must not see nav, viz or bench"
check nav '*' 'sim/|viz/|bench/|box2d' "nav must never see the simulator"
check viz '*' 'sim/|nav/|bench/|box2d' "viz depends on core and io only"
for lib in sim nav viz; do
  [ -d "$lib" ] && check "$lib" '*.hpp' 'box2d|opencv2|yaml-cpp|io/config_yaml' \
    "third-party types stay out of $lib's public headers"
done
[ $fail -eq 0 ] && echo "include rules: ok"
exit $fail
