//! The host of a behaviour compiled to Rust: reads an impersonator script (`--script FILE`,
//! else the behaviour's own), runs the behaviour on a virtual clock (`--virtual-clock`) or the
//! real one, and writes the trace as `proclaim run --trace` does (`--trace FILE`, else standard
//! output), and a recording as `proclaim run --record` does (`--record FILE`, which `proclaim
//! test` replays on the interpreter), until every machine that started is in a final state or
//! `--for` runs out. With `--monitor` the run is on a whiteboard too, and on the monitor's page;
//! with `--listen` or `--connect` on one shared with other processes: what [`HostBoard`] a
//! project's `board.rs` opens (none unless compiled with `--whiteboard`).
//!
//! A generated project's `main` is [`main`] over its `behaviour.rs`, which implements
//! [`CompiledBehaviour`].

use crate::world::{self as runtime, Elsewhere, World};
use crate::{parse_duration, parse_script, Event, ScriptValue, When};
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;
use std::rc::Rc;
use std::time::{Duration, Instant};

/// What a generated `behaviour.rs` gives the host: its machines, the atoms it answers, and a
/// round of its schedule.
pub trait CompiledBehaviour {
    /// The behaviour's own `[impersonator]` script: its file's name and text.
    const SCRIPT: Option<(&'static str, &'static str)>;
    const MACHINE_NAMES: &'static [&'static str];
    /// The world at the start, its events going to `sink` (none are made without one).
    fn init(sink: Option<Box<dyn FnMut(Event)>>) -> World;
    /// Tells the recording and the whiteboard what the start posted.
    fn announce(w: &mut World);
    /// The run's own modules: its machines, its experts and the impersonator.
    fn modules() -> Vec<&'static str>;
    /// One round after `started`; whether a machine fired.
    fn round(w: &mut World, started: impl FnOnce(&mut World)) -> bool;
    /// A posting by `module`, from outside the machines; whether it is news to a machine's
    /// labels.
    fn outside(w: &mut World, module: &str, ty: &str, content: &str) -> bool;
    /// Whether the machines' own postings changed what a label reads.
    fn news(w: &World) -> bool;
    /// Whether `atom` is a theory's answer.
    fn answers(atom: &str) -> bool;
    /// The host supplies `atom` (its script posts it).
    fn supply(w: &mut World, atom: &str) -> bool;
    /// A sensor none of whose atoms the script sets: its name and atoms.
    fn unscripted_sensor(scripted: &[&str]) -> Option<(&'static str, &'static [&'static str])>;
    fn is_machine(name: &str) -> bool;
    /// Milliseconds until the next round is due, if one is.
    fn next_due_ms(w: &World) -> Option<u64>;
    /// Milliseconds until a running machine's time test (or a hold) comes due, if one will.
    fn next_test_ms(w: &World) -> Option<u64>;
    /// Whether every machine that started is in a final state.
    fn finished(w: &World) -> bool;
}

/// The whiteboard a run is on, as the project's `board.rs` opens it.
pub trait HostBoard {
    /// Posts one of the run's messages.
    fn post(&self, module: &str, ty: &str, value: &serde_json::Value);
    /// Asks `atom` of whoever answers it, waiting at most `timeout_ms`.
    fn query(&self, machine: &str, atom: &str, timeout_ms: u64) -> Elsewhere;
    /// Shows one of the trace's events on the page.
    fn observe(&self, event: &Event);
    /// Waits until `deadline` (none: for as long as it takes) for another module's posting or
    /// Ctrl-C; none when the deadline came first.
    fn wait(&self, deadline: Option<Instant>) -> Option<Heard>;
    /// What was heard and not yet taken, without waiting.
    fn heard_now(&self) -> Option<Heard>;
    /// Before a round: the step it rings in, after the page's pause; none at Ctrl-C.
    fn hold(&self, last: u64) -> Option<u64>;
    /// After a round rung in `step`.
    fn rung(&self, step: u64, machines: &[&str]);
    /// After the run: the page stays until Ctrl-C.
    fn linger(&self);
}

/// Opens the whiteboard `place` names; `ours` are the run's own modules.
pub type OpenBoard = fn(&Place, Vec<&'static str>) -> Result<Box<dyn HostBoard>, String>;

/// The opener of a project compiled without `--whiteboard`: it has none, and says how to get one.
pub fn no_whiteboard(
    place: &Place,
    _ours: Vec<&'static str>,
) -> Result<Box<dyn HostBoard>, String> {
    let option = if place.monitor.is_some() {
        "--monitor"
    } else {
        "--listen/--connect"
    };
    Err(format!("{option}: this program was compiled without the whiteboard; compile the behaviour again with `proclaim compile BEHAVIOUR --target rust --whiteboard`"))
}

const USAGE: &str = "usage: behaviour [--script FILE] [--trace FILE.jsonl] [--record FILE.jsonl] [--virtual-clock] [--for DURATION] [--monitor [ADDR]] [--monitor-read-only] [--listen [ENDPOINT] | --connect ENDPOINT] [--board NAME]";

/// Where `--monitor` serves its page when given no address; when that port is taken, on any
/// free one.
pub const MONITOR_ADDR: &str = "127.0.0.1:7480";

/// Where `--listen` listens when given no endpoint.
pub const LISTEN_ENDPOINT: &str = "tcp/127.0.0.1:7447";

/// Where the run's whiteboard is, as the command line says.
#[derive(Default)]
pub struct Place {
    /// Where the monitor's page listens, if there is one.
    pub monitor: Option<String>,
    pub read_only: bool,
    pub listen: Option<String>,
    pub connect: Option<String>,
    /// The shared whiteboard's name (`proclaim` unless given).
    pub board: Option<String>,
}

impl Place {
    /// Whether the run needs a whiteboard at all.
    pub fn wanted(&self) -> bool {
        self.monitor.is_some() || self.shared()
    }

    /// Whether the whiteboard is shared with other processes.
    pub fn shared(&self) -> bool {
        self.listen.is_some() || self.connect.is_some()
    }
}

/// What came to the run from outside while it waited.
pub enum Heard {
    /// Another module's posting: its module, type, text and value as JSON.
    Posting(String, String, String, serde_json::Value),
    /// Ctrl-C.
    Interrupted,
}

/// What the command line asked for.
struct Options {
    script: Option<PathBuf>,
    trace: Option<PathBuf>,
    record: Option<PathBuf>,
    virtual_clock: bool,
    limit_ms: Option<u64>,
    /// The whiteboard, when the run is on one.
    place: Place,
}

fn options() -> Result<Options, String> {
    let mut options = Options {
        script: None,
        trace: None,
        record: None,
        virtual_clock: false,
        limit_ms: None,
        place: Place::default(),
    };
    let mut args = std::env::args().skip(1).peekable();
    while let Some(arg) = args.next() {
        let mut value = |name: &str| {
            args.next()
                .ok_or_else(|| format!("`{name}` wants a value\n{USAGE}"))
        };
        match arg.as_str() {
            "--script" => options.script = Some(value("--script")?.into()),
            "--trace" => options.trace = Some(value("--trace")?.into()),
            "--record" => options.record = Some(value("--record")?.into()),
            "--virtual-clock" => options.virtual_clock = true,
            "--monitor" => {
                // The address is optional, as `proclaim run --monitor`'s is.
                let given = args.next_if(|next| !next.starts_with("--"));
                options.place.monitor = Some(given.unwrap_or_else(|| MONITOR_ADDR.to_string()));
            }
            "--monitor-read-only" => options.place.read_only = true,
            "--listen" => {
                let given = args.next_if(|next| !next.starts_with("--"));
                options.place.listen = Some(given.unwrap_or_else(|| LISTEN_ENDPOINT.to_string()));
            }
            "--connect" => options.place.connect = Some(value("--connect")?),
            "--board" => options.place.board = Some(value("--board")?),
            "--for" => {
                let text = value("--for")?;
                let limit = parse_duration(&text)
                    .filter(|d| d.as_micros() % 1000 == 0)
                    .ok_or_else(|| {
                        format!("`--for {text}`: not a time in whole milliseconds (12s, 500ms)")
                    })?;
                options.limit_ms = Some(limit.as_millis() as u64);
            }
            "--help" | "-h" => return Err(USAGE.to_string()),
            other => return Err(format!("unknown option `{other}`\n{USAGE}")),
        }
    }
    let place = &options.place;
    if place.read_only && place.monitor.is_none() {
        return Err(format!(
            "`--monitor-read-only` is said of a `--monitor` page\n{USAGE}"
        ));
    }
    if place.listen.is_some() && place.connect.is_some() {
        return Err(format!(
            "`--listen` and `--connect` exclude each other\n{USAGE}"
        ));
    }
    if place.board.is_some() && !place.shared() {
        return Err(format!(
            "`--board` names a whiteboard shared with `--listen` or `--connect`\n{USAGE}"
        ));
    }
    if place.shared() && options.virtual_clock {
        return Err(format!("`--virtual-clock` runs alone: other processes live on the real clock, so it cannot `--listen` or `--connect`\n{USAGE}"));
    }
    Ok(options)
}

/// One posting of the impersonator's script.
struct Step {
    at_ms: u64,
    start: bool,
    /// This step's value is the last the trace showed for its type.
    shown: bool,
    name: String,
    /// A truth word or a whole number, as the trace shows it.
    value: String,
}

/// The script `--script` names, else the behaviour's own (`[impersonator]`), as `proclaim run`
/// plays it; none without either.
fn script_steps<B: CompiledBehaviour>(path: Option<&PathBuf>) -> Result<Vec<Step>, String> {
    match (path, B::SCRIPT) {
        (Some(path), _) => {
            let shown = path.display().to_string();
            let text = crate::read_source(path).map_err(|e| format!("{shown}: {e}"))?;
            read_script::<B>(&shown, &text)
        }
        (None, Some((file, text))) => read_script::<B>(file, text),
        (None, None) => Ok(Vec::new()),
    }
}

fn read_script<B: CompiledBehaviour>(shown: &str, text: &str) -> Result<Vec<Step>, String> {
    let script = parse_script(text).map_err(|e| format!("{shown}: {e}"))?;
    let mut steps = Vec::new();
    for s in script.steps {
        let line = s.line;
        let (start, at_ms) = match s.when {
            When::Start => (true, 0),
            When::At(d) if d.as_micros() % 1000 == 0 => (false, d.as_millis() as u64),
            When::At(d) => {
                return Err(format!(
                    "{shown}:{line}: `{d:?}` is not a time in whole milliseconds"
                ))
            }
            When::Step(_) => {
                return Err(format!(
                    "{shown}:{line}: `step N:` lines are not supported by a compiled behaviour"
                ))
            }
        };
        if B::answers(&s.atom) {
            return Err(format!("{shown}:{line}: `{}` is a theory's answer: impersonating an answer is not supported by a compiled behaviour", s.atom));
        }
        if B::is_machine(&s.atom) {
            return Err(format!("{shown}:{line}: `{}` is a machine: control commands from a script are not supported by a compiled behaviour", s.atom));
        }
        let value = match s.value {
            ScriptValue::Truth(b) => b.to_string(),
            ScriptValue::Whole(i) => i.to_string(),
            _ => return Err(format!("{shown}:{line}: `{} = {}`: fractions and text in a script are not supported by a compiled behaviour (truth values and whole numbers)", s.atom, s.value)),
        };
        steps.push(Step {
            at_ms,
            start,
            shown: false,
            name: s.atom,
            value,
        });
    }
    // Start steps first, then the timed ones in time order (a stable sort keeps file order).
    steps.sort_by_key(|s| (!s.start, s.at_ms));
    Ok(steps)
}

/// The script's postings and how far they have come.
struct Impersonator {
    steps: Vec<Step>,
    next: usize,
}

impl Impersonator {
    /// Posts step `i`; the trace shows each type's value once when it changes, as `proclaim
    /// run` does. Whether it was news to a machine.
    fn post<B: CompiledBehaviour>(&mut self, w: &mut World, i: usize) -> bool {
        w.unposted.retain(|a| *a != self.steps[i].name);
        if let Some(k) = w
            .answer_shown
            .iter()
            .position(|(a, _)| *a == self.steps[i].name)
        {
            // The answer shown stands for the type's last value shown.
            let (_, value) = w.answer_shown.remove(k);
            self.steps[i].shown = (if value { "true" } else { "false" }) == self.steps[i].value;
        }
        for j in 0..i {
            if self.steps[j].shown && self.steps[j].name == self.steps[i].name {
                self.steps[j].shown = false;
                if self.steps[j].value == self.steps[i].value {
                    self.steps[i].shown = true;
                }
            }
        }
        let step = &mut self.steps[i];
        let value = runtime::outside_value(&step.value);
        w.message("impersonator", &step.name, || match value {
            Some(v) if v.is_bool => serde_json::Value::Bool(v.i != 0),
            _ => serde_json::Value::from(value.map_or(0, |v| v.i)),
        });
        if !step.shown {
            step.shown = true;
            w.posted_outside("impersonator", &step.name, &step.value);
        }
        B::outside(w, "impersonator", &step.name, &step.value)
    }

    /// Posts the steps due by now; whether one was news.
    fn post_due<B: CompiledBehaviour>(&mut self, w: &mut World) -> bool {
        let mut news = false;
        while self.next < self.steps.len() && self.steps[self.next].at_ms <= w.now_ms {
            self.next += 1;
            news |= self.post::<B>(w, self.next - 1);
        }
        news
    }

    /// When the next step is due, if one is.
    fn next_at(&self) -> Option<u64> {
        self.steps.get(self.next).map(|s| s.at_ms)
    }
}

/// Runs the behaviour `B` as the command line says, on the whiteboard `open` opens when it asks
/// for one: a generated project's `main`.
pub fn main<B: CompiledBehaviour>(open: OpenBoard) -> ExitCode {
    match host::<B>(open) {
        Ok(()) => ExitCode::SUCCESS,
        Err(Stop::Refused(message)) => {
            eprintln!("{message}");
            ExitCode::from(2)
        }
        Err(Stop::Failed(message)) => {
            eprintln!("{message}");
            ExitCode::FAILURE
        }
    }
}

/// Why the host stopped short: what it was given (exit 2), or the run itself (exit 1).
enum Stop {
    Refused(String),
    Failed(String),
}

fn host<B: CompiledBehaviour>(open: OpenBoard) -> Result<(), Stop> {
    let options = options().map_err(Stop::Refused)?;
    let steps = script_steps::<B>(options.script.as_ref()).map_err(Stop::Refused)?;
    let out: Box<dyn Write> = match create(options.trace.as_ref()).map_err(Stop::Refused)? {
        Some(file) => Box::new(file),
        None => Box::new(std::io::stdout()),
    };
    let mut out = std::io::BufWriter::new(out);
    let mut record = create(options.record.as_ref())
        .map_err(Stop::Refused)?
        .map(std::io::BufWriter::new);
    let (sender, events) = std::sync::mpsc::channel();
    let mut w = B::init(Some(Box::new(move |event| {
        let _ = sender.send(event);
    })));
    let scripted: Vec<&str> = steps.iter().map(|s| s.name.as_str()).collect();
    if let Some((sensor, atoms)) = B::unscripted_sensor(&scripted) {
        return Err(Stop::Refused(format!(
            "{}: sets none of the atoms the module `{sensor}` answers ({}): a compiled behaviour has no sensors or expert processes, and takes their atoms from its script (as `proclaim run --script` leaves such a module out when the script sets one of its atoms)",
            options.script.as_ref().map_or("no --script".into(), |p| p.display().to_string()),
            atoms.join(", ")
        )));
    }
    let board = on_board::<B>(&options.place, open, &mut w).map_err(Stop::Refused)?;
    if record.is_some() {
        w.record = Some(runtime::Record::default());
    }
    B::announce(&mut w);
    for step in &steps {
        B::supply(&mut w, &step.name);
        if !w.unposted.contains(&step.name) {
            w.unposted.push(step.name.clone());
        }
    }
    let mut impersonator = Impersonator { steps, next: 0 };
    let virtual_clock = options.virtual_clock;
    let outcome = run::<B>(
        &mut w,
        &mut impersonator,
        &options,
        board.as_deref(),
        &mut |w| {
            for event in events.try_iter() {
                let json = serde_json::to_string(&event).unwrap_or_default();
                let _ = writeln!(out, "{json}");
                if let Some(record) = record.as_mut() {
                    let _ = writeln!(record, "{json}");
                }
                if let Some(board) = &board {
                    board.observe(&event);
                }
            }
            if let (Some(file), Some(lines)) = (record.as_mut(), w.record.as_mut()) {
                for line in lines.lines.drain(..) {
                    let _ = writeln!(file, "{line}");
                }
            }
            // On the real clock the trace is read as the run goes (`tail -f`).
            if !virtual_clock {
                let _ = out.flush();
            }
        },
    );
    let _ = out.flush();
    if let Some(mut record) = record {
        let _ = record.flush();
    }
    if let (Ok(Ended::Finished), Some(board)) = (&outcome, &board) {
        board.linger();
    }
    outcome.map(|_| ()).map_err(Stop::Failed)
}

/// The whiteboard `place` asks for, opened by `open`, with the world posting its messages there
/// (and, on a shared one, asking its experts); none when the run is alone.
fn on_board<B: CompiledBehaviour>(
    place: &Place,
    open: OpenBoard,
    w: &mut World,
) -> Result<Option<Rc<dyn HostBoard>>, String> {
    if !place.wanted() {
        return Ok(None);
    }
    let board = Rc::<dyn HostBoard>::from(open(place, B::modules())?);
    let mirror = board.clone();
    w.mirror = Some(Box::new(move |module, ty, value| {
        mirror.post(module, ty, value)
    }));
    if place.shared() {
        let asker = board.clone();
        w.elsewhere = Some(Box::new(move |machine, atom, timeout_ms| {
            asker.query(machine, atom, timeout_ms)
        }));
    }
    Ok(Some(board))
}

/// The runner's bound on rounds that fire one after another (`MOST_ROUNDS_WITHOUT_WAITING`).
const MOST_ROUNDS_WITHOUT_WAITING: u64 = 10_000;

/// How a run ended without failing.
enum Ended {
    /// Every machine that started is in a final state, `--for` ran out, or nothing can happen.
    Finished,
    /// Ctrl-C, heard on the whiteboard's runtime.
    Interrupted,
}

/// Rounds until every machine that started is in a final state, `--for` runs out, or (alone
/// with its script) a still round after the script's last step; `write` writes the events
/// reported so far. With a whiteboard on the real clock, what other modules
/// post there comes in as the script's postings do.
fn run<B: CompiledBehaviour>(
    w: &mut World,
    impersonator: &mut Impersonator,
    options: &Options,
    board: Option<&dyn HostBoard>,
    write: &mut dyn FnMut(&mut World),
) -> Result<Ended, String> {
    let started = Instant::now();
    // The page's pause and step hold the rounds on either clock.
    let stepping = board;
    let mut step = 0;
    let mut without_waiting = 0;
    // Only a run on the real clock waits long enough to hear anything.
    let board = board.filter(|_| !options.virtual_clock);
    // No whiteboard, no page, no `--for`: only the script speaks to the machines.
    let alone = stepping.is_none() && options.limit_ms.is_none();
    // What the script says from the start is posted before the first round; what it says at
    // 0 ms, as the first round starts.
    while impersonator.next < impersonator.steps.len()
        && impersonator.steps[impersonator.next].start
    {
        impersonator.next += 1;
        impersonator.post::<B>(w, impersonator.next - 1);
    }
    loop {
        write(w);
        if options.limit_ms.is_some_and(|limit| w.now_ms >= limit) {
            return Ok(Ended::Finished);
        }
        if let Some(stepping) = stepping {
            match stepping.hold(step) {
                Some(now) => step = now,
                None => return Ok(Ended::Interrupted),
            }
        }
        if hear_now::<B>(w, board).is_some() {
            return Ok(Ended::Interrupted);
        }
        let changes = w.changes;
        let fired = B::round(w, |w| {
            impersonator.post_due::<B>(w);
        });
        if let Some(stepping) = stepping {
            stepping.rung(step, B::MACHINE_NAMES);
        }
        if w.over || B::finished(w) {
            write(w);
            return Ok(Ended::Finished);
        }
        // As the runner does: rounds that fire one after another hold time still, so past
        // this many the machines go round a cycle that takes no time (docs/spec/behaviour.md §3.1).
        without_waiting = if fired { without_waiting + 1 } else { 0 };
        if without_waiting >= MOST_ROUNDS_WITHOUT_WAITING {
            write(w);
            return Err(format!("halted: {MOST_ROUNDS_WITHOUT_WAITING} rounds fired one after another with no wait: the machines go round a cycle that takes no time, so time cannot pass"));
        }
        // Alone with its script, a run with no end given ends at the first still round after
        // the script's last step: every round after it would be the same (§3.1).
        let still = !fired && w.changes == changes && B::next_test_ms(w).is_none();
        if still && alone && impersonator.next == impersonator.steps.len() {
            write(w);
            return Ok(Ended::Finished);
        }
        // A round that fired, or whose own postings changed what a label reads, is followed at once.
        if fired || B::news(w) {
            continue;
        }
        let waited = Waiting {
            options,
            board,
            started,
        };
        if let Some(ended) = wait_for_round::<B>(w, impersonator, &waited, write) {
            return Ok(ended);
        }
        if w.round > 100_000_000 {
            return Err("stopped after 100,000,000 rounds".into());
        }
    }
}

/// Rounds that follow one another at once still hear the board between them, as the runner's
/// machines do; after a pause, so a posting made while the page held the run is in the round
/// its step lets ring, as the runner's snapshot has it. `Some` at Ctrl-C.
fn hear_now<B: CompiledBehaviour>(w: &mut World, board: Option<&dyn HostBoard>) -> Option<Ended> {
    while let Some(heard) = board.and_then(|b| b.heard_now()) {
        match heard {
            Heard::Posting(module, ty, content, json) => {
                hear::<B>(w, &module, &ty, &content, json);
            }
            Heard::Interrupted => return Some(Ended::Interrupted),
        }
    }
    None
}

/// What a wait between rounds reads: the command line, the board heard on the real clock, and
/// when the run started.
struct Waiting<'a> {
    options: &'a Options,
    board: Option<&'a dyn HostBoard>,
    started: Instant,
}

/// Until the next round is due: the script's steps before then, and what is heard; how the run
/// ended, if it did.
fn wait_for_round<B: CompiledBehaviour>(
    w: &mut World,
    impersonator: &mut Impersonator,
    waiting: &Waiting,
    write: &mut dyn FnMut(&mut World),
) -> Option<Ended> {
    let (options, board, started) = (waiting.options, waiting.board, waiting.started);
    let due = B::next_due_ms(w).map(|d| w.now_ms.saturating_add(d));
    let until = match (options.limit_ms, due) {
        (Some(limit), Some(due)) => Some(limit.min(due)),
        (limit, due) => limit.or(due),
    };
    loop {
        let step = impersonator
            .next_at()
            .filter(|at| until.is_none_or(|until| *at < until));
        // No machine runs and the script has said all it will: only a posting from
        // outside can start a round again.
        if step.or(until).is_none() && board.is_none() {
            write(w);
            return Some(Ended::Finished);
        }
        match wait_until(options.virtual_clock, started, step.or(until), board) {
            None => {
                w.now_ms = step.or(until).unwrap_or(w.now_ms);
                if step.is_none() || impersonator.post_due::<B>(w) {
                    return None;
                }
            }
            Some(Heard::Posting(module, ty, content, json)) => {
                w.now_ms = w.now_ms.max(started.elapsed().as_millis() as u64);
                if hear::<B>(w, &module, &ty, &content, json) {
                    return None;
                }
            }
            Some(Heard::Interrupted) => {
                write(w);
                return Some(Ended::Interrupted);
            }
        }
    }
}

/// Another module's posting (its text, and its value as JSON) comes into the run as a script's
/// does; whether it was news.
fn hear<B: CompiledBehaviour>(
    w: &mut World,
    module: &str,
    ty: &str,
    content: &str,
    json: serde_json::Value,
) -> bool {
    w.unposted.retain(|a| a != ty);
    w.recorded(module, ty, json);
    B::outside(w, module, ty, content)
}

/// The file `path` names, created (none without a path).
fn create(path: Option<&PathBuf>) -> Result<Option<std::fs::File>, String> {
    path.map(|path| std::fs::File::create(path).map_err(|e| format!("{}: {e}", path.display())))
        .transpose()
}

/// On the real clock, sleeps until `at_ms` after the start (none: for as long as it takes),
/// or until something is heard on the whiteboard; on the virtual one time jumps. What was
/// heard, or none when the moment came.
fn wait_until(
    virtual_clock: bool,
    started: Instant,
    at_ms: Option<u64>,
    board: Option<&dyn HostBoard>,
) -> Option<Heard> {
    if virtual_clock {
        return None;
    }
    let at = at_ms.map(|ms| started + Duration::from_millis(ms));
    match board {
        Some(board) => board.wait(at),
        None => {
            if let Some(at) = at {
                std::thread::sleep(at.saturating_duration_since(Instant::now()));
            }
            None
        }
    }
}
