//! A behaviour driven from Python: its folder loaded and started with Python callables as host
//! functions and as experts answering labels (checked against what the machines call and ask,
//! `checks.rs`), stepped round by round (or run for a while) on the virtual clock, which
//! `run_until` moves to the next thing due when nothing else can happen (`clock.rs`), its
//! states, variables, trace and whiteboard read between rounds.
//!
//! The interpreter lock is released while the behaviour runs and taken again for each callable,
//! so the machines never hold it and a callable may run Python freely. An exception a callable
//! raises never unwinds into the runner: a host function's is kept, an expert's answers the
//! label false and is kept, and the call that ran the round raises `CallbackError` from it.

use crate::board::{self, Board, MODULE};
use crate::checks;
use crate::clock::{Calls, Clock, HostCall};
use crate::errors;
use crate::events;
use proclaim_behaviour::testing::{RoundByRound, Stepping};
use proclaim_behaviour::TraceView;
use proclaim_experts::FunctionExpert;
use proclaim_fsm::Argument;
use proclaim_runner::Hosts;
use pyo3::exceptions::{PyRuntimeError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use pyo3::{PyTraverseError, PyVisit};
use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::{Arc, Mutex, TryLockError};
use std::time::Duration;

/// Exceptions raised by callables while the behaviour ran, oldest first, each with what raised.
type Raised = Arc<Mutex<Vec<(String, PyErr)>>>;

/// Every callable given, the only references to them the behaviour holds (the runner's host
/// functions and expert hold an index), so Python's garbage collector sees them all: a callable
/// that refers back to its behaviour makes a cycle, which `__traverse__` shows and `__clear__`
/// breaks (emptied, a callable answers nothing and is not called).
type Callables = Arc<Mutex<Vec<Py<PyAny>>>>;

/// The callable at `index`, a new reference taken under the list's lock, which is not held
/// while it runs (it may take a while, and may be collected meanwhile).
fn callable(py: Python<'_>, callables: &Callables, index: usize) -> Option<Py<PyAny>> {
    let list = callables.lock().ok()?;
    list.get(index).map(|c| c.clone_ref(py))
}

/// A running behaviour and its clock.
struct Driven {
    run: RoundByRound,
    clock: Clock,
    /// The checkpoint asked for (`checkpoint_at`), as text, once taken.
    checkpoint: Option<String>,
}

/// A behaviour (a folder with a `behaviour.toml`) started paused before its first round.
#[pyclass(module = "proclaim", frozen)]
pub(crate) struct Behaviour {
    /// `None` once closed. Locked while a round runs, so a callable that tries to step the
    /// behaviour it is called from gets an error rather than a deadlock.
    running: Mutex<Option<Driven>>,
    board: proclaim_board::Whiteboard,
    raised: Raised,
    folder: PathBuf,
    callables: Callables,
}

fn record(raised: &Raised, what: String, error: PyErr) {
    if let Ok(mut list) = raised.lock() {
        list.push((what, error));
    }
}

/// A Python callable as a host function: called with the call's argument (an int or a str), or
/// with none; each call is noted for the events.
fn host_function(
    name: String,
    index: usize,
    callables: Callables,
    raised: Raised,
    calls: Calls,
) -> impl Fn(Option<&Argument>) {
    move |argument| {
        if let Ok(mut calls) = calls.lock() {
            calls.push(HostCall {
                function: name.clone(),
                argument: argument.cloned(),
            });
        }
        Python::attach(|py| {
            let Some(function) = callable(py, &callables, index) else {
                return;
            };
            let outcome = match argument {
                None => function.call0(py),
                Some(Argument::Int(i)) => function.call1(py, (*i,)),
                Some(Argument::Str(s) | Argument::Word(s)) => function.call1(py, (s.as_str(),)),
            };
            if let Err(error) = outcome {
                record(&raised, format!("the host function `{name}`"), error);
            }
        })
    }
}

/// Python callables as one expert answering their labels: each is called with the whiteboard
/// (a `proclaim.Board`) when a machine asks its label, and answers True, False, or None (no
/// answer: the query times out and the label reads false).
fn expert(labels: Vec<(String, usize)>, callables: Callables, raised: Raised) -> FunctionExpert {
    // In the order given, so notes and the registry list them as the caller wrote them.
    let names: Vec<String> = labels.iter().map(|(label, _)| label.clone()).collect();
    let index: HashMap<String, usize> = labels.into_iter().collect();
    FunctionExpert::new(MODULE, names, move |label, board| {
        let index = *index.get(label)?;
        Python::attach(|py| {
            let function = callable(py, &callables, index)?;
            let what = || format!("the expert for `{label}`");
            let board = Board::new(board.clone());
            let answer = function.call1(py, (board,)).and_then(|value| {
                value.extract::<Option<bool>>(py).map_err(|_| {
                    let shown = value
                        .bind(py)
                        .repr()
                        .map(|r| r.to_string())
                        .unwrap_or_else(|_| "a value".into());
                    PyTypeError::new_err(format!(
                        "it returned {shown}; an expert answers True, False or None"
                    ))
                })
            });
            match answer {
                Ok(answer) => answer,
                Err(error) => {
                    record(&raised, what(), error);
                    // Answered rather than left to time out: the machine moves on at once, as
                    // it would with a reasoner that could not decide.
                    Some(false)
                }
            }
        })
    })
}

/// Callables keyed by name, in the dict's order, each checked to be callable.
fn callables(what: &str, given: Option<&Bound<'_, PyDict>>) -> PyResult<Vec<(String, Py<PyAny>)>> {
    let mut out = Vec::new();
    let Some(given) = given else { return Ok(out) };
    for (key, value) in given.iter() {
        let name: String = key.extract().map_err(|_| {
            PyTypeError::new_err(format!("{what} are keyed by name (a str), not {key}"))
        })?;
        if !value.is_callable() {
            return Err(PyTypeError::new_err(format!(
                "{what}[{name:?}] is not callable: {}",
                value.get_type().name()?
            )));
        }
        out.push((name, value.unbind()));
    }
    Ok(out)
}

fn seconds(value: f64) -> PyResult<Duration> {
    Duration::try_from_secs_f64(value).map_err(|_| {
        PyValueError::new_err(format!("{value} is not a time: give seconds, zero or more"))
    })
}

impl Behaviour {
    /// Runs `body` on the running behaviour with the interpreter lock released, then raises
    /// what a callable raised meanwhile.
    fn drive<T: Send>(
        &self,
        py: Python<'_>,
        body: impl FnOnce(&mut Driven) -> T + Send,
    ) -> PyResult<T> {
        let mut guard = match self.running.try_lock() {
            Ok(guard) => guard,
            Err(TryLockError::WouldBlock) => {
                return Err(PyRuntimeError::new_err(
                    "the behaviour is running a round already (stepped from one of its own \
                     callables, which read and post through the board they are given, or from \
                     another thread while a round runs)",
                ))
            }
            // Never held across a panic (caught below), but a poisoned lock still guards a
            // behaviour that is either whole or already dropped.
            Err(TryLockError::Poisoned(poisoned)) => poisoned.into_inner(),
        };
        let running = guard
            .as_mut()
            .ok_or_else(|| PyValueError::new_err("the behaviour is closed"))?;
        let out =
            py.detach(|| std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| body(running))));
        let out = match out {
            Ok(out) => out,
            Err(panic) => {
                // A bug inside the runner: its state may be half-updated, so it runs no more.
                *guard = None;
                let why = panic
                    .downcast_ref::<String>()
                    .map(String::as_str)
                    .or_else(|| panic.downcast_ref::<&str>().copied())
                    .unwrap_or("no message");
                return Err(errors::Error::new_err(format!(
                    "the behaviour stopped: a bug inside it panicked ({why}); it is closed"
                )));
            }
        };
        drop(guard);
        self.raise_callbacks(py)?;
        Ok(out)
    }

    /// Runs `body` on the behaviour between rounds (to read it, or to keep what it read).
    fn with<T>(&self, body: impl FnOnce(&mut Driven) -> PyResult<T>) -> PyResult<T> {
        let mut guard = match self.running.try_lock() {
            Ok(guard) => guard,
            Err(TryLockError::Poisoned(poisoned)) => poisoned.into_inner(),
            Err(TryLockError::WouldBlock) => {
                return Err(PyRuntimeError::new_err(
                    "the behaviour is running a round; read it between rounds",
                ))
            }
        };
        let running = guard
            .as_mut()
            .ok_or_else(|| PyValueError::new_err("the behaviour is closed"))?;
        body(running)
    }

    fn raise_callbacks(&self, py: Python<'_>) -> PyResult<()> {
        let raised = match self.raised.lock() {
            Ok(mut list) => std::mem::take(&mut *list),
            Err(_) => return Ok(()),
        };
        let mut raised = raised.into_iter();
        match raised.next() {
            None => Ok(()),
            Some((what, error)) => Err(errors::callback_error(py, &what, error, raised.len())),
        }
    }

    /// The events from `first` on, as dicts.
    fn events_from<'py>(&self, py: Python<'py>, first: usize) -> PyResult<Bound<'py, PyList>> {
        self.with(|driven| events::to_python(py, &driven.clock.events_from(&driven.run, first)))
    }

    fn event_count(&self) -> PyResult<usize> {
        self.with(|driven| Ok(driven.clock.event_count(&driven.run)))
    }
}

