//! The closure of a set of clauses under resolution (cdl.md §2, step 1), tautologies dropped.
//! Two-literal clauses are implications (`\\/{~a, b}` is `a → b` and `~b → ~a`); resolving two of
//! them only chains implications, so the engine's closure leaves those resolvents implicit, as
//! paths of its implication graph, and keeps what they imply: the units (`l` when `~l` implies
//! `l`) and every resolvent with a unit or a longer clause. The reference prover materialises
//! them all.

use crate::literal::Lit;
use hashbrown::HashTable;
use rustc_hash::{FxHashMap, FxHashSet};
use std::hash::{BuildHasher, BuildHasherDefault};

/// The most clauses a closure may hold; past it the theory is rejected rather than letting
/// resolution run away (a closure can grow exponentially).
pub const MAX_CLOSURE: usize = 200_000;

/// How a closure ended.
#[derive(Debug, PartialEq, Eq)]
pub enum ClosureOutcome {
    /// Every clause of the closure, each sorted; `given[i]` is the index of the input clause
    /// clause `i` is (derived clauses have none).
    Closed {
        clauses: Vec<Vec<Lit>>,
        given: Vec<Option<usize>>,
    },
    /// The input clauses are their own closure: units, none written twice and no two
    /// complementary (the facts of nearly every large theory), so there is nothing to copy.
    Input,
    /// The empty clause was derived: from these two complementary unit clauses (with the input
    /// clause each one is, when it is one), or from an empty input clause (both empty).
    Inconsistent {
        first: (Vec<Lit>, Option<usize>),
        second: (Vec<Lit>, Option<usize>),
    },
    /// More than [`MAX_CLOSURE`] clauses.
    TooLarge,
}

/// Sorts, deduplicates and tests a clause: `None` for a tautology (holds `l` and `~l`).
pub fn normalize(mut clause: Vec<Lit>) -> Option<Vec<Lit>> {
    clause.sort_unstable();
    clause.dedup();
    if clause.windows(2).any(|w| w[0].atom() == w[1].atom()) {
        None
    } else {
        Some(clause)
    }
}

/// Which resolvents a closure materialises.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Resolvents {
    /// Every one (the reference prover).
    All,
    /// All but those of two two-literal clauses, which stay paths of the implication graph.
    ImplicationsImplicit,
}

/// Closes `clauses` under resolution. Indexing clauses by literal keeps the common case (many
/// unit facts, few real clauses) linear.
pub fn close(input: &[impl AsRef<[Lit]>], resolvents: Resolvents) -> ClosureOutcome {
    if input.iter().all(|clause| clause.as_ref().len() == 1) {
        close_units(input)
    } else {
        close_clauses(input, resolvents)
    }
}

/// [`close`] for any clauses.
fn close_clauses(input: &[impl AsRef<[Lit]>], resolvents: Resolvents) -> ClosureOutcome {
    let mut closure = Closure::default();
    for (i, clause) in input.iter().enumerate() {
        let Some(clause) = normalize(clause.as_ref().to_vec()) else {
            continue;
        };
        if clause.is_empty() {
            return ClosureOutcome::Inconsistent {
                first: (Vec::new(), Some(i)),
                second: (Vec::new(), Some(i)),
            };
        }
        if !closure.holds(&clause) {
            closure.add(clause, Some(i));
        }
    }
    let mut next = 0;
    loop {
        if next == closure.all.len() {
            // Resolved out; with the implications implicit, the units they force come next.
            if resolvents == Resolvents::All {
                break;
            }
            match forced_units(&closure.all, |clause| closure.holds(clause)) {
                Forced::None => break,
                Forced::Units(units) => {
                    if closure.all.len() + units.len() > MAX_CLOSURE {
                        return ClosureOutcome::TooLarge;
                    }
                    for unit in units {
                        closure.add(vec![unit], None);
                    }
                }
                Forced::Both(l) => {
                    return ClosureOutcome::Inconsistent {
                        first: (vec![l], None),
                        second: (vec![l.complement()], None),
                    }
                }
            }
            continue;
        }
        if let Err(stopped) = closure.resolve(next, resolvents) {
            return stopped;
        }
        next += 1;
    }
    ClosureOutcome::Closed {
        clauses: closure.all,
        given: closure.given,
    }
}

