"""The examples of python/examples/ that need nothing but the package, run as their users run
them: a separate Python process, its exit status and output."""

import subprocess
import sys
from pathlib import Path

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def test_the_impersonator_answers_the_microwaves_labels_through_a_cooked_minute():
    done = subprocess.run(
        [sys.executable, str(EXAMPLES / "impersonator.py")],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert done.returncode == 0, done.stdout + done.stderr
    assert "states: IDLE OPEN IDLE COOKING DONE" in done.stdout
    # The theory was left out: the labels were answered by the Python expert.
    assert "left out microwave: the embedding program answers cook, light" in done.stdout
    assert any("cook" in line and "python" in line for line in done.stdout.splitlines())
