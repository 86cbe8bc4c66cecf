//! The fixed text of a behaviour compiled to a Cargo project, with `@NAME@` where
//! `print_rust.rs` fills in the behaviour's own parts.

/// `src/runtime.rs`: values as the runner holds them, `arith`'s operators on them, and the world
/// a compiled behaviour runs in, reporting `proclaim_runner::Event`s.
pub(crate) const RUNTIME: &str = r#"//! The runtime of a behaviour compiled by proclaim (generated: do not edit): values as the
//! runner holds them, `proclaim_runner::arith`'s operators on them, and the world the machines
//! run in, which reports the trace's events.

use proclaim_runner::{Answerer, Event};
use std::time::Duration;

/// A value as the runner holds it: a whole number, or a truth value (0 or 1); or `none`, a
/// whiteboard value never posted, which arithmetic keeps and a comparison finds false.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Value {
    pub i: i64,
    pub is_bool: bool,
    pub none: bool,
}

pub fn v_int(i: i64) -> Value {
    Value {
        i,
        is_bool: false,
        none: false,
    }
}

pub fn v_bool(b: bool) -> Value {
    Value {
        i: i64::from(b),
        is_bool: true,
        none: false,
    }
}

pub fn v_none() -> Value {
    Value {
        i: 0,
        is_bool: false,
        none: true,
    }
}

/// What an activity makes of a value: no value is a whole 0, as the runner's activities have it.
pub fn v_some(v: Value) -> Value {
    if v.none {
        v_int(0)
    } else {
        v
    }
}

pub fn truthy(v: Value) -> bool {
    v.i != 0
}

pub fn v_add(a: Value, b: Value) -> Value {
    if a.none || b.none {
        return v_none();
    }
    v_int(a.i.wrapping_add(b.i))
}

pub fn v_sub(a: Value, b: Value) -> Value {
    if a.none || b.none {
        return v_none();
    }
    v_int(a.i.wrapping_sub(b.i))
}

pub fn v_mul(a: Value, b: Value) -> Value {
    if a.none || b.none {
        return v_none();
    }
    v_int(a.i.wrapping_mul(b.i))
}

/// Dividing by zero gives the largest whole number, as gufsm's INT_MAX.
pub fn v_div(a: Value, b: Value) -> Value {
    if a.none || b.none {
        return v_none();
    }
    match b.i {
        0 => v_int(i64::MAX),
        -1 => v_int(a.i.wrapping_neg()),
        _ => v_int(a.i / b.i),
    }
}

pub fn v_rem(a: Value, b: Value) -> Value {
    if a.none || b.none {
        return v_none();
    }
    match b.i {
        0 => v_int(i64::MAX),
        -1 => v_int(0),
        _ => v_int(a.i % b.i),
    }
}

pub fn v_neg(a: Value) -> Value {
    if a.none {
        return a;
    }
    v_int(a.i.wrapping_neg())
}

pub fn v_abs(a: Value) -> Value {
    if a.i < 0 {
        v_neg(a)
    } else {
        a
    }
}

pub fn v_eq(a: Value, b: Value) -> Value {
    v_bool(!a.none && !b.none && a.i == b.i)
}

pub fn v_ne(a: Value, b: Value) -> Value {
    v_bool(!a.none && !b.none && a.i != b.i)
}

pub fn v_lt(a: Value, b: Value) -> Value {
    v_bool(!a.none && !b.none && a.i < b.i)
}

pub fn v_le(a: Value, b: Value) -> Value {
    v_bool(!a.none && !b.none && a.i <= b.i)
}

pub fn v_gt(a: Value, b: Value) -> Value {
    v_bool(!a.none && !b.none && a.i > b.i)
}

pub fn v_ge(a: Value, b: Value) -> Value {
    v_bool(!a.none && !b.none && a.i >= b.i)
}

/// The first when it is not greater (min) or not less (max), as the runner picks.
pub fn v_min(a: Value, b: Value) -> Value {
    if a.none || b.none {
        return v_none();
    }
    if a.i <= b.i {
        a
    } else {
        b
    }
}

pub fn v_max(a: Value, b: Value) -> Value {
    if a.none || b.none {
        return v_none();
    }
    if a.i >= b.i {
        a
    } else {
        b
    }
}

pub const CONVERT_WHOLE: u8 = 0;
pub const CONVERT_TRUTH: u8 = 1;
pub const CONVERT_KEPT: u8 = 2;

pub fn convert(conversion: u8, v: Value) -> Value {
    match conversion {
        CONVERT_WHOLE => v_int(v.i),
        CONVERT_TRUTH => v_bool(truthy(v)),
        _ => v,
    }
}

/// A value's text, as the trace shows it.
pub fn value_text(v: Value) -> String {
    if v.is_bool {
        (if v.i != 0 { "true" } else { "false" }).to_string()
    } else {
        v.i.to_string()
    }
}

pub const RUNNING: u8 = 0;
pub const SUSPENDED: u8 = 1;
pub const DORMANT: u8 = 2;
pub const COMMAND_UNKNOWN: u8 = 0;
pub const COMMAND_ON: u8 = 1;
pub const COMMAND_OFF: u8 = 2;
pub const COMMAND_SUSPEND: u8 = 3;
pub const COMMAND_RESUME: u8 = 4;
pub const COMMAND_RESTART: u8 = 5;

