"""A sensor wrapper in Python on a proclaim whiteboard held by another process over Zenoh.

It posts `doorOpen` as a sensor would and reads back the reasoner expert's answer (`light`),
speaking the whiteboard's wire format (docs/whiteboard-wire.md) with Zenoh's own Python
package (`pip install eclipse-zenoh==1.9.0`); no proclaim code runs in this process.

    proclaim expert microwave --listen tcp/127.0.0.1:7447 &
    python3 zenoh_sensor.py tcp/127.0.0.1:7447
"""

import json
import queue
import sys
import time

import zenoh

BOARD = "proclaim"  # `--board NAME` of the holder; `proclaim` unless given


def join(endpoint):
    """A Zenoh peer session connected to the holder only, as proclaim's own processes are."""
    config = zenoh.Config()
    config.insert_json5("mode", '"peer"')
    config.insert_json5("connect/endpoints", json.dumps([endpoint]))
    config.insert_json5("scouting/multicast/enabled", "false")
    return zenoh.open(config)


class Board:
    """Posts go up to the holder; every posting comes down, numbered, to everyone."""

    def __init__(self, session, module):
        self.session = session
        self.module = module
        self.postings = queue.Queue()
        self.subscriber = session.declare_subscriber(
            f"proclaim/{BOARD}/down", lambda sample: self.postings.put(sample)
        )

    def post(self, ty, value):
        wire = {"Bool": value} if isinstance(value, bool) else {"Int": value}
        up = {"Post": {"module": self.module, "ty": ty, "value": wire}}
        self.session.put(f"proclaim/{BOARD}/up", json.dumps(up))

    def next_posting(self, ty, timeout):
        """The next posting of `ty` coming down: (value, who posted it), or None."""
        deadline = time.monotonic() + timeout
        while (left := deadline - time.monotonic()) > 0:
            try:
                sample = self.postings.get(timeout=left)
            except queue.Empty:
                return None
            down = json.loads(sample.payload.to_bytes())
            message = down.get("Posted", {}).get("message")
            if message and message["ty"] == ty:
                (kind, value), = message["value"].items()
                return value, message["module"]
        return None


def main(endpoint):
    with join(endpoint) as session:
        board = Board(session, "python-door-sensor")
        time.sleep(0.5)  # routes settle before the first put
        board.post("timeLeft", False)
        for door in (True, False, True):
            board.post("doorOpen", door)
            answer = board.next_posting("light", timeout=5)
            print(f"doorOpen = {door}: light = {answer}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "tcp/127.0.0.1:7447")
