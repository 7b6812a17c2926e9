#!/usr/bin/env bash
# `retrace sweep` and `retrace merge` on bad input: exit code 2, exactly one line on stderr
# naming the problem, and no results folder written (or an existing one left unchanged).
# Usage: sweep_bad_input_test.sh <retrace binary> <source dir>
. "$(dirname "$0")/lib.sh" || exit 1

scenario="$src/scenarios/small.yaml"
sweep() { make_file "$1" "scenario: $scenario\n$2"; }
sweep unknown_key.yaml 'repeats: 2\ngrid:\n  nav.localizer.partcles: [100, 200]\n'
sweep empty_grid.yaml 'grid:\n  nav.localizer.particles: []\n'
sweep unknown_metric.yaml 'grid:\n  nav.localizer.particles: [100]\nmetrics: [success_rate, tracking_rms]\n'
sweep zip_lengths.yaml 'zip:\n  nav.localizer.particles: [100, 200]\n  nav.localizer.beam_step: [5]\n'
sweep bad_value.yaml 'grid:\n  nav.localizer.particles: [100, -5]\n'
sweep bad_mode.yaml 'grid:\n  mode: [partial, slam]\n'
sweep good.yaml 'grid:\n  nav.localizer.particles: [100]\n'

# Nothing may appear under $tmp: no $tmp/out (nor $tmp/out.tmp), no other file.
out=(--out "$tmp/out")
expect_bad unknown-key "unknown_key.yaml:4: nav.localizer.partcles: unknown key; did you mean 'particles'?" sweep "$tmp/unknown_key.yaml" "${out[@]}"
expect_bad empty-grid "empty_grid.yaml:3: grid.nav.localizer.particles: empty list" sweep "$tmp/empty_grid.yaml" "${out[@]}"
expect_bad unknown-metric "unknown metric 'tracking_rms'; did you mean 'tracking_error_m.pooled.rms'?" sweep "$tmp/unknown_metric.yaml" "${out[@]}"
expect_bad zip-lengths "zipped lists must have equal lengths" sweep "$tmp/zip_lengths.yaml" "${out[@]}"
expect_bad bad-value "bad_value.yaml:3: nav.localizer.particles: must be in" sweep "$tmp/bad_value.yaml" "${out[@]}"
expect_bad bad-mode "unknown map mode 'slam'" sweep "$tmp/bad_mode.yaml" "${out[@]}"
expect_bad missing-file "nowhere.yaml: cannot open file" sweep "$tmp/nowhere.yaml" "${out[@]}"
expect_bad bad-shard "--shard: expected i/N with 1 <= i <= N" sweep "$tmp/good.yaml" --shard 4/3 "${out[@]}"
expect_bad bad-shard-text "--shard: expected i/N" sweep "$tmp/good.yaml" --shard two "${out[@]}"
expect_bad bad-set "--set expects key.path=value" sweep "$tmp/good.yaml" --set nonsense "${out[@]}"
expect_bad set-unknown "nav.localizer.partcles: unknown key" sweep "$tmp/good.yaml" --set nav.localizer.partcles=5 "${out[@]}"
expect_bad merge-nothing "no such folder" merge "$tmp/none" --out "$tmp/out"
expect_bad merge-no-record "not a sweep results folder" merge "$tmp" --out "$tmp/out"

# A folder that holds something else is refused and left as it was.
mkdir -p "$tmp/other"
printf 'case,x\n0,1\n' >"$tmp/other/results.csv"
expect_bad foreign-results "holds results of another sweep (a results.csv without sweep.json)" sweep "$tmp/good.yaml" --out "$tmp/other"
[ "$(cat "$tmp/other/results.csv")" = "$(printf 'case,x\n0,1')" ] || failed "the foreign results.csv was changed"
[ ! -e "$tmp/other/sweep.json" ] || failed "sweep.json written into a foreign folder"

# fuzz_sweep's finding of 2026-11-26, its exact bytes: a 7-key grid that expanded into 2 GB of
# strings under the sanitizers before the case limit (then 10^6, now 10^5) refused it. Its
# scenario path is relative (../../scenarios/office.yaml), so it runs two folders down.
mkdir -p "$tmp/fuzz/a/b"
cp "$src/tests/data/fuzz_findings/sweep-oom-3c0d98a1.yaml" "$tmp/fuzz/a/b/"
ln -s "$src/scenarios" "$tmp/fuzz/scenarios"
ln -s "$src/worlds" "$tmp/fuzz/worlds"
expect_bad fuzz-sweep-oom "the sweep has more than 100000 cases" sweep "$tmp/fuzz/a/b/sweep-oom-3c0d98a1.yaml" "${out[@]}"

finish
