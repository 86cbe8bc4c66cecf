"""Typed stubs for proclaim (the Rust extension proclaim._native, re-exported)."""

import os
from types import TracebackType
from typing import (
    Any,
    Callable,
    Dict,
    List,
    Literal,
    Mapping,
    Optional,
    Sequence,
    Tuple,
    Type,
    TypedDict,
    Union,
    final,
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

# Names with a leading underscore are the stub's own (types for annotations): they do not exist
# at run time, so import them only under `typing.TYPE_CHECKING`.


_AlgorithmName = Literal["mu", "pi", "beta", "alpha", "delta"]

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

class _TableRow(TypedDict):
    inputs: Dict[str, bool]
    outputs: Optional[Dict[str, bool]]
    """Keyed by column heading (``beta cook``); None when the inputs contradict the axioms."""

@final
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
    def table(self) -> List[_TableRow]:
        """The truth table's rows, as ``proclaim table --format json`` gives them."""

@final
class Session:
    """Input values and cached answers over one theory; also a context manager."""

    @property
    def closed(self) -> bool: ...
    def set(self, atom: str, value: Optional[bool]) -> None:
        """Sets an input: True, False or None (unknown).

        Raises KeyError (no such atom; names the theory's file and the nearest atom),
        ValueError (not an input), TypeError (not a bool or None), InputConflict (contradicts
        the axioms).
        """
    def get(self, atom: str) -> Optional[bool]:
        """The value an input was set to."""
    def prove(self, query: str, algorithm: _AlgorithmName = "beta") -> bool:
        """Whether the algorithm proves the query, written as ``proclaim prove`` takes it: a
        literal (``cook``, ``~cook``), a clause (``\\/{a, b}``) or a conjunction of clauses
        (``/\\{a, \\/{b, c}}``).

        Raises Undecided, KeyError (no such atom; names the theory's file and the nearest atom),
        ValueError (no query, or no such algorithm).
        """
    def explain(self, literal: str, algorithm: _AlgorithmName = "beta", depth: int = 1) -> str:
        """Why the algorithm proves or refutes the literal, as ``proclaim explain`` prints it;
        ValueError for a clause or conjunction."""
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
    """Loads a theory file; raises OSError when unreadable (FileNotFoundError when missing),
    with ``filename`` set, and TheoryError when it does not load."""

_WhiteboardValue = Union[bool, int, float, str, bytes, Sequence["_WhiteboardValue"]]
"""What the whiteboard holds; a tuple posted reads back as a list."""

class BehaviourError(Error):
    """A behaviour did not load or start."""

    problems: List[Tuple[str, int, int, str]]
    """Every problem of every file: (file, line, column, message); 0 when it has no place."""

class BehaviourWarning(UserWarning):
    """A host function a machine calls that no callable in ``hosts`` answers (the call is
    skipped); ``warnings.simplefilter("error", proclaim.BehaviourWarning)`` makes it an error."""

class CallbackError(Error):
    """A callable given to a Behaviour raised while it ran; ``__cause__`` is what it raised."""

    callable: str
    """Which callable: "the host function `beep`", "the expert for `boiling`"."""

@final
class Board:
    """A behaviour's whiteboard, as an expert's callable is given it."""

    def read(self, type: str) -> Optional[_WhiteboardValue]:
        """The latest value of ``type``; None when never posted."""
    def post(self, type: str, value: _WhiteboardValue) -> None:
        """Posts ``value`` as ``type``, from the module ``python``."""
    def __getitem__(self, key: str, /) -> Optional[_WhiteboardValue]:
        """``board["x"]`` is ``board.read("x")``."""

_Event = Dict[str, Any]
"""One event of the trace, as ``proclaim run --trace`` writes it: ``{"event": "entered", ...}``;
a host call is ``{"event": "called", "function": "beep", "argument": 3, "round": 7}``, after the
events of the round that made it."""

@final
class Behaviour:
    """A behaviour started paused before its first round; also a context manager.

    ``hosts`` maps host function names to callables taking the call's argument (int or str) or
    none; ``experts`` maps labels to callables taking the Board and answering True, False or None
    (no answer), in place of whatever module of the behaviour answered that label: a theory
    keeps answering its other labels; a sensor wrapper with a label taken is left out whole.
    ``script`` is an impersonator script (``"at 1s doorOpen = true"``) played in place of the
    manifest's; left out, the manifest's plays; ``None`` or ``""`` plays none at all.
    An exception in a host function or an expert raises CallbackError from the call that ran the round (an
    expert's also answers its label False). An expert for a label no machine asks or a host
    function no machine calls raises BehaviourError naming the nearest one they do; a host
    function a machine calls that no callable answers warns (BehaviourWarning).

    With ``virtual_clock`` (the default) time is virtual: ``step`` is one round at one moment;
    ``wait`` and ``run`` move the clock; ``run_until`` moves it to the next thing due (a
    ``timeout``/``after`` of a machine's state, a script's timed line) whenever a round moves no
    machine, so it reaches a state behind timeouts by itself. ``time`` says where the clock is.

    ``checkpoint_at=N`` writes the run down before round N (``checkpoint()`` has it once that
    round ran); ``resume=`` a checkpoint's text starts where it left off: its first step plays
    round N, and stepped, waited and run as the first was, it goes on as that run did. Text
    that is no checkpoint is a ValueError; a behaviour it no longer fits (a machine gone, a
    state renamed) raises BehaviourError saying why. A Python expert keeps its state in
    Python, out of a checkpoint's reach: asking for one with ``experts=`` is a BehaviourError.
    """

    def __new__(
        cls,
        folder: Union[str, "os.PathLike[str]"],
        hosts: Optional[Mapping[str, Callable[..., object]]] = None,
        experts: Optional[Mapping[str, Callable[[Board], Optional[bool]]]] = None,
        script: Optional[str] = ...,
        virtual_clock: bool = True,
        checkpoint_at: Optional[int] = None,
        resume: Optional[str] = None,
    ) -> Behaviour: ...
    def checkpoint(self) -> Optional[str]:
        """The checkpoint ``checkpoint_at`` asked for, as text (the JSON ``proclaim run
        --checkpoint-file`` writes), once taken; None before."""
    def step(self) -> List[_Event]:
        """One round: every running machine one ringlet, at the moment the clock is at (time
        does not move); its events."""
    def run_until(self, predicate: Callable[[Behaviour], object], rounds: int = 1000) -> bool:
        """Rounds until ``predicate(self)`` is true, at most ``rounds``; whether it was. When a
        round moves no machine, the virtual clock moves to the next thing due and its round
        runs; with nothing due, time stands still."""
    def run(self, seconds: float) -> List[_Event]:
        """The machines ring freely for ``seconds`` (virtual, by default), then pause after a
        round at exactly ``seconds`` from now (what falls due then happens); its events."""
    def wait(self, seconds: float) -> None:
        """``seconds`` pass with no round run."""
    @property
    def time(self) -> float:
        """Seconds the clock has moved since the start."""
    def post(self, type: str, value: _WhiteboardValue) -> None:
        """Posts ``value`` as ``type`` on the whiteboard, from the module ``python``. ValueError
        for a label the machines ask and another module answers (a theory, the script): the
        posting would not change its answer; answer it with ``experts=`` instead."""
    def read(self, type: str) -> Optional[_WhiteboardValue]:
        """The latest value of ``type``; None when never posted."""
    @property
    def board(self) -> Board: ...
    def states(self) -> Dict[str, Optional[str]]:
        """Every machine to the state it last entered (None before it entered one)."""
    def state(self, machine: str) -> Optional[str]:
        """The state ``machine`` last entered; KeyError for a machine it does not have."""
    def variable(self, machine: str, name: str) -> Optional[_WhiteboardValue]:
        """A variable as ``machine`` sees it; None when it has none of that name."""
    @property
    def events(self) -> List[_Event]:
        """Every event so far, oldest first."""
    @property
    def trace(self) -> List[str]:
        """The run as ``proclaim run`` prints it, a line an event."""
    @property
    def finished(self) -> bool:
        """Whether every machine that started is in a final state or halted."""
    @property
    def rounds(self) -> int: ...
    @property
    def closed(self) -> bool: ...
    def close(self) -> None:
        """Stops the behaviour; later calls raise ValueError."""
    def __enter__(self) -> Behaviour: ...
    def __exit__(
        self,
        kind: Optional[Type[BaseException]],
        value: Optional[BaseException],
        traceback: Optional[TracebackType],
    ) -> bool: ...
