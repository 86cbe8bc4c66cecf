//! `proclaim verify`: a behaviour's properties (the manifest's, or those on the command line)
//! checked over every run under the round schedule; each outcome, its counterexample by rounds,
//! the built-in findings; `--counterexample` writes the first counterexample as an impersonator
//! script (a liveness property's lasso with its loop played several times); `--emit promela` writes the same model for SPIN instead. Exit 0 every property holds, 1 some fails, 3 none fails but some is undecided (the
//! state budget ran out), 2 bad input.

use crate::behaviours::load_behaviour;
use crate::cli::{EmitFormat, EngineName, ReductionName, VerifyArgs};
use crate::failure::Failure;
use indicatif::{ProgressBar, ProgressStyle};
use proclaim_behaviour::Behaviour;
use proclaim_verify::{
    lasso_script, manifest_properties, render, to_promela, to_script, unroll, verify_with_progress,
    Finding, Options, Progress, PropertyKind, PropertyOutcome, PropertySource, Reductions, Report,
    SearchEngine, SearchStats, Verdict, VerifyError,
};
use std::path::Path;
use std::process::ExitCode;
use std::time::Instant;

/// The properties given on the command line.
pub struct Asked {
    pub never: Vec<String>,
    pub always: Vec<String>,
    pub reachable: Vec<String>,
    pub eventually: Vec<String>,
    pub leads_to: Vec<String>,
    pub always_eventually: Vec<String>,
    /// Assumed by every liveness property checked.
    pub fair: Vec<String>,
}

impl Asked {
    fn sources(&self) -> Vec<PropertySource> {
        [
            (PropertyKind::Never, &self.never),
            (PropertyKind::Always, &self.always),
            (PropertyKind::Reachable, &self.reachable),
            (PropertyKind::Eventually, &self.eventually),
            (PropertyKind::LeadsTo, &self.leads_to),
            (PropertyKind::AlwaysEventually, &self.always_eventually),
        ]
        .into_iter()
        .flat_map(|(kind, list)| {
            list.iter().enumerate().map(move |(i, e)| PropertySource {
                // Named after the option, numbered when it is given more than once.
                name: if list.len() == 1 {
                    kind.option()
                } else {
                    format!("{} #{}", kind.option(), i + 1)
                },
                kind,
                expression: e.clone(),
                fair: Vec::new(),
            })
        })
        .collect()
    }

    /// The properties to check: those asked, else the manifest's; `--fair` added to every
    /// liveness property among them (an error when there is none).
    fn properties(
        &self,
        behaviour: &proclaim_behaviour::Behaviour,
    ) -> Result<Vec<PropertySource>, Failure> {
        let mut properties = self.sources();
        if properties.is_empty() {
            properties = manifest_properties(behaviour);
        }
        if !self.fair.is_empty() {
            let mut live = properties
                .iter_mut()
                .filter(|p| p.kind.is_liveness())
                .peekable();
            if live.peek().is_none() {
                return Err(Failure::Argument(
                    "--fair is an assumption of liveness properties: give --eventually, --leads-to or --always-eventually (or declare one in the manifest)".into(),
                ));
            }
            for p in live {
                p.fair.extend(self.fair.iter().cloned());
            }
        }
        Ok(properties)
    }
}

