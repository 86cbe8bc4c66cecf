//! The impersonator (the original `testcdl`): answers atoms from a script, from Rust, or from a
//! person at a terminal prompt, through the same protocol as any expert.

use parking_lot::Mutex;
use proclaim_board::{ModuleDecl, Pattern, Value, Whiteboard, QUERY_TYPE};
use proclaim_syntax::{Script, ScriptValue, When};
use rustc_hash::FxHashMap;
use serde::{Deserialize, Serialize};
use std::sync::Arc;
use tokio::io::{AsyncBufRead, AsyncBufReadExt, AsyncWrite, AsyncWriteExt};
use tracing::Instrument;

type Person = (
    Box<dyn AsyncBufRead + Unpin + Send>,
    Box<dyn AsyncWrite + Unpin + Send>,
);

/// Where a script's impersonator is: the queries it answered (its `step N:` lines count them),
/// the timed steps it played, and the answer it holds for each atom. A run's checkpoint keeps it.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ScriptPosition {
    pub step: u64,
    pub timed_played: usize,
    pub answers: Vec<HeldAnswer>,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct HeldAnswer {
    pub atom: String,
    pub value: serde_json::Value,
}

/// What the serving task counts, readable through any clone.
#[derive(Clone, Copy, Debug, Default)]
struct Counted {
    step: u64,
    timed_played: usize,
    /// The sequence number of the last query it handled (or of the board when it subscribed).
    handled: u64,
}

/// A clonable handle: clones share the answers, so a test can change them while it runs.
#[derive(Clone)]
pub struct Impersonator {
    name: String,
    atoms: Vec<String>,
    answers: Arc<Mutex<FxHashMap<String, Value>>>,
    script: Script,
    person: Arc<tokio::sync::Mutex<Option<Person>>>,
    board: Arc<Mutex<Option<Whiteboard>>>,
    /// When given, the script's timed steps wait until it is notified (the machines started).
    timed_after: Option<Arc<tokio::sync::Notify>>,
    counted: Arc<Mutex<Counted>>,
    /// Taken up from a checkpoint: the moment the script's times count from, and the script's
    /// start played already.
    resumed_at: Option<tokio::time::Instant>,
}

impl Impersonator {
    /// Impersonates the experts of `atoms` (plus every atom the script names).
    pub fn new<S: Into<String>>(
        name: impl Into<String>,
        atoms: impl IntoIterator<Item = S>,
        script: Script,
    ) -> Impersonator {
        let mut all: Vec<String> = atoms.into_iter().map(Into::into).collect();
        for a in script.atoms() {
            if !all.contains(&a) {
                all.push(a);
            }
        }
        Impersonator {
            name: name.into(),
            atoms: all,
            answers: Arc::default(),
            script,
            person: Arc::default(),
            board: Arc::default(),
            timed_after: None,
            counted: Arc::default(),
            resumed_at: None,
        }
    }

    /// Where the script is (read it between two steps of the machines).
    pub fn position(&self) -> ScriptPosition {
        let counted = *self.counted.lock();
        let mut answers: Vec<HeldAnswer> = self
            .answers
            .lock()
            .iter()
            .map(|(atom, value)| HeldAnswer {
                atom: atom.clone(),
                value: value.to_json(),
            })
            .collect();
        answers.sort_by(|a, b| a.atom.cmp(&b.atom));
        ScriptPosition {
            step: counted.step,
            timed_played: counted.timed_played,
            answers,
        }
    }

    /// The sequence number of the last query it handled: a query above it is still to be
    /// answered.
    pub fn handled(&self) -> u64 {
        self.counted.lock().handled
    }

    /// Takes up the script at `position`, its times counted from `start` (the run's epoch):
    /// the start's steps and the timed steps played are not played again.
    pub fn resumed(self, position: &ScriptPosition, start: tokio::time::Instant) -> Impersonator {
        {
            let mut answers = self.answers.lock();
            answers.clear();
            for held in &position.answers {
                answers.insert(held.atom.clone(), Value::from_json(&held.value));
            }
        }
        *self.counted.lock() = Counted {
            step: position.step,
            timed_played: position.timed_played,
            handled: 0,
        };
        Impersonator {
            resumed_at: Some(start),
            ..self
        }
    }

    /// Holds the script's timed steps back until `started` is notified (once the machines are
    /// started), counting their times from the impersonator's own start as ever: a step timed
    /// for the first round's moment then arrives at that round's beginning, as a step timed for
    /// any later round's moment does, and not before the schedule exists. Queries are answered
    /// meanwhile.
    pub fn timed_after(mut self, started: Arc<tokio::sync::Notify>) -> Impersonator {
        self.timed_after = Some(started);
        self
    }

    /// Asks a person for atoms with no scripted value: `readyReceived? [y/n]`.
    pub fn with_person(
        self,
        input: impl AsyncBufRead + Unpin + Send + 'static,
        output: impl AsyncWrite + Unpin + Send + 'static,
    ) -> Impersonator {
        match self.person.try_lock() {
            Ok(mut person) => *person = Some((Box::new(input), Box::new(output))),
            // Only while a running clone is asking its person; keep that one.
            Err(_) => {
                tracing::warn!(name = %self.name, "a person is already answering; the new one was not attached")
            }
        }
        self
    }

