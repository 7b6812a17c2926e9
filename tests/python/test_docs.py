"""Every ```python block of docs/PYTHON.md runs as written: the blocks of each section in order, in
one interpreter (as a reader would run them one after the other; each section imports what it
uses), the sections side by side (one interpreter each, as many at once as there are cores), from
a scratch folder laid out like the repository (its scenarios/, worlds/, bench/ and tests/ linked
in), so that what they write stays there."""

import concurrent.futures
import json
import os
import re
import subprocess
import sys
import textwrap

from conftest import SOURCE_DIR

DRIVER = textwrap.dedent("""
    import json, sys, traceback
    blocks = json.load(open(sys.argv[1]))
    scope = {"__name__": "__main__"}
    for i, (line, code) in enumerate(blocks):
        try:
            exec(compile(code, f"docs/PYTHON.md:{line}", "exec"), scope)
        except Exception:
            traceback.print_exc()
            sys.exit(f"block {i + 1} of {len(blocks)} (docs/PYTHON.md line {line}) failed")
""")


def python_blocks(markdown):
    """{section title: [(line of the block's first code line, code)]} of every ```python block,
    by the `## ` section it is in."""
    sections = {}
    titles = [(m.start(), m.group(1)) for m in re.finditer(r"^## (.*)$", markdown, re.M)]
    for match in re.finditer(r"^```python\n(.*?)^```$", markdown, re.S | re.M):
        title = [t for start, t in titles if start < match.start()][-1]
        line = markdown.count("\n", 0, match.start(1)) + 1
        sections.setdefault(title, []).append((line, match.group(1)))
    return sections


def run_section(folder, index, blocks):
    (folder / f"blocks_{index}.json").write_text(json.dumps(blocks))
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))
    return subprocess.run([sys.executable, "-c", DRIVER, f"blocks_{index}.json"], cwd=folder,
                          env=env, capture_output=True, text=True, timeout=600)


def test_every_python_example_of_the_docs_runs(tmp_path):
    sections = python_blocks((SOURCE_DIR / "docs" / "PYTHON.md").read_text())
    assert sum(len(blocks) for blocks in sections.values()) >= 3
    for folder in ("scenarios", "worlds", "bench", "tests"):
        (tmp_path / folder).symlink_to(SOURCE_DIR / folder)
    with concurrent.futures.ThreadPoolExecutor(max_workers=os.cpu_count()) as pool:
        done = {title: pool.submit(run_section, tmp_path, i, blocks)
                for i, (title, blocks) in enumerate(sections.items())}
    for title, future in done.items():
        result = future.result()
        assert result.returncode == 0, f"section '{title}':\n{result.stdout}{result.stderr}"
    # The examples' figures were drawn.
    assert list((tmp_path / "results").rglob("*.png"))


RESULTS_SCRIPT = SOURCE_DIR / "scripts" / "results.py"


def results_script(*args):
    return subprocess.run([sys.executable, str(RESULTS_SCRIPT), *map(str, args)],
                          capture_output=True, text=True, timeout=120)


def fake_suite_report(folder):
    """A `retrace bench` folder with one entry: what scripts/results.py reads of it."""
    folder.mkdir()
    values = {"success_rate": 0.5, "tracking_error_m.pooled.rms": 0.123,
              "localization_error_m.pooled.p95": 0.25, "localization_error_m.pooled.max": 1.5,
              "repeatability_m": 0.02, "switch_error.max_m": 0.07,
              "collisions.pedestrian_incidents": 0.25, "localizer.silent_failure_time_s": 0.0}
    report = {"entries": [{"name": "small", "modes": ["partial"]}],
              "metrics": {f"small.partial.{k}": {"mean": v} for k, v in values.items()}}
    (folder / "report.json").write_text(json.dumps(report))


def test_the_docs_tables_are_checked_against_their_command(tmp_path):
    """scripts/results.py: a table written from its command's output checks clean; a number
    edited by hand fails the check on the platform the table was made on; elsewhere only the
    table's shape is gated."""
    docs = tmp_path / "docs_root"
    (docs / "docs").mkdir(parents=True)
    for name in ("README.md", "docs/RESULTS.md"):
        (docs / name).write_text((SOURCE_DIR / name).read_text())
    fake_suite_report(tmp_path / "suite")
    given = ["--docs", docs, "--output", f"ci-suite={tmp_path / 'suite'}"]
    results = docs / "docs" / "RESULTS.md"

    written = results_script("write", "ci-suite", *given)
    assert written.returncode == 0, written.stderr
    assert "| small | partial | 0.5 | 0.123 | 0.250 | 1.50 |" in results.read_text()
    clean = results_script("check", "--under", "0", *given)
    assert clean.returncode == 0, clean.stderr

    made = results.read_text()
    results.write_text(made.replace("| 0.123 |", "| 0.124 |"))
    edited = results_script("check", "--under", "0", *given)
    assert edited.returncode == 1
    assert "'ci-suite' differs from what its command gives now" in edited.stderr
    assert "-| small | partial | 0.5 | 0.124 |" in edited.stderr

    # Made on another platform: the number moved by chaos, not by hand, is reported only ...
    foreign = re.sub(r"(<!-- results: ci-suite platform:)\w+", r"\1ffffffff", made)
    results.write_text(foreign.replace("| 0.123 |", "| 0.124 |"))
    moved = results_script("check", "--under", "0", *given)
    assert moved.returncode == 0, moved.stderr
    assert "numbers are not gated here" in moved.stdout
    # ... but a row that is not there is a different table.
    results.write_text(foreign.replace("| small | partial |", "| small | partial | 1 |"))
    assert results_script("check", "--under", "0", *given).returncode == 1

    # A block whose first line does not name its command.
    results.write_text(made.replace("`scripts/results.py write ci-suite`:", "Made by:"))
    unnamed = results_script("check", "--under", "0", *given)
    assert unnamed.returncode == 1
    assert "does not name its command" in unnamed.stderr
