//! A running behaviour written down at the start of a round, and a run taken up from it
//! (`proclaim run --checkpoint-at`, `--resume`; `docs/spec/behaviour.md` §3.4): the round
//! schedule's machines and globals, the whole board with its sequence numbers, each theory's
//! inputs and last answers, the script's position and the warnings already given, at a moment
//! when everything due has arrived and no machine has rung. Only what the run holds itself can
//! be written down: a program, a sensor, a person or another process keeps state of its own,
//! so a behaviour with one is refused, saying which.

use crate::error::BehaviourError;
use crate::{Behaviour, LaunchOptions};
use parking_lot::Mutex;
use proclaim_board::{BoardImage, KindName, Restored, Value, Whiteboard};
use proclaim_experts::{Impersonator, ReasonerMemory, Script, ScriptPosition};
use proclaim_runner::{Checkpoints, Rounds, RoundsImage};
use rustc_hash::{FxHashMap, FxHashSet};
use serde::{Deserialize, Serialize};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::Duration;
use tokio::sync::mpsc;

/// What a checkpoint file says it is.
pub const CHECKPOINT_FORMAT: &str = "proclaim checkpoint";
/// The version of the form this build writes and reads.
pub const CHECKPOINT_VERSION: u32 = 1;

/// A behaviour's run at the start of a round.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Checkpoint {
    pub format: String,
    pub version: u32,
    pub behaviour: String,
    /// The round about to be played.
    pub round: u64,
    /// Its moment, nanoseconds since the run began.
    pub at_ns: u64,
    pub schedule: RoundsImage,
    pub board: BoardImage,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub theories: Vec<TheoryImage>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub script: Option<ScriptImage>,
    /// Postings outside a declared range already warned of (once per type and value).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub range_warnings: Vec<RangeWarning>,
}

/// A theory's expert as the checkpoint found it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TheoryImage {
    pub name: String,
    #[serde(flatten)]
    pub memory: ReasonerMemory,
}

/// The script being played, and where it was.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ScriptImage {
    /// How many steps it has, and a fingerprint of what they say, to tell it from another.
    pub steps: usize,
    pub fingerprint: String,
    #[serde(flatten)]
    pub position: ScriptPosition,
}

#[derive(Clone, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct RangeWarning {
    #[serde(rename = "type")]
    pub ty: String,
    pub value: String,
}

/// When a run writes checkpoints (`--checkpoint-at`, `--checkpoint-every`).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct CheckpointPlan {
    pub at: Vec<u64>,
    pub every: Option<u64>,
}

impl Checkpoint {
    /// A checkpoint file's text read back, or why it is none.
    pub fn read(text: &str) -> Result<Checkpoint, String> {
        let json: serde_json::Value =
            serde_json::from_str(text).map_err(|e| format!("not JSON: {e}"))?;
        let format = json.get("format").and_then(|f| f.as_str());
        if format != Some(CHECKPOINT_FORMAT) {
            return Err(format!(
                "not a checkpoint: its \"format\" is {}, not \"{CHECKPOINT_FORMAT}\"",
                format.map_or_else(|| "missing".to_string(), |f| format!("\"{f}\""))
            ));
        }
        let version = json.get("version").and_then(|v| v.as_u64());
        if version != Some(u64::from(CHECKPOINT_VERSION)) {
            return Err(format!(
                "a checkpoint of version {}, and this proclaim reads version {CHECKPOINT_VERSION}",
                version.map_or_else(|| "none".to_string(), |v| v.to_string())
            ));
        }
        let checkpoint: Checkpoint =
            serde_json::from_value(json).map_err(|e| format!("a checkpoint, but {e}"))?;
        // Far beyond any run, and a count that could not go on.
        if checkpoint.round == 0 || checkpoint.round > 1 << 53 {
            return Err(format!(
                "a checkpoint at round {}, which no run reaches",
                checkpoint.round
            ));
        }
        // The header a person reads and the schedule the run takes up must say one thing.
        let schedule = &checkpoint.schedule;
        if (schedule.round, schedule.at_ns) != (checkpoint.round, checkpoint.at_ns) {
            return Err(format!(
                "its header says round {} at {} ns and its schedule round {} at {} ns",
                checkpoint.round, checkpoint.at_ns, schedule.round, schedule.at_ns
            ));
        }
        Ok(checkpoint)
    }