/// The whiteboard's values the behaviour reads, its machines' states, and where its events go.
pub struct World {
    /// The millisecond clock: set before each round.
    pub now_ms: u64,
    pub round: u64,
    pub state: Vec<i64>,
    pub just_entered: Vec<bool>,
    pub entered_ms: Vec<u64>,
    /// Each theory input: known, then true.
    pub input: Vec<bool>,
    /// The answers each machine's last ringlet saw.
    pub seen: Vec<Vec<bool>>,
    /// The answers each machine's last ringlet asked (a label's `&&` and `||` ask no further
    /// than they need): an atom from outside is news only to a machine that asked it.
    pub asked: Vec<Vec<bool>>,
    pub initial: Vec<i64>,
    /// Running, suspended or dormant; started in this round (it rings from the next).
    pub status: Vec<u8>,
    pub fresh: Vec<bool>,
    /// Each machine's own variables, then the behaviour's globals.
    pub var: Vec<Value>,
    /// Each whiteboard value the machines read: the board's newest value, if any was posted
    /// (one never posted reads as a whole 0 when bound with `extern`, else as none), and who
    /// posted it.
    pub ext: Vec<Option<Value>>,
    pub ext_by: Vec<&'static str>,
    /// As each machine's last ringlet saw them: the board at its snapshot, the values it posted
    /// itself since, and whether it read the snapshot at all (a ringlet that read nothing of the
    /// board finds nothing new in a posting).
    pub ext_seen: Vec<Vec<Option<Value>>>,
    pub ext_seen_by: Vec<Vec<&'static str>>,
    pub ext_own: Vec<Vec<Option<Value>>>,
    pub ext_read: Vec<bool>,
    /// The atoms nobody answers that each machine's last ringlet asked, read from these values,
    /// and what it read: news is then a posting whose truth differs.
    pub asked_posted: Vec<Vec<Option<bool>>>,
    /// The answers the label being proved has read (atom, value, who answered), reported once
    /// it is proved, as the runner reports them.
    pub pending: Vec<(&'static str, bool, By)>,
    /// The machine whose ringlet runs, and whether that ringlet is past its snapshot.
    pub ringing: usize,
    pub past_snapshot: bool,
    /// Changes of globals so far, and as each machine's last ringlet saw them.
    pub globals_changes: u64,
    pub globals_seen: Vec<u64>,
    /// Control commands posted to each machine, obeyed when the ringlet that posted them ends.
    pub commands: Vec<Vec<(u8, &'static str)>>,
    pub commands_waiting: bool,
    /// The text a posting or a print is built in.
    pub text: String,
    /// Where the trace's events go; none are made without one.
    pub sink: Option<Box<dyn FnMut(Event)>>,
    /// Set once every machine that started is in a final state: the trace ends there.
    pub over: bool,
    /// What holds each type under subsumption, for a behaviour that declares any.
    pub suppressor: Option<proclaim_board::Suppressor>,
    /// Whether each output has an answerer: a theory's always, an atom from outside when the
    /// host supplies it (else no expert answers it, false).
    pub supplied: Vec<bool>,
    /// The script's atoms it has not posted yet (the host lists them): the impersonator answers
    /// every query by posting its answer, so one asked before the script posts it shows that
    /// answer first, kept in `answer_shown` as the type's last value shown.
    pub unposted: Vec<String>,
    pub answer_shown: Vec<(String, bool)>,
    /// The recording `--record` writes, when it asks for one.
    pub record: Option<Record>,
    /// Where every whiteboard message of the run is posted too (a real whiteboard, under
    /// `--monitor`): module, type, value.
    pub mirror: Option<Box<dyn FnMut(&str, &str, &serde_json::Value)>>,
    /// Asks an atom of an expert in another process, on a shared whiteboard: the asking
    /// machine, the atom, how long to wait in milliseconds.
    pub elsewhere: Option<Box<dyn FnMut(&str, &str, u64) -> Elsewhere>>,
}

/// Who gave a label's atom its answer, as the trace reports it.
#[derive(Clone, Copy)]
pub enum By {
    Expert(&'static str),
    /// No expert answers it: the newest posting, by this module.
    Posted(&'static str),
    Nobody,
    /// An expert in another process did not answer in time: false.
    TimedOut,
}

/// What a query to another process's expert came to.
pub enum Elsewhere {
    Answered(bool, &'static str),
    TimedOut,
    /// No module anywhere answers the atom.
    NoExpert,
}

/// A recording as `proclaim run --record` writes it, for `proclaim test` and `proclaim replay`:
/// every whiteboard message the interpreter's run would post (numbered in order), and every
/// ringlet as it begins, as JSON lines the host writes out.
#[derive(Default)]
pub struct Record {
    seq: u64,
    pub lines: Vec<String>,
}

/// A posting's content as the whiteboard holds it: a truth value, a whole number, or text.
pub fn board_value(content: &str) -> serde_json::Value {
    match content {
        "true" => serde_json::Value::Bool(true),
        "false" => serde_json::Value::Bool(false),
        _ => match content.parse::<i64>() {
            Ok(whole) => serde_json::json!(whole),
            Err(_) => serde_json::json!(content),
        },
    }
}

impl World {
    pub fn new(
        machines: usize,
        outputs: usize,
        variables: usize,
        externs: usize,
        sink: Option<Box<dyn FnMut(Event)>>,
    ) -> World {
        World {
            now_ms: 0,
            round: 0,
            state: vec![0; machines],
            just_entered: vec![false; machines],
            entered_ms: vec![0; machines],
            input: vec![false; variables],
            seen: vec![vec![false; outputs]; machines],
            asked: vec![vec![false; outputs]; machines],
            initial: vec![0; machines],
            status: vec![RUNNING; machines],
            fresh: vec![false; machines],
            var: Vec::new(),
            ext: vec![None; externs],
            ext_by: vec![""; externs],
            ext_seen: vec![vec![None; externs]; machines],
            ext_seen_by: vec![vec![""; externs]; machines],
            ext_own: vec![vec![None; externs]; machines],
            ext_read: vec![false; machines],
            asked_posted: vec![vec![None; externs]; machines],
            pending: Vec::new(),
            ringing: 0,
            past_snapshot: false,
            globals_changes: 0,
            globals_seen: vec![0; machines],
            commands: vec![Vec::new(); machines],
            commands_waiting: false,
            text: String::new(),
            sink,
            over: false,
            suppressor: None,
            supplied: vec![false; outputs],
            unposted: Vec::new(),
            answer_shown: Vec::new(),
            record: None,
            mirror: None,
            elsewhere: None,
        }
    }

    /// Whether the run's whiteboard messages go anywhere (a recording, a whiteboard).
    pub fn telling(&self) -> bool {
        self.record.is_some() || self.mirror.is_some()
    }

    /// A whiteboard message `module` posts: recorded, and posted on the whiteboard. Its value
    /// is made only when it goes somewhere (a ringlet's hot path pays nothing otherwise).
    #[inline]
    pub fn message(&mut self, module: &str, ty: &str, value: impl FnOnce() -> serde_json::Value) {
        if self.telling() {
            self.tell(module, ty, value());
        }
    }

    #[cold]
    fn tell(&mut self, module: &str, ty: &str, value: serde_json::Value) {
        if let Some(mirror) = self.mirror.as_mut() {
            mirror(module, ty, &value);
        }
        self.recorded(module, ty, value);
    }

    /// Records a whiteboard message `module` posted (one heard there, or one of the run's).
    pub fn recorded(&mut self, module: &str, ty: &str, value: serde_json::Value) {
        let at_us = self.now_ms * 1000;
        if let Some(record) = self.record.as_mut() {
            record.seq += 1;
            let line = serde_json::json!({
                "seq": record.seq,
                "at_us": at_us,
                "module": module,
                "type": ty,
                "value": value,
            });
            record.lines.push(line.to_string());
        }
    }

    /// Records that machine `m` (its place in the schedule) begins a ringlet: after every
    /// message numbered so far, as the runner's schedule records it.
    pub fn ringlet_begins(&mut self, m: usize) {
        if self.record.is_none() {
            return;
        }
        self.record_ringlet(m);
    }

    #[cold]
    fn record_ringlet(&mut self, m: usize) {
        let (round, at) = (self.round, Duration::from_millis(self.now_ms));
        if let Some(record) = self.record.as_mut() {
            let ringlet = proclaim_runner::Ringlet {
                round,
                machine: m,
                seq: record.seq,
                at,
                snapshot: None,
            };
            record.lines.push(serde_json::json!({ "ringlet": ringlet }).to_string());
        }
    }

    /// Reports the event `event` makes of the round and the time now, unless the run is over.
    pub fn report(&mut self, event: impl FnOnce(u64, Duration) -> Event) {
        if self.over {
            return;
        }
        let (round, at) = (self.round, Duration::from_millis(self.now_ms));
        if let Some(sink) = self.sink.as_mut() {
            sink(event(round, at));
        }
    }

    pub fn posted(&mut self, machine: &str, ty: &str, content: &str, priority: u32) {
        self.report(|round, at| Event::Posted {
            machine: machine.to_string(),
            ty: ty.to_string(),
            content: content.to_string(),
            priority,
            round,
            at,
        });
    }

    /// A posting no reader saw: `by`'s, of the higher `by_priority`, holds the type until `until`.
    #[allow(clippy::too_many_arguments)]
    pub fn suppressed(
        &mut self,
        machine: &str,
        ty: &str,
        content: &str,
        priority: u32,
        by: &str,
        by_priority: u32,
        until: Duration,
    ) {
        self.report(|round, at| Event::Suppressed {
            machine: machine.to_string(),
            ty: ty.to_string(),
            content: content.to_string(),
            priority,
            by: by.to_string(),
            by_priority,
            until,
            round,
            at,
        });
    }

    /// A hold ran out and this lower posting, made at `posted`, is on the board now.
    pub fn took_over(&mut self, machine: &str, ty: &str, content: &str, priority: u32, posted: Duration) {
        self.report(|round, at| Event::TookOver {
            machine: machine.to_string(),
            ty: ty.to_string(),
            content: content.to_string(),
            priority,
            posted,
            round,
            at,
        });
    }

    pub fn entered(&mut self, machine: &str, state: &str, id: i64) {
        self.report(|round, at| Event::Entered {
            machine: machine.to_string(),
            state: state.to_string(),
            id,
            round,
            at,
        });
    }

    pub fn finished(&mut self, machine: &str, state: &str) {
        self.report(|round, at| Event::Finished {
            machine: machine.to_string(),
            state: state.to_string(),
            round,
            at,
        });
    }

    /// An expert was asked `atom` and answered `value`, which it posts: the impersonator's answer
    /// to an atom its script has not posted yet is the first the trace shows of it.
    pub fn queried(&mut self, atom: &str, value: bool) {
        if let Some(i) = self.unposted.iter().position(|a| a == atom) {
            self.unposted.remove(i);
            self.posted("impersonator", atom, if value { "true" } else { "false" }, 0);
            self.answer_shown.push((atom.to_string(), value));
        }
    }

    /// A label's atom read `value`, answered as `by` says.
    pub fn answered(&mut self, machine: &str, atom: &str, value: bool, by: By) {
        self.report(|round, at| Event::Answered {
            machine: machine.to_string(),
            atom: atom.to_string(),
            value,
            by: match by {
                By::Expert(e) => Answerer::Expert(e.to_string()),
                By::Posted(p) => Answerer::Posted(p.to_string()),
                By::Nobody => Answerer::NoExpert,
                By::TimedOut => Answerer::TimedOut,
            },
            round,
            at,
        });
    }

    pub fn fired(&mut self, machine: &str, from: i64, to: i64, label: &str) {
        self.report(|round, at| Event::Fired {
            machine: machine.to_string(),
            from,
            to,
            label: label.to_string(),
            round,
            at,
        });
    }

    pub fn assigned(&mut self, machine: &str, variable: &str, value: impl FnOnce() -> String) {
        self.report(|round, at| Event::Assigned {
            machine: machine.to_string(),
            variable: variable.to_string(),
            value: value(),
            round,
            at,
        });
    }

    pub fn printed(&mut self, machine: &str, text: &str) {
        self.report(|round, at| Event::Printed {
            machine: machine.to_string(),
            text: text.to_string(),
            round,
            at,
        });
    }

    pub fn control(&mut self, machine: &str, command: &str) {
        self.report(|round, at| Event::Control {
            machine: machine.to_string(),
            command: command.to_string(),
            round,
            at,
        });
    }

    pub fn warned(&mut self, machine: &str, message: &str) {
        self.report(|round, at| Event::Warned {
            machine: machine.to_string(),
            message: message.to_string(),
            round,
            at,
        });
    }

    /// The snapshot (`docs/spec/behaviour.md` 3.1), after OnEntry: from here to the ringlet's
    /// end machine `m` reads the whiteboard variables as they are now, and its own postings.
    pub fn extern_snapshot(&mut self, m: usize) {
        self.past_snapshot = true;
        self.ext_read[m] = false;
        self.ext_seen[m].clone_from(&self.ext);
        self.ext_seen_by[m].clone_from(&self.ext_by);
        self.ext_own[m].fill(None);
        self.asked_posted[m].fill(None);
    }

    /// Whether the board's value of `e` is news to machine `m`: not what it posted itself in
    /// its last ringlet, or (when that ringlet read the snapshot) not what the snapshot held.
    pub fn extern_news(&self, m: usize, e: usize) -> bool {
        let Some(now) = self.ext[e] else {
            return false;
        };
        if let Some(answer) = self.asked_posted[m][e] {
            return truthy(now) != answer;
        }
        if let Some(own) = self.ext_own[m][e] {
            return own != now;
        }
        self.ext_read[m] && self.ext_seen[m][e] != Some(now)
    }

    pub fn text_clear(&mut self) {
        self.text.clear();
    }

    pub fn text_literal(&mut self, s: &str) {
        self.text.push_str(s);
    }

    pub fn text_value(&mut self, v: Value) {
        let shown = value_text(v);
        self.text.push_str(&shown);
    }

    pub fn text_whole(&mut self, v: Value) {
        self.text_value(v_int(v.i));
    }
}

/// A time test still to come due shortens the wait; one already past (its label false for
/// another reason) does not, as the runner's `next_time_test` has it.
pub fn min_due(due: u64, at: u64, now: u64) -> u64 {
    if at <= now {
        return due;
    }
    if at - now < due {
        at - now
    } else {
        due
    }
}
"#;

/// `src/behaviour.rs` around its machines' code.
pub(crate) const BODY: &str = r#"//! The behaviour `@name@` compiled by proclaim (generated: do not edit): a ringlet a machine,
//! the round schedule, and what its host asks of it.

use crate::runtime::*;
use proclaim_board::QUERY_TYPE;
use proclaim_runner::Event;

pub const MACHINES: usize = @machines@;
pub const OUTPUTS: usize = @outputs@;
pub const VARIABLES: usize = @variables@;
/// The period of rounds without news, in milliseconds.
pub const PERIOD_MS: u64 = @period_ms@;
const COMMANDS: usize = @commands@;
const LOOP_LIMIT: u32 = @loop_limit@;
/// How long a query to an expert in another process waits, in milliseconds.
const ANSWER_TIMEOUT_MS: u64 = @answer_timeout_ms@;
const OUTPUT_NAME: [&str; OUTPUTS] = [@output_names@];
/// The outputs a theory answers come first; the impersonator's atoms follow.
const THEORY_OUTPUTS: usize = @theory_outputs@;
/// The behaviour's own script (`[impersonator]`): its file and text, played without `--script`.
pub const SCRIPT: Option<(&str, &str)> = @script@;
/// Each sensor wrapper and the atoms it answers: the host's script must set one of them.
const SENSORS: [(&str, &[&str]); @sensors_n@] = [@sensors@];
const OUTPUT_EXPERT: [&str; OUTPUTS] = [@experts@];
const MACHINE_NAME: [&str; MACHINES] = [@machine_names@];
/// The machines' names, in schedule order.
pub const MACHINE_NAMES: &[&str] = &MACHINE_NAME;
pub const EXTERNS: usize = @externs@;
const EXTERN_NAME: [&str; EXTERNS] = [@extern_names@];
/// Whether each whiteboard value is bound with `extern` (read as a whole 0 while unposted).
const EXTERN_BOUND: [bool; EXTERNS] = [@extern_bound@];
/// The whiteboard value of each output's atom: an expert's answer is posted there.
const OUTPUT_BOARD: [Option<usize>; OUTPUTS] = [@output_board@];
/// The whiteboard value each machine's running state is posted to (`NameIsRunning`).
const STATUS_BOARD: [Option<usize>; MACHINES] = [@status_board@];
/// Each machine's subsumption layer, which its postings carry.
const PRIORITY: [u32; MACHINES] = [@priorities@];
/// The types under subsumption and how long a higher layer's posting holds each, in ms.
const SUPPRESSED: [(&str, u64); @suppressed_n@] = [@suppressed@];

/// A theory input from a posting's content, as the reasoner expert reads it: true, false, a
/// whole number (true unless 0), or unknown for anything else.
fn set_input(w: &mut World, v: usize, content: &str) {
    let whole = content.strip_prefix('-').unwrap_or(content);
    let (known, value) = match content {
        "true" => (true, true),
        "false" => (true, false),
        _ if !whole.is_empty() && whole.bytes().all(|b| b.is_ascii_digit()) => {
            (true, whole.bytes().any(|b| b != b'0'))
        }
        _ => (false, false),
    };
    w.input[v] = known;
    w.input[v + 1] = value;
}

/// Whether the posting's type is a theory input (then applied).
fn apply_input(w: &mut World, ty: &str, content: &str) -> bool {
    match ty {
@input_cases@        _ => false,
    }
}

pub fn answer(w: &World, k: usize) -> bool {
    match k {
@answer_cases@        _ => false,
    }
}

fn ask(w: &mut World, m: usize, k: usize) -> bool {
    let value = answer(w, k);
    w.asked[m][k] = true;
    // No expert answers it: the runner reads its newest posting instead, from the snapshot.
    if !w.supplied[k] {
        w.ext_read[m] = true;
    } else if let Some(e) = OUTPUT_BOARD[k] {
        // An expert answers by posting its answer, which the machines read as a value.
        w.ext[e] = Some(v_bool(value));
        w.ext_by[e] = OUTPUT_EXPERT[k];
    }
    let expert = w.supplied[k].then_some(OUTPUT_EXPERT[k]);
    if let Some(expert) = expert {
        w.message(MACHINE_NAME[m], QUERY_TYPE, || serde_json::json!(OUTPUT_NAME[k]));
        w.message(expert, OUTPUT_NAME[k], || serde_json::Value::Bool(value));
        // The expert posts its answer: a theory reading the atom as an input sees it.
        apply_input(w, OUTPUT_NAME[k], if value { "true" } else { "false" });
        w.queried(OUTPUT_NAME[k], value);
    }
    let by = expert.map_or(By::Nobody, By::Expert);
    w.pending.push((OUTPUT_NAME[k], value, by));
    value
}

/// Proves a transition's label; the answers it read are reported once it is proved, as the
/// runner reports them.
fn proved(w: &mut World, m: usize, label: impl FnOnce(&mut World) -> bool) -> bool {
    let holds = label(w);
    // By index, so that the list keeps its room for the next label.
    for i in 0..w.pending.len() {
        let (atom, value, by) = w.pending[i];
        w.answered(MACHINE_NAME[m], atom, value, by);
    }
    w.pending.clear();
    holds
}

/// Whether machine `m`'s last ringlet asked an expert the atom whiteboard value `e` is: then a
/// posting of it is news only when the answer changed, which the answers' own test sees.
fn asked_of_expert(w: &World, m: usize, e: usize) -> bool {
    (0..OUTPUTS).any(|k| OUTPUT_BOARD[k] == Some(e) && w.asked[m][k])
}

/// What a whiteboard value never posted reads as.
fn unposted(e: usize) -> Value {
    if EXTERN_BOUND[e] {
        v_int(0)
    } else {
        v_none()
    }
}

/// The output whose atom whiteboard value `e` is, when an expert answered the ringlet's
/// question of it: the ringlet reads that answer, as the runner holds an expert's answer.
fn answered_here(w: &World, e: usize) -> Option<usize> {
    (0..OUTPUTS).find(|k| OUTPUT_BOARD[*k] == Some(e) && w.supplied[*k] && w.asked[w.ringing][*k])
}

/// A whiteboard value as the ringlet reads it: live before the snapshot (in OnEntry), then
/// what the ringlet posted itself, else an expert's answer it asked, else the snapshot; and
/// who posted it (none: nobody).
fn read_board(w: &mut World, e: usize) -> (Value, Option<&'static str>) {
    let m = w.ringing;
    let by = |v: Option<Value>, by: &'static str| match v {
        Some(v) => (v, Some(by)),
        None => (unposted(e), None),
    };
    if !w.past_snapshot {
        return by(w.ext[e], w.ext_by[e]);
    }
    if let Some(own) = w.ext_own[m][e] {
        return (own, Some(MACHINE_NAME[m]));
    }
    if let Some(k) = answered_here(w, e) {
        return (v_bool(answer(w, k)), Some(OUTPUT_EXPERT[k]));
    }
    w.ext_read[m] = true;
    by(w.ext_seen[m][e], w.ext_seen_by[m][e])
}

fn read_extern(w: &mut World, e: usize) -> Value {
    read_board(w, e).0
}

/// A label atom nobody answers: the runner reads the atom's newest posting as the ringlet sees
/// it and reports who posted it (a never posted atom is false, answered by nobody).
fn ask_posted(w: &mut World, m: usize, e: usize, atom: &'static str) -> bool {
    // On a shared whiteboard an expert in another process may answer it, as it answers the
    // runner's query.
    let asked = w.elsewhere.as_mut().map(|ask| ask(MACHINE_NAME[m], atom, ANSWER_TIMEOUT_MS));
    let answered = match asked {
        Some(Elsewhere::Answered(value, expert)) => Some((value, By::Expert(expert))),
        Some(Elsewhere::TimedOut) => Some((false, By::TimedOut)),
        Some(Elsewhere::NoExpert) | None => None,
    };
    if let Some((value, by)) = answered {
        if let By::Expert(expert) = by {
            // The expert posted its answer: the board's value is that answer now.
            w.ext[e] = Some(v_bool(value));
            w.ext_by[e] = expert;
        }
        w.asked_posted[m][e] = Some(value);
        w.pending.push((atom, value, by));
        return value;
    }
    let (v, by) = read_board(w, e);
    let value = !v.none && truthy(v);
    w.asked_posted[m][e] = Some(value);
    let by = match by.filter(|_| !v.none) {
        Some(poster) => By::Posted(poster),
        None => By::Nobody,
    };
    w.pending.push((atom, value, by));
    value
}

/// A machine's posting: shown (then a theory input takes it), or held back by a higher
/// layer's posting of a type under subsumption (then no reader sees it).
fn post(w: &mut World, m: usize, ty: &str, content: &str) {
    if let Some(suppressor) = w.suppressor.as_mut() {
        let now = std::time::Duration::from_millis(w.now_ms);
        let value = proclaim_board::Value::Str(content.to_string());
        let verdict = suppressor.offer(MACHINE_NAME[m], ty, &value, PRIORITY[m], now);
        if let proclaim_board::Visibility::Suppressed { by, priority, until } = verdict {
            w.suppressed(MACHINE_NAME[m], ty, content, PRIORITY[m], &by, priority, until);
            return;
        }
    }
    w.posted(MACHINE_NAME[m], ty, content, PRIORITY[m]);
    w.message(MACHINE_NAME[m], ty, || board_value(content));
    apply_input(w, ty, content);
}

/// Machine `m` posts `v` to whiteboard variable `e` (an assignment to it, or a posting).
fn post_extern(w: &mut World, m: usize, e: usize, v: Value) {
    let v = v_some(v);
    let shown = value_text(v);
    w.posted(MACHINE_NAME[m], EXTERN_NAME[e], &shown, PRIORITY[m]);
    w.message(MACHINE_NAME[m], EXTERN_NAME[e], || board_value(&shown));
    apply_input(w, EXTERN_NAME[e], &shown);
    w.ext[e] = Some(v);
    w.ext_by[e] = MACHINE_NAME[m];
    if w.past_snapshot {
        w.ext_own[m][e] = Some(v);
    }
}

/// A posting from outside to a whiteboard variable's type (a script's truth word): whether it
/// was one.
fn apply_extern(w: &mut World, ty: &str, content: &str) -> bool {
    match EXTERN_NAME.iter().position(|name| *name == ty) {
        Some(e) => {
            w.ext[e] = Some(v_bool(content == "true"));
            w.ext_by[e] = "impersonator";
            true
        }
        None => false,
    }
}

/// At a round's start: every held type whose hold ran out with a lower posting behind it gets
/// that posting, as the runner's schedule has it.
fn take_over(w: &mut World) {
    let Some(suppressor) = w.suppressor.as_mut() else {
        return;
    };
    let released = suppressor.release(std::time::Duration::from_millis(w.now_ms));
    for posting in released {
        let content = match &posting.value {
            proclaim_board::Value::Str(text) => text.clone(),
            other => other.to_string(),
        };
        w.took_over(&posting.module, &posting.ty, &content, posting.priority, posting.at);
        apply_input(w, &posting.ty, &content);
    }
}

/// Posts the text built.
fn post_text(w: &mut World, m: usize, ty: &str) {
    let text = std::mem::take(&mut w.text);
    post(w, m, ty, &text);
    w.text = text;
}

fn print_text(w: &mut World, m: usize) {
    let text = std::mem::take(&mut w.text);
    w.printed(MACHINE_NAME[m], &text);
    w.text = text;
}

fn snapshot(w: &mut World, m: usize) {
    for k in 0..OUTPUTS {
        let value = answer(w, k);
        w.seen[m][k] = value;
        w.asked[m][k] = false;
    }
}

fn elapsed_at_least(w: &World, m: usize, ms: u64) -> bool {
    w.now_ms.wrapping_sub(w.entered_ms[m]) >= ms
}

/// An assignment as the runner makes it: converted to the variable's type, reported when the
/// value changed; a global's change is news to the labels that read globals.
fn assign(w: &mut World, m: usize, slot: usize, conversion: u8, global: bool, name: &str, v: Value) {
    let v = convert(conversion, v_some(v));
    if w.var[slot] == v {
        return;
    }
    w.var[slot] = v;
    if global {
        w.globals_changes += 1;
    }
    w.assigned(MACHINE_NAME[m], name, || value_text(v));
}

/// The machine's run is over: reported, and the trace ends once every machine's is.
fn report_finished(w: &mut World, m: usize, state: &str) {
    if w.over {
        return;
    }
    w.finished(MACHINE_NAME[m], state);
    w.over = finished(w);
}

/// Whether a machine's run is over for now: in a state with no way out, its OnEntry run.
fn done(w: &World, m: usize) -> bool {
    !w.just_entered[m] && final_state(w, m)
}

/// A control command posted to machine `m`, obeyed when the ringlet ends.
fn command(w: &mut World, m: usize, code: u8, word: &'static str) {
    w.message(MACHINE_NAME[w.ringing], MACHINE_NAME[m], || serde_json::json!(word));
    if w.commands[m].len() < COMMANDS {
        w.commands[m].push((code, word));
        w.commands_waiting = true;
    }
}

/// The runner posts a machine's running state to `NameIsRunning` when it starts and whenever
/// that changes.
fn post_status(w: &mut World, m: usize) {
    if w.telling() {
        let ty = format!("{}IsRunning", MACHINE_NAME[m]);
        let running = w.status[m] == RUNNING;
        w.message(MACHINE_NAME[m], &ty, || serde_json::Value::Bool(running));
    }
    if let Some(e) = STATUS_BOARD[m] {
        w.ext[e] = Some(v_bool(w.status[m] == RUNNING));
        w.ext_by[e] = MACHINE_NAME[m];
    }
}

/// gufsm's SuspensibleMachine, as the runner's `control`: whether it started the machine.
fn control(w: &mut World, m: usize, code: u8, word: &str) -> bool {
    let was_running = w.status[m] == RUNNING;
    w.control(MACHINE_NAME[m], word);
    let started = obey_command(w, m, code);
    if was_running != (w.status[m] == RUNNING) {
        post_status(w, m);
    }
    started
}

fn obey_command(w: &mut World, m: usize, code: u8) -> bool {
    match code {
        COMMAND_ON | COMMAND_RESUME => {
            if w.status[m] == DORMANT {
                w.state[m] = w.initial[m];
            } else if w.status[m] == RUNNING {
                return false;
            }
            w.status[m] = RUNNING;
            w.just_entered[m] = true;
            true
        }
        COMMAND_RESTART => {
            w.status[m] = RUNNING;
            w.state[m] = w.initial[m];
            w.just_entered[m] = true;
            true
        }
        COMMAND_SUSPEND => {
            if w.status[m] == RUNNING {
                w.status[m] = SUSPENDED;
            }
            false
        }
        COMMAND_OFF => {
            w.status[m] = DORMANT;
            false
        }
        _ => false,
    }
}

/// The commands waiting for each machine, in schedule order; a machine started rings from the
/// next round.
fn obey(w: &mut World) {
    if !w.commands_waiting {
        return;
    }
    w.commands_waiting = false;
    for m in 0..MACHINES {
        let commands = std::mem::take(&mut w.commands[m]);
        for (code, word) in commands {
            if control(w, m, code, word) {
                w.fresh[m] = true;
            }
        }
    }
}

@code@
fn final_state(w: &World, m: usize) -> bool {
    match m {
@finals@        _ => false,
    }
}

/// The behaviour at its start, reporting its events to `sink` (none made without one).
pub fn init(sink: Option<Box<dyn FnMut(Event)>>) -> World {
    let mut w = World::new(MACHINES, OUTPUTS, VARIABLES, EXTERNS, sink);
    w.supplied[..THEORY_OUTPUTS].fill(true);
    if !SUPPRESSED.is_empty() {
        let holds = SUPPRESSED
            .iter()
            .map(|(ty, ms)| (*ty, std::time::Duration::from_millis(*ms)));
        w.suppressor = Some(proclaim_board::Suppressor::new(holds));
    }
    w.var = vec![@var_inits@];
@inits@    for m in 0..MACHINES {
        post_status(&mut w, m);
    }
    w
}

/// Tells the recording and the whiteboard, when there are any, what the run's start posted:
/// each machine's running state.
pub fn announce(w: &mut World) {
    if w.telling() {
        for m in 0..MACHINES {
            post_status(w, m);
        }
    }
}

/// The run's own modules: its machines, its experts and the impersonator.
pub fn modules() -> Vec<&'static str> {
    let mut modules: Vec<&'static str> = MACHINE_NAME.iter().chain(OUTPUT_EXPERT.iter()).copied().collect();
    modules.push("impersonator");
    modules
}

/// One round: `started` (what came from outside by now is posted), then a ringlet of every
/// machine in manifest order; whether one fired (the next round follows at once).
pub fn round(w: &mut World, started: impl FnOnce(&mut World)) -> bool {
    let mut fired = false;
    w.round += 1;
    started(w);
    take_over(w);
    for m in 0..MACHINES {
        w.fresh[m] = false;
    }
@rings@    fired || w.fresh.iter().any(|f| *f)
}

/// A posting from outside the machines (an impersonator, a sensor); whether it is news to a
/// machine's labels.
pub fn outside(w: &mut World, ty: &str, content: &str) -> bool {
    let applied = apply_input(w, ty, content);
    (apply_extern(w, ty, content) || applied) && news(w)
}

/// Whether an answer a machine's current labels read differs from what its last ringlet saw.
pub fn news(w: &World) -> bool {
@reads@    false
}

/// Whether `atom` is an answer of the behaviour's theories (the script may not set it).
pub fn answers(atom: &str) -> bool {
    OUTPUT_NAME[..THEORY_OUTPUTS].contains(&atom)
}

/// The host answers `atom` from outside (its script sets it): whether it is an atom from
/// outside the behaviour's labels ask.
pub fn supply(w: &mut World, atom: &str) -> bool {
    match OUTPUT_NAME[THEORY_OUTPUTS..].iter().position(|o| *o == atom) {
        Some(k) => {
            w.supplied[THEORY_OUTPUTS + k] = true;
            true
        }
        None => false,
    }
}

/// A sensor none of whose atoms are in `scripted`, and its atoms: the interpreter would run
/// that sensor, which a compiled behaviour does not have.
pub fn unscripted_sensor(scripted: &[&str]) -> Option<(&'static str, &'static [&'static str])> {
    SENSORS
        .iter()
        .find(|(_, atoms)| !atoms.iter().any(|a| scripted.contains(a)))
        .copied()
}

/// Whether `name` is a machine's (a posting to it is a control command).
pub fn is_machine(name: &str) -> bool {
    MACHINE_NAME.contains(&name)
}

/// Milliseconds from now until the next round is due without news (a timeout or the period);
/// none while no machine runs (then only news starts a round, as the runner waits).
pub fn next_due_ms(w: &World) -> Option<u64> {
    let mut due = if w.status.contains(&RUNNING) {
        PERIOD_MS
    } else {
        u64::MAX
    };
@dues@    // A hold running out with a lower posting behind it changes what readers see.
    if let Some(release) = w.suppressor.as_ref().and_then(|s| s.next_release()) {
        due = due.min((release.as_millis() as u64).saturating_sub(w.now_ms));
    }
    (due != u64::MAX).then_some(due)
}

/// Whether every machine that starts with the behaviour is in a final state, its OnEntry run.
pub fn finished(w: &World) -> bool {
@tops@    true
}
"#;

/// One machine's functions (`@m@` is its number).
pub(crate) const RING: &str = r#"fn ring_@m@(w: &mut World) -> bool {
    w.ringing = @m@;
    w.ringlet_begins(@m@);
    w.past_snapshot = false;
    if w.just_entered[@m@] {
        w.just_entered[@m@] = false;
        w.entered_ms[@m@] = w.now_ms;
        match w.state[@m@] {
@entries@            _ => {}
        }
    }
    snapshot(w, @m@);
    w.extern_snapshot(@m@);
    w.globals_seen[@m@] = w.globals_changes;
    match w.state[@m@] {
@cases@        _ => false,
    }
}

fn reads_@m@(w: &World, k: usize) -> bool {
    match w.state[@m@] {
@read_cases@        _ => false,
    }
}

/// Whether the current state's labels read whiteboard variable `e`.
fn reads_extern_@m@(w: &World, e: usize) -> bool {
    match w.state[@m@] {
@extern_cases@        _ => false,
    }
}

/// Whether the current state's labels read a global.
fn reads_globals_@m@(w: &World) -> bool {
    @global_test@
}

fn final_@m@(w: &World) -> bool {
    @final_test@
}

fn due_@m@(w: &World, due: u64) -> u64 {
    match w.state[@m@] {
@due_cases@        _ => due,
    }
}

"#;
