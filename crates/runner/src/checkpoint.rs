//! A round schedule written down at the start of a round and taken up again
//! (`docs/spec/behaviour.md` §3.4): every machine's status, state, time in state, variables and
//! what its last ringlet saw and asked, the behaviour's globals, what holds each suppressed type
//! and the round and moment. Taken once everything due at the round's moment has arrived, before
//! any machine rings, and when the caller says everything outside the machines has handled what
//! was posted to it, so the machines, the board and the experts are all between two steps; a
//! schedule resumed from it plays that round and every later one as the uninterrupted run did.

use crate::machine::{MachineRunner, RunningMachine, Status};
use crate::seen::Seen;
use crate::variables::{Locals, Shared};
use parking_lot::Mutex;
use proclaim_board::{nanos, BoardImage, KindName, MessageImage, TypeImage, Value};
use proclaim_fsm::Machine;
use proclaim_runtime::{Holding, Ranked};
use serde::{Deserialize, Serialize};
use std::sync::Arc;
use std::time::Duration;

/// A round schedule at the start of a round.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RoundsImage {
    /// The round about to be played.
    pub round: u64,
    /// Its moment: nanoseconds since the run's epoch.
    pub at_ns: u64,
    /// Whether the round goes on at the moment of the one before (rounds that fire one after
    /// another at one moment), and how many have so far: a schedule counts them to halt
    /// machines that never let time pass (`MOST_ROUNDS_WITHOUT_WAITING`).
    #[serde(default)]
    pub same_moment: bool,
    #[serde(default)]
    pub rounds_without_waiting: u64,
    /// How many times a global changed (a machine's `globals_seen` is one of these counts).
    pub global_changes: u64,
    pub globals: Vec<VariableImage>,
    /// In schedule order.
    pub machines: Vec<MachineImage>,
    /// What holds each type declared suppressed.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub holds: Vec<HoldImage>,
}

/// A suppressed type's holding ([`proclaim_runtime::Holding`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct HoldImage {
    #[serde(rename = "type")]
    pub ty: String,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shown: Option<RankedImage>,
    pub newest: Vec<RankedImage>,
    pub subsuming: bool,
}

/// A posting as the suppressor keeps it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RankedImage {
    pub module: String,
    pub value: serde_json::Value,
    pub priority: u32,
    /// When it was posted: nanoseconds since the run's epoch.
    pub at_ns: u64,
}

impl HoldImage {
    pub(crate) fn of(holding: &Holding<Value>) -> HoldImage {
        HoldImage {
            ty: holding.ty.to_string(),
            shown: holding.shown.as_ref().map(RankedImage::of),
            newest: holding.newest.iter().map(RankedImage::of).collect(),
            subsuming: holding.subsuming,
        }
    }

    pub(crate) fn holding(&self) -> Holding<Value> {
        let ty: Arc<str> = Arc::from(self.ty.as_str());
        Holding {
            shown: self.shown.as_ref().map(|r| r.ranked(&ty)),
            newest: self.newest.iter().map(|r| r.ranked(&ty)).collect(),
            subsuming: self.subsuming,
            ty,
        }
    }
}

impl RankedImage {
    fn of(ranked: &Ranked<Value>) -> RankedImage {
        RankedImage {
            module: ranked.module.to_string(),
            value: ranked.value.to_json(),
            priority: ranked.priority,
            at_ns: nanos(ranked.at),
        }
    }

    fn ranked(&self, ty: &Arc<str>) -> Ranked<Value> {
        Ranked {
            module: Arc::from(self.module.as_str()),
            ty: ty.clone(),
            value: Value::from_json(&self.value),
            priority: self.priority,
            at: Duration::from_nanos(self.at_ns),
        }
    }
}

/// A variable and its value (and, for a machine's own, its declared type).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct VariableImage {
    pub name: String,
    #[serde(rename = "type", default, skip_serializing_if = "Option::is_none")]
    pub ty: Option<String>,
    pub value: serde_json::Value,
}

/// One machine between two ringlets.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MachineImage {
    pub name: String,
    pub status: StatusName,
    /// Halted, or its state vanished: it rings no more.
    pub over: bool,
    /// The current state, by name (and by id, for a machine whose names repeat).
    pub state: String,
    pub state_id: i64,
    /// Its next ringlet runs the state's OnEntry first.
    pub just_entered: bool,
    /// When it entered its state: nanoseconds since the run's epoch.
    pub entered_ns: u64,
    /// When it entered each composite state of a chart, which its time tests count from.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub composites: Vec<CompositeImage>,
    /// The state it last arrived in (where a machine about to enter another was).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub last_entered: Option<String>,
    pub locals: Vec<VariableImage>,
    pub seen: SeenImage,
    /// The atoms its last ringlet asked, and their answers.
    pub asked: Vec<AskedImage>,
    pub globals_seen: u64,
    /// Host functions already reported missing (each is reported once).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub unknown: Vec<String>,
}

