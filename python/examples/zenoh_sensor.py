"""A sensor wrapper in Python on a proclaim whiteboard shared over Zenoh.

It posts `doorOpen` as a sensor would and reads back the reasoner expert's answer (`light`),
speaking the whiteboard's wire format (docs/whiteboard-wire.md: one key per type, the value as
plain JSON, the rest in a JSON attachment) with Zenoh's own Python package
(`pip install eclipse-zenoh==1.9.0`); no proclaim code runs in this process.

    proclaim expert microwave --listen tcp/127.0.0.1:7447 &
    python3 zenoh_sensor.py tcp/127.0.0.1:7447
"""

import json
import queue
import sys
import time

import zenoh

BOARD = "proclaim"  # `--board NAME` of the other processes; `proclaim` unless given


def join(endpoint):
    """A Zenoh peer session connected to one process of the board; it also listens on a free
    loopback port so that the board's other processes, told of it by Zenoh's gossip, link to it
    directly, as proclaim's own processes do."""
    config = zenoh.Config()
    config.insert_json5("mode", '"peer"')
    config.insert_json5("connect/endpoints", json.dumps([endpoint]))
    config.insert_json5("listen/endpoints", json.dumps(["tcp/127.0.0.1:0"]))
    config.insert_json5("scouting/multicast/enabled", "false")
    # As proclaim's processes: a link that hears nothing for 1.5 s is closed (Zenoh's 10 s
    # default keeps a dead peer's link, and its subscriptions, that long).
    config.insert_json5("transport/link/tx/lease", "1500")
    config.insert_json5("transport/link/tx/keep_alive", "4")
    return zenoh.open(config)


def key(ty):
    return f"proclaim/{BOARD}/{ty}"


class Board:
    """Posts a type by putting its value on the type's key; reads one by subscribing to it."""

    def __init__(self, session, module):
        self.session = session
        self.module = module
        self.seq = {}
        self.postings = {}
        self.subscribers = []

    def post(self, ty, value):
        # The attachment may be left out; with it, readers see who posted and in what order.
        self.seq[ty] = self.seq.get(ty, 0) + 1
        meta = {"module": self.module, "seq": self.seq[ty], "time_ns": time.time_ns()}
        self.session.put(key(ty), json.dumps(value), attachment=json.dumps(meta))

    def follow(self, ty):
        """Keeps every posting of `ty` from now on, for `next_posting`."""
        postings = self.postings.setdefault(ty, queue.Queue())
        self.subscribers.append(
            self.session.declare_subscriber(key(ty), lambda sample: postings.put(sample))
        )

    def next_posting(self, ty, timeout):
        """The next posting of a followed `ty`: (value, who posted it), or None in time."""
        try:
            sample = self.postings[ty].get(timeout=timeout)
        except queue.Empty:
            return None
        value = json.loads(sample.payload.to_string())
        meta = json.loads(sample.attachment.to_string()) if sample.attachment else {}
        return value, meta.get("module")


def main(endpoint):
    with join(endpoint) as session:
        board = Board(session, "python-door-sensor")
        board.follow("light")
        time.sleep(0.5)  # links and routes settle before the first put
        board.post("timeLeft", False)
        for door in (True, False, True):
            board.post("doorOpen", door)
            answer = board.next_posting("light", timeout=5)
            print(f"doorOpen = {door}: light = {answer}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "tcp/127.0.0.1:7447")
