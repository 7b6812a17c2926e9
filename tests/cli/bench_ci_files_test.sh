#!/usr/bin/env bash
# The files `retrace bench` writes for CI systems, read by outside consumers: the JUnit XML
# (--junit) by junitparser (Debian's python3-junitparser), the trend file (--trend) against the
# Bencher Metric Format's published JSON Schema (tests/data/bmf.schema.json, with Debian's
# python3-jsonschema). On the tiny suite tests/data/suite_tiny.yaml (one lap of the test room,
# one seed, one run: under a second a run), against a baseline recorded here:
#   1. the first recording (--update-baseline, no baseline yet): exit 0, every gated metric a
#      passing testcase, the run's version, revision and wall time as properties;
#   2. a passing run: exit 0, the same testcases, no failure; its trend file valid BMF with every
#      row of the table, each under the measure of its direction, lower <= value <= upper;
#   3. a regression (dynamic scan point rejection off): exit 1, and the JUnit file written all the
#      same, its failures exactly the table's FAIL rows, each message with baseline, now, delta
#      and tolerance.
# Each reader is first shown a broken file, to prove it rejects one. The missing packages are a
# failure, not a skip: CI installs them (scripts/install_deps.sh --test).
# Usage: bench_ci_files_test.sh <retrace binary> <source dir>
. "$(dirname "$0")/lib.sh" || exit 1
# The system's Python, where Debian's packages are (a `python3` on PATH may be another one).
py=/usr/bin/python3
"$py" -c 'import junitparser, jsonschema' 2>/dev/null ||
  die "python3-junitparser and python3-jsonschema are not installed (scripts/install_deps.sh --test installs them)"

cd "$src" || exit 1
bench() {  # bench <name> <expected exit code> <extra args...>
  local name="$1" want="$2"
  shift 2
  "$retrace" bench tests/data/suite_tiny.yaml --baseline "$tmp/suite_tiny.json" --jobs 2 --no-report \
    --out "$tmp/$name" --junit "$tmp/$name.xml" --trend "$tmp/$name.json" "$@" \
    >"$tmp/$name.out" 2>"$tmp/$name.err"
  local code=$?
  [ "$code" -eq "$want" ] || die "$name: exit $code, expected $want: $(cat "$tmp/$name.out" "$tmp/$name.err")"
  [ ! -s "$tmp/$name.err" ] || die "$name: stderr: $(cat "$tmp/$name.err")"
}
bench record 0 --update-baseline
bench pass 0
bench regression 1 --set nav.localizer.rejection.enabled=false

# The table's rows and verdicts, for the readers to compare with: "<metric> <verdict>" per line.
for name in record pass regression; do
  grep -vE '^(metric|suite) ' "$tmp/$name.out" |
    sed -E 's/^([^ ]+) +[^ ]+ +[^ ]+ +[^ ]+ +([^ ]+) .*$/\1 \2/' >"$tmp/$name.rows"
done

printf '<?xml version="1.0"?>\n<testsuites><testsuite name="x"><testcase name="y"></testsuite>\n' \
  >"$tmp/broken.xml"
printf '{"a.b.c": {"lower-is-better": {"value": null}}}\n' >"$tmp/broken.json"

"$py" - "$tmp" tests/data/bmf.schema.json <<'EOF'
import json
import sys

import jsonschema
from junitparser import Failure, JUnitXml

tmp, schema_file = sys.argv[1], sys.argv[2]
errors = []


def check(condition, what):
    if not condition:
        errors.append(what)


def table(name):
    """The rows bench printed: {metric: verdict}."""
    rows = {}
    with open(f"{tmp}/{name}.rows") as f:
        for line in f:
            metric, verdict = line.split()
            rows[metric] = verdict
    return rows


def read_junit(name):
    """junitparser's view: suites, {case: failure message or None}, properties of each suite."""
    xml = JUnitXml.fromfile(f"{tmp}/{name}.xml")
    suites = list(xml)
    cases, properties = {}, []
    for suite in suites:
        properties.append({p.name: p.value for p in suite.properties()})
        failed = 0
        for case in suite:
            messages = [r.message for r in case.result if isinstance(r, Failure)]
            cases[case.name] = messages[0] if messages else None
            failed += bool(messages)
            check(case.classname == suite.name, f"{name}: {case.name} classname {case.classname}")
        check(suite.failures == failed, f"{name}: suite {suite.name} says {suite.failures} failures, has {failed}")
    check(xml.tests == len(cases), f"{name}: {xml.tests} tests, {len(cases)} testcases")
    check(xml.failures == sum(m is not None for m in cases.values()), f"{name}: failures count")
    return suites, cases, properties


