"""Typed stubs for proclaim (the Rust extension proclaim._native, re-exported)."""

import os
from types import TracebackType
from typing import Dict, List, Literal, Optional, Tuple, Type, TypedDict, Union


AlgorithmName = Literal["mu", "pi", "beta", "alpha", "delta"]

ALGORITHMS: Tuple[str, str, str, str, str]
"""The algorithm names, in the order cdl.md gives them: mu, pi, beta, alpha, delta."""

class Error(Exception):
    """Every error the reasoner raises derives from this one."""

class TheoryError(Error):
    """A theory did not load."""

    file: str
    """The name the text was loaded under (the path for load_file)."""
    line: int
    """1-based line of the first error; 0 when it has no place."""
    column: int
    """1-based column (in characters) of the first error; 0 when it has no place."""
    message: str
    """Every error, rendered with its line and a caret."""

class Undecided(Error):
    """The search ran out of its step budget inside an attack cycle before deciding."""

    goal: str
    """The goal asked, as ``beta t0``."""
    stalled_at: str
    """The undecided goal of the attack cycle it depends on (itself when it lies on it)."""

class InputConflict(Error):
    """Setting an input would contradict the axioms; the session was left as it was."""

    input: str
    """The refused input literal."""
    clause: str
    """The axiom clause it contradicts."""

class TableRow(TypedDict):
    inputs: Dict[str, bool]
    outputs: Optional[Dict[str, bool]]
    """Keyed by column heading (``beta cook``); None when the inputs contradict the axioms."""

class Theory:
    """A checked theory, immutable; sessions share it and keep it alive."""

    @property
    def name(self) -> Optional[str]:
        """The name the theory gives itself (``name{microwave}.``), if any."""
    @property
    def atoms(self) -> List[str]:
        """Every atom the theory mentions."""
    @property
    def inputs(self) -> List[str]:
        """The declared input atoms, the ones Session.set accepts."""
    def session(self, budget: Optional[int] = None) -> Session:
        """A new session, every input unknown; ``budget``: search steps per attack cycle."""
    def table(self) -> List[TableRow]:
        """The truth table's rows, as ``proclaim table --format json`` gives them."""

class Session:
    """Input values and cached answers over one theory; also a context manager."""

    @property
    def closed(self) -> bool: ...
    def set(self, atom: str, value: Optional[bool]) -> None:
        """Sets an input: True, False or None (unknown).

        Raises KeyError (no such atom), ValueError (not an input), TypeError (not a bool or
        None), InputConflict (contradicts the axioms).
        """
    def get(self, atom: str) -> Optional[bool]:
        """The value an input was set to."""
    def prove(self, literal: str, algorithm: AlgorithmName = "beta") -> bool:
        """Whether the algorithm proves the literal (``cook``, ``~cook``).

        Raises Undecided, KeyError (no such atom), ValueError (no such algorithm).
        """
    def explain(self, literal: str, algorithm: AlgorithmName = "beta", depth: int = 1) -> str:
        """Why the algorithm proves or refutes the literal, as ``proclaim explain`` prints it."""
    def close(self) -> None:
        """Frees the session now; later calls raise ValueError."""
    def __enter__(self) -> Session: ...
    def __exit__(
        self,
        kind: Optional[Type[BaseException]],
        value: Optional[BaseException],
        traceback: Optional[TracebackType],
    ) -> bool: ...

def load(text: str, name: str = "theory") -> Theory:
    """Loads a theory from its text; raises TheoryError when it does not load."""

def load_file(path: Union[str, "os.PathLike[str]"]) -> Theory:
    """Loads a theory file; raises OSError when unreadable, TheoryError when it does not load."""