/// `proclaim verify`: the model written for another checker with `--emit`, else checked here.
pub fn command(args: VerifyArgs) -> Result<ExitCode, Failure> {
    let asked = Asked {
        never: args.never,
        always: args.always,
        reachable: args.reachable,
        eventually: args.eventually,
        leads_to: args.leads_to,
        always_eventually: args.always_eventually,
        fair: args.fair,
    };
    match args.emit {
        Some(language) => emit(
            &args.behaviour,
            &asked,
            Options {
                max_states: args.max_states,
                ..Options::default()
            },
            language,
            args.output.as_deref(),
        ),
        None => {
            let ran = run(
                &args.behaviour,
                &asked,
                Options {
                    clock_order: args.clock_order,
                    ..options(args.max_states, args.max_memory, &args.without, args.engine)
                },
                args.json,
                args.counterexample.as_deref(),
            );
            match ran {
                // A program reading `--json` gets a document whatever happened: the error, as
                // stderr says it too.
                Err(failure) if args.json => {
                    let why = match &failure {
                        Failure::Invalid { what, errors, .. } => {
                            format!(
                                "{what} has {errors} error{}",
                                if *errors == 1 { "" } else { "s" }
                            )
                        }
                        other => other.to_string(),
                    };
                    println!("{}", serde_json::json!({ "error": why, "exit": 2 }));
                    Err(failure)
                }
                other => other,
            }
        }
    }
}

/// The search's options from the command line: the memory budget defaults to half of what
/// the machine has available, so a search stops with an answer before the system stops it.
pub fn options(
    max_states: usize,
    max_memory: Option<usize>,
    without: &[ReductionName],
    engine: EngineName,
) -> Options {
    let mut reductions = Reductions::default();
    for r in without {
        match r {
            ReductionName::ChosenWhenRead => reductions.chosen_when_read = false,
            ReductionName::ConeOfInfluence => reductions.cone_of_influence = false,
            ReductionName::StopWhenDecided => reductions.stop_when_decided = false,
        }
    }
    Options {
        max_states,
        max_memory: max_memory.unwrap_or_else(default_memory_budget),
        clock_order: false,
        reductions,
        engine: match engine {
            EngineName::Auto => SearchEngine::Auto,
            EngineName::Explicit => SearchEngine::Explicit,
            EngineName::Symbolic => SearchEngine::Symbolic,
        },
    }
}

/// Half the memory available now (Linux's `MemAvailable`), or 4 GiB where that cannot be read.
fn default_memory_budget() -> usize {
    let available = std::fs::read_to_string("/proc/meminfo")
        .ok()
        .and_then(|info| {
            let line = info.lines().find(|l| l.starts_with("MemAvailable:"))?;
            let kib: usize = line.split_whitespace().nth(1)?.parse().ok()?;
            Some(kib * 1024)
        });
    available.map_or(4 << 30, |bytes| (bytes / 2).max(64 << 20))
}

/// The behaviour, unless it is a robot of a team: the model has no teammates, so every label
/// reading the team would be wrongly never true. One whose machines race each other is
/// modelled as it runs in rounds, which is said.
fn modelled(behaviour: Behaviour) -> Result<Behaviour, Failure> {
    if behaviour.manifest.schedule == proclaim_behaviour::Schedule::Concurrent {
        eprintln!(
            "warning: `{}` runs its machines concurrently (schedule = \"concurrent\"); verify models the round schedule (docs/spec/behaviour.md §3.1), so what it says holds of the behaviour run in rounds",
            behaviour.name
        );
    }
    match &behaviour.manifest.team {
        Some(team) => Err(Failure::Argument(format!(
            "`{}` is a robot of team `{}`: verify does not model a team's values yet",
            behaviour.name,
            team.name.get_ref()
        ))),
        None => Ok(behaviour),
    }
}