# The readers reject a broken file.
try:
    JUnitXml.fromfile(f"{tmp}/broken.xml")
    errors.append("junitparser read a broken XML file")
except Exception:
    pass
schema = json.load(open(schema_file))
jsonschema.Draft7Validator.check_schema(schema)
try:
    jsonschema.validate(json.load(open(f"{tmp}/broken.json")), schema, cls=jsonschema.Draft7Validator)
    errors.append("the BMF schema accepted a null value")
except jsonschema.ValidationError:
    pass

# The gated metrics: those the compared runs do not call `report` (the first recording calls
# every row "new").
gated = {m for m, v in table("pass").items() if v != "report"}
check(len(gated) == 5, f"the tiny suite gates {sorted(gated)}")
for name in ("record", "pass", "regression"):
    rows = table(name)
    suites, cases, properties = read_junit(name)
    check(set(cases) == gated, f"{name}: testcases {sorted(cases)} are not the gated rows {sorted(gated)}")
    check([s.name for s in suites] == ["small.partial"], f"{name}: testsuites {[s.name for s in suites]}")
    for p in properties:
        for key in ("retrace_version", "git_revision", "wall_time_s", "date", "suite"):
            check(p.get(key), f"{name}: no property {key}")
        check(float(p.get("wall_time_s", "nan")) > 0, f"{name}: wall_time_s {p.get('wall_time_s')}")
    failing = {m for m, v in rows.items() if v == "FAIL"}
    junit_failing = {c for c, message in cases.items() if message is not None}
    check(junit_failing == failing, f"{name}: JUnit failures {sorted(junit_failing)}, table FAIL rows {sorted(failing)}")
    for case, message in cases.items():
        if message is not None:
            for word in ("baseline ", "now ", "delta ", "tolerance "):
                check(word in message, f"{name}: {case}: '{word}' not in '{message}'")
            print(f"{name}: {case}: {message}")

check(len(table("record")) == len(table("pass")), "record and pass list different rows")
check(not [v for v in table("record").values() if v != "new"], "the first recording judged something")
check("small.partial.dynamic_points.recall" in {c for c, m in read_junit("regression")[1].items() if m},
      "the regression run does not fail dynamic_points.recall")

# The trend file: valid BMF, every defined row of the table, its direction as the measure.
trend = json.load(open(f"{tmp}/pass.json"))
jsonschema.validate(trend, schema, cls=jsonschema.Draft7Validator)
check(list(trend) == list(table("pass")), f"trend benchmarks {list(trend)} are not the table's rows")
expected = {"small.partial.success_rate": "higher-is-better",
            "small.partial.dynamic_points.recall": "higher-is-better",
            "small.partial.cpu.real_time_factor": "higher-is-better",
            "small.partial.tracking_error_m.pooled.rms": "lower-is-better",
            "small.partial.localization_error_m.pooled.rms": "lower-is-better"}
for benchmark, measures in trend.items():
    check(len(measures) == 1 and set(measures) <= {"lower-is-better", "higher-is-better"},
          f"trend {benchmark}: measures {list(measures)}")
    for measure, metric in measures.items():
        check(expected.get(benchmark, measure) == measure, f"trend {benchmark}: {measure}")
        check(metric["lower_value"] <= metric["value"] <= metric["upper_value"], f"trend {benchmark}: bounds")
# An undefined metric is left out of the regression run's trend, which is valid all the same.
regression = json.load(open(f"{tmp}/regression.json"))
jsonschema.validate(regression, schema, cls=jsonschema.Draft7Validator)

if errors:
    print("\n".join("FAIL: " + e for e in errors))
    sys.exit(1)
print(f"junitparser read 3 files ({len(read_junit('pass')[1])} testcases each); "
      f"the trend file is valid BMF ({len(trend)} benchmarks)")
EOF
