"""Behaviours driven from Python: the microwave of machines/ from whiteboard postings to its final
state, the kettle of tests/kettle with Python host functions and experts answering its labels,
exceptions in callables, bad folders, the virtual clock."""

import gc
import json
import threading
import time
import weakref
from pathlib import Path

import pytest

import proclaim

ROOT = Path(__file__).resolve().parents[2]
MICROWAVE = ROOT / "machines" / "microwave"
SEARCH = ROOT / "machines" / "search"
KETTLE = Path(__file__).resolve().parent / "kettle"


def entered(events):
    return [(e["machine"], e["state"]) for e in events if e["event"] == "entered"]


def test_the_microwave_with_its_kitchen_script_cooks_a_virtual_minute_to_its_final_state():
    # The manifest's kitchen script opens the door at 1 s, shuts it at 3 s, presses the button
    # at 4 s; the theory answers cook and light; the minute is virtual.
    with proclaim.Behaviour(MICROWAVE) as oven:
        assert oven.states() == {"Microwave": None}
        first = oven.step()
        assert ("Microwave", "IDLE") in entered(first)
        assert oven.read("Light") == "off"
        assert not oven.finished
        started = time.monotonic()
        events = oven.run(70)
        assert time.monotonic() - started < 30, "a virtual minute takes no real minute"
        assert [s for _, s in entered(events)] == ["OPEN", "IDLE", "COOKING", "DONE"]
        done = next(e for e in events if e["event"] == "entered" and e["state"] == "DONE")
        assert done["at_us"] == 64_000_000, "a minute after the button at 4 s"
        assert oven.state("Microwave") == "DONE"
        assert oven.finished
        assert oven.read("Magnetron") == "off"
        assert oven.read("Beeper") == "beep beep beep"
        assert oven.read("timeLeft") is False
        assert [s for _, s in entered(oven.events)] == ["IDLE", "OPEN", "IDLE", "COOKING", "DONE"]
        assert any("DONE" in line for line in oven.trace)


def test_the_microwave_follows_what_python_posts_round_by_round():
    with proclaim.Behaviour(MICROWAVE) as oven:
        oven.step()
        # At virtual time 0, before the kitchen script's first line: the test is the kitchen.
        oven.post("doorOpen", True)
        assert oven.run_until(lambda b: b.state("Microwave") == "OPEN", rounds=10)
        assert oven.read("Light") == "on"
        oven.post("doorOpen", False)
        oven.post("timeLeft", True)
        assert oven.run_until(lambda b: b.state("Microwave") == "COOKING", rounds=10)
        assert oven.read("Magnetron") == "on"
        rounds = oven.rounds
        for _ in range(5):
            oven.step()
        assert (oven.state("Microwave"), oven.time) == ("COOKING", 0.0), "a step takes no time"
        assert oven.rounds == rounds + 5
        # run_until waits for what is due next: the kitchen script opens the door at 1 s.
        assert oven.run_until(lambda b: b.state("Microwave") == "OPEN", rounds=5)
        assert oven.time == 1.0


def test_a_python_expert_for_one_label_leaves_the_theory_answering_the_rest():
    # The theory answers cook and light; Python takes light alone (always dark). The theory
    # once went silent whole, so cook was never answered and the oven never cooked.
    with proclaim.Behaviour(MICROWAVE, experts={"light": lambda board: False}) as oven:
        events = oven.run(5)
        # The door opens at 1 s with no light: the machine stays IDLE; the minute set at 4 s
        # is the theory's cook.
        assert [s for _, s in entered(events)] == ["IDLE", "COOKING"]
        assert oven.read("Magnetron") == "on"


def test_posting_a_label_another_module_answers_is_an_error_not_ignored():
    with proclaim.Behaviour(MICROWAVE) as oven:
        oven.step()
        # The theory answers cook: a posting of it would change nothing the machine asks.
        with pytest.raises(ValueError, match="`cook` is a label the machines ask and microwave answers"):
            oven.post("cook", True)
        # An input the theory reads from the board is a posting that counts.
        oven.post("doorOpen", True)
        assert oven.run_until(lambda b: b.state("Microwave") == "OPEN", rounds=10)


