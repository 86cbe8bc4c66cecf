//! Why a run's theory answered a label as it did: a recording's messages replayed, in the
//! board's order, into a reasoner expert of each of the behaviour's theories up to the query, so
//! the answer can be explained from the inputs the reasoner held then (`proclaim explain
//! --recording`). The expert reads its inputs and queries from one subscription in sequence
//! order, so the inputs before a query's sequence number are exactly the ones it had applied.

use crate::load::Behaviour;
use crate::recorded::Recording;
use proclaim_board::{Value, QUERY_TYPE};
use proclaim_cdl::Explanation;
use proclaim_experts::ReasonerExpert;
use rustc_hash::FxHashSet;
use std::fmt;

/// A label a machine asked a theory of the behaviour in a recorded run.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TheoryAnswer {
    pub round: u64,
    pub machine: String,
    pub label: String,
    pub theory: String,
    /// The answer the recording holds (none if the run ended before it was posted).
    pub recorded: Option<bool>,
    /// The answer the replayed expert gives.
    pub replayed: bool,
}

/// Why a label in a run cannot be explained.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum WhyError {
    /// No theory of the behaviour answers the label.
    NoTheory {
        label: String,
        theories: Vec<String>,
    },
    /// The recording has no query of the label in that round (by that machine); the rounds
    /// that have one.
    NotAsked {
        label: String,
        round: u64,
        asked_in: Vec<u64>,
    },
}

impl fmt::Display for WhyError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            WhyError::NoTheory { label, theories } if theories.is_empty() => {
                write!(f, "`{label}`: the behaviour has no theory to explain it")
            }
            WhyError::NoTheory { label, theories } => write!(
                f,
                "`{label}` is no output of the behaviour's theories ({})",
                theories.join(", ")
            ),
            WhyError::NotAsked {
                label,
                round,
                asked_in,
            } if asked_in.is_empty() => write!(
                f,
                "no machine asked `{label}` of a theory in this recording (round {round} wanted)"
            ),
            WhyError::NotAsked {
                label,
                round,
                asked_in,
            } => {
                let shown: Vec<String> = asked_in.iter().take(12).map(u64::to_string).collect();
                let more = if asked_in.len() > 12 { ", …" } else { "" };
                write!(
                    f,
                    "`{label}` was not asked in round {round}; it was in rounds {}{more}",
                    shown.join(", ")
                )
            }
        }
    }
}

impl std::error::Error for WhyError {}

/// A label as its theory held it when it was asked: what was asked, and the expert then.
pub struct Held {
    pub asked: TheoryAnswer,
    expert: ReasonerExpert,
}

impl Held {
    /// The proof, or failure, of the label `depth` levels down, as `explain --set` gives it.
    pub fn explain(&mut self, depth: usize) -> Explanation {
        self.expert
            .explain(&self.asked.label, depth)
            .expect("the expert owns the label it was asked")
    }

    /// The theory's inputs then: message type and value (`None`: unknown).
    pub fn inputs(&self) -> Vec<(String, Option<bool>)> {
        self.expert.inputs_held()
    }
}

/// Every label the recorded run asked of the behaviour's theories, in order, with the recorded
/// and the replayed answer.
pub fn theory_answers(behaviour: &Behaviour, recording: &Recording) -> Vec<TheoryAnswer> {
    let mut all = Vec::new();
    replay(behaviour, recording, &mut |asked, _| {
        all.push(asked.clone());
        false
    });
    all
}

/// `label` as its theory held it when asked in `round` (by `machine`, if given; the round's
/// first query of it otherwise).
pub fn held_at(
    behaviour: &Behaviour,
    recording: &Recording,
    label: &str,
    round: u64,
    machine: Option<&str>,
) -> Result<Held, WhyError> {
    if !behaviour
        .theories
        .iter()
        .any(|t| expert(t).declaration().answers.iter().any(|a| a == label))
    {
        let theories = behaviour.theories.iter().map(|t| t.name.clone()).collect();
        let label = label.to_string();
        return Err(WhyError::NoTheory { label, theories });
    }
    let mut asked_in = Vec::new();
    let mut held = None;
    replay(behaviour, recording, &mut |asked, expert| {
        if asked.label != label {
            return false;
        }
        if !asked_in.contains(&asked.round) {
            asked_in.push(asked.round);
        }
        let wanted = asked.round == round && machine.is_none_or(|m| m == asked.machine);
        if wanted {
            held = Some((asked.clone(), expert.take()));
        }
        wanted
    });
    match held {
        Some((asked, Some(expert))) => Ok(Held { asked, expert }),
        _ => Err(WhyError::NotAsked {
            label: label.to_string(),
            round,
            asked_in,
        }),
    }
}

fn expert(t: &crate::loaded::LoadedTheory) -> ReasonerExpert {
    ReasonerExpert::new(&t.name, t.theory.clone(), &t.mapping).with_limits(t.limits)
}

/// Replays the recording's messages into an expert of each theory; at each query of one of
/// their outputs, tells `seen` what was asked and offers the answering expert (taken out of
/// the replay when `seen` takes it); stops once `seen` is true.
pub(crate) fn replay(
    behaviour: &Behaviour,
    recording: &Recording,
    seen: &mut dyn FnMut(&TheoryAnswer, &mut Option<ReasonerExpert>) -> bool,
) {
    let mut experts: Vec<Option<ReasonerExpert>> =
        behaviour.theories.iter().map(|t| Some(expert(t))).collect();
    // What each theory answers, looked up at every query.
    let answers: Vec<FxHashSet<String>> = experts
        .iter()
        .flatten()
        .map(|e| e.declaration().answers.into_iter().collect())
        .collect();
    let messages = &recording.messages;
    for (i, m) in messages.iter().enumerate() {
        if m.ty == QUERY_TYPE {
            let label = match &m.value {
                Value::Str(atom) => atom.clone(),
                other => other.to_string(),
            };
            // Who answered is who posted the label next (a script may answer a theory's label
            // in its place); a run that ended first leaves it to the theory that declares it.
            let answer = messages[i + 1..].iter().find(|a| a.ty == label);
            let owns = |t: &usize| {
                experts[*t].is_some()
                    && answers[*t].contains(&label)
                    && answer.is_none_or(|a| a.module == behaviour.theories[*t].name)
            };
            let Some(t) = (0..experts.len()).find(owns) else {
                continue;
            };
            let theory = behaviour.theories[t].name.clone();
            let recorded = answer.map(|a| a.value.truthy());
            let replayed = experts[t]
                .as_mut()
                .and_then(|e| e.answer(&label))
                .unwrap_or(false);
            let asked = TheoryAnswer {
                round: round_of(recording, m.seq),
                machine: m.module.clone(),
                label,
                theory,
                recorded,
                replayed,
            };
            if seen(&asked, &mut experts[t]) {
                return;
            }
            continue;
        }
        for e in experts.iter_mut().flatten() {
            e.apply(&m.ty, &m.value);
        }
    }
}

/// The round of the ringlet a message of sequence number `seq` was posted in: the last ringlet
/// that began before it.
fn round_of(recording: &Recording, seq: u64) -> u64 {
    let before = recording.ringlets.partition_point(|r| r.seq < seq);
    before
        .checked_sub(1)
        .map_or(0, |i| recording.ringlets[i].round)
}
