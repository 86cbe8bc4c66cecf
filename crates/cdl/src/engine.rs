//! The compiled engine: a checked theory's rules indexed for proving (rules by consequent,
//! superiors by rule, strict rules by antecedent, dependents by literal), in flat arrays.
//! Immutable and shareable; the mutable proving state lives in a [`crate::Session`].

use crate::literal::{Lit, RuleId};
use crate::scc::{strongly_connected, Roots};
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
    pub(crate) fn build(keys: usize, pairs: impl Iterator<Item = (u32, u32)> + Clone) -> Csr {
        // Counted one place further on, so that after the sums `start[k + 1]` is where row `k`
        // begins: filled from there, it ends where row `k + 1` begins, with no second array.
        let mut start = vec![0u32; keys + 2];
        for (k, _) in pairs.clone() {
            start[k as usize + 2] += 1;
        }
        for i in 2..keys + 2 {
            start[i] += start[i - 1];
        }
        let mut items = vec![0u32; start[keys + 1] as usize];
        for (k, item) in pairs {
            let slot = &mut start[k as usize + 1];
            items[*slot as usize] = item;
            *slot += 1;
        }
        start.truncate(keys + 1);
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
    /// The implication graph of the closure's two-literal clauses, whose resolvents the closure
    /// leaves implicit ([`crate::closure::Resolvents`]).
    pub(crate) implications: Implications,
}

/// `\/{~x, y}` makes `x → y`; a path `x ⇝ y` (x ≠ y) is the strict rule `x -> y` of a resolvent
/// the closure did not write. A goal about `y` reads those rules as: the other members of `y`'s
/// strongly connected part of the graph (when it is a cycle), each read as its own rule, and one
/// aggregate goal per part, "some literal outside the part with a path into it is proved by λ",
/// which the parts before it share. A chain of n clauses costs n goals, not n² rules. The
/// aggregates read each other along the condensation, which is acyclic, and never enter a
/// proof's history: they are not goals of cdl.md §4, only a shared way to read many rules.
#[derive(Debug, Default)]
pub(crate) struct Implications {
    /// `x → y` edges by `x`.
    pub(crate) forward: Csr,
    /// For each literal of the graph, the literal standing for its part; `NO_PART` elsewhere.
    pub(crate) representative: Vec<u32>,
    /// For each representative of a part that is a cycle, its members.
    pub(crate) members: Csr,
    /// For each representative whose part has an aggregate: the literals outside the part its
    /// aggregate reads the goal of (the members' predecessors, and the whole of a predecessor's
    /// part when that is a cycle).
    pub(crate) direct: Csr,
    /// For each representative, the representatives whose aggregates its aggregate reads.
    pub(crate) chained: Csr,
    /// Whether the part of each representative has an aggregate (something outside leads in).
    pub(crate) has_aggregate: Vec<bool>,
}

pub(crate) const NO_PART: u32 = u32::MAX;

/// Below this many rules the engine is built on one thread: a thread costs more than it saves.
const PARALLEL_RULES: usize = 100_000;

/// `a` and `b`, on two threads when `parallel`, else one after the other.
fn both<A: Send, B: Send>(
    parallel: bool,
    a: impl FnOnce() -> A + Send,
    b: impl FnOnce() -> B + Send,
) -> (A, B) {
    if !parallel {
        return (a(), b());
    }
    std::thread::scope(|scope| {
        let other = scope.spawn(b);
        let a = a();
        // `b` only builds arrays; should it panic, the panic goes on unchanged.
        let b = other
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
        (a, b)
    })
}

