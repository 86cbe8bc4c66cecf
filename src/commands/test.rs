//! `proclaim test BEHAVIOUR RECORDING...`: recorded runs as regression tests. Each recording
//! (`run --record`, or every `.jsonl` in a folder) is replayed on the behaviour as it is now
//! (`proclaim_behaviour::replay_recording`); exit 0 when every replay is the same as its
//! recording, 1 with the first difference of each that is not.

use crate::behaviours::load_behaviour;
use crate::failure::Failure;
use proclaim_behaviour::{read_recording, replay_recording, ReplayOutcome};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// `proclaim test`.
pub fn command(args: crate::cli::TestArgs) -> Result<ExitCode, Failure> {
    let report = TestReport {
        coverage: args.coverage,
        json: args.json,
        update: args.update,
        monitor: args.monitor,
    };
    run(&args.behaviour, &args.recordings, report)
}

/// What to say besides each replay's outcome.
pub struct TestReport {
    /// What the recordings exercised (`--coverage`), as JSON (`--json`) or text.
    pub coverage: bool,
    pub json: bool,
    /// Record again each recording that differs (`--update`).
    pub update: bool,
    /// Where to draw the coverage in the browser (`--coverage --monitor`).
    pub monitor: Option<String>,
}

pub fn run(
    behaviour: &str,
    recordings: &[PathBuf],
    report: TestReport,
) -> Result<ExitCode, Failure> {
    let behaviour = load_behaviour(behaviour)?;
    let files = recording_files(recordings)?;
    if files.is_empty() {
        return Err(Failure::Argument(
            "no recordings given (a .jsonl file from `run --record`, or a folder of them)".into(),
        ));
    }
    let mut failed = 0;
    let mut read = Vec::new();
    for path in &files {
        let text = crate::bounded::read_text(path, "a recording")?;
        let recording = read_recording(&text)
            .map_err(|e| Failure::Argument(format!("{}: not a recording: {e}", path.display())))?;
        match replay_recording(&behaviour, &recording).map_err(Failure::Runtime)? {
            // Under `--json` standard output is the coverage alone.
            ReplayOutcome::Same { rounds, events } => say(
                report.json,
                format!(
                    "ok    {} ({}{rounds} rounds, {events} events as recorded)",
                    path.display(),
                    recording.branch.as_ref().map_or(String::new(), |b| format!(
                        "branch of {} at round {}, ",
                        b.parent, b.round
                    ))
                ),
            ),
            ReplayOutcome::Differs(_) if report.update => {
                let again = proclaim_behaviour::rerecord(&behaviour, &recording)
                    .map_err(Failure::Runtime)?;
                std::fs::write(path, &again.text).map_err(|error| Failure::Write {
                    path: path.clone(),
                    error,
                })?;
                say(report.json, updated(path, &again.changed));
            }
            ReplayOutcome::Differs(difference) => {
                failed += 1;
                say(
                    report.json,
                    format!("FAIL  {}: {difference}", path.display()),
                );
            }
        }
        if report.coverage {
            read.push(recording);
        }
    }
    say(
        report.json,
        format!("{} passed, {failed} failed", files.len() - failed),
    );
    let exit = if failed == 0 {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    };
    if report.coverage {
        let coverage = proclaim_behaviour::coverage(&behaviour, &read);
        print_coverage(&coverage, report.json);
        if let Some(addr) = &report.monitor {
            show_coverage(&behaviour, &coverage, addr)?;
        }
    }
    Ok(exit)
}

/// The machines drawn in the browser with what the recordings never exercised marked, until
/// Ctrl-C.
fn show_coverage(
    behaviour: &proclaim_behaviour::Behaviour,
    coverage: &proclaim_behaviour::Coverage,
    addr: &str,
) -> Result<(), Failure> {
    let never = coverage.states.iter().chain(&coverage.transitions);
    let uncovered = never
        .filter(|c| !c.exercised)
        .filter_map(|c| c.place.clone())
        .map(|p| proclaim_monitor::Uncovered {
            machine: p.machine,
            state: p.state,
            target: p.target,
            label: p.label,
        })
        .collect();
    let charts = super::monitor::charts(behaviour);
    let runtime = super::runtime::runtime(super::runtime::Shape::OneThread)?;
    runtime.block_on(async {
        let monitor = proclaim_monitor::Monitor::replay(behaviour.name.clone(), charts, Vec::new());
        monitor.set_uncovered(uncovered);
        super::monitor::open(&monitor, addr).await?;
        println!("  Ctrl-C to stop");
        let _ = tokio::signal::ctrl_c().await;
        Ok(())
    })
}

/// What `--update` accepted: the recording written again, and the first rounds that changed.
fn updated(path: &Path, changed: &[proclaim_behaviour::RoundChange]) -> String {
    let mut text = format!(
        "updated {}: recorded again, {} round{} changed",
        path.display(),
        changed.len(),
        if changed.len() == 1 { "" } else { "s" }
    );
    for change in changed.iter().take(SHOWN_CHANGES) {
        text.push_str(&format!("\n  round {}:", change.round));
        for line in change.was.iter().filter(|l| !change.now.contains(l)) {
            text.push_str(&format!("\n    - {line}"));
        }
        for line in change.now.iter().filter(|l| !change.was.contains(l)) {
            text.push_str(&format!("\n    + {line}"));
        }
    }
    if changed.len() > SHOWN_CHANGES {
        text.push_str(&format!("\n  … and {} more", changed.len() - SHOWN_CHANGES));
    }
    text
}

/// How many changed rounds `--update` shows.
const SHOWN_CHANGES: usize = 5;

/// A line of the replays' outcome: on standard output, or on standard error when that is JSON.
fn say(json: bool, line: String) {
    if json {
        eprintln!("{line}");
    } else {
        println!("{line}");
    }
}

/// What the recordings exercised, kind by kind, and what they never did.
fn print_coverage(coverage: &proclaim_behaviour::Coverage, json: bool) {
    if json {
        println!("{}", serde_json::to_string(coverage).unwrap_or_default());
        return;
    }
    println!("coverage:");
    for (kind, done, of, never) in coverage.summary() {
        println!("  {kind}: {done} of {of}");
        for what in never {
            println!("    never: {what}");
        }
    }
}

/// The files named, and the `.jsonl` files of the folders named, in name order.
fn recording_files(paths: &[PathBuf]) -> Result<Vec<PathBuf>, Failure> {
    let mut files = Vec::new();
    for path in paths {
        if path.is_dir() {
            let mut found: Vec<PathBuf> = std::fs::read_dir(path)
                .map_err(|error| Failure::Read {
                    path: path.clone(),
                    error,
                })?
                .filter_map(|entry| entry.ok().map(|e| e.path()))
                .filter(|p| p.extension().is_some_and(|e| e == "jsonl"))
                .collect();
            found.sort();
            files.extend(found);
        } else {
            files.push(Path::new(path).to_path_buf());
        }
    }
    Ok(files)
}