/// The closure of unit clauses alone (facts, the common case: half a million in a large theory)
/// without the general machinery: no two units resolve but complementary ones. The same outcome
/// as [`close`]'s general loop: the first occurrence of each unit in order, or the first unit
/// whose complement is also given, with the complement's first occurrence.
fn close_units(input: &[impl AsRef<[Lit]>]) -> ClosureOutcome {
    let unit = |i: usize| input[i].as_ref()[0];
    let slots = input
        .iter()
        .map(|c| c.as_ref()[0].index() | 1)
        .max()
        .map_or(0, |m| m + 1);
    let mut first = vec![u32::MAX; slots];
    let mut repeated = false;
    for i in 0..input.len() {
        let at = &mut first[unit(i).index()];
        if *at == u32::MAX {
            *at = i as u32;
        } else {
            repeated = true;
        }
    }
    let is_first = |&i: &usize| first[unit(i).index()] == i as u32;
    let complement_at = |l: Lit| Some(first[l.complement().index()]).filter(|&c| c != u32::MAX);
    if let Some((l, c)) = (0..input.len())
        .filter(is_first)
        .find_map(|i| complement_at(unit(i)).map(|c| (i, c as usize)))
    {
        return ClosureOutcome::Inconsistent {
            first: (vec![unit(l)], Some(l)),
            second: (vec![unit(c)], Some(c)),
        };
    }
    if !repeated {
        return ClosureOutcome::Input;
    }
    let given: Vec<Option<usize>> = (0..input.len()).filter(is_first).map(Some).collect();
    let clauses = given.iter().flatten().map(|&i| vec![unit(i)]).collect();
    ClosureOutcome::Closed { clauses, given }
}

/// The clauses so far, indexed by literal, each with the input clause it is (if one).
#[derive(Default)]
struct Closure {
    all: Vec<Vec<Lit>>,
    given: Vec<Option<usize>>,
    /// Indices into `all`, found by the clause's hash: each clause is stored once.
    seen: HashTable<u32>,
    by_lit: FxHashMap<Lit, Vec<usize>>,
}

fn hash(clause: &[Lit]) -> u64 {
    BuildHasherDefault::<rustc_hash::FxHasher>::default().hash_one(clause)
}

impl Closure {
    fn holds(&self, clause: &[Lit]) -> bool {
        self.seen
            .find(hash(clause), |&i| self.all[i as usize] == clause)
            .is_some()
    }

    fn add(&mut self, clause: Vec<Lit>, given: Option<usize>) {
        let index = self.all.len();
        for &l in &clause {
            self.by_lit.entry(l).or_default().push(index);
        }
        let all = &self.all;
        self.seen
            .insert_unique(hash(&clause), index as u32, |&i| hash(&all[i as usize]));
        self.all.push(clause);
        self.given.push(given);
    }

    /// Adds every new resolvent of clause `next` with the clauses before it and after; stops
    /// with the outcome when two units contradict or the closure grows too large.
    fn resolve(&mut self, next: usize, resolvents: Resolvents) -> Result<(), ClosureOutcome> {
        let current = self.all[next].clone();
        for &l in &current {
            // By place, not by a copy of the list: resolvents added below never hold `~l`
            // (they would be tautologies), so the list does not change while it is read.
            let partners = self.by_lit.get(&l.complement()).map_or(0, Vec::len);
            for at in 0..partners {
                let p = self.by_lit[&l.complement()][at];
                let other = &self.all[p];
                if resolvents == Resolvents::ImplicationsImplicit
                    && current.len() == 2
                    && other.len() == 2
                {
                    continue;
                }
                if current.len() == 1 && other.len() == 1 {
                    return Err(ClosureOutcome::Inconsistent {
                        first: (current, self.given[next]),
                        second: (other.clone(), self.given[p]),
                    });
                }
                let resolvent: Vec<Lit> = current
                    .iter()
                    .copied()
                    .filter(|&x| x != l)
                    .chain(other.iter().copied().filter(|&x| x != l.complement()))
                    .collect();
                let Some(resolvent) = normalize(resolvent) else {
                    continue;
                };
                if self.holds(&resolvent) {
                    continue;
                }
                if self.all.len() >= MAX_CLOSURE {
                    return Err(ClosureOutcome::TooLarge);
                }
                self.add(resolvent, None);
            }
        }
        Ok(())
    }
}

