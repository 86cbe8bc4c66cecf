//! A recorded run as a regression test (`proclaim test`): the recording of `run --record` holds
//! every whiteboard message, every ringlet (where and when it began) and the machines' events.
//! Replayed, the behaviour's machines and theories run again on the virtual clock under the
//! round schedule, and everything that came from outside them (sensor wrappers, the
//! impersonator, a person, the network, the monitor) is posted again before the ringlet it came before the first time; what
//! outside experts answered is answered again, query by query. The machines' states, postings,
//! answers and variables are then compared with the recording, round by round.

use crate::load::Behaviour;
use crate::runners::{machine_runners, Driving};
use proclaim_board::{Message, ModuleDecl, Pattern, Value, Whiteboard, QUERY_TYPE};
use proclaim_experts::ReasonerExpert;
use proclaim_runner::{Event, Feed, Ringlet, Rounds};
use rustc_hash::{FxHashMap, FxHashSet};
use serde::{Deserialize, Serialize};
use std::collections::VecDeque;
use std::fmt;
use std::time::Duration;
use tokio::sync::mpsc;

/// Where in a run a message came: the round, the machine's place in the schedule, and 0 before
/// its ringlet or k + 1 before the ringlet's query k.
type Place = (u64, usize, usize);
/// The outside messages to post again, each at the place of the first ringlet that saw it.
pub(crate) type Outside = Vec<(Place, Recorded)>;
/// What outside experts answered, atom by atom, in the order they answered.
pub(crate) type Answers = FxHashMap<String, VecDeque<Value>>;

/// A message as the recording keeps it.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Recorded {
    pub seq: u64,
    pub module: String,
    pub ty: String,
    pub value: Value,
}

/// Where a branch came from: the recording and the round it left it at.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct BranchOf {
    pub parent: String,
    pub round: u64,
}

impl BranchOf {
    /// The line a branch's recording starts with.
    pub fn header(&self) -> String {
        serde_json::json!({ "branch": self }).to_string()
    }
}

/// A recording read back.
#[derive(Clone, Debug, Default)]
pub struct Recording {
    pub(crate) messages: Vec<Recorded>,
    pub(crate) ringlets: Vec<Ringlet>,
    pub(crate) events: Vec<Event>,
    /// The recording and round it branched from, when it is a branch.
    pub branch: Option<BranchOf>,
}

impl Recording {
    /// The machines' events, as the run's trace has them.
    pub fn events(&self) -> &[Event] {
        &self.events
    }
}

/// Why a recording cannot be read.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum RecordingError {
    /// A line that is neither a message, a ringlet nor an event.
    BadLine { line: usize, why: String },
    /// The recording has no ringlets: it was made under `schedule = "concurrent"`, or by a
    /// version that did not record them.
    NoRinglets,
}

impl fmt::Display for RecordingError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RecordingError::BadLine { line, why } => write!(f, "line {line}: {why}"),
            RecordingError::NoRinglets => write!(
                f,
                "the recording has no ringlets (record a run in rounds with `proclaim run --record`)"
            ),
        }
    }
}

impl std::error::Error for RecordingError {}

/// One line of a recording as `run --record` writes it.
pub fn ringlet_line(ringlet: &Ringlet) -> String {
    serde_json::json!({ "ringlet": ringlet }).to_string()
}

/// A whiteboard message as a recording's line: `seq`, `at_us`, `module`, `type`, `value`, and a
/// subsumption layer's `priority` when it is not 0 (so older recordings read as they did).
pub fn message_line(m: &Message) -> String {
    let mut line = serde_json::json!({
        "seq": m.seq,
        "at_us": m.time.as_micros() as u64,
        "module": &*m.module,
        "type": &*m.ty,
        "value": m.value.to_json(),
    });
    if m.priority != 0 {
        line["priority"] = serde_json::json!(m.priority);
    }
    line.to_string()
}

