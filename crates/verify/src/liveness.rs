//! Liveness over the explored graph, after exploration: `eventually P`, `leads_to P ~> Q` and
//! `always_eventually P` over infinite runs in which time passes, under a property's `fair`
//! assumptions.
//!
//! - **Runs.** A state with no successors (no machine can ring) stays so for ever: a run may
//!   end there. Every other run is infinite, and only **fair** runs count: for every machine,
//!   infinitely often it is not running, or its state was just entered, or every time test of
//!   its state is due, or its state has none (time passes: a state's timeouts come due if it
//!   stays long enough); and each `fair` expression holds infinitely often. Each of these is a
//!   set of states a fair run meets infinitely often (a generalized Büchi condition).
//! - **Failure** is a run that stays in the "bad" states (¬P; for `leads_to`, ¬Q after a
//!   P∧¬Q state) from where it starts (an initial state; for `leads_to` a reachable P∧¬Q state;
//!   for `always_eventually` any reachable state) and ends in a terminal state or in a cycle
//!   through a strongly connected set of them that meets every acceptance set. Tarjan's
//!   components of the bad states ([`crate::components`]) find one in linear time, and
//!   [`crate::lasso`] draws it.
//! - **Incomplete explorations**: only expanded states (all successors made) take part. A lasso
//!   among them is a real run, so a failure; otherwise the verdict is incomplete.

use crate::acceptance::{acceptance_sets, meets, FailingRun};
use crate::components::Components;
use crate::explore::Graph;
use crate::lasso;
use crate::outcome::{PropertyOutcome, Trace, Verdict};
use crate::property::Property;
use crate::search::Search;
use proclaim_behaviour::PropertyKind;

/// The verdict of liveness property `property` on `graph`, with its lasso when it fails.
pub fn outcome(model: &Search, graph: &Graph, property: &Property) -> PropertyOutcome {
    let found = failing_run(model, graph, property);
    let verdict = match (&found, graph.complete) {
        (Some(_), _) => Verdict::Fails,
        (None, true) => Verdict::Holds,
        (None, false) => Verdict::Incomplete,
    };
    let (trace, cycle) = match found {
        Some(run) => {
            let (prefix, cycle) = lasso::draw(model, graph, property, &run);
            (Some(prefix), Some(cycle))
        }
        None => (None, None),
    };
    property_outcome(property, verdict, trace, cycle)
}

/// A liveness property's outcome: its verdict, and the way in and the loop of a lasso.
pub fn property_outcome(
    property: &Property,
    verdict: Verdict,
    trace: Option<Trace>,
    cycle: Option<Trace>,
) -> PropertyOutcome {
    PropertyOutcome {
        name: property.source.name.clone(),
        kind: property.source.kind.word().to_string(),
        expression: property.source.expression.clone(),
        fair: property.source.fair.clone(),
        verdict,
        trace,
        cycle,
        unconfirmed: false,
        followed: false,
    }
}

/// The bad states and where runs start staying in them, then a failing run if there is one.
fn failing_run(model: &Search, graph: &Graph, property: &Property) -> Option<FailingRun> {
    let kind = property.source.kind;
    let mut inside = vec![false; graph.len()];
    let mut seeds = Vec::new();
    for id in 0..graph.expanded() as u32 {
        let world = graph.world(id);
        let (bad, seed) = match kind {
            PropertyKind::LeadsTo => {
                let bad = !property.then_holds_in(model, &world);
                (bad, bad && property.holds_in(model, &world))
            }
            PropertyKind::Eventually => {
                let bad = !property.holds_in(model, &world);
                (bad, bad && graph.is_initial(id))
            }
            // `always_eventually`: a run may stop meeting P from any state (the safety kinds
            // never come here).
            _ => {
                let bad = !property.holds_in(model, &world);
                (bad, bad)
            }
        };
        inside[id as usize] = bad;
        if seed {
            seeds.push(id);
        }
    }
    let sets = acceptance_sets(model, property);
    let mut found = None;
    {
        let mut components = Components::new(graph, &inside);
        let mut stays_bad = |members: &[u32]| -> bool {
            let bad = match members {
                [v] if graph.edge_range(*v).is_empty() => true,
                [v] if !graph.successors_of(*v).any(|w| w == *v) => false,
                _ => meets_every_set(model, graph, property, members, sets),
            };
            if bad {
                found = Some(members.to_vec());
            }
            bad
        };
        for &seed in &seeds {
            if components.search_from(seed, &mut stays_bad).is_some() {
                let component = found.take().unwrap_or_default();
                // `always_eventually` may start anywhere: straight into the component.
                let seed = if kind == PropertyKind::AlwaysEventually {
                    component.iter().copied().min().unwrap_or(seed)
                } else {
                    seed
                };
                return Some(FailingRun {
                    seed,
                    inside,
                    component,
                });
            }
        }
    }
    None
}

/// Whether the states of a component meet every acceptance set between them.
fn meets_every_set(
    model: &Search,
    graph: &Graph,
    property: &Property,
    members: &[u32],
    sets: usize,
) -> bool {
    let mut met = vec![false; sets];
    let mut left = sets;
    for &v in members {
        let world = graph.world(v);
        for (set, m) in met.iter_mut().enumerate() {
            if !*m && meets(model, property, &world, set) {
                *m = true;
                left -= 1;
            }
        }
        if left == 0 {
            return true;
        }
    }
    left == 0
}
