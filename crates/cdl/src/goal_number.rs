//! How goals are numbered: a literal's goal for each kind of question packed into one `u32`,
//! the implication aggregates after them. Apart from `goal.rs`'s proof conditions so that the
//! engine, which lays the goals out, and the conditions, which read the engine, do not need
//! each other.

use crate::literal::Lit;

/// A goal packed as `literal * KINDS + kind` ([`goal`]); the implication aggregates are packed
/// the same way after the literals' goals ([`crate::engine::Engine::aggregate_goal`]).
pub(crate) type Goal = u32;

pub(crate) const BETA: u32 = 0;
pub(crate) const PI: u32 = 1;
/// Support, the auxiliary algorithm π calls for attackers (and that calls π back).
pub(crate) const SUP: u32 = 2;
pub(crate) const KINDS: usize = 3;
const KINDS_U32: u32 = KINDS as u32;

/// Marks a successor reached through an attacker's antecedent (read negated by the condition).
pub(crate) const ATTACK: u32 = 1 << 31;

#[inline]
pub(crate) fn goal(lit: Lit, kind: u32) -> Goal {
    pack(lit.0, kind)
}

/// `index * KINDS + kind`: the one place goals are packed.
#[inline]
pub(crate) fn pack(index: u32, kind: u32) -> Goal {
    index * KINDS_U32 + kind
}

/// The inverse of [`pack`].
#[inline]
pub(crate) fn unpack(goal: Goal) -> (u32, u32) {
    (goal / KINDS_U32, goal % KINDS_U32)
}

#[inline]
pub(crate) fn lit_of(goal: Goal) -> Lit {
    Lit(unpack(goal).0)
}

#[inline]
pub(crate) fn kind_of(goal: Goal) -> u32 {
    unpack(goal).1
}
