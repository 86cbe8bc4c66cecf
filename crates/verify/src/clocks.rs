//! How the clocks of different machines are ordered (docs/spec/behaviour.md §6, "Time"): a
//! round has one moment, so a machine that arrived in its state no later than another has
//! clocks at least as old, and a constant test of it no longer than a due one of the other's
//! arrival is due too (a 0.5 s timeout of one machine does not lose to a 3 s one of another
//! started with it).
//!
//! What the state keeps for it, per machine that takes part (its **rank**, [`ranks`]):
//! [`Control::order`], bit `r` set where its last arrival was no later than that of the machine
//! of rank `r`, and [`Control::arrived`], that it arrived in this round (a new round clears it),
//! so that two arrivals of one round are known to share their moment. An arrival writes only
//! its own machine's row and column, reading the others' `arrived` ([`arrive`]). A command
//! leaves them as they are: they are facts about the machine's last arrival and this round's
//! moment, true until its next arrival, whatever its mode.
//!
//! A machine that leaves its state forgets its due tests; the others that ring after it in
//! the same round (the same moment) still need them, so it keeps until the round ends what
//! they imply, [`Control::left_due`] and [`Control::left_wait`] ([`left`]). At a snapshot
//! ([`agrees`]) another machine is compared by what it left with, if it left its state in
//! this round, else by its due tests if it is running and has arrived in its state, else not
//! at all.
//!
//! The explicit engine and SPIN's model read these rules as they step; the symbolic engine
//! writes [`agrees`] as a diagram over the other machines' fields from [`implied`].

use crate::model::{MachineModel, StateModel};
use crate::world::{Control, Status, SystemState};

/// At most this many machines take part (a row of bits each of the others): past them, a
/// machine's clocks are unordered against the others' (a sound loss, and a bounded state).
pub(crate) const MAX_ORDERED: usize = 8;

/// At most this many constant durations among them, numbered from 1 in a byte; past that no
/// machine's clocks are ordered.
const MAX_DURATIONS: usize = u8::MAX as usize;

/// Each machine's rank among those whose clocks are ordered: the machines with a constant time
/// test, in manifest order, the first [`MAX_ORDERED`] of them; none where only one has one
/// (there is nothing to order it against, and the state keeps nothing for it) or where they
/// have more than [`MAX_DURATIONS`] durations.
pub(crate) fn ranks(machines: &[MachineModel]) -> Vec<Option<u8>> {
    let mut next = 0u8;
    let ranks: Vec<Option<u8>> = machines
        .iter()
        .map(|m| {
            let takes_part = m.states.iter().any(ordered) && usize::from(next) < MAX_ORDERED;
            takes_part.then(|| {
                next += 1;
                next - 1
            })
        })
        .collect();
    match next {
        2.. if durations(machines, &ranks).len() <= MAX_DURATIONS => ranks,
        _ => vec![None; machines.len()],
    }
}

/// Whether a machine that takes part rings after machine `k` in a round: only such a machine
/// reads what `k` keeps for the rest of the round ([`Control::arrived`], [`left`]), so the
/// last keeps nothing.
pub(crate) fn heard_later(ranks: &[Option<u8>], k: usize) -> bool {
    ranks[k].is_some() && ranks[k + 1..].iter().any(Option::is_some)
}

/// Every constant duration of the machines that take part, shortest first: what
/// [`Control::left_due`] and [`Control::left_wait`] number (from 1).
pub(crate) fn durations(machines: &[MachineModel], ranks: &[Option<u8>]) -> Vec<u64> {
    let mut all: Vec<u64> = (machines.iter().zip(ranks))
        .filter(|(_, r)| r.is_some())
        .flat_map(|(m, _)| m.states.iter().flat_map(|s| &s.time_tests))
        .filter_map(|t| t.micros)
        .collect();
    all.sort_unstable();
    all.dedup();
    all
}

