#!/usr/bin/env bash
# Bad input to `retrace bench`: each case must print exactly one line on stderr that names the
# problem, exit with code 2, run nothing and write nothing (no report folder, no baseline, the
# existing baseline untouched).
# Usage: bench_bad_input_test.sh <retrace binary> <source dir>
. "$(dirname "$0")/lib.sh" || exit 1
cd "$tmp" || exit 1

# Every case runs `retrace bench` (and no file under $tmp may change: no report folder, no new
# baseline, the existing baseline $tmp/t.json untouched).
bad_command=(bench)

small="$src/scenarios/small.yaml"
default_metrics='  "*.*.success_rate": {abs: 0}\n'
suite() {  # suite <file> <name> <entry options> [metrics yaml]
  printf 'name: %s\nentries:\n  - {scenario: %s, modes: [partial], %s}\nmetrics:\n%b' "$2" "$small" "$3" \
    "${4:-$default_metrics}" >"$tmp/$1"
}
suite t.yaml t 'seeds: [1], repeats: 1'
suite other_seeds.yaml t 'seeds: [2], repeats: 1'
suite u.yaml u 'seeds: [1], repeats: 1'
suite nobase.yaml nobase 'seeds: [1], repeats: 1'
suite bad_set.yaml t 'seeds: [1], repeats: 1, set: {nav.localizer.particle: 3}'
suite bad_pattern.yaml t 'seeds: [1], repeats: 1' '  "*.*.tracking_rms": {abs: 0.02}\n'
suite bad_tolerance.yaml t 'seeds: [1], repeats: 1' '  "*.*.success_rate": {abs: -0.1}\n'
suite unknown_entry_key.yaml t 'seeds: [1], repeat: 1'
printf 'name: t\nentries: [{scenario: %s, modes: [partial], seeds: [1]}\nmetrics: {}\n' "$small" >"$tmp/malformed.yaml"
# A baseline of suite t, as `--update-baseline` would write it.
printf '{"format": "retrace-baseline/1", "suite": "t", "suite_file": "t.yaml", "suite_digest": "fnv1a64:0",
 "git_revision": "r", "build_type": "Release", "date": "2025-01-01T00:00:00Z",
 "entries": [{"name": "small", "scenario": "%s", "modes": ["partial"], "seeds": [1], "repeats": 1, "set": {}}],
 "metrics": {"small.partial.success_rate": 1}, "timing": {}}\n' "$small" >"$tmp/t.json"
printf '{"format": "retrace-baseline/1", "suite": "t"' >"$tmp/truncated.json"
mkdir "$tmp/ro"