/// Reads a recording: message lines (`seq`, `module`, `type`, `value`), ringlet lines
/// (`{"ringlet": …}`) and event lines (`{"event": …}`).
pub fn read_recording(text: &str) -> Result<Recording, RecordingError> {
    let mut recording = Recording::default();
    for (i, line) in text.lines().enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        let bad = |why: String| RecordingError::BadLine { line: i + 1, why };
        let json: serde_json::Value =
            serde_json::from_str(line).map_err(|e| bad(format!("not JSON: {e}")))?;
        if let Some(branch) = json.get("branch") {
            let branch = serde_json::from_value(branch.clone())
                .map_err(|e| bad(format!("not a branch's parent and round: {e}")))?;
            recording.branch = Some(branch);
        } else if let Some(ringlet) = json.get("ringlet") {
            let ringlet = serde_json::from_value(ringlet.clone())
                .map_err(|e| bad(format!("not a ringlet: {e}")))?;
            recording.ringlets.push(ringlet);
        } else if json.get("event").is_some() {
            let event =
                serde_json::from_value(json).map_err(|e| bad(format!("not an event: {e}")))?;
            recording.events.push(event);
        } else {
            let field = |name: &str| json.get(name).ok_or_else(|| bad(format!("no `{name}`")));
            let text = |name: &str| {
                field(name).and_then(|v| {
                    v.as_str()
                        .map(str::to_string)
                        .ok_or_else(|| bad(format!("`{name}` is not text")))
                })
            };
            recording.messages.push(Recorded {
                seq: field("seq")?
                    .as_u64()
                    .ok_or_else(|| bad("`seq` is not a number".into()))?,
                module: text("module")?,
                ty: text("type")?,
                value: Value::from_json(field("value")?),
            });
        }
    }
    if recording.ringlets.is_empty() {
        return Err(RecordingError::NoRinglets);
    }
    recording.messages.sort_by_key(|m| m.seq);
    Ok(recording)
}

/// Where a replay first differs from its recording.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Difference {
    pub round: u64,
    pub machine: String,
    pub expected: String,
    pub found: String,
}

impl fmt::Display for Difference {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "round {}, {}: expected {}, found {}",
            self.round, self.machine, self.expected, self.found
        )
    }
}

/// What a replay found.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ReplayOutcome {
    /// Every state, posting, answer and variable as recorded.
    Same {
        rounds: u64,
        events: usize,
    },
    Differs(Difference),
}

/// A firing recorded before labels were shown as written (`Dive_side < 0` for `side < 0`),
/// as the replay shows it now, so such a recording still replays.
fn as_written(behaviour: &Behaviour, event: &Event) -> Option<String> {
    let Event::Fired { from, to, .. } = event else {
        return None;
    };
    let label = written_label(behaviour, event)?;
    Some(format!("fires {from} -> {to} on {label}"))
}

/// The label as written of a firing recorded with its lowered label (a recording made before
/// traces showed labels as written); `None` for any other event.
pub(crate) fn written_label(behaviour: &Behaviour, event: &Event) -> Option<String> {
    let Event::Fired {
        machine,
        from,
        to,
        label,
        ..
    } = event
    else {
        return None;
    };
    let m = behaviour
        .machines
        .iter()
        .find(|m| m.machine.name == *machine)?;
    let t = m.machine.transitions.iter().find(|t| {
        t.source == *from && t.target == *to && t.written.is_some() && t.label.to_string() == *label
    })?;
    Some(t.shown().to_string())
}

