//! Testing a behaviour from Rust in one call: the behaviour's folder and an impersonator script
//! in, the states each machine went through (with times) out. It runs on a virtual clock (tokio's
//! paused clock on a runtime of its own), so a minute of behaviour takes milliseconds and gives
//! the same answer every time. Call it from a plain `#[test]`, not from inside an async runtime.
//!
//! ```no_run
//! use proclaim_behaviour::testing::run_scripted;
//! use std::time::Duration;
//!
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let run = run_scripted("machines/microwave", "at 1s doorOpen = true", Duration::from_secs(5))?;
//! assert_eq!(run.states_of("Microwave"), ["IDLE", "OPEN"]);
//! # Ok(())
//! # }
//! ```

use crate::checkpoint::{Checkpoint, CheckpointPlan};
use crate::error::BehaviourError;
use crate::files::Folder;
use crate::launch::{launch, LaunchOptions};
use crate::load::load;
use crate::trace::TraceView;
use proclaim_board::Whiteboard;
use proclaim_experts::parse_script;
use proclaim_runner::Event;
use std::path::Path;
use std::sync::Arc;
use std::time::Duration;

/// The behaviour in `folder`, named after it.
fn load_folder(folder: &Path) -> Result<crate::Behaviour, BehaviourError> {
    let name = folder
        .file_name()
        .and_then(|n| n.to_str())
        .unwrap_or("behaviour");
    load(name, Arc::new(Folder::new(folder))).map_err(BehaviourError::Files)
}

/// A runtime of its own on tokio's paused clock: time jumps whenever every task waits.
fn paused_runtime() -> Result<tokio::runtime::Runtime, BehaviourError> {
    tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .start_paused(true)
        .build()
        .map_err(BehaviourError::Runtime)
}

/// A machine entering a state, so many seconds into the run.
#[derive(Clone, Debug, PartialEq)]
pub struct Visit {
    pub machine: String,
    pub state: String,
    pub at: Duration,
}

/// What a scripted run did.
#[derive(Clone)]
pub struct ScriptedRun {
    /// Every state entered, in time order.
    pub visits: Vec<Visit>,
    /// The run as `proclaim run` prints it (answers shown when they change).
    pub trace: Vec<String>,
    /// Every event, as `--trace` records them.
    pub events: Vec<Event>,
    /// Whether every machine that started reached a final state (or halted) before the limit.
    pub finished: bool,
    /// The whiteboard as the run left it.
    pub board: Whiteboard,
}

impl ScriptedRun {
    /// The states one machine entered, in order.
    pub fn states_of(&self, machine: &str) -> Vec<&str> {
        self.visits
            .iter()
            .filter(|v| v.machine == machine)
            .map(|v| v.state.as_str())
            .collect()
    }
}

/// Runs the behaviour in `folder` with `script` answering (and leaving out the experts whose
/// atoms it names, as `proclaim run --script` does) until every machine that started is done,
/// or `limit` of virtual time has passed. Errors: the behaviour's or the script's problems, each
/// with its file and line.
pub fn run_scripted(
    folder: impl AsRef<Path>,
    script: &str,
    limit: Duration,
) -> Result<ScriptedRun, BehaviourError> {
    let behaviour = load_folder(folder.as_ref())?;
    let script = parse_script(script).map_err(BehaviourError::Script)?;
    let runtime = paused_runtime()?;
    runtime.block_on(async {
        let board = Whiteboard::local();
        let options = LaunchOptions {
            script: Some(script),
            ..LaunchOptions::default()
        };
        let mut running = launch(&behaviour, &board, options).await?;
        let mut view = TraceView::new(0);
        let mut run = ScriptedRun {
            visits: Vec::new(),
            trace: running.notes.clone(),
            events: Vec::new(),
            finished: false,
            board: board.clone(),
        };
        let (events, finished) = running.follow(limit).await;
        for event in &events {
            if let Event::Entered {
                machine, state, at, ..
            } = event
            {
                run.visits.push(Visit {
                    machine: machine.clone(),
                    state: state.clone(),
                    at: *at,
                });
            }
            if let Some(line) = view.line(event) {
                run.trace
                    .push(line.split_whitespace().collect::<Vec<_>>().join(" "));
            }
        }
        run.events = events;
        run.finished = finished;
        running.stop().await;
        Ok::<_, BehaviourError>(run)
    })
}

