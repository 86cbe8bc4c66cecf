//! What `check` says about a theory's attack cycles (cdl.md §4 and §5.3): the components that
//! only a search decides, and the self-attacking loops through which β or π proves a literal
//! and its complement. Found by proving every literal once, so it runs after checking, on a
//! theory that loaded.

use crate::component::SearchLimits;
use crate::engine::Engine;
use crate::literal::{Atom, Lit, RuleId};
use crate::session::{Searched, Session};
use crate::theory::{Origin, Theory};
use proclaim_syntax::{Algorithm, Diagnostic, Span};
use rustc_hash::FxHashSet;
use std::sync::Arc;

/// Components with fewer goals than this that the search decides are not worth a warning.
const SEARCHED_WARNING_GOALS: usize = 16;

/// How many rules a warning names before it says how many more there are.
const NAMED_RULES: usize = 8;

/// Warnings for the hard parts of a loaded theory, each placed at a rule of the part.
pub fn attack_cycle_warnings(theory: &Arc<Theory>, limits: SearchLimits) -> Vec<Diagnostic> {
    let engine = Arc::new(Engine::new(theory.clone()));
    let mut session = Session::with_limits(engine.clone(), limits);
    let lits = theory.atom_count() as u32 * 2;
    let mut both = Vec::new();
    for alg in [Algorithm::Beta, Algorithm::Pi] {
        for atom in (0..lits / 2).map(Atom) {
            let positive = session.prove(alg, Lit::positive(atom));
            if session.prove(alg, Lit::new(atom, true)) && positive {
                both.push((alg, atom));
            }
        }
    }
    let mut warnings: Vec<Diagnostic> = session
        .searched()
        .iter()
        .filter_map(|searched| searched_warning(theory, &engine, searched, limits))
        .collect();
    warnings.extend(
        both.into_iter()
            .filter_map(|(alg, atom)| loop_warning(theory, &engine, alg, atom)),
    );
    warnings.sort_by_key(|d| (d.span.start, d.span.end));
    warnings
}

/// The warning for a component the search had to work on: large, or left undecided.
fn searched_warning(
    theory: &Theory,
    engine: &Engine,
    searched: &Searched,
    limits: SearchLimits,
) -> Option<Diagnostic> {
    let small = searched.goals.len() < SEARCHED_WARNING_GOALS;
    // Decided by its bounds alone (no step of search): cheap however large.
    if !searched.undecided && (small || searched.steps == 0) {
        return None;
    }
    let atoms: FxHashSet<Atom> = searched.goals.iter().map(|(_, l)| l.atom()).collect();
    let mut rules: Vec<RuleId> = atoms.iter().flat_map(|&a| rules_about(engine, a)).collect();
    rules.sort_unstable();
    let span = first_written(theory, &rules)?;
    let (message, hint) = if searched.undecided {
        (
            format!(
                "rules attack each other in a cycle of {} goals that the search did not decide within its budget of {} steps: {}",
                searched.goals.len(),
                limits.steps,
                names(theory, &rules)
            ),
            "its answers are undecided (`?` in `prove`, false in a running behaviour); raise the budget (`--budget`, or `budget` in behaviour.toml) or break the cycle",
        )
    } else {
        (
            format!(
                "rules attack each other in a cycle of {} goals that only a search decides ({} steps): {}",
                searched.goals.len(),
                searched.steps,
                names(theory, &rules)
            ),
            "inside such a cycle an answer can cost time exponential in its size (cdl.md §4); a priority that decides the conflict, or breaking the cycle, makes it cheap",
        )
    };
    Some(Diagnostic::warning(span, message).with_hint(hint))
}

/// The warning for a literal `alg` proves together with its complement.
fn loop_warning(
    theory: &Theory,
    engine: &Engine,
    alg: Algorithm,
    atom: Atom,
) -> Option<Diagnostic> {
    let rules = self_attacking_loop(engine, atom);
    let span = first_written(theory, &rules)?;
    let name = theory.atom_name(atom);
    Some(
        Diagnostic::warning(
            span,
            format!(
                "{alg} proves both `{name}` and `~{name}`, through a self-attacking loop: {}",
                names(theory, &rules)
            ),
        )
        .with_hint(
            "an attacker whose antecedent depends on what it attacks fails on the history, so proving each side discounts the other's attacker (cdl.md §5.3); rewrite the loop if one side should win",
        ),
    )
}

/// The rules for `atom` and for its complement.
fn rules_about(engine: &Engine, atom: Atom) -> impl Iterator<Item = RuleId> + '_ {
    let [positive, negative] = [Lit::positive(atom), Lit::new(atom, true)];
    engine
        .rules_for(positive)
        .iter()
        .chain(engine.rules_for(negative))
        .copied()
}

/// The rules for `atom` or its complement whose antecedents depend on `atom` again.
fn self_attacking_loop(engine: &Engine, atom: Atom) -> Vec<RuleId> {
    let mut rules: Vec<RuleId> = rules_about(engine, atom)
        .filter(|&r| {
            engine
                .body(r)
                .iter()
                .any(|l| reaches(engine, l.atom(), atom))
        })
        .collect();
    rules.sort_unstable();
    rules
}

/// Whether `from` depends on `to` through the rules (an atom depends on the antecedents of the
/// rules for it and for its complement).
fn reaches(engine: &Engine, from: Atom, to: Atom) -> bool {
    let mut seen = FxHashSet::default();
    let mut work = vec![from];
    while let Some(a) = work.pop() {
        if a == to {
            return true;
        }
        if seen.insert(a) {
            work.extend(
                rules_about(engine, a).flat_map(|r| engine.body(r).iter().map(|l| l.atom())),
            );
        }
    }
    false
}

fn first_written(theory: &Theory, rules: &[RuleId]) -> Option<Span> {
    rules
        .iter()
        .filter_map(|&r| match theory.rule(r).origin {
            Origin::Written(span) => Some(span),
            Origin::Clause(_) => None,
        })
        .min_by_key(|s| s.start)
}

/// `r1, r2, … and 5 more`; an unlabelled rule is named by its text.
fn names(theory: &Theory, rules: &[RuleId]) -> String {
    let mut shown: Vec<String> = rules
        .iter()
        .take(NAMED_RULES)
        .map(|&r| theory.rule_name(r))
        .collect();
    if rules.len() > NAMED_RULES {
        shown.push(format!("and {} more", rules.len() - NAMED_RULES));
    }
    shown.join(", ")
}