/// One event as the comparison sees it: its round, its machine and what happened, without
/// times or who answered.
fn observable(event: &Event) -> Option<(u64, &str, String)> {
    let (round, what) = match event {
        Event::Entered { state, round, .. } => (*round, format!("enters {state}")),
        Event::Fired {
            from,
            to,
            label,
            round,
            ..
        } => (*round, format!("fires {from} -> {to} on {label}")),
        Event::Posted {
            ty,
            content,
            priority: 0,
            round,
            ..
        } => (*round, format!("posts {ty}: {content}")),
        Event::Posted {
            ty,
            content,
            priority,
            round,
            ..
        } => (*round, format!("posts {ty}: {content} @{priority}")),
        Event::Suppressed {
            ty,
            content,
            by,
            round,
            ..
        } => (
            *round,
            format!("is suppressed posting {ty}: {content} (held by {by})"),
        ),
        Event::TookOver {
            ty, content, round, ..
        } => (*round, format!("takes over {ty}: {content}")),
        Event::Assigned {
            variable,
            value,
            round,
            ..
        } => (*round, format!("sets {variable} = {value}")),
        Event::Answered {
            atom, value, round, ..
        } => (*round, format!("reads {atom} = {value}")),
        Event::Control { command, round, .. } => (*round, format!("is told {command}")),
        Event::Finished { state, round, .. } => (*round, format!("finishes in {state}")),
        Event::Halted { reason, round, .. } => (*round, format!("halts: {reason}")),
        Event::Reloaded { state, round, .. } => (*round, format!("is reloaded in {state}")),
        _ => return None,
    };
    Some((round, event.machine(), what))
}

/// Replays `recording` on `behaviour` (on a virtual clock of its own: call it from a plain
/// thread, not inside an async runtime) and compares.
pub fn replay_recording(
    behaviour: &Behaviour,
    recording: &Recording,
) -> Result<ReplayOutcome, std::io::Error> {
    let runtime = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .start_paused(true)
        .build()?;
    let board = Whiteboard::local();
    let found = runtime.block_on(replay(behaviour, recording, board, |_| {}));
    Ok(compare(behaviour, recording, &found))
}

/// The recording's outside posted again on `board`, the behaviour's machines and theories
/// running on it in rounds (`rounds` sees the schedule before it starts); the machines' events.
pub(crate) async fn replay(
    behaviour: &Behaviour,
    recording: &Recording,
    board: Whiteboard,
    rounds: impl FnOnce(&mut Rounds),
) -> Vec<Event> {
    let inside: FxHashSet<String> = behaviour
        .machines
        .iter()
        .map(|m| m.machine.name.clone())
        .chain(behaviour.theories.iter().map(|t| t.name.clone()))
        .collect();
    let machines: Vec<String> = behaviour
        .machines
        .iter()
        .map(|m| m.machine.name.clone())
        .collect();
    let (outside, answers) = split_outside(recording, &inside, &machines, None);
    let mut tasks = tokio::task::JoinSet::new();
    for t in &behaviour.theories {
        let expert =
            ReasonerExpert::new(&t.name, t.theory.clone(), &t.mapping).with_limits(t.limits);
        tasks.spawn(expert.run(board.clone()));
    }
    if !answers.is_empty() {
        tasks.spawn(answer_as_recorded(board.clone(), answers));
    }
    // Experts subscribe before their first query.
    for _ in 0..64 {
        tokio::task::yield_now().await;
    }
    let epoch = tokio::time::Instant::now();
    let (tx, mut events) = mpsc::unbounded_channel();
    let shared = behaviour.shared_variables();
    let hosts = proclaim_runner::Hosts::default();
    let driving = Driving {
        hosts: &hosts,
        halt_on_timeout: false,
        stepper: None,
    };
    let runners = machine_runners(behaviour, driving, &tx, epoch, &shared);
    drop(tx);
    let feed = RecordedFeed::new(recording, outside);
    let mut schedule = Rounds::new(runners).fed_by(feed);
    rounds(&mut schedule);
    schedule.run(board.clone()).await;
    tasks.abort_all();
    let mut found = Vec::new();
    while let Ok(event) = events.try_recv() {
        found.push(event);
    }
    found
}

