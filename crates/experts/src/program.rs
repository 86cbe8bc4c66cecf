//! Any program as an expert: a child process that is told the labels it owns and the
//! whiteboard inputs it follows, and answers queries, in JSON lines on its stdin and stdout
//! (`protocol.rs`). It is supervised: when it dies the death is reported (exit status and the
//! last lines of its stderr) and it is started again after a backoff that doubles up to a
//! bound; meanwhile its labels are not answered, so machines asking them time out (false,
//! counted and warned by the board), as with any expert that is gone.

use crate::protocol::{read_reply, to_json, Located, Request, Said};
use proclaim_board::{undecided_type, ModuleDecl, Pattern, Subscription, Whiteboard, QUERY_TYPE};
use rustc_hash::{FxHashMap, FxHashSet};
use std::collections::VecDeque;
use std::path::PathBuf;
use std::process::Stdio;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::Duration;
use tokio::io::{AsyncBufReadExt, AsyncWriteExt, BufReader};
use tokio::process::{Child, Command};
use tokio::sync::mpsc;
use tracing::Instrument;

/// How long to wait before starting a process that died again.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Backoff {
    /// After the first death.
    pub first: Duration,
    /// The wait doubles at each death up to this.
    pub most: Duration,
    /// A process that ran this long before dying starts the count again from `first`.
    pub stable: Duration,
}

impl Default for Backoff {
    fn default() -> Backoff {
        Backoff {
            first: Duration::from_millis(100),
            most: Duration::from_secs(5),
            stable: Duration::from_secs(10),
        }
    }
}

/// What a program expert has counted since it started (shared: it keeps counting while the
/// expert runs).
#[derive(Debug, Default)]
pub struct ProgramCounters {
    /// Processes started, the first included.
    pub starts: AtomicU64,
    /// Processes that died (or could not be started).
    pub deaths: AtomicU64,
    /// Answers the process could not give (`error`), each answered false.
    pub failed: AtomicU64,
    /// Lines of its stdout that were not the protocol, each ignored with a warning.
    pub garbled: AtomicU64,
    /// The running process's id (0 while none runs).
    pub pid: AtomicU64,
}

impl ProgramCounters {
    pub fn get(counter: &AtomicU64) -> u64 {
        counter.load(Ordering::Relaxed)
    }
}

/// A child process answering labels on the whiteboard.
pub struct ProgramExpert {
    name: String,
    /// The program and its arguments.
    command: Vec<String>,
    cwd: Option<PathBuf>,
    answers: Vec<String>,
    inputs: Vec<String>,
    /// Lines sent after the hello, before the inputs (the Prolog driver's knowledge base).
    greeting: Vec<Request>,
    backoff: Backoff,
    counters: Arc<ProgramCounters>,
    /// Whether every answer to a query carries its id (the Prolog driver's do).
    echoes_ids: bool,
    /// Whether its located warnings were reported already (a behaviour's load checks a
    /// knowledge base): then they are logged at debug, not again as warnings.
    warnings_reported: bool,
}

impl ProgramExpert {
    /// An expert named `name` that runs `command` (program, then arguments) and answers
    /// `answers`, told of every posting of `inputs`. An empty command fails at each start, as a
    /// program that is not there does (reported, retried with backoff).
    pub fn new(
        name: impl Into<String>,
        command: Vec<String>,
        answers: Vec<String>,
        inputs: Vec<String>,
    ) -> ProgramExpert {
        ProgramExpert {
            name: name.into(),
            command,
            cwd: None,
            answers,
            inputs,
            greeting: Vec::new(),
            backoff: Backoff::default(),
            counters: Arc::default(),
            echoes_ids: false,
            warnings_reported: false,
        }
    }

    /// Runs the process in `folder` (a behaviour's, so `ball.py` is found beside its manifest).
    pub fn in_folder(mut self, folder: impl Into<PathBuf>) -> ProgramExpert {
        self.cwd = Some(folder.into());
        self
    }

    pub fn with_backoff(mut self, backoff: Backoff) -> ProgramExpert {
        self.backoff = backoff;
        self
    }

    /// Lines the process is sent after its hello, each time it starts.
    pub(crate) fn with_greeting(mut self, greeting: Vec<Request>) -> ProgramExpert {
        self.greeting = greeting;
        self
    }

    /// Logs the warnings the process places in its files at debug only: whoever made the
    /// expert has reported them already (a behaviour's load checks a knowledge base).
    pub fn warnings_reported(mut self) -> ProgramExpert {
        self.warnings_reported = true;
        self
    }

    /// Declares that the process answers every query with its id, so an answer with none is
    /// one given unasked from its first line on.
    pub(crate) fn echoing_ids(mut self) -> ProgramExpert {
        self.echoes_ids = true;
        self
    }