impl Implications {
    fn new(lit_count: usize, theory: &Theory) -> Implications {
        let edges: Vec<(u32, u32)> = theory
            .closure()
            .iter()
            .filter(|c| c.lits.len() == 2)
            .flat_map(|c| {
                let (a, b) = (c.lits[0], c.lits[1]);
                [(a.complement().0, b.0), (b.complement().0, a.0)]
            })
            .collect();
        if edges.is_empty() {
            return Implications::default();
        }
        let forward = Csr::build(lit_count, edges.iter().copied());
        let backward = Csr::build(lit_count, edges.iter().map(|&(x, y)| (y, x)));
        let mut representative = vec![NO_PART; lit_count];
        let mut cyclic = vec![false; lit_count];
        // Tarjan lists parts successors first; every literal with an edge is in one.
        let parts = strongly_connected(lit_count, |l| forward.row(l), Roots::WithSuccessors);
        for component in &parts {
            let rep = component[0];
            for &l in component {
                representative[l as usize] = rep;
            }
            cyclic[rep as usize] = component.len() > 1 || forward.row(rep as usize).contains(&rep);
        }
        let part_of_rep: rustc_hash::FxHashMap<u32, usize> =
            parts.iter().enumerate().map(|(i, c)| (c[0], i)).collect();
        let mut members: Vec<(u32, u32)> = Vec::new();
        let mut direct: Vec<(u32, u32)> = Vec::new();
        let mut chained: Vec<(u32, u32)> = Vec::new();
        let mut has_aggregate = vec![false; lit_count];
        // Predecessors' parts first, so their aggregates are known when a part reads them.
        for component in parts.iter().rev() {
            let rep = component[0];
            if cyclic[rep as usize] {
                members.extend(component.iter().map(|&m| (rep, m)));
            }
            let mut reads: Vec<u32> = Vec::new();
            let mut chains: Vec<u32> = Vec::new();
            for &m in component {
                for &p in backward.row(m as usize) {
                    let their = representative[p as usize];
                    if their == rep {
                        continue;
                    }
                    if cyclic[their as usize] {
                        reads.extend(&parts[part_of_rep[&their]]);
                    } else {
                        reads.push(p);
                    }
                    if has_aggregate[their as usize] {
                        chains.push(their);
                    }
                }
            }
            reads.sort_unstable();
            reads.dedup();
            chains.sort_unstable();
            chains.dedup();
            has_aggregate[rep as usize] = !reads.is_empty();
            direct.extend(reads.iter().map(|&x| (rep, x)));
            chained.extend(chains.iter().map(|&r| (rep, r)));
        }
        Implications {
            forward,
            representative,
            members: Csr::build(lit_count, members.into_iter()),
            direct: Csr::build(lit_count, direct.into_iter()),
            chained: Csr::build(lit_count, chained.into_iter()),
            has_aggregate,
        }
    }

    #[inline]
    pub(crate) fn any(&self) -> bool {
        !self.representative.is_empty()
    }

    /// The other members of `lit`'s part when it is a cycle: each `x -> lit` is a rule.
    #[inline]
    pub(crate) fn cycle_mates(&self, lit: Lit) -> impl Iterator<Item = Lit> + '_ {
        let row = match self.representative.get(lit.index()) {
            Some(&rep) if rep != NO_PART => self.members.row(rep as usize),
            _ => &[],
        };
        row.iter().map(|&x| Lit(x)).filter(move |&x| x != lit)
    }
}

/// The indexes read by consequent: rules by head, superiors, and the axioms' closure.
struct ByConsequent {
    by_head: Csr,
    superiors: Csr,
    closure_by_lit: Csr,
    implications: Implications,
}

impl ByConsequent {
    fn new(theory: &Theory, lit_count: usize) -> ByConsequent {
        let rules = theory.rule_count();
        ByConsequent {
            by_head: Csr::build(
                lit_count,
                (0..rules as u32).map(|r| (theory.heads[r as usize].0, r)),
            ),
            superiors: Csr::build(rules, theory.priorities.iter().map(|&(w, l)| (l, w))),
            closure_by_lit: Csr::build(
                lit_count,
                theory
                    .closure()
                    .iter()
                    .enumerate()
                    .flat_map(|(i, c)| c.lits.iter().map(move |l| (l.0, i as u32))),
            ),
            implications: Implications::new(lit_count, theory),
        }
    }
}

