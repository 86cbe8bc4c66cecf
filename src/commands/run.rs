//! `proclaim run`: a behaviour on the in-process whiteboard, with a live trace for people, a
//! JSON-lines trace for programs (and `proclaim replay`), and file watching that rereads a
//! machine when its file changes.

use super::{checkpoint, record};
use crate::behaviours::load_behaviour;
use crate::cli::RunArgs;
use crate::failure::Failure;
use proclaim_behaviour::{launch, read_trace, Behaviour, LaunchOptions, TraceView};
use proclaim_board::Whiteboard;
use proclaim_experts::{parse_duration, parse_script};
use proclaim_runner::{RoundsEnd, Stepper};
use proclaim_runtime::Event;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;
use std::time::Duration;

/// What `check` finds stops a run, unless `--force` (or `--step`, where a person answers what
/// no expert does, or a board shared with other processes, whose experts may answer): a
/// machine that asks what nobody answers would only ever count it false.
fn refuse_unchecked(
    behaviour: &Behaviour,
    script: Option<&proclaim_experts::Script>,
    args: &RunArgs,
) -> Result<(), Failure> {
    let shown = args
        .script
        .as_ref()
        .map(|p| p.display().to_string())
        .unwrap_or_default();
    let script = script.map(|s| (shown.as_str(), s));
    // What a script sets that nobody hears is only a warning, but one a person should see.
    for w in proclaim_behaviour::script_warnings(behaviour, script) {
        eprintln!("{w}");
    }
    let findings = proclaim_behaviour::check_behaviour_with(behaviour, script, &args.ask);
    let errors: Vec<String> = findings
        .iter()
        .filter(|d| d.severity == proclaim_fsm::Severity::Error)
        .map(ToString::to_string)
        .collect();
    if errors.is_empty() {
        return Ok(());
    }
    // Over the network, other processes may answer what this behaviour does not.
    if args.force || args.step || !args.network.is_local() {
        for e in &errors {
            eprintln!("{}", e.replacen(": error: ", ": warning: ", 1));
        }
        return Ok(());
    }
    Err(Failure::Invalid {
        what: "the behaviour (run it anyway with --force)",
        errors: errors.len(),
        rendered: errors.join("\n") + "\n",
    })
}

pub fn run(args: RunArgs) -> Result<ExitCode, Failure> {
    let mut behaviour = load_behaviour(&args.behaviour)?;
    if !args.ask.is_empty() {
        // A person answers at their own pace.
        behaviour.answer_timeout = behaviour.answer_timeout.max(PERSON_TIMEOUT);
    }
    let script = match &args.script {
        None => None,
        Some(path) => Some(read_script(path)?),
    };
    refuse_unchecked(&behaviour, script.as_ref(), &args)?;
    checkpoint::refuse_unasked(&args)?;
    super::branch::say_if_replayed_differently(&behaviour, &args)?;
    if args.virtual_clock {
        refuse_processes_on_virtual_clock(&behaviour, script.as_ref())?;
    }
    let limit = match &args.duration {
        Some(text) => Some(parse_duration(text).ok_or_else(|| {
            Failure::Argument(format!(
                "--for {text}: not a duration (write 30s, 500ms or 1.5s)"
            ))
        })?),
        None => behaviour.run_for,
    };
    let mut trace_file = match &args.trace {
        None => None,
        Some(path) => Some(std::io::BufWriter::new(
            std::fs::File::create(path).map_err(|error| Failure::Write {
                path: path.clone(),
                error,
            })?,
        )),
    };
    let runtime = runtime(&args)?;
    let halted = runtime.block_on(run_on_board(
        &behaviour,
        script,
        &args,
        limit,
        &mut trace_file,
    ))?;
    if let Some(mut file) = trace_file {
        let _ = file.flush();
    }
    Ok(if halted {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    })
}

/// The run's whiteboard: its own, or one shared with the network (said where and as whom).
async fn whiteboard(behaviour: &Behaviour, args: &RunArgs) -> Result<Whiteboard, Failure> {
    let team =
        crate::network::TeamPlace::of(behaviour.manifest.team.as_ref(), args.member.as_deref())?;
    let network = args.network.for_team(team.as_ref());
    let board = crate::network::behaviour_whiteboard(&network, team.clone()).await?;
    if !network.is_local() {
        println!("  {}", network.describe());
    }
    if let Some(team) = team {
        println!("  {} of team `{}`", team.member, team.name);
    }
    Ok(board)
}

