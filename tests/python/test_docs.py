"""Every ```python block of docs/PYTHON.md runs as written, in order, in one interpreter (as a
reader would run them one after the other), from a scratch folder laid out like the repository
(its scenarios/, worlds/, bench/ and tests/ linked in), so that what they write stays there."""

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
    """[(line of the block's first code line, code)] of every ```python block."""
    blocks = []
    for match in re.finditer(r"^```python\n(.*?)^```$", markdown, re.S | re.M):
        blocks.append((markdown.count("\n", 0, match.start(1)) + 1, match.group(1)))
    return blocks


def test_every_python_example_of_the_docs_runs(tmp_path):
    blocks = python_blocks((SOURCE_DIR / "docs" / "PYTHON.md").read_text())
    assert len(blocks) >= 3
    for folder in ("scenarios", "worlds", "bench", "tests"):
        (tmp_path / folder).symlink_to(SOURCE_DIR / folder)
    (tmp_path / "blocks.json").write_text(json.dumps(blocks))
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))
    done = subprocess.run([sys.executable, "-c", DRIVER, "blocks.json"], cwd=tmp_path, env=env,
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stdout + done.stderr
    # The examples' figures were drawn.
    assert list((tmp_path / "results").rglob("*.png"))