pub fn run(
    behaviour: &str,
    asked: &Asked,
    options: Options,
    json: bool,
    counterexample: Option<&Path>,
) -> Result<ExitCode, Failure> {
    let loaded = modelled(load_behaviour(behaviour)?)?;
    let properties = asked.properties(&loaded)?;
    let started = Instant::now();
    // A long search shows how far it got (on a terminal only; never in JSON).
    let bar = if json {
        ProgressBar::hidden()
    } else {
        ProgressBar::new_spinner()
    };
    bar.set_style(
        ProgressStyle::with_template("{spinner} {msg} ({elapsed})")
            .unwrap_or_else(|_| ProgressStyle::default_spinner()),
    );
    let mut progress = |p: Progress| {
        bar.set_message(format!(
            "{} states found, {} expanded",
            p.stored, p.expanded
        ));
        bar.tick();
    };
    // A bad property and a behaviour beyond the checker's widths are both bad input (exit 2).
    let report = verify_with_progress(&loaded, &properties, options, &mut progress)
        .map_err(|e: VerifyError| Failure::Argument(e.to_string()));
    bar.finish_and_clear();
    let report = report?;
    let seconds = started.elapsed().as_secs_f64();
    if let Some(path) = counterexample {
        write_counterexample(&report, &loaded, path)?;
    }
    if json {
        let value = serde_json::json!({
            "behaviour": behaviour,
            "seconds": seconds,
            "report": report,
        });
        println!("{value}");
    } else {
        print_report(behaviour, &report, seconds);
    }
    Ok(ExitCode::from(report.exit_code()))
}

/// `--emit`: the model and its properties in another checker's language, to `output` or
/// stdout; the claim of each property is named on stderr.
pub fn emit(
    behaviour: &str,
    asked: &Asked,
    options: Options,
    language: EmitFormat,
    output: Option<&Path>,
) -> Result<ExitCode, Failure> {
    let loaded = modelled(load_behaviour(behaviour)?)?;
    let properties = asked.properties(&loaded)?;
    let text = match language {
        EmitFormat::Promela => {
            let promela = to_promela(&loaded, &properties, options)
                .map_err(|e| Failure::Argument(e.to_string()))?;
            for c in &promela.claims {
                eprintln!("{}: pan -N {}", c.property, c.name);
            }
            if !promela.values_complete {
                eprintln!(
                    "warning: the state budget ran out while numbering the values (--max-states)"
                );
            }
            promela.text
        }
    };
    match output {
        Some(path) => std::fs::write(path, text).map_err(|error| Failure::Write {
            path: path.to_path_buf(),
            error,
        })?,
        None => print!("{text}"),
    }
    Ok(ExitCode::SUCCESS)
}

fn print_report(behaviour: &str, report: &Report, seconds: f64) {
    let again = report.clocks_ordered.as_ref();
    let first = seconds - again.map_or(0.0, |a| a.seconds);
    print_search(behaviour, &report.stats, first.max(0.0));
    if let Some(a) = again {
        println!(
            "  the verdicts a run decided, checked again with the clocks of different machines ordered: {} states, {}, {:.2} s",
            a.stats.states,
            a.stats.stopped.describe(),
            a.seconds
        );
    }
    if report.properties.is_empty() {
        println!(
            "no properties: give --never, --always, --reachable, --eventually, --leads-to or --always-eventually, or [[property]] in the manifest"
        );
    }
    for p in &report.properties {
        print_property(p, &report.stats, !report.inexact.is_empty());
    }
    for f in &report.findings {
        print_finding(f);
    }
    // A run the model found may need a longer test of one machine due before a shorter one of
    // another, where checking it again with the clocks ordered did not decide.
    if !report.unordered_clocks.is_empty() {
        println!(
            "note: the search took the clocks of {} unordered against each other, and a run it found (a verdict's, undecided above, or a deadlock's) was not confirmed with them ordered: it may need one machine's longer timeout up before another's shorter one started no later, which no real run shows (--clock-order checks every property ordered, with the engine and budget given)",
            report.unordered_clocks.join(", ")
        );
    }
    if !report.inexact.is_empty() {
        println!("undecided where nothing was found: the model's values of these free types are not exact, so what it never reached a real run may reach (states never entered and transitions that never fire are not reported):");
        for i in &report.inexact {
            println!("  {i}");
        }
    }
}

/// A symbolic state count as said: a decision diagram counts past what a machine word holds,
/// and the count saturates there.
fn states_counted(states: usize) -> String {
    if states == usize::MAX {
        format!("more than {}", usize::MAX)
    } else {
        states.to_string()
    }
}

