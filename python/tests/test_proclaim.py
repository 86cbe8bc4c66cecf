"""The proclaim package against the `proclaim` binary: same answers on every embedded theory under
every algorithm, errors with their places, wrong types, closed and orphaned objects.

The binary is PROCLAIM_BIN, or target/debug/proclaim (run-tests.sh sets it)."""

import gc
import json
import os
import subprocess
import threading
from pathlib import Path

import pytest

import proclaim

ROOT = Path(__file__).resolve().parents[2]
THEORIES = sorted((ROOT / "theories").glob("*.dl")) + sorted(
    (ROOT / "theories" / "classics").glob("*.dl")
)
MICROWAVE = ROOT / "theories" / "microwave.dl"


def binary():
    path = os.environ.get("PROCLAIM_BIN") or str(
        Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target")) / "debug" / "proclaim"
    )
    if not os.access(path, os.X_OK):
        pytest.fail(f"the proclaim binary is needed to compare answers: {path} (build it with cargo)")
    return path


def cli(*args):
    done = subprocess.run([binary(), *map(str, args)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return done.stdout


def literals(theory):
    return [sign + atom for atom in theory.atoms for sign in ("", "~")]


def test_the_embedded_theories_are_all_here():
    # theories/ holds the nine theories the binary embeds; a new one must not go untested.
    assert len(THEORIES) == 9


@pytest.mark.parametrize("path", THEORIES, ids=lambda p: p.name)
def test_the_truth_table_is_the_clis(path):
    theory = proclaim.load_file(path)
    assert theory.table() == json.loads(cli("table", path, "--format", "json"))["rows"]


@pytest.mark.parametrize("path", THEORIES, ids=lambda p: p.name)
def test_every_algorithm_proves_what_the_cli_proves_in_every_row(path):
    theory = proclaim.load_file(path)
    session = theory.session()
    for row in theory.table():
        sets = []
        for atom, value in row["inputs"].items():
            sets += ["--set", f"{atom}={str(value).lower()}"]
        if row["outputs"] is None:
            continue  # the CLI refuses contradictory inputs; test_an_input_that_contradicts… covers it
        for atom, value in row["inputs"].items():
            session.set(atom, value)
        for algorithm in proclaim.ALGORITHMS:
            conclusions = json.loads(cli("prove", path, "--alg", algorithm, "--json", *sets))
            expected = {c["query"] for c in conclusions if c["proved"]}
            proved = {lit for lit in literals(theory) if session.prove(lit, algorithm)}
            assert proved == expected, (algorithm, row["inputs"])
        for heading, value in row["outputs"].items():
            algorithm, lit = heading.split(" ", 1)
            assert session.prove(lit, algorithm) is value, (heading, row["inputs"])


def test_unknown_inputs_are_unknown_in_the_cli_too():
    theory = proclaim.load_file(MICROWAVE)
    session = theory.session()
    session.set("doorOpen", True)
    session.set("doorOpen", None)
    assert session.get("doorOpen") is None
    for algorithm in proclaim.ALGORITHMS:
        conclusions = json.loads(cli("prove", MICROWAVE, "--alg", algorithm, "--json"))
        expected = {c["query"] for c in conclusions if c["proved"]}
        assert {lit for lit in literals(theory) if session.prove(lit, algorithm)} == expected


def test_a_theory_that_does_not_load_says_where():
    with pytest.raises(proclaim.TheoryError) as raised:
        proclaim.load("input{a}.\nR: a => b.\nS: a => .\n")
    error = raised.value
    assert (error.file, error.line, error.column) == ("theory", 3, 9)
    assert error.message.startswith("theory does not load (1 error)")
    assert "3 │ S: a => ." in error.message
    assert str(error) == error.message
    assert isinstance(error, proclaim.Error)

    with pytest.raises(proclaim.TheoryError) as raised:
        proclaim.load("R: a => b\nS: => c.", name="kitchen.dl")
    assert (raised.value.file, raised.value.line) == ("kitchen.dl", 2)


def test_a_file_that_does_not_load_is_named_and_placed(tmp_path):
    broken = tmp_path / "broken.dl"
    broken.write_text("input{doorOpen}.\nTimer: timeLeft => .\n")
    with pytest.raises(proclaim.TheoryError) as raised:
        proclaim.load_file(broken)
    assert (raised.value.file, raised.value.line) == (str(broken), 2)
    # The CLI places it on the same line.
    done = subprocess.run([binary(), "check", str(broken)], capture_output=True, text=True)
    assert f"{broken}:2:" in done.stdout + done.stderr

    not_utf8 = tmp_path / "latin1.dl"
    not_utf8.write_bytes(b"a.\nb\xff.")
    with pytest.raises(proclaim.TheoryError) as raised:
        proclaim.load_file(not_utf8)
    assert (raised.value.line, raised.value.column) == (2, 2)
    assert "not UTF-8" in raised.value.message

    with pytest.raises(FileNotFoundError):
        proclaim.load_file(tmp_path / "missing.dl")


def test_wrong_types_are_type_errors():
    session = proclaim.load_file(MICROWAVE).session()
    for call in (
        lambda: session.set("doorOpen", 1),
        lambda: session.set("doorOpen", "true"),
        lambda: session.set(1, True),
        lambda: session.prove(None),
        lambda: session.prove("cook", 2),
        lambda: session.explain("cook", "beta", "deep"),
        lambda: proclaim.load(b"a."),
        lambda: proclaim.load_file(3),
        lambda: proclaim.load_file(MICROWAVE).session(budget="big"),
    ):
        with pytest.raises(TypeError):
            call()


def test_unknown_names_are_key_errors_and_bad_values_value_errors():
    session = proclaim.load_file(MICROWAVE).session()
    with pytest.raises(KeyError):
        session.set("dorOpen", True)
    with pytest.raises(KeyError):
        session.prove("coook")
    with pytest.raises(ValueError, match="not an input"):
        session.set("cook", True)
    with pytest.raises(ValueError, match="not an algorithm"):
        session.prove("cook", "gamma")
    with pytest.raises(ValueError):
        proclaim.load_file(MICROWAVE).session(budget=0)


def test_an_undecided_answer_is_its_own_exception():
    ladder = cli("gen", "ladder", "6") + "x: t0 => ~t2.\n"
    theory = proclaim.load(ladder)
    tight = theory.session(budget=1000)
    with pytest.raises(proclaim.Undecided) as raised:
        tight.prove("t0")
    assert raised.value.goal == "beta t0"
    assert raised.value.stalled_at == "beta t0"
    assert tight.prove("~t0") is False
    assert theory.session().prove("t0") is True


def test_an_input_that_contradicts_the_axioms_is_refused_and_changes_nothing():
    session = proclaim.load("input{a}. input{b}. \\/{~a, ~b}. R: a => c.").session()
    session.set("a", True)
    with pytest.raises(proclaim.InputConflict) as raised:
        session.set("b", True)
    assert raised.value.input == "b"
    assert session.get("b") is None
    assert session.prove("c") is True


def test_an_explanation_is_the_clis():
    session = proclaim.load_file(MICROWAVE).session()
    session.set("doorOpen", True)
    session.set("timeLeft", True)
    expected = cli("explain", MICROWAVE, "cook", "--set", "doorOpen=true", "--set", "timeLeft=true")
    assert session.explain("cook") == expected
    assert "DoorCut stands" in session.explain("cook", "beta", depth=2)


def test_a_session_outlives_its_theory_and_a_closed_one_refuses():
    theory = proclaim.load_file(MICROWAVE)
    session = theory.session()
    del theory
    gc.collect()
    session.set("timeLeft", True)
    assert session.prove("cook") is True

    session.close()
    session.close()  # closing twice is allowed
    assert session.closed
    for call in (
        lambda: session.prove("cook"),
        lambda: session.set("timeLeft", False),
        lambda: session.explain("cook"),
    ):
        with pytest.raises(ValueError, match="closed"):
            call()

    with proclaim.load_file(MICROWAVE).session() as scoped:
        scoped.set("timeLeft", True)
        assert scoped.prove("cook", "alpha") is True
    assert scoped.closed


def test_sessions_of_one_theory_are_independent_across_threads():
    theory = proclaim.load_file(MICROWAVE)
    answers = {}

    def cook_with_door(open_door):
        session = theory.session()
        session.set("timeLeft", True)
        session.set("doorOpen", open_door)
        answers[open_door] = [session.prove("cook") for _ in range(1000)]

    threads = [threading.Thread(target=cook_with_door, args=(v,)) for v in (False, True)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert set(answers[False]) == {True} and set(answers[True]) == {False}


def test_the_theory_describes_itself():
    theory = proclaim.load_file(MICROWAVE)
    assert theory.name == "microwave"
    assert theory.inputs == ["doorOpen", "timeLeft"]
    assert {"cook", "light", "doorOpen", "timeLeft"} <= set(theory.atoms)
    assert proclaim.ALGORITHMS == ("mu", "pi", "beta", "alpha", "delta")
    assert "microwave" in repr(theory)


QUERIES = [
    "cook",
    "~cook",
    "\\/{cook, light}",
    "\\/{~cook, ~light}",
    "\\/{cook, ~cook}",
    "/\\{light, ~cook}",
    "/\\{light, \\/{cook, doorOpen}}",
    "/\\{\\/{cook, ~cook}, ~light}",
]


@pytest.mark.parametrize("query", QUERIES)
def test_a_query_in_the_clis_language_gets_the_clis_answer_on_every_row(query):
    theory = proclaim.load_file(MICROWAVE)
    session = theory.session()
    for row in theory.table():
        sets = []
        for atom, value in row["inputs"].items():
            session.set(atom, value)
            sets += ["--set", f"{atom}={str(value).lower()}"]
        for algorithm in proclaim.ALGORITHMS:
            [answer] = json.loads(cli("prove", MICROWAVE, query, "--alg", algorithm, "--json", *sets))
            assert session.prove(query, algorithm) is answer["proved"], (algorithm, row["inputs"])


@pytest.mark.parametrize(
    "call, kind, message",
    [
        (lambda s: s.prove("coook"), KeyError, "no atom `coook` (in {file}); did you mean `cook`?"),
        (lambda s: s.prove("\\/{cook, ligt}"), KeyError, "`ligt` (in {file}); did you mean `light`?"),
        (lambda s: s.prove("/\\{~Cook, light}"), KeyError, "`Cook` (in {file}); did you mean `cook`?"),
        (lambda s: s.set("dorOpen", True), KeyError, "`dorOpen` (in {file}); did you mean `doorOpen`?"),
        (lambda s: s.explain("coook"), KeyError, "did you mean `cook`?"),
        (lambda s: s.prove("\\/{cook,"), ValueError, "is not a query"),
        (lambda s: s.explain("\\/{cook, light}"), ValueError, "only a literal"),
    ],
)
def test_a_misspelt_atom_gets_the_nearest_and_the_file_and_a_bad_query_says_so(call, kind, message):
    session = proclaim.load_file(MICROWAVE).session()
    with pytest.raises(kind) as raised:
        call(session)
    # KeyError's str() is the repr of its message.
    text = raised.value.args[0]
    assert message.format(file=MICROWAVE) in text, text


def test_a_missing_file_is_file_not_found_naming_it(tmp_path):
    missing = tmp_path / "missing.dl"
    with pytest.raises(FileNotFoundError) as raised:
        proclaim.load_file(missing)
    assert raised.value.filename == str(missing)
    assert raised.value.errno == 2
    assert str(missing) in str(raised.value)
    with pytest.raises(IsADirectoryError) as raised:
        proclaim.load_file(tmp_path)
    assert raised.value.filename == str(tmp_path)