    pub fn name(&self) -> &str {
        &self.name
    }

    pub fn counters(&self) -> Arc<ProgramCounters> {
        self.counters.clone()
    }

    /// What it posts, reads and answers, for the registry.
    pub fn declaration(&self) -> ModuleDecl {
        ModuleDecl::new(&self.name)
            .reads(self.inputs.iter().cloned().chain([QUERY_TYPE.to_string()]))
            .posts(self.answers.clone())
            .answers(self.answers.clone())
    }

    /// Registers, starts the process and keeps one running, answering its labels, until the
    /// whiteboard is gone.
    pub async fn run(self, board: Whiteboard) {
        let span = tracing::info_span!("program_expert", name = %self.name);
        self.supervise(board).instrument(span).await
    }

    async fn supervise(self, board: Whiteboard) {
        // Subscribed before registering, so no query sent once it is registered is missed.
        let mut types = self.inputs.clone();
        types.push(QUERY_TYPE.to_string());
        let mut messages = board.subscribe_pattern(Pattern::Any(types));
        board.register(self.declaration());
        let mut answers = Answers {
            echoes_ids: self.echoes_ids,
            ..Answers::default()
        };
        let mut wait = self.backoff.first;
        loop {
            let started = tokio::time::Instant::now();
            let why = match self.spawn() {
                Ok(mut child) => {
                    self.counters.starts.fetch_add(1, Ordering::Relaxed);
                    let pid = child.id().map_or(0, u64::from);
                    self.counters.pid.store(pid, Ordering::Relaxed);
                    let ended = self
                        .serve(&mut child, &board, &mut messages, &mut answers)
                        .await;
                    self.counters.pid.store(0, Ordering::Relaxed);
                    match ended {
                        Ended::BoardGone => return,
                        Ended::Died(why) => why,
                    }
                }
                Err(e) => format!("cannot start `{}`: {e}", self.command.join(" ")),
            };
            self.counters.deaths.fetch_add(1, Ordering::Relaxed);
            if started.elapsed() >= self.backoff.stable {
                wait = self.backoff.first;
            }
            tracing::warn!(
                expert = %self.name,
                restart_in = ?wait,
                "{why}; its labels time out until it is back"
            );
            // Queries meanwhile go unanswered (they time out); inputs are read again at the
            // start.
            let until = tokio::time::Instant::now() + wait;
            loop {
                match tokio::time::timeout_at(until, messages.next()).await {
                    Ok(Some(_)) => {}
                    Ok(None) => return,
                    Err(_) => break,
                }
            }
            answers.asked.clear();
            wait = (wait * 2).min(self.backoff.most);
        }
    }