/// A branch replayed on the paused clock lets real time run once `live` says it went live.
fn real_time_from(live: Arc<tokio::sync::Notify>) {
    tokio::spawn(async move {
        live.notified().await;
        tokio::time::resume();
    });
}

/// What the page's Stop button tells: the run ends as at Ctrl-C (a branch's recording kept
/// whole).
fn stop_button(
    monitor: Option<&proclaim_monitor::Monitor>,
    args: &RunArgs,
) -> Arc<tokio::sync::Notify> {
    let stop = Arc::new(tokio::sync::Notify::new());
    if let Some(monitor) = monitor.filter(|_| !args.monitor_read_only) {
        monitor.set_stopper(stop.clone());
    }
    stop
}

fn launch_options(
    args: &RunArgs,
    script: Option<proclaim_experts::Script>,
    limit: Option<Duration>,
) -> Result<LaunchOptions, Failure> {
    // With no end given and nothing outside but the script, a run that can no longer change
    // ends (a page, a watched file, a person or the network could still change it).
    let alone = limit.is_none()
        && args.monitor.is_none()
        && !args.watch
        && !args.step
        && args.ask.is_empty()
        && args.network.is_local();
    Ok(LaunchOptions {
        script,
        no_simulator: args.no_simulator,
        halt_on_timeout: args.halt_on_timeout,
        hosts: proclaim_runner::Hosts::default(),
        // The page's pause and step buttons; machines run freely until pressed.
        stepper: if args.step {
            Some(Stepper::default())
        } else {
            let stepper = || {
                if args.paused {
                    Stepper::default()
                } else {
                    Stepper::free()
                }
            };
            args.monitor.as_ref().map(|_| stepper())
        },
        person: person(&args.ask),
        ringlets: args.record.is_some(),
        experts: Vec::new(),
        end_when_still: alone,
        checkpoints: checkpoint::plan(args).map(|(plan, _)| plan),
        resume: args.resume.as_deref().map(checkpoint::read).transpose()?,
        branch: super::branch::asked(args)?.map(Arc::new),
    })
}

/// Launches the behaviour on its whiteboard and follows it (or steps it) to the end; whether
/// a machine halted.
async fn run_on_board(
    behaviour: &Behaviour,
    script: Option<proclaim_experts::Script>,
    args: &RunArgs,
    limit: Option<Duration>,
    trace_file: &mut Option<std::io::BufWriter<std::fs::File>>,
) -> Result<bool, Failure> {
    let mut interrupt = crate::interrupt::Interrupt::new();
    // A branch plays no script: its recording says what came from outside.
    let script_used = (script.is_some() || behaviour.script.is_some()) && args.branch.is_none();
    let options = launch_options(args, script, limit)?;
    let header = options.branch.as_ref().map(|b| b.header());
    if let Some(branch) = options.branch.as_ref().filter(|_| !args.virtual_clock) {
        real_time_from(branch.live.clone());
    }
    let stepper = options.stepper.clone();
    let board = whiteboard(behaviour, args).await?;
    // Subscribed before anything starts, so the record misses nothing.
    let mut recorder = match &args.record {
        Some(path) => Some(record::start(&board, path, header.as_deref())?),
        None => None,
    };
    let mut running = launch(behaviour, &board, options)
        .await
        .map_err(Failure::Start)?;
    announce(behaviour, limit, &running.notes);
    if let (Some(recorder), Some(ringlets)) = (recorder.as_mut(), running.ringlets.take()) {
        recorder.follow(ringlets);
    }
    let mut view = trace_view(behaviour, script_used);
    let monitor = match &args.monitor {
        Some(addr) => Some(
            super::monitor::live(
                behaviour,
                &args.behaviour,
                &board,
                stepper.clone(),
                addr,
                args.monitor_read_only,
            )
            .await?,
        ),
        None => None,
    };
    if let Some(stepper) = stepper.filter(|_| args.step) {
        let why = super::step::prompt(behaviour, &board, &mut running, &stepper, &mut view).await;
        println!("stopped: {why}");
        running.stop().await;
        return Ok(false);
    }
    let live = Live {
        view,
        stop: stop_button(monitor.as_ref(), args),
        trace_file,
        changed: watch(behaviour, args.watch),
        monitor: monitor.clone(),
        behaviour,
        recorder: recorder.as_ref(),
        interrupt: &mut interrupt,
        scripted: script_used,
        checkpoints: checkpoint::plan(args).map(|(_, files)| files),
    };
    let (why, halted) = live.follow(&board, &mut running, limit).await;
    let stats = board.stats();
    println!("stopped: {why}");
    println!(
        "  {} postings, {} queries ({} timed out, {} unanswerable)",
        stats.posts, stats.queries, stats.timeouts, stats.unanswerable
    );
    running.stop().await;
    if let Some(recorder) = recorder {
        let (written, path) = recorder.finish().await;
        println!("  {written} messages recorded in {}", path.display());
    }
    if monitor.is_some() && why != "interrupted" {
        // The page shows where everything ended until the person is done looking.
        println!("  the monitor page stays open; Ctrl-C to close it");
        interrupt.next().await;
    }
    Ok(halted)
}