/// What a machine's last ringlet saw of the board, as far as telling news from what it knew
/// needs: the newest message of each type its current state's labels read, as its snapshot
/// held it, and what it posted itself.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SeenImage {
    /// The board's sequence number at its snapshot; none when it read nothing of the board.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub snapshot_seq: Option<u64>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub read: Vec<TypeImage>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub own: Vec<TypeImage>,
}

/// When a machine entered one of its composite states, by path: nanoseconds since the run's
/// epoch, none while the move into it has not arrived.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CompositeImage {
    pub name: String,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub entered_ns: Option<u64>,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct AskedImage {
    pub atom: String,
    pub value: bool,
}

/// [`Status`] as a checkpoint names it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum StatusName {
    Running,
    Suspended,
    Dormant,
}

/// When a schedule writes itself down, and who takes what it wrote.
pub struct Checkpoints {
    at: Vec<u64>,
    every: Option<u64>,
    next_every: u64,
    ready: Box<dyn Fn() -> bool + Send>,
    take: Box<dyn FnMut(RoundsImage) -> bool + Send>,
}

impl Checkpoints {
    /// At the first round at or after each of `at`, and of each multiple of `every`, at whose
    /// start `ready` says everything outside the machines has handled all that was posted to it
    /// (an expert yet to read an input the last round posted holds state a checkpoint cannot
    /// see); each image to `take`, at once, which says whether it took it (looking again at
    /// everything together, it may find a module still busy: the next round is tried).
    pub fn new(
        mut at: Vec<u64>,
        every: Option<u64>,
        ready: impl Fn() -> bool + Send + 'static,
        take: impl FnMut(RoundsImage) -> bool + Send + 'static,
    ) -> Checkpoints {
        at.sort_unstable();
        let every = every.filter(|n| *n > 0);
        Checkpoints {
            at,
            next_every: every.unwrap_or(u64::MAX),
            every,
            ready: Box::new(ready),
            take: Box::new(take),
        }
    }

    /// Counted on from `round`, where a run was taken up: the checkpoint it came from is not
    /// written again.
    pub fn after(mut self, round: u64) -> Checkpoints {
        if let Some(every) = self.every {
            self.next_every = (round / every).saturating_add(1).saturating_mul(every);
        }
        self
    }

    /// Whether a checkpoint is asked for at `round`.
    fn due(&self, round: u64) -> bool {
        self.at.first().is_some_and(|r| *r <= round) || round >= self.next_every
    }

    /// A checkpoint was taken at `round`: the next is counted from there.
    fn taken(&mut self, round: u64) {
        self.at.retain(|r| *r > round);
        if let Some(every) = self.every.filter(|_| round >= self.next_every) {
            self.next_every = (round / every).saturating_add(1).saturating_mul(every);
        }
    }

    /// Writes the schedule down at `round` if a checkpoint is due and can be taken.
    pub(crate) fn offer(&mut self, round: u64, image: impl FnOnce() -> RoundsImage) {
        if self.due(round) && (self.ready)() && (self.take)(image()) {
            self.taken(round);
        }
    }
}

/// A checkpoint's machines taken by a behaviour whose machines may have changed since: what no
/// longer fits, and what changed but fits.
#[derive(Debug, Default)]
pub struct Fit {
    pub refused: Vec<String>,
    pub notes: Vec<String>,
}

impl RoundsImage {
    /// Whether `machines` (in schedule order) can go on from this image.
    pub fn fit(&self, machines: &[MachineRunner]) -> Fit {
        let mut fit = Fit::default();
        let names: Vec<&str> = machines.iter().map(|m| m.machine().name.as_str()).collect();
        let kept: Vec<&str> = self.machines.iter().map(|m| m.name.as_str()).collect();
        if names != kept {
            fit.refused.push(format!(
                "the checkpoint runs the machines {} and the behaviour {}: a schedule goes on with the same machines in the same order",
                kept.join(", "),
                names.join(", ")
            ));
            return fit;
        }
        for (image, runner) in self.machines.iter().zip(machines) {
            image.fit(runner.machine(), &mut fit);
        }
        fit
    }
}

impl MachineImage {
    /// The state this image names in `machine`: by name when the name is unique, else by id.
    pub fn state_in(&self, machine: &Machine) -> Option<i64> {
        state_of(machine, &self.state, self.state_id)
    }