/// A behaviour stepped round by round from a test (§3.1): each [`RoundByRound::round`] gives
/// every running machine one ringlet, and between rounds the test reads where each machine is
/// and what its variables hold. Time stands still unless the test moves it
/// ([`RoundByRound::wait`]), so a `timeout` comes due exactly when the test says.
///
/// ```no_run
/// use proclaim_behaviour::testing::RoundByRound;
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let mut press = RoundByRound::start("machines/press", "")?;
/// press.round();
/// assert_eq!(press.state_of("Controller"), Some("Closing"));
/// assert_eq!(press.variable("Controller", "low"), Some(proclaim_board::Value::Int(1)));
/// press.round();
/// assert_eq!(press.state_of("Sensor"), Some("Clear"));
/// # Ok(())
/// # }
/// ```
pub struct RoundByRound {
    runtime: tokio::runtime::Runtime,
    running: crate::launch::Running,
    stepper: proclaim_runner::Stepper,
    machines: Vec<String>,
    states: rustc_hash::FxHashMap<String, String>,
    /// (machine, variable) → the value its last change gave it, as text.
    locals: rustc_hash::FxHashMap<(String, String), String>,
    answer_timeout: Duration,
    /// Every event so far, in order.
    pub events: Vec<Event>,
    pub board: Whiteboard,
}

/// How a [`RoundByRound`] is started beyond its folder: who answers and who is called.
#[derive(Clone, Default)]
pub struct Stepping {
    /// An impersonator script in place of the manifest's (`None`: the manifest's; empty
    /// text: no script at all).
    pub script: Option<String>,
    /// Host functions the machines' activities call.
    pub hosts: proclaim_runner::Hosts,
    /// Experts of the embedding program, each in place of whatever answered its atoms.
    pub experts: Vec<proclaim_experts::FunctionExpert>,
    /// Time as the wall clock has it, instead of the virtual clock that moves only when the
    /// test waits (or when every task waits during [`RoundByRound::run_for`]).
    pub real_time: bool,
    /// Write a checkpoint at the first round at or after this one where one can be taken
    /// ([`RoundByRound::checkpoint`] has it; `docs/spec/behaviour.md` §3.4).
    pub checkpoint_at: Option<u64>,
    /// Take the run up where this checkpoint left it: the first [`RoundByRound::round`] plays
    /// the checkpoint's round; stepped, waited and let run free as the run it came from was,
    /// it goes on as that run did.
    pub resume: Option<Checkpoint>,
}

impl RoundByRound {
    /// Loads the behaviour in `folder` and starts it paused before its first round, with
    /// `script` answering (it may be empty). Errors: the behaviour's or the script's problems.
    pub fn start(folder: impl AsRef<Path>, script: &str) -> Result<RoundByRound, BehaviourError> {
        RoundByRound::start_with(
            folder,
            Stepping {
                script: (!script.trim().is_empty()).then(|| script.to_string()),
                ..Stepping::default()
            },
        )
    }

    /// [`RoundByRound::start`] with host functions, outside experts, or the wall clock.
    pub fn start_with(
        folder: impl AsRef<Path>,
        stepping: Stepping,
    ) -> Result<RoundByRound, BehaviourError> {
        let behaviour = load_folder(folder.as_ref())?;
        let script = match &stepping.script {
            Some(text) => Some(parse_script(text).map_err(BehaviourError::Script)?),
            None => None,
        };
        let runtime = if stepping.real_time {
            tokio::runtime::Builder::new_current_thread()
                .enable_all()
                .build()
                .map_err(BehaviourError::Runtime)?
        } else {
            paused_runtime()?
        };
        let board = Whiteboard::local();
        let stepper = proclaim_runner::Stepper::default();
        let options = LaunchOptions {
            script,
            stepper: Some(stepper.clone()),
            hosts: stepping.hosts,
            experts: stepping.experts,
            checkpoints: stepping.checkpoint_at.map(|at| CheckpointPlan {
                at: vec![at],
                every: None,
            }),
            resume: stepping.resume.map(Arc::new),
            ..LaunchOptions::default()
        };
        let resumed = options.resume.clone();
        let running = runtime.block_on(launch(&behaviour, &board, options))?;
        let mut run = RoundByRound {
            runtime,
            running,
            stepper,
            machines: behaviour
                .machines
                .iter()
                .map(|m| m.machine.name.clone())
                .collect(),
            states: Default::default(),
            locals: Default::default(),
            answer_timeout: behaviour.answer_timeout,
            events: Vec::new(),
            board,
        };
        if let Some(checkpoint) = resumed {
            run.taken_up(&checkpoint);
        }
        Ok(run)
    }