    pub fn declaration(&self) -> ModuleDecl {
        ModuleDecl::new(&self.name)
            .reads([QUERY_TYPE])
            .posts(self.atoms.clone())
            .answers(self.atoms.clone())
    }

    /// Sets an answer from Rust; posted at once when running (an unprompted proclamation).
    pub fn set(&self, atom: &str, value: bool) {
        self.set_value(atom, Value::Bool(value));
    }

    /// Sets an atom's value (a number or text, as a sensor posts them); a query for it is
    /// answered with the value itself, which a label reads as its truth.
    pub fn set_value(&self, atom: &str, value: Value) {
        self.answers.lock().insert(atom.to_string(), value.clone());
        if let Some(board) = self.board.lock().as_ref() {
            board.post(&self.name, atom, value);
        }
    }

    fn current(&self, atom: &str) -> Option<Value> {
        self.answers.lock().get(atom).cloned()
    }

    /// Registers and answers queries until the whiteboard is gone.
    pub async fn run(self, board: Whiteboard) {
        let span = tracing::info_span!("impersonator", name = %self.name);
        self.serve(board).instrument(span).await
    }

    async fn serve(self, board: Whiteboard) {
        let mut queries = board.subscribe_pattern(Pattern::Type(QUERY_TYPE.to_string()));
        self.counted.lock().handled = board.snapshot().seq;
        board.register(self.declaration());
        *self.board.lock() = Some(board.clone());
        let start_steps = self.script.steps.iter().filter(|s| s.when == When::Start);
        for step in start_steps.filter(|_| self.resumed_at.is_none()) {
            self.set_value(&step.atom, value_of(&step.value));
        }
        let start = self.resumed_at.unwrap_or_else(tokio::time::Instant::now);
        let Counted {
            mut step,
            timed_played,
            ..
        } = *self.counted.lock();
        let mut timed: Vec<_> = self
            .script
            .steps
            .iter()
            .filter_map(|s| match s.when {
                When::At(t) => Some((t, s.atom.clone(), value_of(&s.value))),
                _ => None,
            })
            .collect();
        timed.sort_by_key(|(t, _, _)| *t);
        let mut timed = timed.into_iter().skip(timed_played).peekable();
        let mut held = self.timed_after.clone();
        loop {
            let next_time = timed.peek().map(|(t, _, _)| start + *t);
            let query = match (next_time, &held) {
                (Some(_), Some(started)) => tokio::select! {
                    q = queries.next() => q,
                    () = started.notified() => {
                        held = None;
                        continue;
                    }
                },
                (Some(at), None) => tokio::select! {
                    q = queries.next() => q,
                    _ = tokio::time::sleep_until(at) => {
                        let (_, atom, value) = timed.next().expect("peeked");
                        // Posted and counted as one: whoever reads the position sees both.
                        let mut counted = self.counted.lock();
                        self.set_value(&atom, value);
                        counted.timed_played += 1;
                        continue;
                    }
                },
                (None, _) => queries.next().await,
            };
            let Some(query) = query else { return };
            self.counted.lock().handled = query.seq;
            let Value::Str(atom) = &query.value else {
                continue;
            };
            if !self.atoms.contains(atom) {
                continue;
            }
            step += 1;
            self.counted.lock().step = step;
            for s in self
                .script
                .steps
                .iter()
                .filter(|s| s.when == When::Step(step))
            {
                self.answers
                    .lock()
                    .insert(s.atom.clone(), value_of(&s.value));
            }
            let answer = match self.current(atom) {
                Some(v) => Some(v),
                None => self.ask_person(atom).await.map(Value::Bool),
            };
            if let Some(v) = answer {
                board.post(&self.name, atom, v);
            }
        }
    }

    async fn ask_person(&self, atom: &str) -> Option<bool> {
        let mut guard = self.person.lock().await;
        let (input, output) = guard.as_mut()?;
        loop {
            output
                .write_all(format!("{atom}? [y/n] ").as_bytes())
                .await
                .ok()?;
            output.flush().await.ok()?;
            let mut line = String::new();
            if input.read_line(&mut line).await.ok()? == 0 {
                return None; // the person left: no more answers, queries time out
            }
            match line.trim().to_ascii_lowercase().as_str() {
                "y" | "yes" | "t" | "true" | "1" => return Some(true),
                "n" | "no" | "f" | "false" | "0" => return Some(false),
                _ => {
                    output.write_all(b"please answer y or n\n").await.ok()?;
                }
            }
        }
    }
}

/// A script's value as the whiteboard holds it.
pub fn value_of(value: &ScriptValue) -> Value {
    match value {
        ScriptValue::Truth(b) => Value::Bool(*b),
        ScriptValue::Whole(i) => Value::Int(*i),
        ScriptValue::Fraction(x) => Value::Float(*x),
        ScriptValue::Text(s) => Value::Str(s.clone()),
    }
}