    /// The file's text: one line of JSON.
    pub fn to_text(&self) -> Result<String, String> {
        let mut text = serde_json::to_string(self).map_err(|e| e.to_string())?;
        text.push('\n');
        Ok(text)
    }

    /// The moment it was taken, since the run began.
    pub fn at(&self) -> Duration {
        Duration::from_nanos(self.at_ns)
    }

    /// What of it `behaviour` does not take up, each said: another behaviour's name, a theory
    /// it no longer has (what that theory held is dropped).
    fn misfits(&self, behaviour: &Behaviour) -> Vec<String> {
        let mut said = Vec::new();
        if self.behaviour != behaviour.name {
            said.push(format!(
                "the checkpoint was taken of `{}`, and this is `{}`",
                self.behaviour, behaviour.name
            ));
        }
        for theory in &self.theories {
            if !behaviour.theories.iter().any(|t| t.name == theory.name) {
                said.push(format!(
                    "the theory `{}` is no longer in the behaviour; what it held is dropped",
                    theory.name
                ));
            }
        }
        said
    }
}

/// A script's fingerprint: what its steps say (not where they stand in the file) as this build
/// writes them, hashed (FNV-1a).
fn fingerprint(script: &Script) -> String {
    let said = script.steps.iter().map(|s| (&s.when, &s.atom, &s.value));
    let text = format!("{:?}", said.collect::<Vec<_>>());
    let hash = text.bytes().fold(0xcbf2_9ce4_8422_2325_u64, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    });
    format!("{hash:016x}")
}

/// What a run that writes or takes up checkpoints holds of its modules: the handles it reads
/// them through, and the checkpoint it takes up.
#[derive(Default)]
pub(crate) struct Kept {
    /// Whether checkpoints are written or taken up at all (handles cost a little per message).
    keep: bool,
    resume: Option<Arc<Checkpoint>>,
    theories: Vec<(String, Arc<Mutex<ReasonerMemory>>)>,
    script: Option<(Impersonator, ScriptImage)>,
    range_warnings: Arc<Mutex<FxHashSet<RangeWarning>>>,
    /// What each module follows on the board, and the last of it it handled.
    follows: Vec<(Vec<String>, Handled)>,
}

/// The sequence number of the last message a module handled.
type Handled = Box<dyn Fn() -> u64 + Send + Sync>;

impl Kept {
    /// For a run that writes checkpoints (`checkpointed`) or takes up `resume`.
    pub fn new(checkpointed: bool, resume: Option<Arc<Checkpoint>>) -> Kept {
        let warned = resume.iter().flat_map(|c| c.range_warnings.iter().cloned());
        Kept {
            keep: checkpointed || resume.is_some(),
            range_warnings: Arc::new(Mutex::new(warned.collect())),
            resume,
            ..Kept::default()
        }
    }

    /// A theory's expert, remembered for checkpoints and taken up from the one resumed.
    pub fn theory(
        &mut self,
        name: &str,
        mut expert: proclaim_experts::ReasonerExpert,
    ) -> proclaim_experts::ReasonerExpert {
        if !self.keep {
            return expert;
        }
        let resumed = self.resume.as_deref();
        if let Some(kept) = resumed.and_then(|c| c.theories.iter().find(|t| t.name == name)) {
            expert = expert.resumed(&kept.memory);
        }
        let memory = expert.remembered();
        let follows = expert.declaration().reads;
        self.follows
            .push((follows, Box::new(move_handled(&memory))));
        self.theories.push((name.to_string(), memory));
        expert
    }

    /// The script's impersonator, held for checkpoints and taken up where the one resumed was.
    pub fn script(
        &mut self,
        script: &Script,
        imp: Impersonator,
        epoch: tokio::time::Instant,
    ) -> Impersonator {
        if !self.keep {
            return imp;
        }
        let imp = match self.resume.as_deref().and_then(|c| c.script.as_ref()) {
            Some(kept) => imp.resumed(&kept.position, epoch),
            None => imp,
        };
        let image = ScriptImage {
            steps: script.steps.len(),
            fingerprint: fingerprint(script),
            position: ScriptPosition::default(),
        };
        let handle = imp.clone();
        self.follows.push((
            vec![proclaim_board::QUERY_TYPE.to_string()],
            Box::new(move || handle.handled()),
        ));
        self.script = Some((imp.clone(), image));
        imp
    }