@pytest.mark.parametrize("none", [None, ""])
def test_script_none_or_empty_plays_no_script_and_left_out_plays_the_manifests(none):
    with proclaim.Behaviour(MICROWAVE, script=none) as oven:
        oven.run(10)
        assert oven.state("Microwave") == "IDLE", "no kitchen script: nobody opens the door"
        assert oven.read("doorOpen") is None
    with proclaim.Behaviour(MICROWAVE) as oven:
        oven.run(10)
        assert oven.state("Microwave") == "COOKING"


def kettle(boiling, beeps, **options):
    """The kettle with Python answering both labels; `beeps` collects the host calls."""
    hosts = {"beep": beeps.append, "alarm": beeps.append}
    experts = {"switchedOn": lambda board: True, "boiling": boiling}
    return proclaim.Behaviour(KETTLE, hosts=hosts, experts=experts, **options)


def test_a_python_expert_answers_a_label_from_the_board_and_a_host_function_gets_its_argument():
    asked = []

    def boiling(board):
        asked.append(board["temperature"])
        return (board.read("temperature") or 0) >= 100

    beeps = []
    with kettle(boiling, beeps) as k:
        assert k.run_until(lambda b: b.state("Kettle") == "HEATING", rounds=5)
        assert k.read("Element") == "on"
        for temperature in (20, 60, 99):
            k.post("temperature", temperature)
            k.step()
            assert k.state("Kettle") == "HEATING"
        assert beeps == []
        k.post("temperature", 100)
        assert k.run_until(lambda b: b.finished, rounds=5)
        assert k.state("Kettle") == "BOILED"
        assert beeps == [3]
        assert k.read("Element") == "off"
        assert asked[-1] == 100 and 20 in asked and 99 in asked


def test_the_kettle_times_out_after_five_virtual_minutes_and_calls_alarm_with_a_string():
    beeps = []
    with kettle(lambda board: False, beeps) as k:
        k.run_until(lambda b: b.state("Kettle") == "HEATING", rounds=5)
        k.wait(299)
        k.step()
        assert k.state("Kettle") == "HEATING"
        k.wait(1)
        assert k.run_until(lambda b: b.finished, rounds=5)
        assert k.state("Kettle") == "TIMED_OUT"
        assert beeps == ["no boil"]


def test_an_expert_that_raises_answers_false_and_the_step_raises_callback_error():
    def broken(board):
        raise ZeroDivisionError("the thermometer divided by zero")

    beeps = []
    with kettle(broken, beeps) as k:
        # The round that enters HEATING asks `boiling` at once.
        with pytest.raises(proclaim.CallbackError) as raised:
            k.run_until(lambda b: b.state("Kettle") == "HEATING", rounds=5)
        assert raised.value.callable == "the expert for `boiling`"
        assert isinstance(raised.value.__cause__, ZeroDivisionError)
        assert "thermometer" in str(raised.value)
        # Answered false: still heating, and the behaviour can go on.
        assert k.state("Kettle") == "HEATING"
        with pytest.raises(proclaim.CallbackError):
            k.step()


def test_an_expert_that_answers_what_is_no_truth_value_is_a_callback_error():
    with kettle(lambda board: "yes", []) as k:
        with pytest.raises(proclaim.CallbackError) as raised:
            k.run_until(lambda b: b.state("Kettle") == "HEATING", rounds=5)
        assert isinstance(raised.value.__cause__, TypeError)
        assert "'yes'" in str(raised.value.__cause__)
        assert k.state("Kettle") == "HEATING"


def test_a_host_function_that_raises_is_a_callback_error_after_its_round():
    def beep(times):
        raise RuntimeError(f"the speaker is gone ({times} beeps lost)")

    k = proclaim.Behaviour(
        KETTLE,
        hosts={"beep": beep},
        experts={"switchedOn": lambda board: True, "boiling": lambda board: True},
    )
    with pytest.raises(proclaim.CallbackError) as raised:
        k.run_until(lambda b: b.finished, rounds=10)
    assert raised.value.callable == "the host function `beep`"
    assert "3 beeps lost" in str(raised.value.__cause__)
    assert k.state("Kettle") == "BOILED"
    k.close()
    assert k.closed
    with pytest.raises(ValueError, match="closed"):
        k.step()
    k.close()