/// The search's one line: how much it explored, why it stopped, how fast and how small.
fn print_search(behaviour: &str, s: &SearchStats, seconds: f64) {
    if s.engine == SearchEngine::Symbolic.word() {
        let states = states_counted(s.states);
        println!(
            "{behaviour}: {states} states in {} layers (symbolic), {}, {:.2} s, {:.1} MB of decision diagrams",
            s.transitions,
            s.stopped.describe(),
            seconds,
            s.bytes as f64 / 1e6,
        );
    } else {
        println!(
            "{behaviour}: {} states, {} steps, {}, {:.0} states/s, {:.1} bytes/state ({:.1} packed)",
            s.states,
            s.transitions,
            s.stopped.describe(),
            s.states as f64 / seconds.max(1e-9),
            s.bytes_per_state,
            s.packed_bytes_per_state,
        );
    }
}

/// A property's verdict, and the run that shows it when there is one.
fn print_property(p: &PropertyOutcome, s: &SearchStats, inexact: bool) {
    let verdict = match p.verdict {
        Verdict::Holds if p.followed => "holds (its run, found with the clocks of different machines unordered, followed with them ordered)",
        Verdict::Fails if p.followed => "FAILS (its run, found with the clocks of different machines unordered, followed with them ordered)",
        Verdict::Holds => "holds",
        Verdict::Fails => "FAILS",
        Verdict::Incomplete if p.unconfirmed => {
            "undecided (its run not confirmed with the clocks of different machines ordered: below)"
        }
        Verdict::Incomplete => match s.stopped {
            proclaim_verify::Stop::MemoryBudget => "undecided (memory budget)",
            proclaim_verify::Stop::StateBudget => "undecided (state budget)",
            proclaim_verify::Stop::ChoiceBudget => "undecided (choice budget)",
            _ if inexact => "undecided (free values not exact: below)",
            _ => "undecided",
        },
    };
    let assuming = if p.fair.is_empty() {
        String::new()
    } else {
        format!(", assuming fair {}", p.fair.join(", fair "))
    };
    println!(
        "{}: {verdict} ({} {}{assuming})",
        p.name, p.kind, p.expression
    );
    if let Some(cycle) = &p.cycle {
        let run = match p.kind.as_str() {
            "leads_to" => "a run where the second never follows the first",
            "always_eventually" => "a run where it stops coming back",
            _ => "a run that never gets there",
        };
        let prefix = p.trace.as_ref().map(render).unwrap_or_default();
        if prefix.is_empty() {
            println!("  {run}, from the start:");
        } else {
            println!("  {run}: the way in, by rounds:");
            print!("{prefix}");
        }
        if cycle.steps.is_empty() {
            println!("  then no machine can ring any more, for ever");
        } else {
            println!("  then this loop, for ever:");
            print!("{}", render(cycle));
        }
        return;
    }
    if let Some(trace) = &p.trace {
        // A run followed through the ordered model is one it has, not its shortest.
        let what = match (p.kind == "reachable", p.followed) {
            (true, false) => "the shortest way there",
            (true, true) => "a way there",
            (false, false) => "shortest counterexample",
            (false, true) => "a counterexample",
        };
        println!("  {what}, by rounds:");
        print!("{}", render(trace));
    }
}

fn print_finding(f: &Finding) {
    match f {
        Finding::NeverEntered { machine, state } => {
            println!("warning: {machine}.{state} is never entered")
        }
        Finding::NeverFires {
            machine,
            from,
            to,
            label,
            line,
        } => println!(
            "warning: {machine}: the transition {from} -> {to} (when {label}, line {line}) never fires"
        ),
        Finding::Deadlock { waiting, trace } => {
            println!(
                "warning: deadlock: nothing can fire any more while {} wait",
                waiting.join(", ")
            );
            print!("{}", render(trace));
        }
    }
}