/// The outside messages to post again, each at its place (the ringlet it came before, or the
/// query of a ringlet it came before: a message may arrive while a ringlet waits for an
/// answer), and the outside experts' answers, atom by atom in the order they were given.
/// `machines` names the schedule's machines in order (a ringlet names its machine by place).
pub(crate) fn split_outside(
    recording: &Recording,
    inside: &FxHashSet<String>,
    machines: &[String],
    before_round: Option<u64>,
) -> (Outside, Answers) {
    let ringlets = &recording.ringlets;
    // The ringlet a sequence number falls in: the last that started before it.
    let within = |seq: u64| ringlets.partition_point(|r| r.seq < seq).checked_sub(1);
    // Each ringlet's queries, by sequence number.
    let mut queries: Vec<Vec<u64>> = vec![Vec::new(); ringlets.len()];
    for m in recording.messages.iter().filter(|m| m.ty == QUERY_TYPE) {
        if let Some(i) = within(m.seq) {
            if machines.get(ringlets[i].machine) == Some(&m.module) {
                queries[i].push(m.seq);
            }
        }
    }
    let place_of = |seq: u64| -> Option<Place> {
        let Some(i) = within(seq) else {
            return ringlets.first().map(|r| (r.round, r.machine, 0));
        };
        let r = &ringlets[i];
        // Came after the ringlet began but was in its snapshot: it came before the ringlet
        // as far as the ringlet could tell.
        if r.snapshot.is_some_and(|snapshot| seq <= snapshot) {
            return Some((r.round, r.machine, 0));
        }
        match queries[i].iter().position(|q| *q > seq) {
            Some(k) => Some((r.round, r.machine, k + 1)),
            None => ringlets
                .get(i + 1)
                .map(|next| (next.round, next.machine, 0)),
        }
    };
    let mut pending: FxHashSet<String> = FxHashSet::default();
    let mut answers: FxHashMap<String, VecDeque<Value>> = FxHashMap::default();
    let mut outside = Vec::new();
    for m in &recording.messages {
        if m.ty == QUERY_TYPE {
            if let Value::Str(atom) = &m.value {
                pending.insert(atom.clone());
            }
            continue;
        }
        let answers_a_query = pending.remove(&m.ty);
        if inside.contains(&m.module) {
            continue;
        }
        let place = place_of(m.seq);
        // A branch takes only what came before its round, the rest being the future it
        // replaces: an answer by the round of the ringlet that asked, a message by the round
        // that saw it first.
        let round = if answers_a_query {
            within(m.seq).map(|i| ringlets[i].round)
        } else {
            place.map(|p| p.0)
        };
        if before_round.is_some_and(|cut| round.is_none_or(|r| r >= cut)) {
            continue;
        }
        if answers_a_query {
            answers
                .entry(m.ty.clone())
                .or_default()
                .push_back(m.value.clone());
            continue;
        }
        if let Some(place) = place {
            outside.push((place, m.clone()));
        }
    }
    (outside, answers)
}

/// Answers each query for an atom an outside expert answered with the next recorded answer.
pub(crate) async fn answer_as_recorded(board: Whiteboard, mut answers: Answers) {
    let mut queries = board.subscribe_pattern(Pattern::Type(QUERY_TYPE.to_string()));
    board.register(ModuleDecl::new("recording").answers(answers.keys().cloned()));
    while let Some(query) = queries.next().await {
        let Value::Str(atom) = &query.value else {
            continue;
        };
        if let Some(value) = answers.get_mut(atom).and_then(VecDeque::pop_front) {
            board.post("recording", atom, value);
        }
    }
}

/// Paces the replay by the recording: before each ringlet, the clock goes to the recorded
/// ringlet's time and the outside messages that came before it are posted; before each query,
/// those that came before that query.
pub(crate) struct RecordedFeed {
    /// The recorded ringlets by place (round, machine) and their times since the epoch.
    times: Vec<((u64, usize), Duration)>,
    outside: Outside,
    posted: usize,
    last_round: u64,
}

impl RecordedFeed {
    fn new(recording: &Recording, outside: Outside) -> RecordedFeed {
        RecordedFeed::until(recording, outside, u64::MAX)
    }

