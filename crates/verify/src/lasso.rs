//! A failing liveness property's run drawn as a lasso: the shortest way to where it starts
//! staying bad (the exploration's breadth-first parents), the shortest way on through bad
//! states into the component where it stays, then a loop inside that component through one
//! state of every acceptance set and back; both replayed step by step as counterexamples are.

use crate::acceptance::{acceptance_sets, meets, FailingRun};
use crate::explore::Graph;
use crate::outcome::Trace;
use crate::property::Property;
use crate::ringlet::StepGenerator;
use crate::search::Search;
use crate::trace;
use rustc_hash::{FxHashMap, FxHashSet};
use std::collections::VecDeque;

/// The lasso of `run`: the way in (from an initial state) and the loop (no steps when the
/// run ends in a state where no machine can ring).
pub fn draw(
    model: &Search,
    graph: &Graph,
    property: &Property,
    run: &FailingRun,
) -> (Trace, Trace) {
    let component: FxHashSet<u32> = run.component.iter().copied().collect();
    let in_component = |v: u32| component.contains(&v);
    let (initial, mut steps) = graph.path(model, run.seed);
    let to_seed = steps.len();
    let mut states = vec![run.seed];
    if !in_component(run.seed) {
        let inside = |v: u32| run.inside[v as usize];
        states.extend(shortest(graph, run.seed, &inside, &in_component));
    }
    let prefix_states = states.len();
    let start = *states.last().unwrap_or(&run.seed);
    let ends = graph.edge_range(start).is_empty();
    if !ends {
        states.extend(cycle(model, graph, property, start, &component));
    }
    let stepper = StepGenerator::new(model);
    for pair in states.windows(2) {
        match graph.choice_between(&stepper, pair[0], pair[1]) {
            Some(choice) => steps.push((pair[0], choice)),
            // Every edge was made by a step; one not made again would be a bug in the model,
            // and the lasso ends where it could be followed.
            None => break,
        }
    }
    let whole = trace::replay(model, graph, initial, &steps);
    whole.split(to_seed + prefix_states - 1)
}

/// From `start` (in the component) through a state of every acceptance set and back to
/// `start`, inside the component; the states after `start`, ending with it.
fn cycle(
    model: &Search,
    graph: &Graph,
    property: &Property,
    start: u32,
    component: &FxHashSet<u32>,
) -> Vec<u32> {
    let in_component = |v: u32| component.contains(&v);
    let sets = acceptance_sets(model, property);
    let mut met = vec![false; sets];
    let mark = |v: u32, met: &mut Vec<bool>| {
        let world = graph.world(v);
        for (set, m) in met.iter_mut().enumerate() {
            *m = *m || meets(model, property, &world, set);
        }
    };
    mark(start, &mut met);
    let mut path = Vec::new();
    let mut at = start;
    for set in 0..sets {
        if met[set] {
            continue;
        }
        let is_member = |v: u32| meets(model, property, &graph.world(v), set);
        let way = shortest(graph, at, &in_component, &is_member);
        for &v in &way {
            mark(v, &mut met);
        }
        at = way.last().copied().unwrap_or(at);
        path.extend(way);
    }
    path.extend(shortest(graph, at, &in_component, &|v| v == start));
    path
}

/// The shortest way from `from` through states where `allowed` holds to one (not `from`
/// itself unless by a step) where `target` holds: the states after `from`.
fn shortest(
    graph: &Graph,
    from: u32,
    allowed: &dyn Fn(u32) -> bool,
    target: &dyn Fn(u32) -> bool,
) -> Vec<u32> {
    let mut parent: FxHashMap<u32, u32> = FxHashMap::default();
    let mut queue = VecDeque::from([from]);
    while let Some(v) = queue.pop_front() {
        for w in graph.successors_of(v) {
            if !allowed(w) || parent.contains_key(&w) {
                continue;
            }
            parent.insert(w, v);
            if target(w) {
                let mut way = vec![w];
                let mut at = w;
                while let Some(&p) = parent.get(&at) {
                    if p == from {
                        break;
                    }
                    way.push(p);
                    at = p;
                }
                way.reverse();
                return way;
            }
            queue.push_back(w);
        }
    }
    Vec::new()
}