    /// Where each machine is and what its variables hold, as the checkpoint taken up says
    /// (what its events would have said).
    fn taken_up(&mut self, checkpoint: &Checkpoint) {
        for machine in &checkpoint.schedule.machines {
            if let Some(state) = &machine.last_entered {
                self.states.insert(machine.name.clone(), state.clone());
            }
            for v in &machine.locals {
                let value = proclaim_board::Value::from_json(&v.value).to_string();
                self.locals
                    .insert((machine.name.clone(), v.name.clone()), value);
            }
        }
    }

    /// Runs one round; its events.
    pub fn round(&mut self) -> &[Event] {
        let step = self.stepper.advance();
        let limit = self.answer_timeout * 4 + Duration::from_secs(1);
        let (stepper, machines) = (&self.stepper, &self.machines);
        self.runtime
            .block_on(async { stepper.settled(machines, step, limit).await });
        self.take_events()
    }

    /// Lets the machines ring freely for `time` (on the virtual clock, time jumps whenever every
    /// task waits, so a minute's `timeout` takes no real time), then pauses them; the events.
    pub fn run_for(&mut self, time: Duration) -> &[Event] {
        self.stepper.resume();
        // The sleep is made inside the runtime: its timer belongs to that runtime's clock.
        self.runtime
            .block_on(async move { tokio::time::sleep(time).await });
        self.stepper.pause();
        self.take_events()
    }

    /// The events that arrived since last taken, folded into the states and variables.
    fn take_events(&mut self) -> &[Event] {
        let first = self.events.len();
        while let Ok(event) = self.running.events.try_recv() {
            self.running.observe(&event);
            match &event {
                Event::Entered { machine, state, .. } => {
                    self.states.insert(machine.clone(), state.clone());
                }
                Event::Assigned {
                    machine,
                    variable,
                    value,
                    ..
                } => {
                    self.locals
                        .insert((machine.clone(), variable.clone()), value.clone());
                }
                _ => {}
            }
            self.events.push(event);
        }
        &self.events[first..]
    }

    /// What was started or left out (`left out microwave: the embedding program answers cook`).
    pub fn notes(&self) -> &[String] {
        &self.running.notes
    }

    /// Whether every machine that started is in a final state (its OnEntry run) or halted.
    pub fn is_over(&self) -> bool {
        self.running.is_over()
    }

    /// Every machine of the behaviour, in manifest order, with the state it last entered
    /// (`None` before it entered one: not started yet, or not started at all).
    pub fn states(&self) -> Vec<(&str, Option<&str>)> {
        self.machines
            .iter()
            .map(|m| (m.as_str(), self.state_of(m)))
            .collect()
    }

    /// Lets `time` pass on the virtual clock with no round run (a `timeout` may come due).
    pub fn wait(&mut self, time: Duration) {
        self.runtime
            .block_on(async move { tokio::time::sleep(time).await });
        self.take_events();
    }

    /// The state `machine` last entered.
    pub fn state_of(&self, machine: &str) -> Option<&str> {
        self.states.get(machine).map(String::as_str)
    }

    /// A variable as `machine` sees it: its own, else the behaviour's global of that name
    /// (an extern reads the whiteboard: [`RoundByRound::board`]).
    pub fn variable(&self, machine: &str, name: &str) -> Option<proclaim_board::Value> {
        let own = self
            .locals
            .get(&(machine.to_string(), name.to_string()))
            .filter(|_| !self.running.shared.is_global(name));
        match own {
            Some(text) => Some(proclaim_board::Value::parse(text)),
            None => self.running.shared.global(name),
        }
    }

    /// When the soonest time test of a machine's current state comes due, since the run's
    /// start, as the machines' last rings left them (none: no machine waits on one).
    pub fn next_time_test(&self) -> Option<Duration> {
        let due = self.stepper.soonest_due()?;
        Some(due.saturating_duration_since(self.running.epoch))
    }

    /// The round the schedule is in.
    pub fn rounds(&self) -> u64 {
        self.running.round.get()
    }

    /// The checkpoint asked for ([`Stepping::checkpoint_at`]), once it has been taken.
    pub fn checkpoint(&mut self) -> Option<Checkpoint> {
        self.running.checkpoints.as_mut()?.try_recv().ok()
    }
}
