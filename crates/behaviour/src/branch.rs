//! A branch of a recording (`proclaim run --branch REC --at ROUND`, `docs/spec/behaviour.md`
//! §3.5): the recorded run replayed up to a round as `proclaim test` replays it, then live from
//! there, so a person (or nothing) changes what the world does next; recorded, the branch is a
//! recording of its own that names its parent and round.

use crate::recorded::{
    answer_as_recorded, replay_recording, split_outside, BranchOf, Difference, RecordedFeed,
    Recording, ReplayOutcome,
};
use crate::{Behaviour, BehaviourError};
use proclaim_board::Whiteboard;
use proclaim_runner::Rounds;
use rustc_hash::FxHashSet;
use std::future::Future;
use std::sync::Arc;

/// A recording to replay up to `of.round`, and go on live from.
#[derive(Clone, Debug)]
pub struct Branch {
    pub recording: Recording,
    pub of: BranchOf,
    /// Told when the replay is over and the run goes on live: a run that replayed on the
    /// paused clock lets real time run from there.
    pub live: Arc<tokio::sync::Notify>,
}

impl Branch {
    /// The branch of `recording` (read from `parent`) at the start of `round`: refused, saying
    /// why, before its first round (there is nothing to replay) or after the round after its
    /// last.
    pub fn new(recording: Recording, parent: String, round: u64) -> Result<Branch, String> {
        let last = recording
            .ringlets
            .iter()
            .map(|r| r.round)
            .max()
            .unwrap_or(0);
        if round < 2 {
            return Err(format!(
                "a branch starts at round 2 or later: before round {round} there is nothing to go back to (run the behaviour without --branch)"
            ));
        }
        if round > last.saturating_add(1) {
            return Err(format!(
                "round {round} is past the recording, whose last round is {last}: a branch starts at round 2 to {}",
                last.saturating_add(1)
            ));
        }
        Ok(Branch {
            recording,
            of: BranchOf { parent, round },
            live: Arc::default(),
        })
    }

    /// Where the behaviour as it is now, replayed up to the branch's round, does not do what
    /// the recording did: the branch then starts where the behaviour is now, not where the
    /// recording was. Call it from a plain thread (it replays on a clock of its own).
    pub fn replayed_differently(
        &self,
        behaviour: &Behaviour,
    ) -> Result<Option<Difference>, std::io::Error> {
        let cut = self.of.round;
        let before = Recording {
            messages: self.recording.messages.clone(),
            ringlets: (self.recording.ringlets.iter())
                .filter(|r| r.round < cut)
                .cloned()
                .collect(),
            events: (self.recording.events.iter())
                .filter(|e| e.round() < cut)
                .cloned()
                .collect(),
            branch: None,
        };
        Ok(match replay_recording(behaviour, &before)? {
            ReplayOutcome::Same { .. } => None,
            ReplayOutcome::Differs(difference) => Some(difference),
        })
    }

    /// The first line of the branch's own recording.
    pub fn header(&self) -> String {
        self.of.header()
    }

    /// The schedule fed by the recording until the branch's round, then live.
    pub(crate) fn feeding(
        &self,
        rounds: Option<Rounds>,
        behaviour: &Behaviour,
    ) -> Result<Option<Rounds>, BehaviourError> {
        let Some(rounds) = rounds else {
            return Err(BehaviourError::Branch(
                "the machines run concurrently (the manifest's schedule = \"concurrent\"), with no rounds to branch at".into(),
            ));
        };
        let (outside, _) = self.outside(behaviour);
        let feed = RecordedFeed::until(&self.recording, outside, self.of.round);
        Ok(Some(rounds.fed_then_live(feed, self.live.clone())))
    }

    /// What answers the atoms that outside experts answered before the branch's round, query
    /// by query as they did; none when they answered nothing.
    pub(crate) fn answers(
        &self,
        behaviour: &Behaviour,
        board: &Whiteboard,
    ) -> Option<(Vec<String>, impl Future<Output = ()> + Send + 'static)> {
        let (_, answers) = self.outside(behaviour);
        if answers.is_empty() {
            return None;
        }
        let atoms = answers.keys().cloned().collect();
        Some((atoms, answer_as_recorded(board.clone(), answers)))
    }

    fn outside(
        &self,
        behaviour: &Behaviour,
    ) -> (crate::recorded::Outside, crate::recorded::Answers) {
        let machines: Vec<String> = behaviour
            .machines
            .iter()
            .map(|m| m.machine.name.clone())
            .collect();
        let inside: FxHashSet<String> = machines
            .iter()
            .cloned()
            .chain(behaviour.theories.iter().map(|t| t.name.clone()))
            .collect();
        split_outside(&self.recording, &inside, &machines, Some(self.of.round))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::read_recording;

    fn recording(last_round: u64) -> Recording {
        let line =
            format!(r#"{{"ringlet":{{"at_us":0,"machine":0,"round":{last_round},"seq":1}}}}"#);
        read_recording(&line).unwrap()
    }

    #[test]
    fn a_branch_starts_from_round_two_to_the_round_after_the_last() {
        let refused = |last, round| Branch::new(recording(last), "r".into(), round).err();
        assert!(refused(5, 1).unwrap().contains("round 2 or later"));
        assert_eq!(refused(5, 2), None);
        assert_eq!(refused(5, 6), None);
        assert!(refused(5, 7).unwrap().contains("whose last round is 5"));
        // A recording that claims the last round there is cannot make the check overflow.
        assert_eq!(refused(u64::MAX, u64::MAX), None);
    }
}
