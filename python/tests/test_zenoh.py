"""The whiteboard from Python over Zenoh: a Python sensor wrapper (examples/zenoh_sensor.py, with
Zenoh's own `eclipse-zenoh` package and no proclaim code) subscribes to `light` and posts
`doorOpen`, each on its own key with a plain JSON value, to a board shared with `proclaim expert
microwave --listen` in another process, and reads the reasoner's answer back; a get on `light`'s
key is answered with its current value. Loopback only, on a free port.

Needs a `proclaim` built with the `zenoh` feature: PROCLAIM_ZENOH_BIN (.ci/run sets it after
its Zenoh build, in a run of this test alone); skipped without it."""

import importlib.util
import os
import socket
import statistics
import subprocess
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "python" / "examples"))


def zenoh_binary():
    path = os.environ.get("PROCLAIM_ZENOH_BIN")
    if not path:
        pytest.skip("PROCLAIM_ZENOH_BIN names no proclaim built with the zenoh feature")
    # Asked for, so what it needs must be there.
    if importlib.util.find_spec("zenoh") is None:
        pytest.fail("the eclipse-zenoh package is not installed")
    if not os.access(path, os.X_OK):
        pytest.fail(f"PROCLAIM_ZENOH_BIN={path} is not a program")
    return path


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture
def expert():
    binary = zenoh_binary()
    endpoint = f"tcp/127.0.0.1:{free_port()}"
    process = subprocess.Popen(
        [binary, "expert", "microwave", "--listen", endpoint, "--for", "60s"],
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
    )
    # The expert says where it listens once it does.
    for line in process.stdout:
        if endpoint in line:
            break
    yield endpoint
    process.terminate()
    process.wait(timeout=10)


def test_a_python_sensor_posts_and_reads_the_reasoners_answer(expert):
    import json

    import zenoh_sensor

    with zenoh_sensor.join(expert) as session:
        board = zenoh_sensor.Board(session, "python-door-sensor")
        board.follow("light")
        time.sleep(0.5)
        board.post("timeLeft", False)
        board.post("doorOpen", True)
        assert board.next_posting("light", timeout=10) == (True, "microwave")
        board.post("doorOpen", False)
        assert board.next_posting("light", timeout=10) == (False, "microwave")

        # A late reader asks for the current value: the process that posted it answers.
        replies = list(session.get("proclaim/proclaim/light", timeout=5))
        answers = [json.loads(r.ok.payload.to_string()) for r in replies if r.ok is not None]
        assert answers == [False], replies

        # Round trips: a posting from Python, the reasoner's changed answer back in Python.
        samples = []
        for i in range(200):
            door = i % 2 == 0
            started = time.perf_counter()
            board.post("doorOpen", door)
            assert board.next_posting("light", timeout=10) == (door, "microwave")
            samples.append(time.perf_counter() - started)
        samples.sort()
        p50 = statistics.median(samples) * 1e6
        p99 = samples[int(len(samples) * 0.99) - 1] * 1e6
        print(f"\npython post -> reasoner -> python read over Zenoh: p50 {p50:.0f} us, p99 {p99:.0f} us")
