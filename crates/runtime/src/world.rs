//! The world a behaviour compiled to Rust runs in: values as the runner holds them
//! (`proclaim_lower::arith`'s operators on them), every machine's state and the board's values
//! it reads, and the reports of the trace's events and of a recording. The generated
//! `behaviour.rs` is written against it.

use crate::event::{Answerer, Event};
use crate::suppress::Suppressor;
use std::time::Duration;

/// A value as the runner holds it: a whole number, or a truth value (0 or 1); or `none`, a
/// whiteboard value never posted, which arithmetic keeps and a comparison finds false.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Scalar {
    pub i: i64,
    pub is_bool: bool,
    pub none: bool,
}

pub fn v_int(i: i64) -> Scalar {
    Scalar {
        i,
        is_bool: false,
        none: false,
    }
}

pub fn v_bool(b: bool) -> Scalar {
    Scalar {
        i: i64::from(b),
        is_bool: true,
        none: false,
    }
}

pub fn v_none() -> Scalar {
    Scalar {
        i: 0,
        is_bool: false,
        none: true,
    }
}

/// What an activity makes of a value: no value is a whole 0, as the runner's activities have it.
pub fn v_some(v: Scalar) -> Scalar {
    if v.none {
        v_int(0)
    } else {
        v
    }
}

/// A value from outside as a compiled behaviour holds it: a truth value or a whole number
/// (`-5`), as the runner reads a posting's; none for text or a fraction, which it cannot hold.
pub fn outside_value(content: &str) -> Option<Scalar> {
    match content {
        "true" => Some(v_bool(true)),
        "false" => Some(v_bool(false)),
        _ => content.parse::<i64>().ok().map(v_int),
    }
}

pub fn truthy(v: Scalar) -> bool {
    v.i != 0
}

pub fn v_add(a: Scalar, b: Scalar) -> Scalar {
    if a.none || b.none {
        return v_none();
    }
    v_int(a.i.wrapping_add(b.i))
}

pub fn v_sub(a: Scalar, b: Scalar) -> Scalar {
    if a.none || b.none {
        return v_none();
    }
    v_int(a.i.wrapping_sub(b.i))
}

pub fn v_mul(a: Scalar, b: Scalar) -> Scalar {
    if a.none || b.none {
        return v_none();
    }
    v_int(a.i.wrapping_mul(b.i))
}

/// Dividing by zero gives the largest whole number, as gufsm's INT_MAX.
pub fn v_div(a: Scalar, b: Scalar) -> Scalar {
    if a.none || b.none {
        return v_none();
    }
    match b.i {
        0 => v_int(i64::MAX),
        -1 => v_int(a.i.wrapping_neg()),
        _ => v_int(a.i / b.i),
    }
}

pub fn v_rem(a: Scalar, b: Scalar) -> Scalar {
    if a.none || b.none {
        return v_none();
    }
    match b.i {
        0 => v_int(i64::MAX),
        -1 => v_int(0),
        _ => v_int(a.i % b.i),
    }
}

pub fn v_neg(a: Scalar) -> Scalar {
    if a.none {
        return a;
    }
    v_int(a.i.wrapping_neg())
}

pub fn v_abs(a: Scalar) -> Scalar {
    if a.i < 0 {
        v_neg(a)
    } else {
        a
    }
}

pub fn v_eq(a: Scalar, b: Scalar) -> Scalar {
    v_bool(!a.none && !b.none && a.i == b.i)
}

pub fn v_ne(a: Scalar, b: Scalar) -> Scalar {
    v_bool(!a.none && !b.none && a.i != b.i)
}

pub fn v_lt(a: Scalar, b: Scalar) -> Scalar {
    v_bool(!a.none && !b.none && a.i < b.i)
}

pub fn v_le(a: Scalar, b: Scalar) -> Scalar {
    v_bool(!a.none && !b.none && a.i <= b.i)
}

pub fn v_gt(a: Scalar, b: Scalar) -> Scalar {
    v_bool(!a.none && !b.none && a.i > b.i)
}

pub fn v_ge(a: Scalar, b: Scalar) -> Scalar {
    v_bool(!a.none && !b.none && a.i >= b.i)
}

/// The first when it is not greater (min) or not less (max), as the runner picks.
pub fn v_min(a: Scalar, b: Scalar) -> Scalar {
    if a.none || b.none {
        return v_none();
    }
    if a.i <= b.i {
        a
    } else {
        b
    }
}

