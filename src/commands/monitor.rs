//! `--monitor`: the browser page of `proclaim run` and `proclaim replay` (the page itself is the
//! `proclaim-monitor` crate); where it listens, and the machines it draws.

use crate::behaviours::load_behaviour;
use crate::failure::Failure;
use proclaim_behaviour::{read_trace, Behaviour};
use proclaim_monitor::{Access, Chart, Explainer, Monitor};
use proclaim_runtime::Event;
use std::net::SocketAddr;
use std::path::Path;
use std::process::ExitCode;
use std::sync::Arc;

/// `7480`, `127.0.0.1:7480`, `[::1]:7480` or `0.0.0.0:8080`.
pub fn parse_addr(text: &str) -> Result<SocketAddr, Failure> {
    proclaim_monitor::parse_address(text).ok_or_else(|| {
        Failure::Argument(format!(
            "--monitor {}: not an address to listen on (write 127.0.0.1:7480, or a port alone)",
            text.trim()
        ))
    })
}

/// Every machine of a behaviour as `proclaim draw` draws it.
pub fn charts(behaviour: &Behaviour) -> Vec<Chart> {
    behaviour
        .machines
        .iter()
        .map(|m| Chart::of_machine(&m.machine, m.start))
        .collect()
}

/// The page of a running behaviour on `board`, served at `addr`; `stepper` (the one its
/// machines were launched with) makes its pause and step buttons work; `named` (the behaviour
/// as the command line named it) is read again to explain an answer clicked on.
pub async fn live(
    behaviour: &Behaviour,
    named: &str,
    board: &proclaim_board::Whiteboard,
    stepper: Option<proclaim_runner::Stepper>,
    addr: &str,
    read_only: bool,
) -> Result<Monitor, Failure> {
    let monitor = Monitor::live(
        behaviour.name.clone(),
        charts(behaviour),
        board.clone(),
        stepper,
    );
    monitor.set_explainer(explainer(named));
    let access = move |bound: SocketAddr| Access::for_address(bound, read_only);
    open_with(&monitor, addr, access).await?;
    Ok(monitor)
}

/// Why a machine read an answer, for the page: the behaviour `named` read again (so the
/// explanation is of the theories as they are), the run's events read as a trace.
fn explainer(named: &str) -> Explainer {
    let named = named.to_string();
    Arc::new(move |events, asked| {
        let behaviour = load_behaviour(&named).map_err(|e| e.to_string())?;
        super::explain::answer_in_events(&behaviour, events, asked)
    })
}

/// Serves the page and says where. The default port, when taken, gives way to any free one
/// (a second run beside the first); an address given is kept to or refused.
pub async fn open(monitor: &Monitor, addr: &str) -> Result<SocketAddr, Failure> {
    open_with(monitor, addr, |_| Access::Open).await
}

/// [`open`], with who may change the run decided by the address asked for.
async fn open_with(
    monitor: &Monitor,
    addr: &str,
    access: impl FnOnce(SocketAddr) -> Access,
) -> Result<SocketAddr, Failure> {
    let (bound, shown) = monitor
        .serve_asked(addr, crate::cli::MONITOR_ADDR, access)
        .await
        .map_err(Failure::Argument)?;
    println!("  monitor: {shown}");
    Ok(bound)
}

/// `proclaim replay TRACE --monitor`: the trace at any of its moments, until Ctrl-C.
pub fn replay(trace: &Path, addr: &str, behaviour: Option<&str>) -> Result<ExitCode, Failure> {
    let text = crate::bounded::read_text(trace, "a trace or a recording")?;
    let first: Option<serde_json::Value> = text
        .lines()
        .find(|l| !l.trim().is_empty())
        .and_then(|l| serde_json::from_str(l).ok());
    let recorded = first.is_some_and(|f| {
        (f.get("seq").is_some() || f.get("branch").is_some()) && f.get("event").is_none()
    });
    // A recording replayed with its behaviour can be branched off at any round.
    let branchable = recorded && behaviour.is_some();
    if recorded && !branchable {
        return Err(Failure::Argument(format!(
            "{} is a `--record` file of whiteboard messages: give its `--behaviour` to replay it here (and branch off it), or print it with `proclaim replay {}`",
            trace.display(),
            trace.display()
        )));
    }
    let events = if branchable {
        super::branch::read(trace)?.events().to_vec()
    } else {
        read_trace(&text).map_err(|e| {
            Failure::Argument(format!(
                "{}: {e} (the monitor replays traces written by `proclaim run --trace`)",
                trace.display()
            ))
        })?
    };
    let (name, charts) = match behaviour {
        Some(b) => {
            let behaviour = load_behaviour(b)?;
            (behaviour.name.clone(), charts(&behaviour))
        }
        None => (
            trace
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_else(|| "trace".into()),
            charts_of_trace(&events),
        ),
    };
    let count = events.len();
    let runtime = super::runtime::runtime(super::runtime::Shape::OneThread)?;
    runtime.block_on(async {
        let monitor = Monitor::replay(name, charts, events);
        if let Some(named) = behaviour {
            monitor.set_explainer(explainer(named));
        }
        println!("replaying {} ({count} events)", trace.display());
        // Off loopback, only the page's own address (with its token) may branch: a branch
        // starts a process and writes a file.
        let page = open_with(&monitor, addr, |bound| Access::for_address(bound, false)).await?;
        let started = super::branch::Started::default();
        if let Some(named) = behaviour.filter(|_| branchable) {
            let brancher = super::branch::brancher(named, trace, page, started.clone());
            monitor.set_brancher(brancher);
            println!("  branch off any round from the page");
        }
        println!("  Ctrl-C to stop");
        let _ = tokio::signal::ctrl_c().await;
        started.stop_all();
        Ok(ExitCode::SUCCESS)
    })
}

/// Each machine of a trace as far as the trace shows it: the states it entered, the
/// transitions it fired, its first state as the initial one.
fn charts_of_trace(events: &[Event]) -> Vec<Chart> {
    struct Seen {
        name: String,
        initial: Option<i64>,
        states: Vec<(i64, String)>,
        transitions: Vec<(i64, i64, String)>,
    }
    let mut machines: Vec<Seen> = Vec::new();
    for event in events {
        let name = event.machine();
        let index = match machines.iter().position(|m| m.name == name) {
            Some(i) => i,
            None => {
                machines.push(Seen {
                    name: name.to_string(),
                    initial: None,
                    states: Vec::new(),
                    transitions: Vec::new(),
                });
                machines.len() - 1
            }
        };
        let seen = &mut machines[index];
        match event {
            Event::Entered { state, id, .. } => {
                seen.initial.get_or_insert(*id);
                if !seen.states.iter().any(|(s, _)| s == id) {
                    seen.states.push((*id, state.clone()));
                }
            }
            Event::Fired {
                from, to, label, ..
            } => {
                let t = (*from, *to, label.clone());
                if !seen.transitions.contains(&t) {
                    seen.transitions.push(t);
                }
            }
            _ => {}
        }
    }
    machines
        .into_iter()
        // The script's postings show under `impersonator`, which is no machine.
        .filter(|m| !(m.states.is_empty() && m.transitions.is_empty()))
        .map(|mut m| {
            // A transition fired into a state not yet entered when the trace ends.
            for (from, to, _) in &m.transitions {
                for id in [*from, *to] {
                    if !m.states.iter().any(|(s, _)| *s == id) {
                        m.states.push((id, format!("state {id}")));
                    }
                }
            }
            Chart::of_trace(m.name, m.initial.unwrap_or(0), m.states, m.transitions)
        })
        .collect()
}