enum Forced {
    None,
    /// New units: literals `l` with a path from `~l` to `l`.
    Units(Vec<Lit>),
    /// `l` and `~l` imply each other: the clauses are inconsistent.
    Both(Lit),
}

/// The units the two-literal clauses force and the closure does not hold yet: `l` whenever `~l`
/// implies `l` (resolving along that path ends in `{l}`). A path can only join literals of one
/// weakly connected part of the graph, so only literals whose complement lies in their part are
/// searched.
fn forced_units(all: &[Vec<Lit>], holds: impl Fn(&[Lit]) -> bool) -> Forced {
    let mut succ: FxHashMap<Lit, Vec<Lit>> = FxHashMap::default();
    for clause in all.iter().filter(|c| c.len() == 2) {
        let (a, b) = (clause[0], clause[1]);
        succ.entry(a.complement()).or_default().push(b);
        succ.entry(b.complement()).or_default().push(a);
    }
    let mut part: FxHashMap<Lit, Lit> = FxHashMap::default();
    fn find(part: &mut FxHashMap<Lit, Lit>, l: Lit) -> Lit {
        let mut root = l;
        while let Some(&up) = part.get(&root).filter(|&&up| up != root) {
            root = up;
        }
        let mut at = l;
        while at != root {
            let up = part[&at];
            part.insert(at, root);
            at = up;
        }
        root
    }
    for (&from, tos) in &succ {
        part.entry(from).or_insert(from);
        for &to in tos {
            part.entry(to).or_insert(to);
            let (a, b) = (find(&mut part, from), find(&mut part, to));
            if a != b {
                part.insert(a, b);
            }
        }
    }
    let mut literals: Vec<Lit> = part.keys().copied().collect();
    literals.sort_unstable();
    let mut units = Vec::new();
    let mut visited: FxHashSet<Lit> = FxHashSet::default();
    for l in literals {
        if holds(&[l]) || !part.contains_key(&l.complement()) {
            continue;
        }
        if find(&mut part, l) != find(&mut part, l.complement()) {
            continue;
        }
        visited.clear();
        let mut work = vec![l.complement()];
        let mut forced = false;
        while let Some(x) = work.pop() {
            if x == l {
                forced = true;
                break;
            }
            if visited.insert(x) {
                work.extend(succ.get(&x).into_iter().flatten().copied());
            }
        }
        if forced {
            if units.contains(&l.complement()) {
                return Forced::Both(l);
            }
            units.push(l);
        }
    }
    if units.is_empty() {
        Forced::None
    } else {
        Forced::Units(units)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Units alone give what the general loop gives: the same clauses in the same order, and
    /// the same pair (and the same given clauses) when two contradict.
    #[test]
    fn units_alone_close_as_the_general_loop_closes_them() {
        for units in [
            vec![],
            vec![0],
            vec![4, 2, 4, 7, 2],
            vec![4, 2, 5, 3],
            vec![9, 1, 6, 8, 0, 6, 7],
            vec![3, 3, 2],
        ] {
            let input: Vec<Vec<Lit>> = units.iter().map(|&l| vec![Lit(l)]).collect();
            // `Input` says the general loop keeps every given clause as it is.
            let units_outcome = match close_units(&input) {
                ClosureOutcome::Input => ClosureOutcome::Closed {
                    clauses: input.clone(),
                    given: (0..input.len()).map(Some).collect(),
                },
                other => other,
            };
            for resolvents in [Resolvents::All, Resolvents::ImplicationsImplicit] {
                assert_eq!(
                    units_outcome,
                    close_clauses(&input, resolvents),
                    "{units:?}"
                );
            }
        }
    }
}