pub fn v_max(a: Scalar, b: Scalar) -> Scalar {
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

pub fn convert(conversion: u8, v: Scalar) -> Scalar {
    match conversion {
        CONVERT_WHOLE => v_int(v.i),
        CONVERT_TRUTH => v_bool(truthy(v)),
        _ => v,
    }
}

/// A value's text, as the trace shows it.
pub fn value_text(v: Scalar) -> String {
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
    /// When each composite state ([`crate::Tables::COMPOSITE_MACHINE`]) was entered, and
    /// whether a move into it waits for its machine's next ringlet to arrive (its time starts
    /// then, as its state's does).
    pub composite_ms: Vec<u64>,
    pub composite_entering: Vec<bool>,
    /// The values from outside already said to leave their type's declared range, by type
    /// and value (said once each, as the runner says them).
    pub range_said: std::collections::HashSet<(String, String)>,
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
    pub var: Vec<Scalar>,
    /// Each whiteboard value the machines read: the board's newest value, if any was posted
    /// (one never posted reads as a whole 0 when bound with `extern`, else as none), and who
    /// posted it.
    pub ext: Vec<Option<Scalar>>,
    pub ext_by: Vec<&'static str>,
    /// As each machine's last ringlet saw them: the board at its snapshot, the values it posted
    /// itself since, and whether it read the snapshot at all (a ringlet that read nothing of the
    /// board finds nothing new in a posting).
    pub ext_seen: Vec<Vec<Option<Scalar>>>,
    pub ext_seen_by: Vec<Vec<&'static str>>,
    pub ext_own: Vec<Vec<Option<Scalar>>>,
    pub ext_read: Vec<bool>,
    /// The atoms nobody answers that each machine's last ringlet asked, read from these values,
    /// and what it read: news is then a posting whose truth differs.
    pub asked_posted: Vec<Vec<Option<bool>>>,
    /// Each whiteboard value a label asks that the host's script answers as the impersonator
    /// (no module of the behaviour declares the atom; the host's `supply` marks it): the
    /// script's value of it now, false until the script posts one.
    pub scripted: Vec<Option<bool>>,
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
    /// How many of the machines' events so far were changes ([`Event::is_change`]; not the
    /// impersonator's postings): a round that leaves it as it was changed nothing.
    pub changes: u64,
    /// What holds each type under subsumption, for a behaviour that declares any.
    pub suppressor: Option<Suppressor<String>>,
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
    pub mirror: Option<Mirror>,
    /// Asks an atom of an expert in another process, on a shared whiteboard: the asking
    /// machine, the atom, how long to wait in milliseconds.
    pub elsewhere: Option<AskElsewhere>,
}

/// Where every whiteboard message of a run goes too: module, type, value.
pub type Mirror = Box<dyn FnMut(&str, &str, &serde_json::Value)>;

/// Asks an atom of another process's expert: the asking machine, the atom, the milliseconds
/// to wait.
pub type AskElsewhere = Box<dyn FnMut(&str, &str, u64) -> Elsewhere>;

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
            composite_ms: Vec::new(),
            composite_entering: Vec::new(),
            range_said: std::collections::HashSet::new(),
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
            scripted: vec![None; externs],
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
            changes: 0,
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
            let ringlet = crate::event::Ringlet {
                round,
                machine: m,
                seq: record.seq,
                at,
                snapshot: None,
            };
            record
                .lines
                .push(serde_json::json!({ "ringlet": ringlet }).to_string());
        }
    }

    /// Reports the event `event` makes of the round and the time now, unless the run is over:
    /// a machine's change (an answer read is reported by [`World::answered`]).
    pub fn report(&mut self, event: impl FnOnce(u64, Duration) -> Event) {
        self.report_as(true, event);
    }

    /// [`World::report`], counted in `changes` if `change` (as [`Event::is_change`] says of
    /// it: the event is made only for a sink).
    fn report_as(&mut self, change: bool, event: impl FnOnce(u64, Duration) -> Event) {
        if self.over {
            return;
        }
        self.changes += u64::from(change);
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

    /// A posting by a module that is not a machine (the impersonator), shown in the trace; no
    /// change of the machines'.
    pub fn posted_outside(&mut self, module: &str, ty: &str, content: &str) {
        self.report_as(false, |round, at| Event::Posted {
            machine: module.to_string(),
            ty: ty.to_string(),
            content: content.to_string(),
            priority: 0,
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
    pub fn took_over(
        &mut self,
        machine: &str,
        ty: &str,
        content: &str,
        priority: u32,
        posted: Duration,
    ) {
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
            self.posted_outside("impersonator", atom, if value { "true" } else { "false" });
            self.answer_shown.push((atom.to_string(), value));
        }
    }

    /// A label's atom read `value`, answered as `by` says.
    pub fn answered(&mut self, machine: &str, atom: &str, value: bool, by: By) {
        self.report_as(false, |round, at| Event::Answered {
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

    pub fn text_value(&mut self, v: Scalar) {
        let shown = value_text(v);
        self.text.push_str(&shown);
    }

    pub fn text_whole(&mut self, v: Scalar) {
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