    /// Paces the rounds before `round` alone (a branch's replayed part).
    pub(crate) fn until(recording: &Recording, mut outside: Outside, round: u64) -> RecordedFeed {
        let mut times: Vec<_> = recording
            .ringlets
            .iter()
            .filter(|r| r.round < round)
            .map(|r| ((r.round, r.machine), r.at))
            .collect();
        times.sort_unstable();
        outside.sort_by_key(|(place, m)| (*place, m.seq));
        // A run stopped inside a ringlet once left that round's events without its ringlet
        // (the schedule now sends it as it stops): the round is played all the same.
        let evented = (recording.events.iter())
            .filter_map(|e| Some(observable(e)?.0))
            .filter(|&r| r < round)
            .max();
        let paced = times.last().map(|((round, _), _)| *round);
        RecordedFeed {
            last_round: paced.max(evented).unwrap_or(0),
            times,
            outside,
            posted: 0,
        }
    }

    /// Posts every outside message whose place is not after `place`.
    fn post_up_to(&mut self, place: Place, board: &Whiteboard) {
        while let Some((p, m)) = self.outside.get(self.posted) {
            if *p > place {
                break;
            }
            board.post(&m.module, &m.ty, m.value.clone());
            self.posted += 1;
        }
    }
}

impl Feed for RecordedFeed {
    fn before(&mut self, ringlet: Ringlet, board: &Whiteboard) -> Option<Duration> {
        let at = (ringlet.round, ringlet.machine);
        self.post_up_to((ringlet.round, ringlet.machine, 0), board);
        self.times
            .iter()
            .take_while(|(p, _)| *p <= at)
            .last()
            .map(|(_, time)| *time)
    }

    fn before_query(&mut self, ringlet: Ringlet, nth: usize, board: &Whiteboard) {
        self.post_up_to((ringlet.round, ringlet.machine, nth + 1), board);
    }

    fn after_round(&mut self, round: u64) -> bool {
        round < self.last_round
    }
}