/// Of `state`'s constant tests with `due` due: the longest due on a clock its arrival started
/// and the shortest not due. What a machine leaving with them keeps for the round ([`left`]),
/// and what a machine ringing after it is compared with by them.
pub(crate) fn bounds(state: &StateModel, due: u16) -> (Option<u64>, Option<u64>) {
    let tests = || state.time_tests.iter().enumerate();
    let longest_due = tests()
        .filter(|(i, t)| due & (1 << i) != 0 && state.arrival_starts(t.clock))
        .filter_map(|(_, t)| t.micros)
        .max();
    let shortest_waiting = tests()
        .filter(|(i, _)| due & (1 << i) == 0)
        .filter_map(|(_, t)| t.micros)
        .min();
    (longest_due, shortest_waiting)
}

/// Duration `d`'s number in `durations`, from 1 (0: none, or not among them).
pub(crate) fn number(durations: &[u64], d: Option<u64>) -> u8 {
    d.and_then(|d| durations.iter().position(|&e| e == d))
        .map_or(0, |i| i as u8 + 1)
}

/// What a machine leaving `state` with `due` due at its snapshot keeps for the rest of the
/// round, its [`bounds`] numbered in `durations`: the longest due (the others' tests no longer
/// are due, those of a machine that arrived no later) and the shortest not due (a test of one
/// that arrived no earlier is not due unless shorter).
pub(crate) fn left(durations: &[u64], state: &StateModel, due: u16) -> (u8, u8) {
    let (longest, shortest) = bounds(state, due);
    (number(durations, longest), number(durations, shortest))
}

/// Whether an arrival into `state` takes part in the order: it has a constant time test.
pub(crate) fn ordered(state: &StateModel) -> bool {
    state.time_tests.iter().any(|t| t.micros.is_some())
}

/// The pairs `(y, x)` an order implies, where `earlier`'s machine arrived no later than
/// `later`'s: `y` a constant test of `later` whose clock its arrival started (so as old as
/// that arrival), `x` a constant test of `earlier` of no longer duration (on a clock at least
/// as old). At any one moment, `y` is then due only if `x` is.
pub(crate) fn implied<'s>(
    earlier: &'s StateModel,
    later: &'s StateModel,
) -> impl Iterator<Item = (usize, usize)> + 's {
    let started = |t: &&crate::model::TimeTest| later.arrival_starts(t.clock);
    later
        .time_tests
        .iter()
        .enumerate()
        .filter(move |(_, y)| started(y))
        .filter_map(|(i, y)| Some((i, y.micros?)))
        .flat_map(move |(i, d)| {
            (earlier.time_tests.iter().enumerate())
                .filter(move |(_, x)| x.micros.is_some_and(|c| c <= d))
                .map(move |(j, _)| (i, j))
        })
}

/// Machine `k`'s arrival into its current state, in `w`: into a state that takes part, its
/// arrival is the latest (no earlier than every other's) and as early as those of this round;
/// into one that does not, its bits are cleared (nothing of it is compared).
pub(crate) fn arrive(
    machines: &[MachineModel],
    ranks: &[Option<u8>],
    w: &mut SystemState,
    k: usize,
) {
    let Some(rank) = ranks[k] else { return };
    let state = &machines[k].states[usize::from(w.machines[k].state)];
    let takes_part = ordered(state);
    let mut row = 0u8;
    for (j, r) in ranks.iter().enumerate() {
        let Some(r) = *r else { continue };
        if j == k {
            continue;
        }
        let other = &mut w.machines[j];
        if takes_part {
            other.order |= 1 << rank;
            row |= u8::from(other.arrived) << r;
        } else {
            other.order &= !(1 << rank);
        }
    }
    let c = &mut w.machines[k];
    c.order = row;
    c.arrived = takes_part && heard_later(ranks, k);
}

