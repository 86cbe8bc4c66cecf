//! Goals (an algorithm's question about one literal), their proof conditions (cdl.md §4) and
//! their successors in the goal graph, shared by every evaluation strategy of the session.

use crate::engine::Engine;
use crate::literal::Lit;

/// A goal packed as `literal * 3 + kind`.
pub(crate) type Goal = u32;

pub(crate) const BETA: u32 = 0;
pub(crate) const PI: u32 = 1;
/// Support, the auxiliary algorithm π calls for attackers (and that calls π back).
pub(crate) const SUP: u32 = 2;
pub(crate) const KINDS: usize = 3;

/// Marks a successor reached through an attacker's antecedent (read negated by the condition).
pub(crate) const ATTACK: u32 = 1 << 31;

#[inline]
pub(crate) fn goal(lit: Lit, kind: u32) -> Goal {
    lit.0 * 3 + kind
}

#[inline]
pub(crate) fn lit_of(goal: Goal) -> Lit {
    Lit(goal / 3)
}

#[inline]
pub(crate) fn kind_of(goal: Goal) -> u32 {
    goal % 3
}

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
                .any(|&r| engine.kind(r).supports() && applicable(r, kind, SUPPORT_READ, value));
            if !supported {
                return false;
            }
            // An attacker counts when its antecedent is proved (β) or merely supported (π).
            let attacker_kind = if kind == BETA { BETA } else { SUP };
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

/// Pushes the sub-goals `condition` may read, attack edges marked with [`ATTACK`]; `keep`
/// filters out goals whose value is already settled.
pub(crate) fn successors(
    engine: &Engine,
    mu: &[bool],
    goal: Goal,
    out: &mut Vec<u32>,
    keep: impl Fn(Goal) -> bool,
) {
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
        }
    }
}
