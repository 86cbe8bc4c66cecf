//! Goals (an algorithm's question about one literal), their proof conditions (cdl.md §4) and
//! their successors in the goal graph, shared by every evaluation strategy of the session.
//! Besides the literals' goals there are the implication aggregates of
//! [`crate::engine::Implications`], which stand for the strict rules of implicit resolvents.

use crate::engine::Engine;
use crate::literal::Lit;

pub(crate) use crate::goal_number::{goal, kind_of, lit_of, Goal, ATTACK, BETA, KINDS, PI, SUP};

/// How a condition reads a sub-goal: as support (read positively) or through an attacker's
/// antecedent (read negatively: a true sub-goal makes the condition harder to meet).
pub(crate) type Read = bool;
pub(crate) const SUPPORT_READ: Read = false;
pub(crate) const ATTACK_READ: Read = true;

/// The proof condition of `goal`, reading the values of its sub-goals through `value`, which is
/// told whether each read is a support or an attack read. `mu` is the monotonic closure, which
/// never depends on a history.
pub(crate) fn condition(
    engine: &Engine,
    mu: &[bool],
    goal: Goal,
    value: &mut dyn FnMut(Goal, Read) -> bool,
) -> bool {
    if engine.implications.any() && engine.is_aggregate(goal) {
        return aggregate_condition(engine, goal, value);
    }
    let q = lit_of(goal);
    let nq = q.complement();
    let kind = kind_of(goal);
    let applicable =
        |rule: u32, kind: u32, read: Read, value: &mut dyn FnMut(Goal, Read) -> bool| {
            engine
                .body(rule)
                .iter()
                .all(|&a| value(self::goal(a, kind), read))
        };
    match kind {
        BETA | PI => {
            if mu[q.index()] {
                return true;
            }
            if mu[nq.index()] {
                return false;
            }
            let supporters = engine.rules_for(q);
            let supported = supporters
                .iter()
                .any(|&r| engine.kind(r).supports() && applicable(r, kind, SUPPORT_READ, value))
                || implied(engine, q, kind, SUPPORT_READ, value);
            if !supported {
                return false;
            }
            // An attacker counts when its antecedent is proved (β) or merely supported (π).
            let attacker_kind = if kind == BETA { BETA } else { SUP };
            // The strict rules of implicit resolvents are unlabelled: no priority beats them.
            if implied(engine, nq, attacker_kind, ATTACK_READ, value) {
                return false;
            }
            for &s in engine.rules_for(nq) {
                if !applicable(s, attacker_kind, ATTACK_READ, value) {
                    continue;
                }
                let beaten = engine.superiors_of(s).iter().any(|&t| {
                    engine.head(t) == q
                        && engine.kind(t).supports()
                        && applicable(t, kind, SUPPORT_READ, value)
                });
                if !beaten {
                    return false;
                }
            }
            true
        }
        _ => {
            if mu[q.index()] {
                return true;
            }
            // Implicit resolvents' rules have no superiors to stand against them.
            if implied(engine, q, SUP, SUPPORT_READ, value) {
                return true;
            }
            engine.rules_for(q).iter().any(|&r| {
                engine.kind(r).supports()
                    && applicable(r, SUP, SUPPORT_READ, value)
                    && engine
                        .superiors_of(r)
                        .iter()
                        .all(|&s| engine.head(s) != nq || !applicable(s, PI, ATTACK_READ, value))
            })
        }
    }
}

/// An aggregate's condition: some literal it stands for is proved (out of line: the common
/// theory has none, and the literals' conditions stay small enough to inline).
#[cold]
#[inline(never)]
fn aggregate_condition(
    engine: &Engine,
    goal: Goal,
    value: &mut dyn FnMut(Goal, Read) -> bool,
) -> bool {
    let (rep, kind) = engine.aggregate_parts(goal);
    let i = &engine.implications;
    i.direct
        .row(rep as usize)
        .iter()
        .any(|&x| value(self::goal(Lit(x), kind), SUPPORT_READ))
        || i.chained
            .row(rep as usize)
            .iter()
            .any(|&r| value(engine.aggregate_goal(r, kind), SUPPORT_READ))
}

