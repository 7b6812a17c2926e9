# shellcheck shell=bash
# What the command-line tests in tests/cli share. Each *_test.sh sources it first, with its own
# arguments (`. "$(dirname "$0")/lib.sh" || exit 1`, as tests/CMakeLists.txt runs it:
# <retrace binary> <source dir> [more]), and keeps only its own checks. Sourcing it
#   - sets bash's strict mode as the tests use it: set -uo pipefail (not -e: the checks run
#     commands that are meant to fail and look at their exit codes);
#   - checks the arguments (set cli_more_args=("<name>"...) before sourcing for more than two)
#     and sets $retrace (the binary, an absolute path: some tests cd) and $src (the source dir);
#   - makes the scratch folder $tmp and removes it on exit, killing $bg_pid first if a test set
#     it (a background run of its own). Set before sourcing: cli_tmp_template, a mktemp template
#     for $tmp; cli_keep_tmp_on_failure=1, keep $tmp when the test fails (and say where).
# The counted checks (passed, failed, check, expect_bad) add to $pass and $fail; `finish` prints
# them and exits 1 if anything failed.

set -uo pipefail

[ -n "${cli_more_args+set}" ] || cli_more_args=()
if [ $# -lt $((2 + ${#cli_more_args[@]})) ]; then
  echo "usage: $0 <retrace binary> <source dir>${cli_more_args[*]:+ ${cli_more_args[*]}}" >&2
  exit 2
fi
case "$1" in
  /*) retrace="$1" ;;
  */*) retrace="$PWD/$1" ;;
  *) retrace=$(command -v "$1") || retrace="$1" ;;
