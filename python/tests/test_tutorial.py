"""The book's tutorial from Python: its files written as the tutorial shows them (every block after
a `<!-- file: PATH -->` mark) and its pytest run on them, so the Python part of the tutorial is
tested wherever the package is (the Rust side, tests/book.rs, runs the rest of it)."""

import re
import subprocess
import sys
from pathlib import Path

TUTORIAL = Path(__file__).resolve().parents[2] / "docs" / "book" / "src" / "tutorial.md"


def files(text):
    """(path, text, appended) for each marked code block, in order."""
    found = []
    for mark, body in re.findall(r"<!-- file: ([^>]*?) -->\n```[^\n]*\n(.*?)```", text, re.S):
        appended = mark.endswith("(appended)")
        found.append((mark.replace("(appended)", "").strip(), body, appended))
    return found


def test_the_tutorials_python_test_passes_on_its_goalkeeper(tmp_path):
    written = files(TUTORIAL.read_text())
    assert any(path == "test_goalkeeper.py" for path, _, _ in written)
    for path, body, appended in written:
        target = tmp_path / path
        target.parent.mkdir(parents=True, exist_ok=True)
        with open(target, "a" if appended else "w") as out:
            out.write(body)
    run = subprocess.run(
        [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "test_goalkeeper.py"],
        cwd=tmp_path,
        capture_output=True,
        text=True,
    )
    assert run.returncode == 0, run.stdout + run.stderr
    assert "2 passed" in run.stdout, run.stdout