    fn fit(&self, machine: &Machine, fit: &mut Fit) {
        // A machine whose state vanished rings no more: where it was does not matter.
        if !self.over && self.state_in(machine).is_none() {
            fit.refused.push(format!(
                "{} is in state {} in the checkpoint, which the machine no longer has",
                self.name, self.state
            ));
        }
        let declared = Locals::declared(machine);
        for v in &self.locals {
            match declared.type_of(&v.name) {
                None => fit.notes.push(format!(
                    "{}: `{}` is no longer declared; its value {} is dropped",
                    self.name, v.name, v.value
                )),
                Some(ty) if v.ty.as_deref() != Some(ty) => fit.refused.push(format!(
                    "{}: `{}` was {} in the checkpoint and is {ty} now",
                    self.name,
                    v.name,
                    v.ty.as_deref().unwrap_or("untyped")
                )),
                Some(_) => {}
            }
        }
        for name in declared.names() {
            if !self.locals.iter().any(|v| v.name == name) {
                fit.notes
                    .push(format!("{}: `{name}` is new; it starts at zero", self.name));
            }
        }
    }
}

/// The state a checkpoint names: by name when the name is unique, else by id (as `reread`
/// keeps a state).
fn state_of(machine: &Machine, name: &str, id: i64) -> Option<i64> {
    let named: Vec<i64> = machine
        .states
        .iter()
        .filter(|s| s.name == name)
        .map(|s| s.id)
        .collect();
    match named.as_slice() {
        [only] => Some(*only),
        _ => named.into_iter().find(|s| *s == id),
    }
}

impl RunningMachine<'_> {
    /// This machine between two ringlets.
    pub(crate) fn image(&mut self, over: bool) -> MachineImage {
        let types = self.reads().0.to_vec();
        let epoch = self.reporter.epoch;
        let mut unknown: Vec<String> = self.unknown.iter().cloned().collect();
        unknown.sort();
        MachineImage {
            name: self.name.clone(),
            status: match self.status {
                Status::Running => StatusName::Running,
                Status::Suspended => StatusName::Suspended,
                Status::Dormant => StatusName::Dormant,
            },
            over,
            state: self
                .machine
                .state(self.current)
                .map_or_else(String::new, |s| s.name.clone()),
            state_id: self.current,
            just_entered: self.just_entered,
            entered_ns: nanos(self.entered_at.saturating_duration_since(epoch)),
            composites: self
                .machine
                .composites
                .iter()
                .zip(&self.composites_entered)
                .map(|(c, entered)| CompositeImage {
                    name: c.name.clone(),
                    entered_ns: entered.map(|at| nanos(at.saturating_duration_since(epoch))),
                })
                .collect(),
            last_entered: self.last_entered.clone(),
            locals: self.locals.image(),
            seen: self.seen.image(&types),
            asked: self
                .asked
                .iter()
                .map(|(atom, value)| AskedImage {
                    atom: atom.clone(),
                    value: *value,
                })
                .collect(),
            globals_seen: self.globals_seen,
            unknown,
        }
    }

    /// Takes up where `image` left off (a fitting image: [`RoundsImage::fit`]).
    pub(crate) fn restore(&mut self, image: &MachineImage) {
        self.status = match image.status {
            StatusName::Running => Status::Running,
            StatusName::Suspended => Status::Suspended,
            StatusName::Dormant => Status::Dormant,
        };
        if let Some(id) = state_of(&self.machine, &image.state, image.state_id) {
            self.current = id;
        }
        self.just_entered = image.just_entered;
        self.entered_at = self.reporter.epoch + Duration::from_nanos(image.entered_ns);
        // A composite the checkpoint does not name counts from its state's entry (from the
        // arrival, when a move into the state has not arrived yet).
        let unnamed = (!self.just_entered).then_some(self.entered_at);
        for (c, entered) in self
            .machine
            .composites
            .iter()
            .zip(&mut self.composites_entered)
        {
            let named = image.composites.iter().find(|i| i.name == c.name);
            *entered = match named {
                Some(i) => i
                    .entered_ns
                    .map(|ns| self.reporter.epoch + Duration::from_nanos(ns)),
                None => unnamed,
            };
        }
        self.last_entered.clone_from(&image.last_entered);
        for v in &image.locals {
            self.locals.set(&v.name, Value::from_json(&v.value));
        }
        self.seen = Seen::restored(&image.seen);
        self.asked = image
            .asked
            .iter()
            .map(|a| (a.atom.clone(), a.value))
            .collect();
        self.globals_seen = image.globals_seen;
        self.unknown = image.unknown.iter().cloned().collect();
    }
}

