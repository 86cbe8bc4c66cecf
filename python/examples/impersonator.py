"""An impersonator in Python: answers the microwave's labels in place of its CDL theory, as the
original `testcdl` did, so the machine can be tried before (or without) the reasoner.

The machine (machines/microwave/Microwave.machine) asks `cook` and `light`; here a Python object
answers them from values this script changes as the virtual minutes go by, and the machine
cannot tell it from the theory. Run from the repository's root after `pip install ./python`:

    python3 python/examples/impersonator.py

It prints the run's trace and exits 0 when the microwave went IDLE, OPEN, IDLE, COOKING, DONE
(python/tests/test_examples.py runs it so).
"""

import sys
from pathlib import Path

import proclaim

MICROWAVE = Path(__file__).resolve().parents[2] / "machines" / "microwave"


class Impersonator:
    """Answers labels from a table its owner changes; remembers every question."""

    def __init__(self, **answers):
        self.answers = answers
        self.asked = []

    def experts(self):
        """One callable per label, as proclaim.Behaviour takes them."""
        return {label: self._answerer(label) for label in self.answers}

    def _answerer(self, label):
        def answer(board):
            self.asked.append(label)
            return self.answers[label]

        return answer


def main():
    oven = Impersonator(cook=False, light=False)
    # The theory answers cook and light in the manifest; these experts replace it.
    with proclaim.Behaviour(MICROWAVE, experts=oven.experts()) as microwave:
        microwave.step()
        oven.answers["light"] = True  # someone opens the door
        microwave.run(1)
        oven.answers["light"] = False  # and shuts it
        microwave.run(1)
        oven.answers.update(cook=True, light=True)  # presses the one-minute button
        # The machine leaves COOKING on its own minute's timeout, virtual seconds.
        microwave.run(61)
        for line in microwave.trace:
            print(line)
        visited = [e["state"] for e in microwave.events if e["event"] == "entered"]
        print(f"states: {' '.join(visited)}; labels asked {len(oven.asked)} times")
        return 0 if visited == ["IDLE", "OPEN", "IDLE", "COOKING", "DONE"] else 1


if __name__ == "__main__":
    sys.exit(main())
