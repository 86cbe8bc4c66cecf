//! The order of different machines' clocks ([`crate::clocks`]) as the symbolic engine applies
//! it. The ringlet on an open world knows only the ringing machine's control, so what the
//! explicit stepper reads of the others is written here over their fields: an arrival's
//! writes (a step a value of the flags it copies), and each leaf's **guard**, the rule of
//! [`crate::clocks::agrees`] as a diagram over the world before the step.

use super::{Encoding, Field};
use crate::clocks::{bounds, heard_later, implied, ordered};
use crate::search::Search;
use crate::world::Control;
use biodivine_lib_bdd::{Bdd, BddPartialValuation};

/// What an arrival of machine `k` copies: the "arrived this round" flag of each machine ranked
/// before it, one value each (the machines after it have not rung this round). One empty
/// copy for a step that is not an arrival into a state whose clocks are ordered.
pub(super) fn arrivals(model: &Search, k: usize, before: &Control) -> Vec<Vec<(usize, bool)>> {
    let state = &model.machines[k].states[usize::from(before.state)];
    if !before.just_entered || model.clock_ranks[k].is_none() || !ordered(state) {
        return vec![Vec::new()];
    }
    let earlier: Vec<usize> = (0..k).filter(|&j| model.clock_ranks[j].is_some()).collect();
    (0..1usize << earlier.len())
        .map(|bits| {
            (earlier.iter().enumerate())
                .map(|(i, &j)| (j, bits >> i & 1 == 1))
                .collect()
        })
        .collect()
}

/// A step's clock-order fields: machine `k`'s own bits are no part of what its control writes
/// (nor of what it needs: [`Encoding::set_ringing_control`]); an arrival writes its row (the
/// copied flags of `copied`, which it needs), its column in the others' rows and its flag.
pub(super) fn needs_and_writes(
    model: &Search,
    enc: &Encoding,
    k: usize,
    before: &Control,
    copied: &[(usize, bool)],
    needs: &mut BddPartialValuation,
    writes: &mut BddPartialValuation,
) {
    let mine = &enc.machines[k];
    for v in mine.arrived.bits.iter().chain(&mine.order.bits) {
        writes.unset_value(*v);
    }
    let Some(rank) = model.clock_ranks[k] else {
        return;
    };
    if !before.just_entered {
        return;
    }
    let takes_part = ordered(&model.machines[k].states[usize::from(before.state)]);
    for (j, r) in model.clock_ranks.iter().enumerate() {
        let Some(r) = *r else { continue };
        if j == k {
            continue;
        }
        let copy = copied.iter().find(|(i, _)| *i == j).map(|&(_, v)| v);
        if let Some(v) = copy {
            needs.set_value(enc.machines[j].arrived.bits[0], v);
        }
        writes.set_value(mine.order.bits[usize::from(r)], copy == Some(true));
        writes.set_value(enc.machines[j].order.bits[usize::from(rank)], takes_part);
    }
    if let Some(&v) = mine.arrived.bits.first() {
        writes.set_value(v, takes_part && heard_later(&model.clock_ranks, k));
    }
}

/// The worlds in which machine `k` in its state of `before` may have `mask` due at its
/// snapshot as the others' clocks stand ([`crate::clocks::agrees`]), over the world before the
/// step: an arrival's own bits are those it writes (`copied`), not the world's.
pub(super) fn guard(
    model: &Search,
    enc: &Encoding,
    k: usize,
    before: &Control,
    mask: u16,
    copied: &[(usize, bool)],
) -> Bdd {
    let vars = &enc.vars;
    let Some(rank) = model.clock_ranks[k] else {
        return vars.mk_true();
    };
    let state = &model.machines[k].states[usize::from(before.state)];
    let is = |f: &Field, i: usize| {
        let mut cube = BddPartialValuation::empty();
        f.set(i, &mut cube);
        enc.mk(&cube)
    };
    let mut all = vars.mk_true();
    for (j, r) in model.clock_ranks.iter().enumerate() {
        let Some(r) = *r else { continue };
        if j == k {
            continue;
        }
        let theirs = &enc.machines[j];
        let (mine_older, theirs_older) = match before.just_entered {
            true => {
                let copy = copied.iter().any(|&(i, v)| i == j && v);
                (bool_bdd(enc, copy), vars.mk_true())
            }
            false => (
                vars.mk_var(enc.machines[k].order.bits[usize::from(r)]),
                vars.mk_var(theirs.order.bits[usize::from(rank)]),
            ),
        };
        let older = (&mine_older, &theirs_older);
        let broken = settled_broken(model, enc, (k, j), state, mask, older);
        let settled = is(&theirs.status, 0).and(&is(&theirs.just_entered, 0));
        let left = left_broken(model, enc, j, state, mask, &mine_older, &theirs_older);
        let moved = is(&theirs.left_due, 0).and(&is(&theirs.left_wait, 0)).not();
        all = all
            .and_not(&moved.not().and(&settled).and(&broken))
            .and_not(&moved.and(&left));
    }
    all
}