    /// A module of the run's own that follows `types` (the trace's view of the script, the
    /// range watch): the count it keeps of what it handled, to be set as it handles each.
    pub fn follower(&mut self, types: &[String], board: &Whiteboard) -> Arc<AtomicU64> {
        let handled = Arc::new(AtomicU64::new(board.snapshot().seq));
        let read = handled.clone();
        self.follows.push((
            types.to_vec(),
            Box::new(move || read.load(Ordering::Relaxed)),
        ));
        handled
    }

    /// Whether every module the run holds has handled everything posted to it: nothing of
    /// theirs is between two steps, so the board and their images are the whole of it.
    fn settled(&self, board: &Whiteboard) -> bool {
        self.settled_on(&board.snapshot())
    }

    /// [`Kept::settled`] as to the board `snapshot` holds.
    fn settled_on(&self, snapshot: &proclaim_board::Snapshot) -> bool {
        self.follows.iter().all(|(types, handled)| {
            let handled = handled();
            types
                .iter()
                .all(|ty| snapshot.newest(ty).is_none_or(|m| m.seq <= handled))
        })
    }

    /// What the trace has shown of the script's atoms: nothing at a run's start; taken up,
    /// what the impersonator last posted of each.
    pub fn script_shown(&self, board: &Whiteboard, atoms: &[String]) -> FxHashMap<String, Value> {
        if self.resume.is_none() {
            return FxHashMap::default();
        }
        let snapshot = board.snapshot();
        atoms
            .iter()
            .filter_map(|atom| snapshot.newest(atom))
            .filter(|m| &*m.module == "impersonator")
            .map(|m| (m.ty.to_string(), m.value.clone()))
            .collect()
    }

    /// The range warnings given, shared with the watch that gives them.
    pub fn range_warnings(&self) -> Arc<Mutex<FxHashSet<RangeWarning>>> {
        self.range_warnings.clone()
    }

    /// Refuses a checkpointed run with a module whose state is not the run's: only theories,
    /// the script and what follows them can be written down.
    pub fn refuse_unheld<'m>(
        &self,
        behaviour: &Behaviour,
        mut modules: impl Iterator<Item = &'m str>,
    ) -> Result<(), BehaviourError> {
        let held = |name: &str| {
            matches!(name, "impersonator" | "script" | "ranges")
                || behaviour.theories.iter().any(|t| t.name == name)
        };
        match modules.find(|m| !held(m)).filter(|_| self.keep) {
            None => Ok(()),
            Some(module) => Err(BehaviourError::Checkpoint(format!(
                "`{module}` keeps state of its own outside the run (a program, a sensor, a person or the embedding program), which a checkpoint cannot hold; give a --script that answers its labels instead"
            ))),
        }
    }

    /// The round schedule taken up from the checkpoint resumed and writing the checkpoints
    /// `options` ask for, with the receiver they come on.
    pub fn schedule(
        self,
        rounds: Option<Rounds>,
        behaviour: &Behaviour,
        options: &LaunchOptions,
        board: &Whiteboard,
        notes: &mut Vec<String>,
    ) -> Result<(Option<Rounds>, Option<mpsc::UnboundedReceiver<Checkpoint>>), BehaviourError> {
        if !self.keep {
            return Ok((rounds, None));
        }
        let Some(mut rounds) = rounds else {
            return Err(BehaviourError::Checkpoint(
                "the machines run concurrently (the manifest's schedule = \"concurrent\"), with no rounds to write a checkpoint between".into(),
            ));
        };
        let mut after = 0;
        if let Some(c) = &self.resume {
            let (resumed, changed) = rounds
                .resumed_from(c.schedule.clone())
                .map_err(BehaviourError::Resume)?;
            rounds = resumed;
            notes.extend(changed.into_iter().map(|n| format!("taken up: {n}")));
            notes.extend(
                c.misfits(behaviour)
                    .into_iter()
                    .map(|n| format!("taken up: {n}")),
            );
            after = c.round;
        }
        let Some(plan) = &options.checkpoints else {
            return Ok((Some(rounds), None));
        };
        let (checkpoints, taken) = Arc::new(self).checkpoints(plan, &behaviour.name, board);
        Ok((
            Some(rounds.checkpointed(checkpoints.after(after))),
            Some(taken),
        ))
    }

    /// The whole run at `schedule`'s round: the board first, then what each module holds,
    /// then whether each had handled all of that board (on the real clock a module may have
    /// moved on meanwhile; then none is taken, and the next round tries again).
    fn checkpoint(
        &self,
        behaviour: &str,
        schedule: RoundsImage,
        board: &Whiteboard,
    ) -> Option<Checkpoint> {
        let snapshot = board.snapshot();
        let image = snapshot.image(board.stats());
        let theories = self.theories.iter().map(|(name, memory)| TheoryImage {
            name: name.clone(),
            memory: memory.lock().clone(),
        });
        let mut range_warnings: Vec<RangeWarning> =
            self.range_warnings.lock().iter().cloned().collect();
        range_warnings.sort_by(|a, b| (&a.ty, &a.value).cmp(&(&b.ty, &b.value)));
        let checkpoint = Checkpoint {
            format: CHECKPOINT_FORMAT.into(),
            version: CHECKPOINT_VERSION,
            behaviour: behaviour.to_string(),
            round: schedule.round,
            at_ns: schedule.at_ns,
            board: image,
            theories: theories.collect(),
            script: self.script.as_ref().map(|(imp, image)| ScriptImage {
                position: imp.position(),
                ..image.clone()
            }),
            range_warnings,
            schedule,
        };
        self.settled_on(&snapshot).then_some(checkpoint)
    }

    /// The schedule's checkpoints as `plan` says, each sent whole (board and experts read at
    /// the same moment as the machines) to the receiver returned.
    pub fn checkpoints(
        self: Arc<Self>,
        plan: &CheckpointPlan,
        behaviour: &str,
        board: &Whiteboard,
    ) -> (Checkpoints, mpsc::UnboundedReceiver<Checkpoint>) {
        let (tx, rx) = mpsc::unbounded_channel();
        let (board, behaviour) = (board.clone(), behaviour.to_string());
        let (kept, seen) = (self.clone(), board.clone());
        let ready = move || kept.settled(&seen);
        let take = move |schedule: RoundsImage| {
            let Some(taken) = self.checkpoint(&behaviour, schedule, &board) else {
                return false;
            };
            // A run whose receiver is gone has nobody to write checkpoints for.
            let _ = tx.send(taken);
            true
        };
        (
            Checkpoints::new(plan.at.clone(), plan.every, ready, take),
            rx,
        )
    }
}