    fn spawn(&self) -> std::io::Result<Child> {
        let Some((program, args)) = self.command.split_first() else {
            return Err(std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                "the command is empty",
            ));
        };
        let mut command = Command::new(program);
        command
            .args(args)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .kill_on_drop(true);
        if let Some(cwd) = &self.cwd {
            command.current_dir(cwd);
        }
        command.spawn()
    }

    /// One process's life: greets it, forwards inputs and queries, posts its answers; returns
    /// when it dies (why) or the board is gone.
    async fn serve(
        &self,
        child: &mut Child,
        board: &Whiteboard,
        messages: &mut Subscription,
        answers: &mut Answers,
    ) -> Ended {
        let (Some(stdin), Some(stdout), Some(stderr)) =
            (child.stdin.take(), child.stdout.take(), child.stderr.take())
        else {
            return Ended::Died("its pipes could not be opened".into());
        };
        // A writer of its own, so a process that stops reading never stops us reading it.
        let (to_child, lines_out) = mpsc::unbounded_channel::<String>();
        tokio::spawn(write_lines(stdin, lines_out));
        let stderr_tail = Arc::new(parking_lot::Mutex::new(VecDeque::new()));
        tokio::spawn(keep_tail(stderr, stderr_tail.clone(), self.name.clone()));

        let mut hello = vec![Request::Hello {
            expert: self.name.clone(),
            answers: self.answers.clone(),
            inputs: self.inputs.clone(),
        }];
        hello.extend(self.greeting.iter().cloned());
        for ty in &self.inputs {
            if let Some(m) = board.latest(ty) {
                hello.push(Request::Input {
                    name: ty.clone(),
                    value: to_json(&m.value),
                    seq: answers.input_sent(),
                });
            }
        }
        for request in hello {
            let _ = to_child.send(request.line());
        }

        let mut stdout = BufReader::new(stdout);
        // Bytes, not text: a line that is not UTF-8 is garbled output, not a death. Kept across
        // the loop's turns, as a read the board interrupts goes on where it stopped.
        let mut line = Vec::new();
        loop {
            tokio::select! {
                // The board first: an answer the process gives unasked is posted only once
                // every query already on the board is known, so none takes a stale one.
                biased;
                message = messages.next() => {
                    let Some(m) = message else {
                        return Ended::BoardGone;
                    };
                    let request = if &*m.ty == QUERY_TYPE {
                        match &m.value {
                            proclaim_board::Value::Str(label) if self.answers.contains(label) => {
                                Request::Query { label: label.clone(), id: answers.ask(label) }
                            }
                            _ => continue,
                        }
                    } else {
                        Request::Input {
                            name: m.ty.to_string(),
                            value: to_json(&m.value),
                            seq: answers.input_sent(),
                        }
                    };
                    let _ = to_child.send(request.line());
                }
                read = stdout.read_until(b'\n', &mut line) => match read {
                    Ok(n) if n > 0 && line.ends_with(b"\n") => {
                        let text = String::from_utf8_lossy(&line);
                        self.heard(read_reply(text.trim_end()), board, answers);
                        line.clear();
                    }
                    _ => return Ended::Died(death(child, &stderr_tail).await),
                }
            }
        }
    }

    /// Acts on one line of the process.
    fn heard(&self, said: Said, board: &Whiteboard, answers: &mut Answers) {
        match said {
            Said::Answer {
                label,
                value,
                id,
                after,
            } => {
                if self.owns(&label) {
                    answers.give(&self.name, board, label, value, (id, after), false);
                }
            }
            Said::Failed {
                label,
                why,
                id,
                after,
            } => {
                if self.owns(&label) {
                    self.counters.failed.fetch_add(1, Ordering::Relaxed);
                    tracing::warn!(expert = %self.name, label, why, "no answer; answered false");
                    answers.give(&self.name, board, label, false, (id, after), true);
                }
            }
            Said::Warning(located) if self.warnings_reported => {
                tracing::debug!(expert = %self.name, ?located, "a warning reported at load");
            }
            Said::Warning(located) => warn_located(&self.name, &located),
            Said::Ready => tracing::debug!(expert = %self.name, "ready"),
            Said::Garbled(why) => {
                self.counters.garbled.fetch_add(1, Ordering::Relaxed);
                tracing::warn!(expert = %self.name, "ignored a line of its output: {why}");
            }
        }
    }

    fn owns(&self, label: &str) -> bool {
        let owns = self.answers.iter().any(|a| a == label);
        if !owns {
            tracing::warn!(
                expert = %self.name,
                label,
                "answered a label it does not own (the manifest's `answers` lists those it does); ignored"
            );
        }
        owns
    }
}

/// What the expert last posted, and the queries the process has not answered yet.
#[derive(Default)]
struct Answers {
    last: FxHashMap<String, bool>,
    /// Labels last answered with an error (their `…Undecided` is true).
    failed: FxHashSet<String>,
    /// Label → the ids of its queries not yet answered, oldest first.
    asked: FxHashMap<String, VecDeque<u64>>,
    next_id: u64,
    /// How many inputs have been sent to this process (each input line's `seq`).
    inputs_sent: u64,
    /// Whether the process echoes ids (known once it has, or from the start for the Prolog
    /// driver): then an answer with none is one given unasked.
    echoes_ids: bool,
}

impl Answers {
    /// One more input sent: its `seq`.
    fn input_sent(&mut self) -> u64 {
        self.inputs_sent += 1;
        self.inputs_sent
    }

    /// A new query for `label`: its id.
    fn ask(&mut self, label: &str) -> u64 {
        self.next_id += 1;
        self.asked
            .entry(label.to_string())
            .or_default()
            .push_back(self.next_id);
        self.next_id
    }

    /// Posts an answer to a query, or one given unasked that changed while no query for its
    /// label is outstanding (the reply to that query will say what holds after every input
    /// sent before it). From a process that has never echoed an id, an answer with none is the
    /// reply to the oldest query of its label: a program need not echo ids if it never answers
    /// unasked. A failed answer (false) is marked so first, as the reasoner marks an undecided
    /// one.
    fn give(
        &mut self,
        expert: &str,
        board: &Whiteboard,
        label: String,
        value: bool,
        (id, after): (Option<u64>, Option<u64>),
        failed: bool,
    ) {
        self.echoes_ids |= id.is_some();
        // Given unasked about inputs an input sent since has changed: that input's own
        // answer, or the next query's, will say what holds.
        if id.is_none() && after.is_some_and(|after| after < self.inputs_sent) {
            return;
        }
        let outstanding = self.asked.entry(label.clone()).or_default();
        let reply = match id {
            Some(id) => match outstanding.iter().position(|&q| q == id) {
                Some(at) => {
                    // Older queries were answered by this one too.
                    outstanding.drain(..=at);
                    true
                }
                None => false,
            },
            None => !self.echoes_ids && outstanding.pop_front().is_some(),
        };
        if !reply && (!outstanding.is_empty() || self.last.get(&label) == Some(&value)) {
            return;
        }
        let was_failed = self.failed.contains(&label);
        if failed != was_failed {
            if failed {
                self.failed.insert(label.clone());
            } else {
                self.failed.remove(&label);
            }
            board.post(expert, &undecided_type(&label), failed);
        }
        board.post(expert, &label, value);
        self.last.insert(label, value);
    }
}