/// The next checkpoint taken, if checkpoints are asked for (never otherwise).
async fn next_checkpoint(
    taken: &mut Option<tokio::sync::mpsc::UnboundedReceiver<proclaim_behaviour::Checkpoint>>,
) -> Option<proclaim_behaviour::Checkpoint> {
    match taken {
        Some(rx) => rx.recv().await,
        None => std::future::pending().await,
    }
}

fn read_script(path: &Path) -> Result<proclaim_experts::Script, Failure> {
    crate::load::line_file(path, "the script", parse_script)
}

/// A Prolog or program expert is a process on the real clock: under the paused clock every
/// query to it would time out before it could answer. Refused, unless the script answers all
/// its labels (then it is left out).
fn refuse_processes_on_virtual_clock(
    behaviour: &Behaviour,
    script: Option<&proclaim_experts::Script>,
) -> Result<(), Failure> {
    let scripted = script
        .or(behaviour.script.as_ref())
        .map(|s| s.atoms())
        .unwrap_or_default();
    match behaviour
        .programs
        .iter()
        .find(|p| !p.answers.iter().all(|a| scripted.contains(a)))
    {
        None => Ok(()),
        Some(p) => Err(Failure::Argument(format!(
            "--virtual-clock: the expert `{}` is a process on the real clock, so every query to it would time out on a paused clock; run without --virtual-clock, or give a --script that answers {}",
            p.name,
            p.answers.join(", ")
        ))),
    }
}

/// Two worker threads; or, for `--virtual-clock`, one thread and tokio's paused clock.
fn runtime(args: &RunArgs) -> Result<tokio::runtime::Runtime, Failure> {
    if args.virtual_clock && !args.network.is_local() {
        return Err(Failure::Argument(
            "--virtual-clock runs on a board of its own: it cannot --listen or --connect".into(),
        ));
    }
    // A branch replays on the paused clock, so going back a minute takes no minute; on the
    // real clock it lets time run from the branch's round on (`Branch::live`), on one thread.
    super::runtime::runtime(if args.virtual_clock || args.branch.is_some() {
        super::runtime::Shape::VirtualClock
    } else {
        super::runtime::Shape::TwoThreads
    })
}

/// `--ask`: an impersonator that asks the person at this terminal.
fn person(atoms: &[String]) -> Option<proclaim_experts::Impersonator> {
    (!atoms.is_empty()).then(|| {
        proclaim_experts::Impersonator::new("person", atoms.to_vec(), Default::default())
            .with_person(
                tokio::io::BufReader::new(tokio::io::stdin()),
                tokio::io::stdout(),
            )
    })
}

/// The live trace, its names column as wide as the longest machine's name (or the
/// impersonator's, under which a script's postings show).
fn trace_view(behaviour: &Behaviour, script_used: bool) -> TraceView {
    let scripted = script_used.then_some("impersonator");
    let names = behaviour.machines.iter().map(|m| m.machine.name.as_str());
    TraceView::new(names.chain(scripted).map(str::len).max().unwrap_or(8))
}