#[pymethods]
impl Behaviour {
    /// Loads the behaviour in `folder` and starts it paused before its first round: its
    /// experts and sensor wrappers registered, its machines waiting. `hosts` maps host function
    /// names (`call beep(3)`) to callables taking the call's argument; `experts` maps labels to
    /// callables taking the board and answering True, False or None, each in place of the
    /// module that answered that label (a theory keeps answering the rest). `script` is an
    /// impersonator script (`at 1s doorOpen = true`) in place of the manifest's; `None` or ""
    /// is no script at all. With `virtual_clock` (the default) time is virtual: it moves
    /// by `wait` and `run`, and in `run_until` when nothing else can happen, so a test gives
    /// the same answer every time and a minute takes no real minute. Raises BehaviourError with
    /// every problem of every file when it does not load, and when an expert is given for a
    /// label no machine asks or a host function no machine calls (with the nearest name that
    /// is); warns (BehaviourWarning) of a host function a machine calls that no callable
    /// answers. `checkpoint_at=N` writes the run down before round N (`checkpoint()`);
    /// `resume=` a checkpoint's text takes the run up where it left it (ValueError for text
    /// that is not one; BehaviourError for a behaviour it no longer fits, saying why).
    #[new]
    // `script`: left out (`Some(None)`), the manifest's; `None` or "", no script at all.
    #[pyo3(signature = (folder, hosts = None, experts = None, script = Some(None), virtual_clock = true, checkpoint_at = None, resume = None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        folder: PathBuf,
        hosts: Option<&Bound<'_, PyDict>>,
        experts: Option<&Bound<'_, PyDict>>,
        script: Option<Option<String>>,
        virtual_clock: bool,
        checkpoint_at: Option<u64>,
        resume: Option<&str>,
    ) -> PyResult<Behaviour> {
        let resume = resume
            .map(|text| {
                proclaim_behaviour::Checkpoint::read(text).map_err(|why| {
                    PyValueError::new_err(format!("resume= is not a checkpoint to take up: {why}"))
                })
            })
            .transpose()?;
        if checkpoint_at == Some(0) {
            return Err(PyValueError::new_err(
                "checkpoint_at=0: rounds count from 1; give the round to write the run down before",
            ));
        }
        let raised: Raised = Arc::default();
        let mut given = Vec::new();
        let mut host_functions = Hosts::default();
        for (name, function) in callables("hosts", hosts)? {
            given.push((name, function));
        }
        let host_count = given.len();
        let mut labels = Vec::new();
        for (label, function) in callables("experts", experts)? {
            labels.push((label.clone(), given.len()));
            given.push((label, function));
        }
        let (names, functions): (Vec<String>, Vec<Py<PyAny>>) = given.into_iter().unzip();
        let expert_labels: Vec<String> = labels.iter().map(|(label, _)| label.clone()).collect();
        let manifest_script = checked(py, &folder, &expert_labels, &names[..host_count])?;
        let list: Callables = Arc::new(Mutex::new(functions));
        let calls: Calls = Arc::default();
        for (index, name) in names.iter().enumerate().take(host_count) {
            let host = host_function(
                name.clone(),
                index,
                list.clone(),
                raised.clone(),
                calls.clone(),
            );
            host_functions.register(name, host);
        }
        // `None` from Python is no script at all: the empty one.
        let script: Option<String> = match script {
            None => Some(String::new()),
            Some(given) => given,
        };
        let given_script = script
            .as_deref()
            .and_then(|text| proclaim_experts::parse_script(text).ok());
        let stepping = Stepping {
            script: script.clone(),
            hosts: host_functions,
            experts: if labels.is_empty() {
                Vec::new()
            } else {
                vec![expert(labels, list.clone(), raised.clone())]
            },
            real_time: !virtual_clock,
            checkpoint_at,
            resume: resume.clone(),
        };
        let started = py
            .detach(|| RoundByRound::start_with(&folder, stepping))
            .map_err(|error| errors::behaviour_error(py, &folder, error))?;
        let board = started.board.clone();
        // The script given replaces the manifest's, as in the runner.
        let script = if script.is_none() {
            manifest_script
        } else {
            given_script
        };
        let mut clock = Clock::new(script.as_ref(), calls, virtual_clock);
        if let Some(checkpoint) = &resume {
            clock.taken_up(checkpoint);
        }
        let behaviour = Behaviour {
            running: Mutex::new(Some(Driven {
                run: started,
                clock,
                checkpoint: None,
            })),
            board,
            raised,
            folder,
            callables: list,
        };
        behaviour.raise_callbacks(py)?;
        Ok(behaviour)
    }

    /// Runs one round (every running machine one ringlet, in manifest order) at the moment the
    /// clock is at: time does not move in a step, so a test can post and step a moment at a
    /// time (`wait`, `run` and `run_until` move it). The events the round made, as dicts
    /// (`{"event": "entered", "machine": ..., "state": ..., "at_us": ...}`; host calls as
    /// `{"event": "called", "function": ..., "argument": ..., "round": ...}`). Raises
    /// CallbackError when a callable raised during it.
    fn step<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let first = self.event_count()?;
        self.drive(py, |driven| driven.clock.step(&mut driven.run, false))?;
        self.events_from(py, first)
    }

    /// Runs rounds until `predicate(behaviour)` is true, at most `rounds` of them; whether it
    /// became true. The predicate is asked before the first round too. Time passes as it must
    /// for the machines to get on: when a round moves no machine and something is due later (a
    /// `timeout`/`after` of a machine's current state, a timed line of the script), the
    /// virtual clock moves to that moment and the round it wakes runs too (one of the
    /// `rounds`); when nothing is due, time stands still (a machine waiting on the whiteboard
    /// waits for a post).
    #[pyo3(signature = (predicate, rounds = 1000))]
    fn run_until(
        slf: &Bound<'_, Self>,
        predicate: &Bound<'_, PyAny>,
        rounds: u64,
    ) -> PyResult<bool> {
        let py = slf.py();
        let this = slf.get();
        for _ in 0..rounds {
            if predicate.call1((slf,))?.is_truthy()? {
                return Ok(true);
            }
            this.drive(py, |driven| driven.clock.step(&mut driven.run, true))?;
        }
        predicate.call1((slf,))?.is_truthy()
    }

    /// Lets the machines run freely for `seconds` (seconds of the virtual clock: a minute's
    /// timeout takes no real time), then pauses them after a last round at exactly `seconds`
    /// from now, so what falls due then (a `timeout(2s)` under `run(2)`) happens within the
    /// run; the events.
    fn run<'py>(&self, py: Python<'py>, seconds: f64) -> PyResult<Bound<'py, PyList>> {
        let time = self::seconds(seconds)?;
        let first = self.event_count()?;
        self.drive(py, |driven| driven.clock.run(&mut driven.run, time))?;
        self.events_from(py, first)
    }

    /// Lets `seconds` pass with no round run: a `timeout` may come due (the next round sees
    /// it), a script's timed line may post.
    fn wait(&self, py: Python<'_>, seconds: f64) -> PyResult<()> {
        let time = self::seconds(seconds)?;
        self.drive(py, |driven| driven.clock.wait(&mut driven.run, time))
    }

    /// How far the clock has moved since the start, in seconds (virtual seconds on the virtual
    /// clock): what `wait`, `run` and `run_until`'s waits for what was due added up to.
    #[getter]
    fn time(&self) -> PyResult<f64> {
        self.with(|driven| Ok(driven.clock.now().as_secs_f64()))
    }

    /// Posts `value` (bool, int, float, str, bytes or a list of them) as `type` on the
    /// whiteboard, from the module `python`. ValueError for a label the machines ask and
    /// another module answers (the script's impersonator, a theory): its answer is that
    /// module's, so the posting would change nothing.
    fn post(&self, r#type: &str, value: &Bound<'_, PyAny>) -> PyResult<()> {
        if let Some(why) = answered_elsewhere(&self.board, r#type) {
            return Err(pyo3::exceptions::PyValueError::new_err(why));
        }
        board::post(&self.board, r#type, value)
    }

    /// The latest value of `type` on the whiteboard, None when never posted.
    fn read<'py>(&self, py: Python<'py>, r#type: &str) -> PyResult<Bound<'py, PyAny>> {
        board::read(py, &self.board, r#type)
    }

    /// The whiteboard, as the experts' callables get it.
    #[getter]
    fn board(&self) -> Board {
        Board::new(self.board.clone())
    }

    /// Every machine, in manifest order, to the state it last entered (None before it entered
    /// one).
    fn states<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        self.with(|running| {
            let dict = PyDict::new(py);
            for (machine, state) in running.run.states() {
                dict.set_item(machine, state)?;
            }
            Ok(dict)
        })
    }

    /// The state `machine` last entered; None before it entered one. KeyError for a machine the
    /// behaviour does not have.
    fn state(&self, machine: &str) -> PyResult<Option<String>> {
        self.with(|running| {
            running
                .run
                .states()
                .into_iter()
                .find(|(m, _)| *m == machine)
                .map(|(_, state)| state.map(str::to_string))
                .ok_or_else(|| {
                    let known: Vec<&str> =
                        running.run.states().into_iter().map(|(m, _)| m).collect();
                    pyo3::exceptions::PyKeyError::new_err(format!(
                        "no machine `{machine}`; the behaviour's machines are {}",
                        known.join(", ")
                    ))
                })
        })
    }

    /// A variable as `machine` sees it (its own, else the behaviour's global); None when it has
    /// none of that name.
    fn variable<'py>(
        &self,
        py: Python<'py>,
        machine: &str,
        name: &str,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.with(|running| match running.run.variable(machine, name) {
            Some(value) => board::to_python(py, &value),
            None => Ok(py.None().into_bound(py)),
        })
    }

    /// Every event so far, as dicts, oldest first (the JSON lines of `proclaim run --trace`).
    #[getter]
    fn events<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        self.events_from(py, 0)
    }

    /// The run so far as `proclaim run` prints it: what was started or left out, then a line
    /// an event (answers shown only when they change).
    #[getter]
    fn trace(&self) -> PyResult<Vec<String>> {
        self.with(|running| {
            let mut view = TraceView::new(0);
            let lines = running
                .run
                .events
                .iter()
                .filter_map(|event| view.line(event))
                .map(|line| line.split_whitespace().collect::<Vec<_>>().join(" "));
            Ok(running.run.notes().iter().cloned().chain(lines).collect())
        })
    }

    /// Whether every machine that started is in a final state (its OnEntry run) or halted.
    #[getter]
    fn finished(&self) -> PyResult<bool> {
        self.with(|running| Ok(running.run.is_over()))
    }

    /// How many rounds have run.
    #[getter]
    fn rounds(&self) -> PyResult<u64> {
        self.with(|running| Ok(running.run.rounds()))
    }

    /// The checkpoint asked for with `checkpoint_at=N`, as text (one line of JSON, the form
    /// `proclaim run --checkpoint-file` writes), once it has been taken; None before. It holds
    /// the run as it stood before round N (or the first round after it where every expert had
    /// answered everything posted), and is taken when that round runs; a behaviour made with
    /// `resume=` the text plays that round at its first step and goes on as this one did.
    fn checkpoint(&self) -> PyResult<Option<String>> {
        self.with(|driven| {
            if driven.checkpoint.is_none() {
                if let Some(taken) = driven.run.checkpoint() {
                    let text = taken.to_text().map_err(errors::Error::new_err)?;
                    driven.checkpoint = Some(text);
                }
            }
            Ok(driven.checkpoint.clone())
        })
    }

    /// Stops every module and machine now; later calls raise ValueError. Closing twice is
    /// allowed.
    fn close(&self) -> PyResult<()> {
        let taken = match self.running.try_lock() {
            Ok(mut guard) => guard.take(),
            Err(TryLockError::Poisoned(poisoned)) => poisoned.into_inner().take(),
            Err(TryLockError::WouldBlock) => {
                return Err(PyRuntimeError::new_err(
                    "the behaviour cannot be closed while it is running a round (from one of \
                     its own callables, or from another thread)",
                ))
            }
        };
        // The machines' tasks never run again; the callables they held are released here, with
        // the interpreter lock held.
        drop(taken);
        Ok(())
    }

    #[getter]
    fn closed(&self) -> bool {
        match self.running.try_lock() {
            Ok(guard) => guard.is_none(),
            Err(TryLockError::Poisoned(poisoned)) => poisoned.into_inner().is_none(),
            Err(TryLockError::WouldBlock) => false,
        }
    }

    fn __traverse__(&self, visit: PyVisit<'_>) -> Result<(), PyTraverseError> {
        // Never waits: a list in use is skipped this time round.
        if let Ok(callables) = self.callables.try_lock() {
            for callable in callables.iter() {
                visit.call(callable)?;
            }
        }
        Ok(())
    }

    fn __clear__(&self) {
        if let Ok(mut running) = self.running.try_lock() {
            running.take();
        }
        if let Ok(mut callables) = self.callables.try_lock() {
            callables.clear();
        }
    }

    fn __enter__(slf: Py<Self>) -> Py<Self> {
        slf
    }

    fn __exit__(
        &self,
        _kind: Option<Bound<'_, PyAny>>,
        _value: Option<Bound<'_, PyAny>>,
        _traceback: Option<Bound<'_, PyAny>>,
    ) -> PyResult<bool> {
        self.close()?;
        Ok(false)
    }

    fn __repr__(&self) -> String {
        format!("<proclaim.Behaviour {}>", self.folder.display())
    }
}