/// Where `mask` of a machine in `state` breaks what machine `j`, having left its state earlier
/// in the round, kept ([`crate::clocks::left`]): a constant test not in `mask` no longer than
/// `j`'s longest due one, when its machine is the older; one in `mask` of its arrival's clocks
/// no shorter than `j`'s shortest not due, when `j`'s is.
fn left_broken(
    model: &Search,
    enc: &Encoding,
    j: usize,
    state: &crate::model::StateModel,
    mask: u16,
    mine_older: &Bdd,
    theirs_older: &Bdd,
) -> Bdd {
    let (due, not_due) = bounds(state, mask);
    let theirs = &enc.machines[j];
    let numbered = |f: &Field, keep: &dyn Fn(u64) -> bool| {
        let mut any = enc.vars.mk_false();
        for (n, &d) in model.clock_durations.iter().enumerate() {
            if keep(d) {
                let mut cube = BddPartialValuation::empty();
                f.set(n + 1, &mut cube);
                any = any.or(&enc.mk(&cube));
            }
        }
        any
    };
    let mut broken = enc.vars.mk_false();
    if let Some(shortest_not_due) = not_due {
        let longer = numbered(&theirs.left_due, &|d| d >= shortest_not_due);
        broken = broken.or(&mine_older.and(&longer));
    }
    if let Some(longest_due) = due {
        let shorter = numbered(&theirs.left_wait, &|d| d <= longest_due);
        broken = broken.or(&theirs_older.and(&shorter));
    }
    broken
}

/// Where `mask` of machine `k` in `state` breaks the rule against machine `j` in its state: a
/// due test of `j`'s arrival implies one of `k` not in `mask`, when `k`'s machine is the
/// older; or (`j` rang before `k`) one in `mask` implies one of `j` not due, when `j`'s is.
fn settled_broken(
    model: &Search,
    enc: &Encoding,
    (k, j): (usize, usize),
    state: &crate::model::StateModel,
    mask: u16,
    (mine_older, theirs_older): (&Bdd, &Bdd),
) -> Bdd {
    let vars = &enc.vars;
    let theirs = &enc.machines[j];
    let due = |bit: usize| vars.mk_var(theirs.time.bits[bit]);
    let mut broken = vars.mk_false();
    for (t, other) in model.machines[j].states.iter().enumerate() {
        let mut here = vars.mk_false();
        for (y, x) in implied(state, other) {
            if mask & (1 << x) == 0 {
                here = here.or(&mine_older.and(&due(y)));
            }
        }
        if j < k {
            for (y, x) in implied(other, state) {
                if mask & (1 << y) != 0 {
                    here = here.or(&theirs_older.and(&due(x).not()));
                }
            }
        }
        if !here.is_false() {
            let mut cube = BddPartialValuation::empty();
            theirs.state.set(t, &mut cube);
            broken = broken.or(&enc.mk(&cube).and(&here));
        }
    }
    broken
}

fn bool_bdd(enc: &Encoding, value: bool) -> Bdd {
    match value {
        true => enc.vars.mk_true(),
        false => enc.vars.mk_false(),
    }
}
