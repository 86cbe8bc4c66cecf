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
"""

from ._native import (
    ALGORITHMS,
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
    "Error",
    "InputConflict",
    "Session",
    "Theory",
    "TheoryError",
    "Undecided",
    "load",
    "load_file",
]