def test_a_callable_cannot_step_the_behaviour_that_called_it():
    holder = {}

    def boiling(board):
        holder["k"].step()

    k = kettle(boiling, [])
    holder["k"] = k
    with pytest.raises(proclaim.CallbackError) as raised:
        k.run_until(lambda b: b.state("Kettle") == "HEATING", rounds=5)
    assert isinstance(raised.value.__cause__, RuntimeError)
    assert "running a round" in str(raised.value.__cause__)
    holder["k"] = None
    k.close()


def test_other_threads_run_while_the_behaviour_runs():
    ticks = []
    stop = threading.Event()

    def tick():
        while not stop.is_set():
            ticks.append(1)
            time.sleep(0.001)

    ticker = threading.Thread(target=tick)
    ticker.start()
    try:
        with kettle(lambda board: False, []) as k:
            k.run_until(lambda b: b.state("Kettle") == "HEATING", rounds=5)
            before = len(ticks)
            # Real time on the wall clock, so the waiting is real and the lock must be free.
            k2 = proclaim.Behaviour(KETTLE, virtual_clock=False)
            k2.wait(0.2)
            k2.close()
            assert len(ticks) > before
    finally:
        stop.set()
        ticker.join()


def test_a_folder_that_is_no_behaviour_raises_behaviour_error_with_each_problem(tmp_path):
    with pytest.raises(proclaim.BehaviourError) as raised:
        proclaim.Behaviour(tmp_path)
    assert raised.value.problems
    assert str(tmp_path) in str(raised.value)
    (tmp_path / "behaviour.toml").write_text('[[machine]]\nfile = "M.machine"\n')
    (tmp_path / "M.machine").write_text("machine M\ninitial A\nstate A {\n  when x -> NOWHERE\n}\n")
    with pytest.raises(proclaim.BehaviourError) as raised:
        proclaim.Behaviour(tmp_path)
    files = {Path(file).name for file, _line, _column, _message in raised.value.problems}
    assert "M.machine" in files
    assert any(line == 4 for _file, line, _column, _message in raised.value.problems)


@pytest.mark.parametrize(
    "hosts, experts, message",
    [
        ({"beep": 3}, None, "not callable"),
        (None, {"boiling": "hot"}, "not callable"),
        ({1: print}, None, "keyed by name"),
    ],
)
def test_callables_are_checked_when_given(hosts, experts, message):
    with pytest.raises(TypeError, match=message):
        proclaim.Behaviour(KETTLE, hosts=hosts, experts=experts)


@pytest.mark.parametrize(
    "value",
    [True, False, 7, -2**63, 2.5, "on", b"\x00\x01", [1, "two", [3.0, False]]],
    ids=repr,
)
def test_values_cross_the_whiteboard_unchanged(value):
    with proclaim.Behaviour(KETTLE) as k:
        k.post("anything", value)
        expected = list(value) if isinstance(value, tuple) else value
        assert k.read("anything") == expected
        assert type(k.read("anything")) is type(expected)
        assert k.board.read("anything") == expected


@pytest.mark.parametrize("value", [None, {"a": 1}, 2**64, object()], ids=repr)
def test_what_the_whiteboard_cannot_hold_is_a_type_error(value):
    with proclaim.Behaviour(KETTLE) as k:
        with pytest.raises(TypeError):
            k.post("anything", value)


def test_a_negative_time_is_a_value_error():
    with proclaim.Behaviour(KETTLE) as k:
        with pytest.raises(ValueError, match="seconds"):
            k.wait(-1)
        with pytest.raises(ValueError, match="seconds"):
            k.run(float("nan"))


def test_unknown_machines_and_variables():
    with proclaim.Behaviour(KETTLE) as k:
        with pytest.raises(KeyError, match="Kettle"):
            k.state("Toaster")
        assert k.variable("Kettle", "nothing") is None