impl Locals {
    /// Every variable with its type and value, by name.
    pub(crate) fn image(&self) -> Vec<VariableImage> {
        let mut vars: Vec<VariableImage> = self
            .names()
            .into_iter()
            .map(|name| VariableImage {
                ty: self.type_of(&name).map(str::to_string),
                value: self
                    .get(&name)
                    .map_or(serde_json::Value::Null, Value::to_json),
                name,
            })
            .collect();
        vars.sort_by(|a, b| a.name.cmp(&b.name));
        vars
    }
}

impl Shared {
    /// Every global and its value, by name; and how many times one changed.
    pub(crate) fn image(&self) -> (Vec<VariableImage>, u64) {
        let (globals, changes) = self.globals_and_changes();
        let mut vars: Vec<VariableImage> = globals
            .into_iter()
            .map(|(name, value)| VariableImage {
                name,
                ty: None,
                value: value.to_json(),
            })
            .collect();
        vars.sort_by(|a, b| a.name.cmp(&b.name));
        (vars, changes)
    }
}

impl Seen {
    /// What telling news from what the machine knew needs of this: see [`SeenImage`].
    pub(crate) fn image(&self, types: &[String]) -> SeenImage {
        let held = |ty: &str, m: &proclaim_board::Message| TypeImage {
            ty: ty.to_string(),
            kind: KindName::State,
            latest: Some(MessageImage::of(m)),
            history: Vec::new(),
            signals: Vec::new(),
            last_signal: None,
            posts: 0,
        };
        let snapshot = self.last_snapshot();
        let read = snapshot.map_or_else(Vec::new, |s| {
            types
                .iter()
                .filter_map(|ty| s.newest(ty).map(|m| held(ty, m)))
                .collect()
        });
        let mut own: Vec<TypeImage> = self.own().map(|(ty, m)| held(ty, m)).collect();
        own.sort_by(|a, b| a.ty.cmp(&b.ty));
        SeenImage {
            snapshot_seq: snapshot.map(|s| s.seq),
            read,
            own,
        }
    }

    /// Seen as `image` says, between two ringlets.
    pub(crate) fn restored(image: &SeenImage) -> Seen {
        let snapshot = image.snapshot_seq.map(|seq| {
            BoardImage {
                seq,
                time_ns: 0,
                posts: 0,
                queries: 0,
                timeouts: 0,
                unanswerable: 0,
                drops: 0,
                types: image.read.clone(),
            }
            .snapshot()
        });
        let own = image.own.iter().filter_map(|t| {
            let ty: Arc<str> = Arc::from(t.ty.as_str());
            Some((t.ty.clone(), t.latest.as_ref()?.message(&ty)))
        });
        Seen::between_ringlets(snapshot, own.collect())
    }
}

/// A schedule's checkpoints, shared by the task that plays it.
pub(crate) type SharedCheckpoints = Arc<Mutex<Checkpoints>>;

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicU64, Ordering};

    #[test]
    fn checkpoints_come_at_the_first_round_at_or_after_each_asked_that_is_ready() {
        // Round 20 finds a module busy (`ready` false) and round 21 one the take turns down.
        let now = Arc::new(AtomicU64::new(0));
        let taken = Arc::new(Mutex::new(Vec::new()));
        let (seen, into) = (now.clone(), taken.clone());
        let mut c = Checkpoints::new(
            vec![5, 3],
            Some(10),
            move || seen.load(Ordering::Relaxed) != 20,
            move |i: RoundsImage| {
                let keep = i.round != 21;
                if keep {
                    into.lock().push(i.round);
                }
                keep
            },
        );
        for round in [1, 2, 4, 6, 9, 12, 19, 20, 21, 22, 35] {
            now.store(round, Ordering::Relaxed);
            c.offer(round, || image(round));
        }
        assert_eq!(*taken.lock(), [4, 6, 12, 22, 35]);
    }

    #[test]
    fn a_schedule_taken_up_counts_its_checkpoints_on_from_there() {
        let taken = Arc::new(Mutex::new(Vec::new()));
        let into = taken.clone();
        let mut c = Checkpoints::new(
            Vec::new(),
            Some(100),
            || true,
            move |i: RoundsImage| {
                into.lock().push(i.round);
                true
            },
        )
        .after(500);
        for round in [500, 501, 599, 600, 650, 700] {
            c.offer(round, || image(round));
        }
        assert_eq!(*taken.lock(), [600, 700]);
    }

    fn image(round: u64) -> RoundsImage {
        RoundsImage {
            round,
            at_ns: 0,
            same_moment: false,
            rounds_without_waiting: 0,
            global_changes: 0,
            globals: Vec::new(),
            machines: Vec::new(),
            holds: Vec::new(),
        }
    }
}