fn announce(behaviour: &Behaviour, limit: Option<Duration>, notes: &[String]) {
    let machines = behaviour.machines.len();
    println!(
        "running {}{} ({} machine{}{})",
        behaviour.name,
        behaviour
            .manifest
            .description
            .as_deref()
            .map(|d| format!(": {d}"))
            .unwrap_or_default(),
        machines,
        if machines == 1 { "" } else { "s" },
        match limit {
            Some(d) => format!(", for {d:?} at most"),
            None => String::new(),
        }
    );
    for note in notes {
        println!("  {note}");
    }
}

/// What a live run prints and writes as it goes.
struct Live<'t> {
    view: TraceView,
    trace_file: &'t mut Option<std::io::BufWriter<std::fs::File>>,
    /// Machines whose files changed (`--watch`).
    changed: tokio::sync::mpsc::UnboundedReceiver<String>,
    /// The browser page (`--monitor`).
    monitor: Option<proclaim_monitor::Monitor>,
    /// The behaviour running, whose machines the page draws anew when they are read again.
    behaviour: &'t Behaviour,
    /// `--record`: the events go into the recording too.
    recorder: Option<&'t record::Recorder>,
    /// Ctrl-C, heard from before the run started.
    interrupt: &'t mut crate::interrupt::Interrupt,
    /// The page's Stop button.
    stop: Arc<tokio::sync::Notify>,
    /// Whether a script plays (what a run that ends still says is over).
    scripted: bool,
    /// Where the checkpoints asked for are written.
    checkpoints: Option<checkpoint::CheckpointFiles>,
}

impl Live<'_> {
    /// Prints and records events until the run is over, the limit passes or Ctrl-C; why it
    /// stopped, and whether a machine halted.
    async fn follow(
        mut self,
        board: &Whiteboard,
        running: &mut proclaim_behaviour::Running,
        limit: Option<Duration>,
    ) -> (String, bool) {
        // A resumed run began before it was taken up: its limit and times count from then.
        let started = running.epoch;
        let deadline = limit.map(|d| started + d);
        let mut taken = running.checkpoints.take();
        let mut halted = false;
        let why = loop {
            let sleep = async {
                match deadline {
                    Some(at) => tokio::time::sleep_until(at).await,
                    None => std::future::pending().await,
                }
            };
            tokio::select! {
                event = running.events.recv() => {
                    let Some(event) = event else {
                        // A schedule drops its event senders before it says how it ended.
                        let end = running.end.wait_for(Option::is_some).await;
                        if matches!(end.as_deref(), Ok(Some(RoundsEnd::Still))) {
                            break self.still(started);
                        }
                        break "every machine stopped".to_string();
                    };
                    self.show(&event);
                    halted |= matches!(event, Event::Halted { .. });
                    if running.observe(&event) {
                        break format!(
                            "every machine that started is in a final state or halted, after {:.3} s",
                            started.elapsed().as_secs_f64()
                        );
                    }
                }
                () = sleep => break format!("ran for {:?}", limit.unwrap_or_default()),
                Ok(()) = running.end.changed() => {
                    if *running.end.borrow() != Some(RoundsEnd::Still) {
                        continue;
                    }
                    // The schedule's last events were sent before it ended.
                    while let Ok(event) = running.events.try_recv() {
                        self.show(&event);
                        halted |= matches!(event, Event::Halted { .. });
                        running.observe(&event);
                    }
                    break self.still(started);
                }
                () = self.interrupt.next() => break "interrupted".to_string(),
                () = self.stop.notified() => break "stopped from the page".to_string(),
                Some(first) = self.changed.recv() => self.reread(first, board).await,
                Some(checkpoint) = next_checkpoint(&mut taken) => self.keep(&checkpoint),
            }
        };
        // Checkpoints taken before the end are written, however the run ended.
        while let Some(checkpoint) = taken.as_mut().and_then(|rx| rx.try_recv().ok()) {
            self.keep(&checkpoint);
        }
        if self.checkpoints.as_ref().is_some_and(|f| f.taken() == 0) {
            println!(
                "  no checkpoint was taken: the run ended at round {}, before one asked for could be",
                running.round.get()
            );
        }
        (why, halted)
    }

    /// Writes a checkpoint taken, saying where (or why it could not).
    fn keep(&mut self, checkpoint: &proclaim_behaviour::Checkpoint) {
        let Some(files) = &mut self.checkpoints else {
            return;
        };
        let started = std::time::Instant::now();
        match files.write(checkpoint) {
            Ok((path, bytes)) => println!(
                "  checkpoint at round {} ({:.3} s): {} ({bytes} bytes, written in {:.1} ms)",
                checkpoint.round,
                checkpoint.at().as_secs_f64(),
                path.display(),
                started.elapsed().as_secs_f64() * 1e3
            ),
            Err(failure) => eprintln!("warning: {failure}"),
        }
    }

    /// Why a run that ended at a still round stopped.
    fn still(&self, started: tokio::time::Instant) -> String {
        let outside = if self.scripted {
            "the script is over"
        } else {
            "nothing outside posts"
        };
        format!(
            "{outside} and the machines are still (no change, no time test to come), after {:.3} s",
            started.elapsed().as_secs_f64()
        )
    }

    fn show(&mut self, event: &Event) {
        if let Some(monitor) = &self.monitor {
            monitor.observe(event);
            if let Event::Reloaded { machine, .. } = event {
                self.redraw(monitor, machine);
            }
        }
        if let Some(line) = self.view.line(event) {
            println!("{line}");
        }
        if let Some(recorder) = self.recorder {
            recorder.event(event);
        }
        if let Some(file) = self.trace_file.as_mut() {
            let json = serde_json::to_string(event).unwrap_or_default();
            if let Err(e) = writeln!(file, "{json}") {
                eprintln!("warning: the trace file could not be written: {e}");
                *self.trace_file = None;
            }
        }
    }

    /// The page draws a machine read again from its file as it is now (Graphviz runs off the
    /// async threads).
    fn redraw(&self, monitor: &proclaim_monitor::Monitor, machine: &str) {
        let Some(loaded) = self
            .behaviour
            .machines
            .iter()
            .find(|m| m.machine.name == machine)
        else {
            return;
        };
        let (loader, start, monitor) = (loaded.loader.clone(), loaded.start, monitor.clone());
        tokio::task::spawn_blocking(move || {
            if let Ok(machine) = loader() {
                monitor.redraw(proclaim_monitor::Chart::of_machine(&machine, start));
            }
        });
    }

    /// One save is several file events (create, write, metadata): gathers those of the next
    /// moments and rereads each machine once.
    async fn reread(&mut self, first: String, board: &Whiteboard) {
        let mut machines = vec![first];
        let settle = tokio::time::sleep(WATCH_SETTLE);
        tokio::pin!(settle);
        loop {
            tokio::select! {
                _ = &mut settle => break,
                Some(more) = self.changed.recv() => {
                    if !machines.contains(&more) {
                        machines.push(more);
                    }
                }
            }
        }
        for machine in machines {
            println!("          {machine}: its file changed; rereading");
            board.post("watch", &machine, proclaim_runner::Command::Reread.word());
        }
    }
}

