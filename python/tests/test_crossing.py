"""The pelican crossing of tests/crossing driven from Python: `run_until` alone takes it through
its timeouts to WALK (the virtual clock moves to what is due when nothing else can happen), a
step is one round at one moment, `run(s)` includes what falls due at exactly s, host calls are
events, and a misspelt expert or host function is an error with the nearest name."""

import warnings
from pathlib import Path

import pytest

import proclaim

CROSSING = Path(__file__).resolve().parent / "crossing"


def entered(events):
    return [e["state"] for e in events if e["event"] == "entered"]


def crossing(waiting, chimes=None, **options):
    """The crossing with Python answering `pedestrianWaiting`; `chimes` collects the host calls."""
    hosts = {"chime": (chimes if chimes is not None else []).append}
    return proclaim.Behaviour(CROSSING, hosts=hosts, experts={"pedestrianWaiting": waiting}, **options)


def light(behaviour):
    return behaviour.state("TrafficLight")


def test_run_until_alone_takes_the_crossing_through_its_timeouts_to_walk():
    chimes = []
    with crossing(lambda board: board.read("button") is True, chimes) as c:
        assert c.run_until(lambda b: light(b) == "GREEN", rounds=3)
        c.post("button", True)
        assert c.run_until(lambda b: light(b) == "WALK", rounds=10)
        assert c.time == 4.0, "amber for 3 s, red for 1 s"
        assert chimes == ["walk"]
        events = c.events
        walk = next(i for i, e in enumerate(events) if e.get("state") == "WALK")
        assert events[walk]["at_us"] == 4_000_000
        [call] = [(i, e) for i, e in enumerate(events) if e["event"] == "called"]
        assert call[1] == {
            "event": "called",
            "function": "chime",
            "argument": "walk",
            "round": events[walk]["round"],
        }
        assert call[0] > walk, "after the round's events"
        # On through the flashing amber to green again, and round once more.
        assert c.run_until(lambda b: light(b) == "GREEN" and b.time > 4, rounds=10)
        assert c.time == 11.0
        assert entered(c.events) == ["GREEN", "AMBER", "RED", "WALK", "FLASHING", "GREEN"]


def test_a_step_is_one_round_at_one_moment_and_wait_moves_the_clock():
    with crossing(lambda board: True) as c:
        c.step()
        c.step()
        assert light(c) == "AMBER"
        for _ in range(5):
            assert c.step() == []
        assert (light(c), c.time) == ("AMBER", 0.0)
        c.wait(2.5)
        c.step()
        assert (light(c), c.time) == ("AMBER", 2.5)
        c.wait(0.5)
        # The transition fires at 3 s; the new state is entered in the next round, as a
        # ringlet's transition is followed by the target's OnEntry in the next.
        assert [e["label"] for e in c.step() if e["event"] == "fired"] == ["timeout(3s)"]
        assert entered(c.step()) == ["RED"]
        assert c.time == 3.0


def test_run_includes_what_falls_due_at_exactly_its_end():
    with crossing(lambda board: True) as c:
        assert c.run_until(lambda b: light(b) == "AMBER", rounds=3)
        assert entered(c.run(3)) == ["RED"], "the timeout(3s) is due at exactly +3 s"
        assert (light(c), c.time) == ("RED", 3.0)
        assert entered(c.run(0.5)) == []
        assert entered(c.run(0.5)) == ["WALK"]


def test_with_nothing_due_run_until_leaves_the_clock_alone():
    with crossing(lambda board: False) as c:
        assert not c.run_until(lambda b: light(b) == "AMBER", rounds=5)
        assert (light(c), c.time, c.rounds) == ("GREEN", 0.0, 5)


def test_run_until_waits_for_the_scripts_next_line_too():
    # No Python expert: the script answers the label at 2 s.
    c = proclaim.Behaviour(CROSSING, hosts={"chime": print}, script="at 2s pedestrianWaiting = true")
    with c:
        assert c.run_until(lambda b: light(b) == "AMBER", rounds=5)
        assert c.time == 2.0


@pytest.mark.parametrize(
    "hosts, experts, message",
    [
        (
            {"chime": print},
            {"pedestrianWating": lambda board: True},
            'experts["pedestrianWating"]: no machine asks `pedestrianWating`; '
            "did you mean `pedestrianWaiting`?",
        ),
        (
            {"chme": print},
            {"pedestrianWaiting": lambda board: True},
            'hosts["chme"]: no machine calls `chme`; did you mean `chime`?',
        ),
        (
            {"chime": print, "beep": print},
            {"pedestrianWaiting": lambda board: True, "button": lambda board: True},
            'hosts["beep"]: no machine calls `beep`',
        ),
    ],
)
def test_an_expert_or_host_function_the_machines_do_not_use_is_an_error(hosts, experts, message):
    with pytest.raises(proclaim.BehaviourError) as raised:
        proclaim.Behaviour(CROSSING, hosts=hosts, experts=experts)
    assert message in str(raised.value)
    assert any(message in problem[3] for problem in raised.value.problems)


def test_a_call_with_no_host_function_is_a_warning_that_can_be_made_an_error():
    experts = {"pedestrianWaiting": lambda board: True}
    with pytest.warns(proclaim.BehaviourWarning, match=r"Crossing\.machine:\d+: .*`chime`.*skipped"):
        proclaim.Behaviour(CROSSING, experts=experts).close()
    with pytest.warns(proclaim.BehaviourWarning, match="did you mean `chimes`"):
        with pytest.raises(proclaim.BehaviourError, match="did you mean `chime`"):
            proclaim.Behaviour(CROSSING, hosts={"chimes": print}, experts=experts)
    with warnings.catch_warnings():
        warnings.simplefilter("error", proclaim.BehaviourWarning)
        with pytest.raises(proclaim.BehaviourWarning):
            proclaim.Behaviour(CROSSING, experts=experts)
