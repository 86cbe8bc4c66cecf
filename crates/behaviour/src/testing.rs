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
) -> Result<ScriptedRun, String> {
    let folder = folder.as_ref();
    let name = folder
        .file_name()
        .and_then(|n| n.to_str())
        .unwrap_or("behaviour")
        .to_string();
    let behaviour = load(&name, Arc::new(Folder::new(folder))).map_err(|e| {
        e.iter()
            .map(ToString::to_string)
            .collect::<Vec<_>>()
            .join("\n")
    })?;
    let script = parse_script(script).map_err(|errors| {
        errors
            .iter()
            .map(|e| format!("script: {e}"))
            .collect::<Vec<_>>()
            .join("\n")
    })?;
    let runtime = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .start_paused(true)
        .build()
        .map_err(|e| format!("no async runtime: {e}"))?;
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
        let deadline = tokio::time::Instant::now() + limit;
        while let Ok(Some(event)) = tokio::time::timeout_at(deadline, running.events.recv()).await {
            if let Event::Entered {
                machine, state, at, ..
            } = &event
            {
                run.visits.push(Visit {
                    machine: machine.clone(),
                    state: state.clone(),
                    at: *at,
                });
            }
            if let Some(line) = view.line(&event) {
                run.trace
                    .push(line.split_whitespace().collect::<Vec<_>>().join(" "));
            }
            let over = running.observe(&event);
            run.events.push(event);
            if over {
                run.finished = true;
                break;
            }
        }
        running.stop().await;
        Ok::<_, String>(run)
    })
}