#[cold]
#[inline(never)]
fn aggregate_successors(
    engine: &Engine,
    goal: Goal,
    out: &mut Vec<u32>,
    keep: &impl Fn(Goal) -> bool,
) {
    let (rep, kind) = engine.aggregate_parts(goal);
    let i = &engine.implications;
    let reads = i
        .direct
        .row(rep as usize)
        .iter()
        .map(|&x| self::goal(Lit(x), kind));
    let chained = i
        .chained
        .row(rep as usize)
        .iter()
        .map(|&r| engine.aggregate_goal(r, kind));
    out.extend(reads.chain(chained).filter(|&g| keep(g)));
}

/// Whether some implicit resolvent's rule `x -> lit` applies: `x` is another member of `lit`'s
/// cycle of implications, or the aggregate of what leads into the cycle holds.
#[inline]
fn implied(
    engine: &Engine,
    lit: Lit,
    kind: u32,
    read: Read,
    value: &mut dyn FnMut(Goal, Read) -> bool,
) -> bool {
    engine.implications.any() && implied_through_clauses(engine, lit, kind, read, value)
}

/// [`implied`]'s work, out of line: a theory without two-literal clauses pays one branch, and
/// `condition` stays small enough to inline into the session's loop (it shows on chains).
#[cold]
#[inline(never)]
fn implied_through_clauses(
    engine: &Engine,
    lit: Lit,
    kind: u32,
    read: Read,
    value: &mut dyn FnMut(Goal, Read) -> bool,
) -> bool {
    engine
        .implications
        .cycle_mates(lit)
        .any(|x| value(goal(x, kind), read))
        || engine
            .aggregate_for(lit, kind)
            .is_some_and(|a| value(a, read))
}

/// The goals [`implied`] may read, flagged with `flag`.
#[inline]
fn push_implied(
    engine: &Engine,
    lit: Lit,
    kind: u32,
    flag: u32,
    out: &mut Vec<u32>,
    keep: &impl Fn(Goal) -> bool,
) {
    if engine.implications.any() {
        push_implied_through_clauses(engine, lit, kind, flag, out, keep);
    }
}

/// [`push_implied`]'s work, out of line for the same reason as [`implied_through_clauses`].
#[cold]
#[inline(never)]
fn push_implied_through_clauses(
    engine: &Engine,
    lit: Lit,
    kind: u32,
    flag: u32,
    out: &mut Vec<u32>,
    keep: &impl Fn(Goal) -> bool,
) {
    let mates = engine.implications.cycle_mates(lit).map(|x| goal(x, kind));
    for g in mates.chain(engine.aggregate_for(lit, kind)) {
        if keep(g) {
            out.push(g | flag);
        }
    }
}

/// Pushes the sub-goals `condition` may read, attack edges marked with [`ATTACK`]; `keep`
/// filters out goals whose value is already settled.
pub(crate) fn successors(
    engine: &Engine,
    mu: &[bool],
    goal: Goal,
    out: &mut Vec<u32>,
    keep: impl Fn(Goal) -> bool,
) {
    if engine.implications.any() && engine.is_aggregate(goal) {
        aggregate_successors(engine, goal, out, &keep);
        return;
    }
    let q = lit_of(goal);
    let nq = q.complement();
    let kind = kind_of(goal);
    let mut push_body = |rule: u32, kind: u32, flag: u32| {
        for &a in engine.body(rule) {
            let g = self::goal(a, kind);
            if keep(g) {
                out.push(g | flag);
            }
        }
    };
    match kind {
        BETA | PI => {
            if mu[q.index()] || mu[nq.index()] {
                return;
            }
            for &r in engine.rules_for(q) {
                if engine.kind(r).supports() {
                    push_body(r, kind, 0);
                }
            }
            let attacker_kind = if kind == BETA { BETA } else { SUP };
            for &s in engine.rules_for(nq) {
                push_body(s, attacker_kind, ATTACK);
            }
            push_implied(engine, q, kind, 0, out, &keep);
            push_implied(engine, nq, attacker_kind, ATTACK, out, &keep);
        }
        _ => {
            if mu[q.index()] {
                return;
            }
            for &r in engine.rules_for(q) {
                if !engine.kind(r).supports() {
                    continue;
                }
                push_body(r, SUP, 0);
                for &s in engine.superiors_of(r) {
                    if engine.head(s) == nq {
                        push_body(s, PI, ATTACK);
                    }
                }
            }
            push_implied(engine, q, SUP, 0, out, &keep);
        }
    }
}