/// The indexes read by antecedent: strict rules and dependents by body literal.
struct ByAntecedent {
    strict_uses: Csr,
    dependents: Csr,
    strict_facts: Vec<RuleId>,
    strict_body_len: Vec<u32>,
}

impl ByAntecedent {
    fn new(theory: &Theory, lit_count: usize) -> ByAntecedent {
        let rules = theory.rule_count();
        let is_strict = |r: u32| theory.kinds[r as usize] == RuleKind::Strict;
        let body_pairs = || {
            (0..rules as u32).flat_map(move |r| {
                let (a, b) = (
                    theory.body_start[r as usize] as usize,
                    theory.body_start[r as usize + 1] as usize,
                );
                theory.bodies[a..b].iter().map(move |l| (l.0, r))
            })
        };
        let strict_body_len = (0..rules)
            .map(|r| theory.body_start[r + 1] - theory.body_start[r])
            .collect::<Vec<_>>();
        ByAntecedent {
            strict_uses: Csr::build(lit_count, body_pairs().filter(|&(_, r)| is_strict(r))),
            dependents: Csr::build(
                lit_count,
                body_pairs().map(|(l, r)| (l, theory.heads[r as usize].0)),
            ),
            strict_facts: (0..rules as u32)
                .filter(|&r| is_strict(r) && strict_body_len[r as usize] == 0)
                .collect(),
            strict_body_len,
        }
    }
}

impl Engine {
    /// Compiles a checked theory. Linear in its size. A large theory's indexes by consequent and
    /// by antecedent are built on two threads at once: they read the theory and nothing else.
    pub fn new(theory: impl Into<Arc<Theory>>) -> Engine {
        let theory = theory.into();
        let t: &Theory = &theory;
        let lit_count = t.atom_count() * 2;
        let parallel = t.rule_count() >= PARALLEL_RULES;
        let (by_consequent, by_antecedent) = both(
            parallel,
            || ByConsequent::new(t, lit_count),
            || ByAntecedent::new(t, lit_count),
        );
        Engine {
            implications: by_consequent.implications,
            closure_by_lit: by_consequent.closure_by_lit,
            lit_count,
            by_head: by_consequent.by_head,
            superiors: by_consequent.superiors,
            strict_uses: by_antecedent.strict_uses,
            dependents: by_antecedent.dependents,
            strict_facts: by_antecedent.strict_facts,
            strict_body_len: by_antecedent.strict_body_len,
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

    /// Goals of the literals themselves come first ([`crate::goal::goal`]); the implication
    /// aggregates after them.
    #[inline]
    pub(crate) fn aggregate_base(&self) -> u32 {
        crate::goal_number::pack(self.lit_count as u32, 0)
    }

    /// The goal of part `rep`'s aggregate for `kind`.
    #[inline]
    pub(crate) fn aggregate_goal(&self, rep: u32, kind: u32) -> u32 {
        self.aggregate_base() + crate::goal_number::pack(rep, kind)
    }

    /// How many goals a session keeps a value for.
    pub(crate) fn goal_count(&self) -> usize {
        let base = self.aggregate_base() as usize;
        if self.implications.any() {
            2 * base
        } else {
            base
        }
    }

    /// The aggregate "some literal outside `lit`'s part with a path to it is proved by `kind`",
    /// when one leads there.
    #[inline]
    pub(crate) fn aggregate_for(&self, lit: Lit, kind: u32) -> Option<u32> {
        let i = &self.implications;
        match i.representative.get(lit.index()) {
            Some(&rep) if rep != NO_PART && i.has_aggregate[rep as usize] => {
                Some(self.aggregate_goal(rep, kind))
            }
            _ => None,
        }
    }

    #[inline]
    pub(crate) fn is_aggregate(&self, goal: u32) -> bool {
        goal >= self.aggregate_base()
    }

    /// The representative literal and kind of an aggregate goal.
    #[inline]
    pub(crate) fn aggregate_parts(&self, goal: u32) -> (u32, u32) {
        crate::goal_number::unpack(goal - self.aggregate_base())
    }
}
