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