/// Whether machine `k`, in its state in `w` (its arrival, if any, already made), may have the
/// time tests `mask` due at its snapshot as the other machines' clocks stand: no due test of
/// one that arrived no later than `k` lacks what it implies in `k`, and, of one that rang in
/// this round (before `k`: its tests stand at this round's moment too) and arrived no later,
/// nothing `k`'s `mask` implies is missing.
pub(crate) fn agrees(
    machines: &[MachineModel],
    ranks: &[Option<u8>],
    durations: &[u64],
    w: &SystemState,
    k: usize,
    mask: u16,
) -> bool {
    let Some(rank) = ranks[k] else { return true };
    let me = &w.machines[k];
    let state = &machines[k].states[usize::from(me.state)];
    let due = |c: &Control, bit: usize| c.time & (1 << bit) != 0;
    ranks.iter().enumerate().all(|(j, r)| {
        let Some(r) = *r else { return true };
        let other = &w.machines[j];
        if j == k {
            return true;
        }
        let mine_older = me.order & (1 << r) != 0;
        let theirs_older = other.order & (1 << rank) != 0;
        if other.left_due != 0 || other.left_wait != 0 {
            return agrees_with_left(durations, state, mask, other, mine_older, theirs_older);
        }
        if other.status != Status::Running || other.just_entered {
            return true;
        }
        let theirs = &machines[j].states[usize::from(other.state)];
        let theirs_older = j < k && theirs_older;
        (!mine_older || implied(state, theirs).all(|(y, x)| !due(other, y) || mask & (1 << x) != 0))
            && (!theirs_older
                || implied(theirs, state).all(|(y, x)| mask & (1 << y) == 0 || due(other, x)))
    })
}

/// [`agrees`] against a machine that left its state earlier in this round, by what it kept
/// ([`left`]).
fn agrees_with_left(
    durations: &[u64],
    state: &StateModel,
    mask: u16,
    other: &Control,
    mine_older: bool,
    theirs_older: bool,
) -> bool {
    let duration = |n: u8| durations.get(usize::from(n).wrapping_sub(1)).copied();
    let (longest_due, shortest_waiting) = bounds(state, mask);
    // A test of mine no longer than its longest due one is due; one of my arrival's no
    // shorter than its shortest not due is not.
    let implied_broken = mine_older
        && duration(other.left_due).is_some_and(|d| shortest_waiting.is_some_and(|w| w <= d));
    let implying_broken = theirs_older
        && duration(other.left_wait).is_some_and(|w| longest_due.is_some_and(|d| d >= w));
    !implied_broken && !implying_broken
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::TimeTest;
    use proclaim_fsm::Expr;

    fn state(tests: &[(Option<u64>, Option<usize>)], arrival_enters: &[usize]) -> StateModel {
        StateModel {
            name: "S".into(),
            transitions: Vec::new(),
            time_tests: tests
                .iter()
                .map(|&(micros, clock)| TimeTest {
                    call: Expr::Int(micros.unwrap_or(0) as i64),
                    micros,
                    clock,
                })
                .collect(),
            arrival_enters: arrival_enters.to_vec(),
            time_order: Vec::new(),
        }
    }

    #[test]
    fn a_due_test_of_a_later_arrival_implies_the_no_longer_tests_of_an_earlier_one() {
        let half = state(&[(Some(500_000), None), (Some(4_000_000), None)], &[]);
        let three = state(&[(Some(3_000_000), None)], &[]);
        // Three seconds since the later arrival: the earlier machine's half second has passed,
        // its four seconds need not have.
        assert_eq!(implied(&half, &three).collect::<Vec<_>>(), vec![(0, 0)]);
        // Half a second since the later arrival says nothing of the earlier's three seconds;
        // four seconds do.
        assert_eq!(implied(&three, &half).collect::<Vec<_>>(), vec![(1, 0)]);
        // A computed duration orders nothing.
        let computed = state(&[(None, None)], &[]);
        assert_eq!(implied(&computed, &three).count(), 0);
        assert_eq!(implied(&three, &computed).count(), 0);
    }

    #[test]
    fn only_a_clock_the_arrival_started_is_as_old_as_the_arrival() {
        // The later state's 3 s counts from a composite entered before its arrival: it may be
        // older than the other machine's clocks, so it implies nothing of them.
        let inside = state(&[(Some(3_000_000), Some(0)), (Some(5_000_000), None)], &[]);
        let half = state(&[(Some(500_000), None)], &[]);
        assert_eq!(implied(&half, &inside).collect::<Vec<_>>(), vec![(1, 0)]);
        let entered = state(&[(Some(3_000_000), Some(0))], &[0]);
        assert_eq!(implied(&half, &entered).collect::<Vec<_>>(), vec![(0, 0)]);
    }
}
