#!/usr/bin/env bash
# The CI suite catches a real navigation regression: with dynamic scan point rejection turned
# off (the paper's defence against pedestrians), `retrace bench bench/suites/ci.yaml --only
# office.partial` against the committed baseline must exit 1, print FAIL rows for the office's
# partial-map success rate and localization error and a FAIL verdict line, judge nothing it did
# not run, write its report, and leave the baseline untouched. The office's partial maps are
# what the rejection protects, so `--only` runs just them: lost runs end early, about 25 s of
# CPU instead of the whole suite's 600 (system tier all the same).
# Usage: bench_regression_test.sh <retrace binary> <source dir>
. "$(dirname "$0")/lib.sh" || exit 1
cd "$src" || exit 1
baseline="results/baselines/ci.json"
before=$(cksum <"$baseline")

"$retrace" bench bench/suites/ci.yaml --only office.partial --jobs 2 --out "$tmp/report" \
  --set nav.localizer.rejection.enabled=false \
  >"$tmp/stdout" 2>"$tmp/stderr"
code=$?

check "exit code 1 (got $code)" [ "$code" -eq 1 ]
# Not only the dynamic-point statistics (trivially 0 without rejection): the robot gets lost.
check "office partial success FAIL" grep -qE '^office\.partial\.success_rate .* FAIL ' "$tmp/stdout"
check "office partial localization FAIL" grep -qE '^office\.partial\.localization_error_m\.pooled\.p95 .* FAIL ' "$tmp/stdout"
check "the verdict line" grep -qE '^suite ci: FAIL: [0-9]+ of [0-9]+ metrics regressed .*1 entry \(--only office\.partial\)' "$tmp/stdout"
check "no row of a mode it did not run" bash -c "! grep -qE '^(small\.|office\.(single|consistent)\.)' '$tmp/stdout'"
check "report.json says FAIL" grep -q '"verdict": "FAIL"' "$tmp/report/report.json"
check "report.md written" grep -q '^# Suite ci: FAIL' "$tmp/report/report.md"
check "report.md says what ran" grep -qF -- '- `--only office.partial`' "$tmp/report/report.md"
check "the baseline untouched" [ "$(cksum <"$baseline")" = "$before" ]
check "nothing on stderr" [ ! -s "$tmp/stderr" ]
if [ "$fail" -ne 0 ]; then
  cat "$tmp/stdout" "$tmp/stderr"
  finish
fi
check "the FAIL rows and the verdict line printed" grep -E ' FAIL |^suite ' "$tmp/stdout"
finish