base=(--baseline "$tmp/t.json" --out "$tmp/out")
expect_bad no-baseline "no baseline results/baselines/nobase.json for suite 'nobase'; record one with \`retrace bench nobase.yaml --update-baseline\`" nobase.yaml
expect_bad no-baseline-file "no baseline $tmp/none.json for suite 't'" t.yaml --baseline "$tmp/none.json"
expect_bad other-suite "t.json is the baseline of suite 't', not of 'u'" u.yaml "${base[@]}"
expect_bad changed-entry "entry 'small' has changed since the baseline (seeds [1] -> [2])" other_seeds.yaml "${base[@]}"
expect_bad truncated-baseline "truncated.json: invalid JSON" t.yaml --baseline "$tmp/truncated.json" --out "$tmp/out"
expect_bad set-unknown-key "nav.localizer.particle: unknown key; did you mean 'particles'?" t.yaml "${base[@]}" --set nav.localizer.particle=3
expect_bad set-bad-value "--set nav.localizer.particles=-5" t.yaml "${base[@]}" --set nav.localizer.particles=-5
expect_bad set-seed "--set seed=3: cannot set seed: a suite entry's \`seeds\` and \`repeats\` decide it" t.yaml "${base[@]}" --set seed=3
expect_bad set-syntax "--set expects key.path=value" t.yaml "${base[@]}" --set particles
expect_bad suite-set-unknown-key "bad_set.yaml:3: entry 'small': " bad_set.yaml --update-baseline --baseline "$tmp/new.json" --out "$tmp/out"
expect_bad set-with-update "--set cannot be combined with --update-baseline" t.yaml --update-baseline --baseline "$tmp/new.json" --set seed=3
expect_bad only-unknown-entry "--only office: suite 't' has no entry 'office' (entries: small)" t.yaml "${base[@]}" --only office
expect_bad only-unknown-mode "--only small.single: entry 'small' does not run mode 'single' (its modes: partial)" t.yaml "${base[@]}" --only small.single
expect_bad only-with-update "--only cannot be combined with --update-baseline" t.yaml --update-baseline --baseline "$tmp/new.json" --only small
expect_bad update-other-suite "t.json is the baseline of suite 't'; --update-baseline does not overwrite another suite's baseline" u.yaml --update-baseline "${base[@]}"
expect_bad malformed-suite "malformed.yaml:3: invalid YAML" malformed.yaml "${base[@]}"
expect_bad missing-suite "missing.yaml: cannot open file" missing.yaml "${base[@]}"
expect_bad pattern-matches-nothing "bad_pattern.yaml:5: metrics.*.*.tracking_rms: matches no metric" bad_pattern.yaml "${base[@]}"
expect_bad bad-tolerance "metrics.*.*.success_rate.abs: must be >= 0, got -0.1" bad_tolerance.yaml "${base[@]}"
expect_bad unknown-entry-key "entries[0].repeat: unknown key; did you mean 'repeats'?" unknown_entry_key.yaml "${base[@]}"
expect_bad no-suite-argument "suite is required" --out "$tmp/out"

# The files for CI systems (--junit, --trend): a path that cannot be written fails before
# anything runs, and leaves no file, partial or temporary, behind.
expect_bad junit-is-a-folder "--junit $tmp/ro: is a folder, not a file" t.yaml "${base[@]}" --junit "$tmp/ro"
expect_bad trend-is-a-folder "--trend $tmp/ro/: is a folder, not a file" t.yaml "${base[@]}" --trend "$tmp/ro/"
expect_bad junit-under-a-file "--junit $tmp/t.json/j.xml: cannot write there: $tmp/t.json is not a folder" \
  t.yaml "${base[@]}" --junit "$tmp/t.json/j.xml"
expect_bad trend-under-a-file "--trend $tmp/t.json/a/b.json: cannot write there: $tmp/t.json is not a folder" \
  t.yaml "${base[@]}" --trend "$tmp/t.json/a/b.json"
expect_bad junit-and-trend-alike "--junit and --trend name the same file $tmp/same.xml" \
  t.yaml "${base[@]}" --junit "$tmp/same.xml" --trend "$tmp/./same.xml"
# An unwritable folder: root writes anywhere, so as root retrace runs as nobody here.
chmod 555 "$tmp/ro"
if [ "$(id -u)" -eq 0 ]; then
  chmod 755 "$tmp"
  bad_prefix=(setpriv --reuid=65534 --regid=65534 --clear-groups)
fi
expect_bad junit-unwritable-folder "--junit $tmp/ro/j.xml: cannot write in $tmp/ro: Permission denied" \
  t.yaml "${base[@]}" --junit "$tmp/ro/j.xml"
expect_bad trend-unwritable-folder "--trend $tmp/ro/new/t.json: cannot write in $tmp/ro: Permission denied" \
  t.yaml "${base[@]}" --trend "$tmp/ro/new/t.json"
bad_prefix=()
if [ -n "$(ls -A "$tmp/ro")" ] || [ -e "$tmp/same.xml" ]; then
  failed "files left behind: $(ls -A "$tmp/ro") $(ls "$tmp"/same.xml 2>/dev/null)"
fi

finish