fn write_counterexample(
    report: &Report,
    behaviour: &proclaim_behaviour::Behaviour,
    path: &Path,
) -> Result<(), Failure> {
    let failing = report
        .properties
        .iter()
        .find(|p| p.verdict == Verdict::Fails && p.trace.is_some());
    let Some(p) = failing else {
        eprintln!("no counterexample to write: no property fails");
        return Ok(());
    };
    let Some(trace) = &p.trace else {
        return Ok(());
    };
    let title = format!(
        "Counterexample to `{}` ({} {}) of {}",
        p.name, p.kind, p.expression, behaviour.name
    );
    let (script, notes) = match &p.cycle {
        Some(cycle) => lasso_script(trace, cycle, behaviour.ring_period, &title),
        None => to_script(trace, behaviour.ring_period, &title),
    };
    for n in notes {
        eprintln!("note: the script does not reproduce: {n}");
    }
    std::fs::write(path, &script).map_err(|error| Failure::Write {
        path: path.to_path_buf(),
        error,
    })?;
    // The script run by the runner itself, as a trace the monitor replays.
    let played = match &p.cycle {
        Some(cycle) => unroll(trace, cycle),
        None => trace.clone(),
    };
    let rounds = played.steps.iter().map(|s| s.round).max().unwrap_or(0);
    let limit = behaviour.ring_period * (rounds + 10) + std::time::Duration::from_secs(1);
    let events = run_script(behaviour, &script, limit, u64::from(rounds) + 10)?;
    let trace_path = path.with_extension("jsonl");
    let lines: String = events
        .iter()
        .map(|e| serde_json::to_string(e).unwrap_or_default() + "\n")
        .collect();
    std::fs::write(&trace_path, lines).map_err(|error| Failure::Write {
        path: trace_path.clone(),
        error,
    })?;
    // Paths, not names, so the command works from anywhere; an end, so a counterexample that
    // leaves a machine waiting for ever still stops.
    let absolute =
        |p: &std::path::Path| std::fs::canonicalize(p).unwrap_or_else(|_| p.to_path_buf());
    let folder = behaviour.files.folder().map_or_else(
        || behaviour.name.clone(),
        |f| absolute(f).display().to_string(),
    );
    eprintln!(
        "counterexample: {} (replay it with `proclaim run {folder} --script {} --virtual-clock --for {}ms`, or walk it live from its first round with `--monitor --paused`) and {}, that run's trace (`proclaim replay --monitor {} --behaviour {folder}`)",
        path.display(),
        absolute(path).display(),
        limit.as_millis(),
        trace_path.display(),
        absolute(&trace_path).display(),
    );
    Ok(())
}

/// Runs the behaviour with `script` answering, on the virtual clock, until every machine is
/// done, `limit` of virtual time passes or round `last_round` is over; every event.
fn run_script(
    behaviour: &proclaim_behaviour::Behaviour,
    script: &str,
    limit: std::time::Duration,
    last_round: u64,
) -> Result<Vec<proclaim_runtime::Event>, Failure> {
    let script = proclaim_experts::parse_script(script).map_err(|errors| {
        Failure::Argument(format!(
            "the counterexample's script does not read back: {}",
            errors
                .iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join("; ")
        ))
    })?;
    let runtime = super::runtime::runtime(super::runtime::Shape::VirtualClock)?;
    runtime.block_on(async {
        let board = proclaim_board::Whiteboard::local();
        let options = proclaim_behaviour::LaunchOptions {
            script: Some(script),
            no_simulator: true,
            ..Default::default()
        };
        let mut running = proclaim_behaviour::launch(behaviour, &board, options)
            .await
            .map_err(Failure::Start)?;
        let (events, _) = running.follow_rounds(limit, last_round).await;
        running.stop().await;
        Ok(events)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_saturated_count_is_said_to_be_more() {
        assert_eq!(states_counted(5), "5");
        assert_eq!(states_counted(usize::MAX), "more than 18446744073709551615");
    }
}