/// How long a machine waits for the answer of a person at the prompt (`--ask`).
const PERSON_TIMEOUT: Duration = Duration::from_secs(600);

/// How long `--watch` gathers the file events of one save before it rereads.
const WATCH_SETTLE: Duration = Duration::from_millis(150);

/// With `--watch` and a behaviour on disk: the names of machines whose files change.
fn watch(behaviour: &Behaviour, on: bool) -> tokio::sync::mpsc::UnboundedReceiver<String> {
    let (tx, rx) = tokio::sync::mpsc::unbounded_channel();
    let Some(folder) = behaviour.files.folder().filter(|_| on) else {
        if on {
            eprintln!("note: --watch watches files on disk; a built-in behaviour has none (run it from its folder, machines/NAME)");
        }
        return rx;
    };
    // File name → machine names (a T/A pair is watched through both files).
    let mut by_file: Vec<(String, String)> = Vec::new();
    for m in &behaviour.machines {
        let path = folder.join(&m.file);
        let partner = proclaim_fsm::partner_of(&path);
        for p in std::iter::once(path).chain(partner) {
            if let Some(name) = p.file_name().and_then(|f| f.to_str()) {
                by_file.push((name.to_string(), m.machine.name.clone()));
            }
        }
    }
    let watcher = notify::recommended_watcher(move |event: notify::Result<notify::Event>| {
        let Ok(event) = event else { return };
        if !(event.kind.is_modify() || event.kind.is_create()) {
            return;
        }
        let mut machines: Vec<&String> = Vec::new();
        for path in &event.paths {
            let name = path
                .file_name()
                .and_then(|f| f.to_str())
                .unwrap_or_default();
            for (file, machine) in &by_file {
                if file == name && !machines.contains(&machine) {
                    machines.push(machine);
                }
            }
        }
        for m in machines {
            let _ = tx.send(m.clone());
        }
    });
    match watcher {
        Ok(mut w) => {
            use notify::Watcher;
            // Watch the folders: editors often replace a file rather than write it in place.
            let mut folders: Vec<PathBuf> = behaviour
                .machines
                .iter()
                .filter_map(|m| folder.join(&m.file).parent().map(Path::to_path_buf))
                .collect();
            folders.dedup();
            for f in &folders {
                if let Err(e) = w.watch(f, notify::RecursiveMode::NonRecursive) {
                    eprintln!("warning: cannot watch {}: {e}", f.display());
                }
            }
            // Said once the watches are in place: a save from then on is seen (tests wait for it).
            eprintln!("note: --watch: a save to a machine's file rereads the machine from now on");
            // The watcher lives as long as the process.
            std::mem::forget(w);
        }
        Err(e) => eprintln!("warning: file watching is not available here: {e}"),
    }
    rx
}