def test_a_behaviour_whose_callable_refers_back_to_it_is_collected():
    def cycle():
        holder = {}

        def boiling(board):
            return holder["kettle"].finished

        holder["kettle"] = kettle(boiling, [])
        holder["kettle"].step()
        return weakref.ref(boiling)

    gone = cycle()
    gc.collect()
    assert gone() is None, "the behaviour and its callable were left in a cycle"


def after_round(events, first):
    return [e for e in events if e["round"] >= first]


def test_a_checkpoint_taken_up_by_a_new_behaviour_goes_on_as_the_run_it_came_from():
    with proclaim.Behaviour(MICROWAVE, checkpoint_at=6) as first:
        first.step()
        first.wait(3)
        while first.checkpoint() is None:
            assert first.rounds < 100, "the checkpoint asked for is taken"
            first.step()
        text = first.checkpoint()
        at = json.loads(text)["round"]
        assert first.rounds == at, "taken when the round it holds the run before runs"
        first.run(70)
        whole = after_round(first.events, at)
        assert first.state("Microwave") == "DONE"
        with proclaim.Behaviour(MICROWAVE, resume=text) as second:
            assert second.time == 3.0, "the clock is where the checkpoint left it"
            assert second.state("Microwave") == "IDLE"
            assert second.rounds == at - 1
            second.step()
            second.run(70)
            assert second.events == whole
            assert (second.time, second.rounds) == (first.time, first.rounds)
            assert second.read("Beeper") == first.read("Beeper") == "beep beep beep"


def test_run_until_from_a_checkpoint_waits_for_what_was_due_as_the_first_run_did():
    # Taken while cooking: run_until must know when COOKING was entered to wait for its minute.
    with proclaim.Behaviour(MICROWAVE, checkpoint_at=40) as first:
        assert first.run_until(lambda b: b.state("Microwave") == "COOKING")
        assert first.rounds < 40
        while first.checkpoint() is None:
            first.step()
        text = first.checkpoint()
        at = json.loads(text)["round"]
        assert first.state("Microwave") == "COOKING"
        assert first.run_until(lambda b: b.finished)
        with proclaim.Behaviour(MICROWAVE, resume=text) as second:
            second.step()
            assert second.run_until(lambda b: b.finished)
            assert second.events == after_round(first.events, at)
            assert second.time == first.time == 64.0


def test_run_until_waits_for_a_composites_time_counted_from_its_entry_not_its_last_turn():
    # The search (entered at 1.5 s, when the ball is lost) turns the head every 400 ms, and
    # gives up 3 s after it began, whatever the turns: run_until moves the clock to that moment.
    with proclaim.Behaviour(SEARCH) as striker:
        assert striker.run_until(lambda b: b.state("Search") == "GIVE_UP")
        gave_up = [e for e in striker.events if e["event"] == "entered" and e["state"] == "GIVE_UP"]
        assert [e["at_us"] for e in gave_up] == [4_500_000]
        assert striker.time == 4.5


def test_wait_moves_the_clock_by_its_time_when_the_script_posted_meanwhile():
    with proclaim.Behaviour(MICROWAVE) as oven:
        oven.step()
        oven.wait(3)
        assert oven.time == 3.0, "the kitchen script posted at 1 s; the wait still ends at 3 s"
        oven.wait(0.5)
        assert oven.time == 3.5


def test_what_is_no_checkpoint_or_no_longer_fits_is_refused_saying_why():
    with pytest.raises(ValueError, match="resume= is not a checkpoint to take up"):
        proclaim.Behaviour(MICROWAVE, resume="{}")
    with pytest.raises(ValueError, match="rounds count from 1"):
        proclaim.Behaviour(MICROWAVE, checkpoint_at=0)
    with proclaim.Behaviour(MICROWAVE, checkpoint_at=1) as oven:
        oven.step()
        text = oven.checkpoint()
    with pytest.raises(proclaim.BehaviourError, match="cannot be taken up: the checkpoint plays a script"):
        proclaim.Behaviour(KETTLE, resume=text)
    # A Python expert keeps what it knows in Python, where no checkpoint can reach it.
    with pytest.raises(proclaim.BehaviourError, match="embedding program"):
        proclaim.Behaviour(MICROWAVE, experts={"light": lambda board: False}, checkpoint_at=2)