enum Ended {
    BoardGone,
    /// The process died, or closed its stdout: why, for the report.
    Died(String),
}

/// Logs a warning the process placed in a file (`file:line:column`).
pub(crate) fn warn_located(expert: &str, located: &Located) {
    match &located.file {
        Some(file) => tracing::warn!(
            expert,
            "{file}:{}:{}: {}",
            located.line,
            located.column,
            located.message
        ),
        None => tracing::warn!(expert, "{}", located.message),
    }
}

async fn write_lines(
    mut stdin: tokio::process::ChildStdin,
    mut lines: mpsc::UnboundedReceiver<String>,
) {
    while let Some(line) = lines.recv().await {
        if stdin.write_all(line.as_bytes()).await.is_err() || stdin.flush().await.is_err() {
            return;
        }
    }
}

/// How many lines of a process's stderr its death report quotes.
const STDERR_TAIL: usize = 12;

/// Keeps the last lines of the process's stderr (logged at debug as they come), read to its end
/// whatever it holds, so the process never blocks on a full pipe.
async fn keep_tail(
    stderr: tokio::process::ChildStderr,
    tail: Arc<parking_lot::Mutex<VecDeque<String>>>,
    expert: String,
) {
    let mut stderr = BufReader::new(stderr);
    let mut bytes = Vec::new();
    while matches!(stderr.read_until(b'\n', &mut bytes).await, Ok(n) if n > 0) {
        let line = String::from_utf8_lossy(&bytes).trim_end().to_string();
        bytes.clear();
        tracing::debug!(expert, stderr = %line);
        let mut tail = tail.lock();
        if tail.len() == STDERR_TAIL {
            tail.pop_front();
        }
        tail.push_back(line);
    }
}

/// Waits for a process whose stdout closed (killing it if it lingers) and says how it ended.
async fn death(child: &mut Child, tail: &parking_lot::Mutex<VecDeque<String>>) -> String {
    let status = match tokio::time::timeout(Duration::from_secs(1), child.wait()).await {
        Ok(Ok(status)) => status.to_string(),
        Ok(Err(e)) => format!("unknown status ({e})"),
        Err(_) => {
            let _ = child.kill().await;
            "closed its stdout; killed".to_string()
        }
    };
    // Its stderr reader may still be taking the last lines.
    tokio::time::sleep(Duration::from_millis(20)).await;
    let tail: Vec<String> = tail.lock().iter().cloned().collect();
    if tail.is_empty() {
        format!("the process ended ({status})")
    } else {
        format!(
            "the process ended ({status}); its stderr ended with:\n  {}",
            tail.join("\n  ")
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The label's latest posting: its sequence number and value.
    fn latest(board: &Whiteboard) -> Option<(u64, proclaim_board::Value)> {
        board.latest("near").map(|m| (m.seq, m.value))
    }

    #[test]
    fn an_answer_given_unasked_about_overtaken_inputs_is_dropped() {
        use proclaim_board::Value::Bool;
        let board = Whiteboard::local();
        let mut answers = Answers {
            echoes_ids: true,
            ..Answers::default()
        };
        answers.input_sent();
        answers.input_sent();
        // Computed after input 1 only: input 2 is on its way, and its own answer will come.
        answers.give("kb", &board, "near".into(), true, (None, Some(1)), false);
        assert_eq!(latest(&board), None);
        // After input 2: posted.
        answers.give("kb", &board, "near".into(), true, (None, Some(2)), false);
        let (first, value) = latest(&board).expect("posted");
        assert_eq!(value, Bool(true));
        // A program that does not say `after` is taken at its word.
        answers.give("kb", &board, "near".into(), false, (None, None), false);
        let (second, value) = latest(&board).expect("posted");
        assert!(second > first);
        assert_eq!(value, Bool(false));
        // A query's reply is posted whatever came since.
        let id = answers.ask("near");
        answers.input_sent();
        answers.give(
            "kb",
            &board,
            "near".into(),
            true,
            (Some(id), Some(2)),
            false,
        );
        assert_eq!(latest(&board).map(|(_, v)| v), Some(Bool(true)));
    }
}