/// An aggregate goal's ways: each literal with a direct implication into the part, each part
/// chained into it.
fn aggregate_supporters(
    engine: &Engine,
    goal: Goal,
    supporter: &mut dyn FnMut(&mut dyn Iterator<Item = Goal>),
) {
    let (rep, kind) = engine.aggregate_parts(goal);
    let i = &engine.implications;
    for &x in i.direct.row(rep as usize) {
        supporter(&mut std::iter::once(self::goal(Lit(x), kind)));
    }
    for &r in i.chained.row(rep as usize) {
        supporter(&mut std::iter::once(engine.aggregate_goal(r, kind)));
    }
}

/// Whether a rule's antecedent is settled and proved.
fn all_settled_true(
    engine: &Engine,
    settled: &dyn Fn(Goal) -> Option<bool>,
    rule: u32,
    kind: u32,
) -> bool {
    engine
        .body(rule)
        .iter()
        .all(|&a| settled(goal(a, kind)) == Some(true))
}

/// Whether an attacker on `q`, applicable outside the component, stands unbeaten by any team
/// of superiors settled outside it. `Err` when a superior reads a member (an AND of ways).
fn an_attacker_stands(
    engine: &Engine,
    q: Lit,
    kind: u32,
    settled: &dyn Fn(Goal) -> Option<bool>,
) -> Result<bool, ()> {
    let reads_member = |rule: u32| {
        engine
            .body(rule)
            .iter()
            .any(|&a| settled(goal(a, kind)).is_none())
    };
    let attacker_kind = if kind == BETA { BETA } else { SUP };
    for &s in engine.rules_for(q.complement()) {
        if !all_settled_true(engine, settled, s, attacker_kind) {
            continue; // fails in the upper bound, or outside it
        }
        let team = engine
            .superiors_of(s)
            .iter()
            .filter(|&&t| engine.head(t) == q && engine.kind(t).supports());
        let mut beaten = false;
        for &t in team {
            if all_settled_true(engine, settled, t, kind) {
                beaten = true;
            } else if reads_member(t) {
                return Err(());
            }
        }
        if !beaten {
            return Ok(true);
        }
    }
    Ok(false)
}

/// The goal's ways to be supported when every internal attack fails (the reading of the upper
/// bound): each call of `supporter` gives the goals one way reads, all of which must hold (an
/// empty list holds outright). `settled` gives a settled goal's value, `None` for a member of the
/// component being evaluated. `Err` when the goal also needs a member through a team of
/// superior rules (an AND the caller cannot read as ways of support). Mirrors `condition`.
pub(crate) fn supporters(
    engine: &Engine,
    mu: &[bool],
    goal: Goal,
    settled: &dyn Fn(Goal) -> Option<bool>,
    supporter: &mut dyn FnMut(&mut dyn Iterator<Item = Goal>),
) -> Result<(), ()> {
    if engine.is_aggregate(goal) {
        aggregate_supporters(engine, goal, supporter);
        return Ok(());
    }
    let q = lit_of(goal);
    let nq = q.complement();
    let kind = kind_of(goal);
    let proved_outside = |rule: u32, kind: u32| all_settled_true(engine, settled, rule, kind);
    if mu[q.index()] {
        supporter(&mut std::iter::empty());
        return Ok(());
    }
    if kind == SUP {
        for &r in engine.rules_for(q) {
            if !engine.kind(r).supports() {
                continue;
            }
            // A superior attacker applicable outside the component blocks this way.
            let blocked = engine
                .superiors_of(r)
                .iter()
                .any(|&s| engine.head(s) == nq && proved_outside(s, PI));
            if !blocked {
                supporter(&mut engine.body(r).iter().map(|&a| self::goal(a, SUP)));
            }
        }
    } else {
        if mu[nq.index()] {
            return Ok(());
        }
        if an_attacker_stands(engine, q, kind, settled)? {
            return Ok(()); // no way to hold at all
        }
        for &r in engine.rules_for(q) {
            if engine.kind(r).supports() {
                supporter(&mut engine.body(r).iter().map(|&a| self::goal(a, kind)));
            }
        }
    }
    for x in engine.implications.cycle_mates(q) {
        supporter(&mut std::iter::once(self::goal(x, kind)));
    }
    if let Some(a) = engine.aggregate_for(q, kind) {
        supporter(&mut std::iter::once(a));
    }
    Ok(())
}
