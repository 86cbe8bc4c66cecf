"""The proclaim reasoner from Python: clausal defeasible logic (cdl.md).

>>> import proclaim
>>> theory = proclaim.load("input{doorOpen}. input{timeLeft}. "
...     "Cook: timeLeft => cook. Door: doorOpen => ~cook. Door > Cook.")
>>> session = theory.session()
>>> session.set("timeLeft", True)
>>> session.prove("cook", "beta")
True

A theory that does not load raises :class:`TheoryError` (with ``file``, ``line``, ``column``); an
answer the search could not decide within its budget raises :class:`Undecided`.

A behaviour (a folder with a ``behaviour.toml``) runs from Python with callables as host functions
and experts, round by round on a virtual clock (see :class:`Behaviour`)::

    kettle = proclaim.Behaviour("python/tests/kettle", hosts={"beep": print},
                                experts={"switchedOn": lambda board: True,
                                         "boiling": lambda board: board["temperature"] >= 100})
    kettle.post("temperature", 100)
    assert kettle.run_until(lambda b: b.finished, rounds=10)

A step is one round at one moment; ``run_until`` moves the virtual clock to the next thing due
(a timeout, a script's line) when a round moves no machine, and ``run(s)`` includes what falls
due at exactly ``s`` seconds.
"""

from ._native import (
    ALGORITHMS,
    Behaviour,
    BehaviourError,
    BehaviourWarning,
    Board,
    CallbackError,
    Error,
    InputConflict,
    Session,
    Theory,
    TheoryError,
    Undecided,
    load,
    load_file,
)

__all__ = [
    "ALGORITHMS",
    "Behaviour",
    "BehaviourError",
    "BehaviourWarning",
    "Board",
    "CallbackError",
    "Error",
    "InputConflict",
    "Session",
    "Theory",
    "TheoryError",
    "Undecided",
    "load",
    "load_file",
]