/// What a theory's memory says it handled.
fn move_handled(memory: &Arc<Mutex<ReasonerMemory>>) -> impl Fn() -> u64 + Send + Sync {
    let memory = memory.clone();
    move || memory.lock().handled
}

/// Takes `checkpoint` up on `board` for a run playing `script`: the board restored, and the
/// moment the run's times count from (the checkpoint's moment before now). The machines are
/// the schedule's to judge ([`RoundsImage::fit`]).
pub(crate) fn take_up(
    checkpoint: &Checkpoint,
    script: Option<&Script>,
    board: &Whiteboard,
    ours: &[String],
) -> Result<tokio::time::Instant, BehaviourError> {
    let refused = |why: String| BehaviourError::Resume(vec![why]);
    let kept = checkpoint.script.as_ref();
    match (kept, script) {
        (Some(_), None) => return Err(refused("the checkpoint plays a script, and this run none".into())),
        (None, Some(_)) => return Err(refused("this run plays a script, and the checkpoint none".into())),
        (Some(kept), Some(script)) if kept.fingerprint != fingerprint(script) => {
            return Err(refused(format!(
                "the script is not the one the checkpoint played ({} steps then, {} now): a script is taken up where it was",
                kept.steps,
                script.steps.len()
            )))
        }
        _ => {}
    }
    let epoch = tokio::time::Instant::now().checked_sub(checkpoint.at()).ok_or_else(|| {
        refused(format!(
            "the checkpoint was taken {:?} into its run, further back than this machine's clock reaches",
            checkpoint.at()
        ))
    })?;
    if board.restore(&checkpoint.board).map_err(refused)? == Restored::Numbering {
        reclaim(checkpoint, board, ours);
    }
    Ok(epoch)
}

/// On a shared board, this process's state types go on holding what it had posted: the others
/// marked them stale when the process that posted them went, and a current value is posted
/// again by whoever owns it (signals and data, which are events, are not posted twice).
fn reclaim(checkpoint: &Checkpoint, board: &Whiteboard, ours: &[String]) {
    for ty in &checkpoint.board.types {
        let Some(latest) = ty.latest.as_ref().filter(|m| ours.contains(&m.module)) else {
            continue;
        };
        if ty.kind == KindName::State {
            board.post(&latest.module, &ty.ty, Value::from_json(&latest.value));
        }
    }
}