/// The first difference between what was recorded and what the replay did, machine events of
/// the behaviour only; a replay may run on past the end of the recording's last round (the
/// recording stopped mid-round).
fn compare(behaviour: &Behaviour, recording: &Recording, found: &[Event]) -> ReplayOutcome {
    let ours = |e: &&Event| {
        behaviour
            .machines
            .iter()
            .any(|m| m.machine.name == e.machine())
    };
    let expected: Vec<_> = recording
        .events
        .iter()
        .filter(ours)
        .filter_map(|e| {
            let (round, machine, what) = observable(e)?;
            Some((round, machine, as_written(behaviour, e).unwrap_or(what)))
        })
        .collect();
    let got: Vec<_> = found.iter().filter(ours).filter_map(observable).collect();
    for (i, want) in expected.iter().enumerate() {
        match got.get(i) {
            Some(have) if have == want => {}
            Some((round, machine, what)) => {
                return ReplayOutcome::Differs(Difference {
                    round: want.0.min(*round),
                    machine: if want.1 == *machine {
                        machine.to_string()
                    } else {
                        format!("{} (found {machine})", want.1)
                    },
                    expected: want.2.clone(),
                    found: what.clone(),
                })
            }
            None => {
                return ReplayOutcome::Differs(Difference {
                    round: want.0,
                    machine: want.1.to_string(),
                    expected: want.2.clone(),
                    found: "nothing: the replay ended".into(),
                })
            }
        }
    }
    let last = expected.last().map_or(0, |e| e.0);
    if let Some((round, machine, what)) = got.get(expected.len()).filter(|e| e.0 < last) {
        return ReplayOutcome::Differs(Difference {
            round: *round,
            machine: machine.to_string(),
            expected: "nothing more".into(),
            found: what.clone(),
        });
    }
    ReplayOutcome::Same {
        rounds: recording
            .ringlets
            .iter()
            .map(|r| r.round)
            .max()
            .unwrap_or(0),
        events: expected.len(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ringlet(round: u64, machine: usize, seq: u64, snapshot: Option<u64>) -> Ringlet {
        Ringlet {
            round,
            machine,
            seq,
            at: Duration::ZERO,
            snapshot,
        }
    }

    fn message(seq: u64, ty: &str) -> Recorded {
        Recorded {
            seq,
            module: "impersonator".into(),
            ty: ty.into(),
            value: Value::Bool(true),
        }
    }

    /// Where each outside message is posted again, by its sequence number.
    fn places(ringlets: Vec<Ringlet>, messages: Vec<Recorded>) -> Vec<(u64, Place)> {
        let recording = Recording {
            messages,
            ringlets,
            events: Vec::new(),
            branch: None,
        };
        let (outside, _) = split_outside(&recording, &FxHashSet::default(), &["A".into()], None);
        outside
            .into_iter()
            .map(|(place, m)| (m.seq, place))
            .collect()
    }

    #[test]
    fn a_message_in_a_ringlets_snapshot_is_posted_before_that_ringlet() {
        // Ringlet (1, 0) began at 10 and took its snapshot at 12; (2, 0) began at 14.
        let ringlets = vec![ringlet(1, 0, 10, Some(12)), ringlet(2, 0, 14, None)];
        let messages = vec![message(9, "a"), message(11, "b"), message(13, "c")];
        assert_eq!(
            places(ringlets, messages),
            [(9, (1, 0, 0)), (11, (1, 0, 0)), (13, (2, 0, 0))]
        );
    }

    /// A recording made before a stopped ringlet was sent as it stopped: round 3 has an event
    /// but no ringlet, and its replay plays round 3 all the same (it once ended a round short).
    #[test]
    fn a_round_with_events_but_no_ringlet_is_played() {
        let entered = Event::Entered {
            machine: "A".into(),
            state: "OPEN".into(),
            id: 1,
            round: 3,
            at: Duration::ZERO,
        };
        let recording = Recording {
            messages: Vec::new(),
            ringlets: vec![ringlet(1, 0, 10, None), ringlet(2, 0, 14, None)],
            events: vec![entered],
            branch: None,
        };
        let mut feed = RecordedFeed::new(&recording, Vec::new());
        assert!(feed.after_round(2), "round 3 is played");
        assert!(!feed.after_round(3));
        let mut branch = RecordedFeed::until(&recording, Vec::new(), 3);
        assert!(
            !branch.after_round(2),
            "a branch at round 3 plays to round 2"
        );
    }

    #[test]
    fn without_a_snapshot_a_message_after_a_ringlet_began_comes_before_the_next() {
        let ringlets = vec![ringlet(1, 0, 10, None), ringlet(2, 0, 14, None)];
        assert_eq!(places(ringlets, vec![message(11, "b")]), [(11, (2, 0, 0))]);
    }

    #[test]
    fn a_branch_takes_what_came_from_outside_before_its_round_and_no_later() {
        let ringlets = vec![
            ringlet(1, 0, 10, None),
            ringlet(2, 0, 20, None),
            ringlet(3, 0, 30, None),
        ];
        // a before round 1; b between rounds 1 and 2, for round 2 to see; c for round 3.
        let mut messages = vec![message(9, "a"), message(15, "b"), message(25, "c")];
        // An outside expert's answer to round 1's ringlet, and one to round 3's.
        let query = |seq: u64| Recorded {
            seq,
            module: "A".into(),
            ty: QUERY_TYPE.into(),
            value: Value::Str("x".into()),
        };
        let answer = |seq: u64, value: bool| Recorded {
            value: Value::Bool(value),
            ..message(seq, "x")
        };
        messages.extend([query(11), answer(12, true), query(31), answer(32, false)]);
        let recording = Recording {
            messages,
            ringlets,
            events: Vec::new(),
            branch: None,
        };
        let inside = FxHashSet::default();
        let (outside, answers) = split_outside(&recording, &inside, &["A".into()], Some(2));
        let posted: Vec<u64> = outside.iter().map(|(_, m)| m.seq).collect();
        assert_eq!(
            posted,
            [9],
            "what round 2 would have seen is the branch's to decide"
        );
        assert_eq!(
            answers["x"],
            [Value::Bool(true)],
            "round 3's answer is the future"
        );
        let (outside, answers) = split_outside(&recording, &inside, &["A".into()], None);
        assert_eq!(outside.len(), 3);
        assert_eq!(answers["x"], [Value::Bool(true), Value::Bool(false)]);
    }
}
