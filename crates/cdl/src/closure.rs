//! The closure of a set of clauses under resolution (cdl.md §2, step 1), tautologies dropped.

use crate::literal::Lit;
use rustc_hash::{FxHashMap, FxHashSet};

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

/// Closes `clauses` under resolution. Indexing clauses by literal keeps the common case (many
/// unit facts, few real clauses) linear.
pub fn close(input: &[Vec<Lit>]) -> ClosureOutcome {
    let mut all: Vec<Vec<Lit>> = Vec::new();
    let mut given: Vec<Option<usize>> = Vec::new();
    let mut seen: FxHashSet<Vec<Lit>> = FxHashSet::default();
    let mut by_lit: FxHashMap<Lit, Vec<usize>> = FxHashMap::default();
    for (i, clause) in input.iter().enumerate() {
        let Some(clause) = normalize(clause.clone()) else {
            continue;
        };
        if clause.is_empty() {
            return ClosureOutcome::Inconsistent {
                first: (Vec::new(), Some(i)),
                second: (Vec::new(), Some(i)),
            };
        }
        if seen.insert(clause.clone()) {
            for &l in &clause {
                by_lit.entry(l).or_default().push(all.len());
            }
            all.push(clause);
            given.push(Some(i));
        }
    }
    let mut next = 0;
    while next < all.len() {
        let current = all[next].clone();
        for &l in &current {
            let Some(partners) = by_lit.get(&l.complement()) else {
                continue;
            };
            for p in partners.clone() {
                let other = &all[p];
                if current.len() == 1 && other.len() == 1 {
                    return ClosureOutcome::Inconsistent {
                        first: (current, given[next]),
                        second: (other.clone(), given[p]),
                    };
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
                if seen.contains(&resolvent) {
                    continue;
                }
                if all.len() >= MAX_CLOSURE {
                    return ClosureOutcome::TooLarge;
                }
                for &x in &resolvent {
                    by_lit.entry(x).or_default().push(all.len());
                }
                seen.insert(resolvent.clone());
                all.push(resolvent);
                given.push(None);
            }
        }
        next += 1;
    }
    ClosureOutcome::Closed {
        clauses: all,
        given,
    }
}