/// Why posting `ty` would change nothing, if it would not: the machines only ask it (they
/// read none of its postings) and some module answers it.
fn answered_elsewhere(board: &proclaim_board::Whiteboard, ty: &str) -> Option<String> {
    let registry = board.registry();
    let modules = registry.modules();
    let asked = modules.iter().any(|m| m.waits_on.iter().any(|t| t == ty));
    let read = modules.iter().any(|m| m.reads.iter().any(|t| t == ty));
    let answerers = registry.answerers(ty);
    (asked && !read && !answerers.is_empty()).then(|| {
        format!(
            "`{ty}` is a label the machines ask and {} answers: a posting would not change its answer; answer it from Python with experts={{\"{ty}\": ...}}, or set it in the script",
            answerers.join(", ")
        )
    })
}

/// The behaviour in `folder` loaded to check the callables given against it: BehaviourError for
/// an expert no machine asks for or a host function no machine calls, a BehaviourWarning for a
/// host function called that no callable answers. Its script, for the clock; none when it does
/// not load (starting it then raises the load's errors).
fn checked(
    py: Python<'_>,
    folder: &std::path::Path,
    experts: &[String],
    hosts: &[String],
) -> PyResult<Option<proclaim_experts::Script>> {
    let name = folder
        .file_name()
        .and_then(|n| n.to_str())
        .unwrap_or("behaviour");
    let files = Arc::new(proclaim_behaviour::Folder::new(folder));
    let Ok(behaviour) = proclaim_behaviour::load(name, files) else {
        return Ok(None);
    };
    let findings = checks::check(
        &behaviour.machines,
        &behaviour.shared_variables(),
        experts,
        hosts,
    );
    let category = py.get_type::<errors::BehaviourWarning>();
    for warning in &findings.warnings {
        let message =
            std::ffi::CString::new(warning.message.replace('\0', " ")).unwrap_or_default();
        PyErr::warn(py, &category, &message, 1)?;
    }
    if !findings.errors.is_empty() {
        let message: Vec<&str> = findings.errors.iter().map(|p| p.message.as_str()).collect();
        let problems: Vec<(String, usize, usize, String)> = findings
            .errors
            .iter()
            .map(|p| (p.file.clone(), p.line, 0, p.message.clone()))
            .collect();
        let error = errors::BehaviourError::new_err(format!(
            "the behaviour in {} was given callables its machines do not use:\n{}",
            folder.display(),
            message.join("\n")
        ));
        error.value(py).setattr("problems", problems)?;
        return Err(error);
    }
    Ok(behaviour.script)
}