esac
case "$2" in /*) src="$2" ;; *) src="$PWD/$2" ;; esac
if [ ! -f "$retrace" ] || [ ! -x "$retrace" ]; then
  echo "FAIL: not an executable: $retrace"
  exit 1
fi
[ -d "$src" ] || { echo "FAIL: no source dir: $src"; exit 1; }

bg_pid=""
tmp=$(mktemp -d ${cli_tmp_template:+"$cli_tmp_template"}) || { echo "FAIL: mktemp"; exit 1; }
cli_cleanup() {  # on exit: stop the test's background run, remove $tmp (or keep it: see above)
  local code=$?
  if [ -n "$bg_pid" ]; then kill -9 "$bg_pid" 2>/dev/null; fi
  if [ "$code" -ne 0 ] && [ -n "${cli_keep_tmp_on_failure:-}" ]; then
    echo "(kept $tmp)"
  else
    rm -rf "$tmp"
  fi
}
trap cli_cleanup EXIT

pass=0
fail=0

die() {  # die <message>: a step the test cannot go on without failed; exit 1 at once
  echo "FAIL: $*"
  exit 1
}

passed() { pass=$((pass + 1)); }

failed() {  # failed <what> [file...]: count a failure, say what failed and show the files
  fail=$((fail + 1))
  echo "FAIL $1"
  shift
  if [ $# -gt 0 ]; then cat -- "$@"; fi
}

check() {  # check <name> <command...>: the command must succeed (counted)
  local name="$1"
  shift
  if "$@"; then passed; else failed "$name"; fi
}

# shellcheck disable=SC2119,SC2120  # (the label is optional)
finish() {  # finish [label]: print "[label: ]<pass> passed, <fail> failed"; exit 0 only if none failed
  echo "${1:+$1: }$pass passed, $fail failed"
  [ "$fail" -eq 0 ] || exit 1
  exit 0
}

run() {  # run <name> <retrace args...>: a step the test needs, which must exit 0 (die if not);
         # its stdout and stderr stay in $tmp/<name>.out and $tmp/<name>.err
  local name="$1"
  shift
  "$retrace" "$@" >"$tmp/$name.out" 2>"$tmp/$name.err" ||
    die "$name: retrace $1 exited $?: $(cat "$tmp/$name.out" "$tmp/$name.err")"
}

make_file() {  # make_file <name> <text>: write <text>, its backslash escapes (\n) expanded, to $tmp/<name>
  printf '%b' "$2" >"$tmp/$1"
}

ros_map() {  # ros_map <yaml> <image> <origin>: a ROS map YAML in $tmp, thresholds as map_server's defaults
  make_file "$1" "image: $2\nresolution: 0.05\norigin: $3\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"
}

pnm_file() {  # pnm_file <name> <header> <bytes>: a PGM/PPM in $tmp, that header then that many zero bytes
  make_file "$1" "$2"
  head -c "$3" /dev/zero >>"$tmp/$1"
}

# The small scenario's teaching drive shortened to 12 m (with one map switch, at 6 m), as the
# arguments of `retrace`: "$retrace" "${short_teach[@]}" --mode ... --out ...
# shellcheck disable=SC2034  # (used by the scripts)
short_teach=(teach "$src/scenarios/small.yaml" --set 'route.points=[[1, 1], [9, 1], [9, 5]]'
             --set 'route.switch_points=[6]')

tree_state() {  # tree_state: every entry under $tmp but $tmp/stdout and $tmp/stderr, files and
                # links with their size and modification time, one a line, sorted
  find "$tmp" -mindepth 1 \( -path "$tmp/stdout" -o -path "$tmp/stderr" \) -prune -o \
    \( -type d -printf '%P/\n' \) -o -printf '%P %s %T@\n' | sort
}

# expect_bad <name> <expected substring> <args...>: bad input refused. Runs
#   timeout $bad_timeout "${bad_prefix[@]}" "$retrace" "${bad_command[@]}" <args...> "${bad_suffix[@]}"
# and requires, counted as one check:
#   - exit code 2 (so no crash, no sanitizer abort, no timeout);
#   - exactly one line on stderr, ended by a line break, that is retrace's own ("retrace: ...")
#     and contains the substring;
#   - nothing on stdout;
#   - nothing written, changed or removed under $tmp (but $tmp/stdout and $tmp/stderr): no output
#     file or folder, no staging folder, no partial output, inputs untouched;
#   - if $bad_max_ms is set, an answer in less than that many milliseconds.
# Passing, it prints "ok   <name> (<ms> ms): <the stderr line>"; failing, what was wrong and stderr.
bad_prefix=()   # a command retrace runs under, e.g. (setpriv ...) to run it as another user
bad_command=()  # words before each case's arguments, e.g. (bench): the subcommand
bad_suffix=()   # words after each case's arguments, e.g. (--out "$tmp/study")
bad_timeout=300 # s; a run that takes longer is killed (exit 124)
bad_max_ms=""   # ms; empty: not timed
expect_bad() {
  local name="$1" want="$2"
  shift 2
  local before after start end code ms lines ends
  local why=()
  before=$(tree_state)
  start=$(date +%s%N)
  timeout "$bad_timeout" "${bad_prefix[@]}" "$retrace" "${bad_command[@]}" "$@" "${bad_suffix[@]}" \
    >"$tmp/stdout" 2>"$tmp/stderr"
  code=$?
  end=$(date +%s%N)
  ms=$(((end - start) / 1000000))
  after=$(tree_state)
  lines=$(grep -c '' "$tmp/stderr")
  ends=$(wc -l <"$tmp/stderr")
  [ "$code" -eq 2 ] || why+=("exit $code, not 2")
  if [ "$lines" -ne 1 ] || [ "$ends" -ne 1 ]; then
    why+=("$lines stderr lines ($ends line breaks), not one")
  fi
  grep -q '^retrace: ' "$tmp/stderr" || why+=("stderr is not retrace's line")
  grep -qF -- "$want" "$tmp/stderr" || why+=("stderr does not say '$want'")
  [ ! -s "$tmp/stdout" ] || why+=("stdout not empty: $(head -c 300 "$tmp/stdout")")
  if [ "$before" != "$after" ]; then
    why+=("written, changed or removed under $tmp: $(diff <(echo "$before") <(echo "$after") |
      sed -n 's/^[<>] //p' | cut -d' ' -f1 | sort -u | tr '\n' ' ')")
  fi
  if [ -n "$bad_max_ms" ] && [ "$ms" -ge "$bad_max_ms" ]; then
    why+=("took $ms ms, limit $bad_max_ms")
  fi
  if [ ${#why[@]} -eq 0 ]; then
    passed
    echo "ok   $name ($ms ms): $(cat "$tmp/stderr")"
  else
    failed "$name: $(printf '%s; ' "${why[@]}")stderr:" "$tmp/stderr"
  fi
}
