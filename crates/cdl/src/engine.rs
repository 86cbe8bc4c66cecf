//! The compiled engine: a checked theory's rules indexed for proving (rules by consequent,
//! superiors by rule, strict rules by antecedent, dependents by literal), in flat arrays.
//! Immutable and shareable; the mutable proving state lives in a [`crate::Session`].

use crate::literal::{Lit, RuleId};
use crate::theory::{RuleKind, Theory};
use std::sync::Arc;

/// Compressed sparse rows: `items[start[i]..start[i + 1]]` belong to key `i`.
#[derive(Clone, Debug, Default)]
pub(crate) struct Csr {
    start: Vec<u32>,
    items: Vec<u32>,
}

impl Csr {
    /// Builds rows for `keys` keys from `(key, item)` pairs, keeping each row in pair order.
    fn build(keys: usize, pairs: impl Iterator<Item = (u32, u32)> + Clone) -> Csr {
        let mut start = vec![0u32; keys + 1];
        for (k, _) in pairs.clone() {
            start[k as usize + 1] += 1;
        }
        for i in 0..keys {
            start[i + 1] += start[i];
        }
        let mut fill = start.clone();
        let mut items = vec![0u32; start[keys] as usize];
        for (k, item) in pairs {
            let slot = &mut fill[k as usize];
            items[*slot as usize] = item;
            *slot += 1;
        }
        Csr { start, items }
    }

    #[inline]
    pub(crate) fn row(&self, key: usize) -> &[u32] {
        &self.items[self.start[key] as usize..self.start[key + 1] as usize]
    }
}

/// A theory compiled for proving. Cheap to share between sessions (`Arc`).
#[derive(Debug)]
pub struct Engine {
    pub(crate) theory: Arc<Theory>,
    pub(crate) lit_count: usize,
    /// Rules by consequent literal.
    pub(crate) by_head: Csr,
    /// For each rule `s`, the rules `t` with `t > s`.
    pub(crate) superiors: Csr,
    /// For each literal, the strict rules it is an antecedent of (forward chaining for μ).
    pub(crate) strict_uses: Csr,
    /// For each literal `x`, the consequents of rules with `x` in their antecedent: the literals
    /// whose proofs (and whose complements' proofs) may read `x`.
    pub(crate) dependents: Csr,
    /// Strict rules with an empty antecedent (facts), the roots of μ.
    pub(crate) strict_facts: Vec<RuleId>,
    pub(crate) strict_body_len: Vec<u32>,
    /// For each literal, the clauses of the axioms' closure that hold it.
    pub(crate) closure_by_lit: Csr,
}

impl Engine {
    /// Compiles a checked theory. Linear in its size.
    pub fn new(theory: impl Into<Arc<Theory>>) -> Engine {
        let theory = theory.into();
        let lit_count = theory.atom_count() * 2;
        let rules = theory.rule_count();
        let by_head = Csr::build(
            lit_count,
            (0..rules as u32).map(|r| (theory.heads[r as usize].0, r)),
        );
        let superiors = Csr::build(rules, theory.priorities.iter().map(|&(w, l)| (l, w)));
        let is_strict = |r: u32| theory.kinds[r as usize] == RuleKind::Strict;
        let t: &Theory = &theory;
        let body_pairs = || {
            (0..rules as u32).flat_map(move |r| {
                let theory = t;
                let (a, b) = (
                    theory.body_start[r as usize] as usize,
                    theory.body_start[r as usize + 1] as usize,
                );
                theory.bodies[a..b].iter().map(move |l| (l.0, r))
            })
        };
        let strict_uses = Csr::build(lit_count, body_pairs().filter(|&(_, r)| is_strict(r)));
        let dependents = Csr::build(
            lit_count,
            body_pairs().map(|(l, r)| (l, theory.heads[r as usize].0)),
        );
        let strict_body_len = (0..rules)
            .map(|r| theory.body_start[r + 1] - theory.body_start[r])
            .collect::<Vec<_>>();
        let strict_facts = (0..rules as u32)
            .filter(|&r| is_strict(r) && strict_body_len[r as usize] == 0)
            .collect();
        let closure_by_lit = Csr::build(
            lit_count,
            theory
                .closure
                .iter()
                .enumerate()
                .flat_map(|(i, c)| c.lits.iter().map(move |l| (l.0, i as u32))),
        );
        Engine {
            closure_by_lit,
            lit_count,
            by_head,
            superiors,
            strict_uses,
            dependents,
            strict_facts,
            strict_body_len,
            theory,
        }
    }

    pub fn theory(&self) -> &Theory {
        &self.theory
    }

    pub(crate) fn rules_for(&self, lit: Lit) -> &[RuleId] {
        self.by_head.row(lit.index())
    }

    #[inline]
    pub(crate) fn head(&self, rule: RuleId) -> Lit {
        self.theory.heads[rule as usize]
    }

    #[inline]
    pub(crate) fn kind(&self, rule: RuleId) -> RuleKind {
        self.theory.kinds[rule as usize]
    }

    #[inline]
    pub(crate) fn body(&self, rule: RuleId) -> &[Lit] {
        let t = &self.theory;
        &t.bodies[t.body_start[rule as usize] as usize..t.body_start[rule as usize + 1] as usize]
    }

    pub(crate) fn superiors_of(&self, rule: RuleId) -> &[RuleId] {
        self.superiors.row(rule as usize)
    }
}
