#!/usr/bin/env bash
# `retrace compare` on bad input: each case must print exactly one line on stderr that names the
# problem, exit with code 2 and leave no output folder (nor its staging folder) behind.
# Usage: compare_bad_input_test.sh <retrace binary> <source dir>
. "$(dirname "$0")/lib.sh" || exit 1
small="$src/scenarios/small.yaml"

# Every case: `retrace compare <args> --out $tmp/study` (and nothing written: neither the study
# nor its staging folder study.tmp, nothing on stdout).
bad_command=(compare)
bad_suffix=(--out "$tmp/study")

expect_bad unknown-mode "--modes: unknown mode 'perfect'" "$small" --modes partial,perfect --seeds 2
expect_bad one-mode "--modes: a comparison needs at least two modes (or two --stacks)" "$small" --modes partial --reference partial
expect_bad unknown-stack "--stacks: unknown stack 'nope'; registered: odometry, retrace" "$small" --stacks retrace,nope --seeds 2
expect_bad stack-twice "--stacks: 'retrace' is named twice" "$small" --stacks retrace,retrace --seeds 2
expect_bad twice "--modes: mode 'partial' is given twice" "$small" --modes partial,partial,consistent
expect_bad all-in-a-list "--modes: all means every mode; give it alone" "$small" --modes partial,all --seeds 2
expect_bad reference-missing "--reference: mode 'consistent' is not among the compared modes" "$small" --modes partial,single
expect_bad reference-unknown "--reference: unknown mode 'slam'" "$small" --reference slam
expect_bad one-seed "--seeds: at least 2 seeds are needed for a confidence interval, got 1" "$small" --seeds 1
expect_bad seeds-not-a-number "--seeds" "$small" --seeds many
expect_bad zero-repeats "--repeats" "$small" --repeats 0
expect_bad unknown-set-key "particle" "$small" --set nav.localizer.particle=100
expect_bad bad-set-syntax "--set expects key.path=value" "$small" --set nonsense
expect_bad online-no-switching "\`online\` switching needs a map mode that switches maps" "$small" --modes single,consistent --set route.switch_points=online --seeds 2
expect_bad missing-scenario "missing.yaml" "$tmp/missing.yaml"

# An output folder that cannot be created fails before any run (the staging folder comes first).
bad_suffix=()
expect_bad unwritable-output "/proc/retrace/study.tmp" "$small" --seeds 2 --out /proc/retrace/study

finish