/// The lines of a `--record` file (`None` when the file is a trace instead), each with the
/// moment it was recorded; or the number of the first line that is not a recorded message.
fn read_record(text: &str) -> Option<Result<Vec<(Duration, String)>, usize>> {
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty());
    let first: serde_json::Value = serde_json::from_str(lines.clone().next()?.1).ok()?;
    first
        .get("seq")
        .or_else(|| first.get("ringlet"))
        .or_else(|| first.get("branch"))?;
    Some(lines.try_fold(Vec::new(), |mut out, (i, l)| {
        let value: serde_json::Value = serde_json::from_str(l).map_err(|_| i + 1)?;
        // The ringlets and events are for `proclaim test`, a branch's parent for the reader.
        let skipped = ["ringlet", "event", "branch"];
        if skipped.iter().any(|k| value.get(k).is_some()) {
            return Ok(out);
        }
        let shown = record::shown(&value).ok_or(i + 1)?;
        let at = Duration::from_micros(value["at_us"].as_u64().unwrap_or(0));
        out.push((at, shown));
        Ok(out)
    }))
}

/// Lines printed at `speed` times the pace they were recorded at (`None`: at once).
struct Pace {
    speed: Option<f64>,
    start: std::time::Instant,
}

impl Pace {
    fn new(speed: Option<f64>) -> Pace {
        Pace {
            speed,
            start: std::time::Instant::now(),
        }
    }

    /// Waits until what happened `at` into the recording is due.
    fn wait_for(&self, at: Duration) {
        let Some(speed) = self.speed else { return };
        if let Some(wait) = at.div_f64(speed).checked_sub(self.start.elapsed()) {
            // A recording with a gap of days is not worth waiting days for.
            std::thread::sleep(wait.min(Duration::from_secs(3600)));
        }
    }
}

/// `proclaim replay`: a JSON-lines trace or a `--record` file printed as the live trace was, at
/// `speed` times its real pace (`None`: at once).
pub fn replay(file: &Path, speed: Option<f64>) -> Result<ExitCode, Failure> {
    let text = crate::bounded::read_text(file, "a trace or a recording")?;
    if speed.is_some_and(|s| !(s.is_finite() && s > 0.0)) {
        return Err(Failure::Argument(
            "--speed must be a positive number".into(),
        ));
    }
    let pace = Pace::new(speed);
    if let Some(recorded) = read_record(&text) {
        let recorded = recorded.map_err(|line| {
            Failure::Argument(format!(
                "{}: line {line}: not a recorded message",
                file.display()
            ))
        })?;
        for (at, line) in recorded {
            pace.wait_for(at);
            println!("{line}");
        }
        return Ok(ExitCode::SUCCESS);
    }
    let events =
        read_trace(&text).map_err(|e| Failure::Argument(format!("{}: {e}", file.display())))?;
    let width = events.iter().map(|e| e.machine().len()).max().unwrap_or(8);
    let mut view = TraceView::new(width);
    for event in &events {
        if let Some(at) = event.at() {
            pace.wait_for(at);
        }
        if let Some(line) = view.line(event) {
            println!("{line}");
        }
    }
    Ok(ExitCode::SUCCESS)
}
