//! A run found with the clocks of different machines unordered, followed through the model with
//! them ordered (§6, time; `refine.rs`), for a property whose ordered search ran out: the
//! ordered model may be far too large to search, but a run of the first model is one path to
//! follow. The follower keeps the *set* of ordered worlds that fit the run's worlds, step by
//! step. A counterexample or witness is followed loosely: every ordered world whose machines
//! without ordered clocks, free values and turn are the run's, whatever the machines with
//! ordered clocks did (the run's may have taken a longer timeout before a shorter one), and a
//! world at its end that is the property's target decides it. A lasso is followed exactly (its
//! loop's verdict rests on every machine), round its loop until a set of worlds at the loop's
//! start comes back, which makes a loop of ordered worlds. A run not followed decides nothing.

use crate::clocks;
use crate::outcome::{PropertyOutcome, Trace, Verdict};
use crate::property::Property;
use crate::ringlet::{initial_worlds, Choice, StepGenerator};
use crate::search::Search;
use crate::seen::{Run, Seen};
use crate::trace::{seen, trace_of};
use crate::world::SystemState;
use proclaim_behaviour::PropertyKind;
use rustc_hash::{FxHashMap, FxHashSet};

/// The most worlds one step of a run is matched by; past it the run is not followed.
const MOST_WORLDS: usize = 1 << 16;

/// How often a lasso's loop is followed round before its start's worlds must have come back.
const MOST_LAPS: usize = 64;

/// Which parts of a world the follower holds to the run's.
enum Fit {
    Exact,
    /// The machines whose clocks are not ordered (`true`), the free slots (`true`), the turn.
    Loose {
        machines: Vec<bool>,
        slots: Vec<bool>,
    },
}

impl Fit {
    fn loose(model: &Search) -> Fit {
        let mut slots = vec![false; model.slots.len()];
        for (slot, _) in model.free_slots() {
            slots[slot] = true;
        }
        Fit::Loose {
            machines: (clocks::ranks(&model.machines).iter())
                .map(Option::is_none)
                .collect(),
            slots,
        }
    }

    /// Whether world `got` of the ordered model fits world `run` of the run.
    fn fits(&self, got: &Seen, run: &Seen) -> bool {
        let Fit::Loose { machines, slots } = self else {
            return got == run;
        };
        fn held<T: PartialEq>(got: &[T], run: &[T], held: &[bool]) -> bool {
            got.len() == run.len()
                && (got.iter().zip(run).zip(held)).all(|((a, b), &held)| !held || a == b)
        }
        got.turn == run.turn
            && held(&got.machines, &run.machines, machines)
            && held(&got.values, &run.values, slots)
    }
}

/// The runs the unordered search found, a property each: its way (or its way in) and its loop.
#[derive(Clone, Debug, Default)]
pub(crate) struct Found {
    pub way: Run,
    pub cycle: Option<Run>,
}

impl Found {
    /// The run that decided `outcome`, if one did.
    pub(crate) fn of(outcome: &PropertyOutcome) -> Option<Found> {
        Some(Found {
            way: outcome.trace.as_ref()?.run.clone(),
            cycle: outcome.cycle.as_ref().map(|c| c.run.clone()),
        })
    }
}

/// Each undecided property of `outcomes` (checked in `model` as `properties`) whose `found`
/// run follows through the model, decided by that run.
pub(crate) fn confirm(
    model: &Search,
    properties: &[Property],
    outcomes: &mut [PropertyOutcome],
    found: &[Option<Found>],
) {
    for ((outcome, property), found) in outcomes.iter_mut().zip(properties).zip(found) {
        let Some(found) = found else { continue };
        if outcome.verdict != Verdict::Incomplete || found.way.0.is_empty() {
            continue;
        }
        let followed = match &found.cycle {
            None => follow_way(model, property, &found.way).map(|trace| (trace, None)),
            Some(cycle) => {
                follow_lasso(model, &found.way, cycle).map(|(way_in, round)| (way_in, Some(round)))
            }
        };
        if let Some((trace, cycle)) = followed {
            outcome.verdict = match property.source.kind {
                PropertyKind::Reachable => Verdict::Holds,
                _ => Verdict::Fails,
            };
            outcome.trace = Some(trace);
            outcome.cycle = cycle;
            outcome.followed = true;
        }
    }
}

/// An ordered world that shows a world of the run, and how it was reached.
struct Node {
    world: SystemState,
    /// Its parent's place in the step before, and the choice taken there; for the first step,
    /// the number of the initial world.
    from: Result<(usize, Choice), usize>,
    /// Transitions fired on the way by machines with ordered clocks, which a loose fit lets
    /// do what they like: of the ways to a world, the one with fewest is kept, so that a
    /// counterexample shows what its verdict needs and not every timeout the run let fire.
    fired: u32,
}

/// The worlds of each step of the run so far.
struct Layers<'a> {
    model: &'a Search<'a>,
    fit: Fit,
    /// The machines whose clocks are ordered.
    ordered: Vec<bool>,
    stepper: StepGenerator<'a>,
    layers: Vec<Vec<Node>>,
}

impl<'a> Layers<'a> {
    /// The initial worlds that show `first`.
    fn start(model: &'a Search<'a>, fit: Fit, first: &Seen) -> Option<Layers<'a>> {
        let layer: Vec<Node> = (initial_worlds(model).enumerate())
            .filter(|(_, w)| fit.fits(&seen(model, w), first))
            .map(|(i, world)| Node {
                world,
                from: Err(i),
                fired: 0,
            })
            .collect();
        (!layer.is_empty()).then(|| Layers {
            model,
            fit,
            ordered: (clocks::ranks(&model.machines).iter())
                .map(Option::is_some)
                .collect(),
            stepper: StepGenerator::new(model),
            layers: vec![layer],
        })
    }

    /// One step on, to the worlds that show `next`; `false` where none does, or too many.
    fn step(&mut self, next: &Seen) -> bool {
        let last = self.layers.last().expect("a first layer");
        let mut layer: Vec<Node> = Vec::new();
        let mut met: FxHashMap<SystemState, usize> = FxHashMap::default();
        let mut successors = Vec::new();
        for (at, node) in last.iter().enumerate() {
            successors.clear();
            self.stepper.successors(&node.world, false, &mut successors);
            for s in successors.drain(..) {
                if !self.fit.fits(&seen(self.model, &s.world), next) {
                    continue;
                }
                let fired = node.fired + u32::from(self.ordered[s.machine] && s.fired.is_some());
                let from = Ok((at, s.choice));
                match met.get(&s.world) {
                    Some(&i) if layer[i].fired > fired => {
                        layer[i].from = from;
                        layer[i].fired = fired;
                    }
                    Some(_) => {}
                    None => {
                        met.insert(s.world.clone(), layer.len());
                        layer.push(Node {
                            world: s.world,
                            from,
                            fired,
                        });
                    }
                }
            }
            if layer.len() > MOST_WORLDS {
                return false;
            }
        }
        let going = !layer.is_empty();
        self.layers.push(layer);
        going
    }

    /// Follows `run` after its first world.
    fn follow(&mut self, run: &[Seen]) -> bool {
        run.iter().skip(1).all(|next| self.step(next))
    }

    /// The way to node `at` of layer `layer` from the layer `down_to`'s node it came from:
    /// that node, and each step's world and choice.
    fn way(&self, layer: usize, at: usize, down_to: usize) -> (usize, Vec<(SystemState, Choice)>) {
        let (mut layer, mut at) = (layer, at);
        let mut steps = Vec::new();
        while layer > down_to {
            let Ok((parent, choice)) = self.layers[layer][at].from else {
                unreachable!("only the first layer's worlds are initial");
            };
            layer -= 1;
            at = parent;
            steps.push((self.layers[layer][at].world.clone(), choice));
        }
        steps.reverse();
        (at, steps)
    }

    /// The way from an initial world to node `at` of layer `layer`, as a trace.
    fn trace(&self, layer: usize, at: usize, then: Vec<(SystemState, Choice)>) -> (Trace, usize) {
        let (first, mut steps) = self.way(layer, at, 0);
        let Err(initial) = self.layers[0][first].from else {
            unreachable!("the first layer's worlds are initial");
        };
        let split = steps.len();
        steps.extend(then);
        (trace_of(self.model, initial, steps), split)
    }

    fn worlds(&self, layer: usize) -> FxHashMap<&SystemState, usize> {
        (self.layers[layer].iter().enumerate())
            .map(|(i, n)| (&n.world, i))
            .collect()
    }
}

/// A counterexample or witness: `way` followed loosely to a world that is `property`'s target.
fn follow_way(model: &Search, property: &Property, way: &Run) -> Option<Trace> {
    let mut layers = Layers::start(model, Fit::loose(model), way.0.first()?)?;
    if !layers.follow(&way.0) {
        return None;
    }
    let last = layers.layers.len() - 1;
    let at = (layers.layers[last].iter().enumerate())
        .filter(|(_, n)| property.is_target(model, &n.world))
        .min_by_key(|(_, n)| n.fired)?
        .0;
    Some(layers.trace(last, at, Vec::new()).0)
}

/// A lasso: `way` followed to the loop's start, then round `cycle` until the worlds at its
/// start are a set met at an earlier lap. Every world of that set was reached from one of it
/// by some laps, so walking back from one lands on a world met again: the ordered loop.
fn follow_lasso(model: &Search, way: &Run, cycle: &Run) -> Option<(Trace, Trace)> {
    let mut layers = Layers::start(model, Fit::Exact, way.0.first()?)?;
    if !layers.follow(&way.0) {
        return None;
    }
    let start = layers.layers.len() - 1;
    if cycle.0.len() < 2 {
        // The run ends where no machine can ring; so must the ordered one.
        let stepper = StepGenerator::new(model);
        let mut next = Vec::new();
        let at = (layers.layers[start].iter()).position(|n| {
            next.clear();
            stepper.successors(&n.world, false, &mut next);
            next.is_empty()
        })?;
        let (way_in, _) = layers.trace(start, at, Vec::new());
        let stays = Trace {
            initially: Vec::new(),
            steps: Vec::new(),
            unposted: Vec::new(),
            run: Run::default(),
        };
        return Some((way_in, stays));
    }
    let lap = cycle.0.len() - 1;
    let set = |layers: &Layers, at: usize| -> FxHashSet<SystemState> {
        layers.layers[at].iter().map(|n| n.world.clone()).collect()
    };
    let mut starts = vec![set(&layers, start)];
    for laps in 1..=MOST_LAPS {
        if !layers.follow(&cycle.0) {
            return None;
        }
        let now = set(&layers, start + laps * lap);
        let Some(earlier) = starts.iter().position(|s| *s == now) else {
            starts.push(now);
            continue;
        };
        return Some(close_loop(
            &layers,
            start + earlier * lap,
            start + laps * lap,
        ));
    }
    None
}

/// With the worlds of layers `from` and `to` one set, the loop through them and the way to it.
fn close_loop(layers: &Layers, from: usize, to: usize) -> (Trace, Trace) {
    let at_to = layers.worlds(to);
    // Walking back from a world of `to` to `from` lands on a world of the set again.
    let mut met: Vec<&SystemState> = Vec::new();
    let mut backs: Vec<Vec<(SystemState, Choice)>> = Vec::new();
    let mut at = 0;
    let repeat = loop {
        let world = &layers.layers[to][at].world;
        if let Some(i) = met.iter().position(|w| *w == world) {
            break i;
        }
        met.push(world);
        let (landed, steps) = layers.way(to, at, from);
        backs.push(steps);
        at = at_to[&layers.layers[from][landed].world];
    };
    // met[k+1] leads to met[k] by backs[k]: from met[last] (= met[repeat]'s world) forward.
    let loop_steps: Vec<(SystemState, Choice)> =
        backs[repeat..].iter().rev().flatten().cloned().collect();
    let from_at = layers.worlds(from)[met[repeat]];
    let (whole, split) = layers.trace(from, from_at, loop_steps);
    debug_assert!(
        whole.run.0.get(split) == whole.run.0.last(),
        "the loop ends where it starts"
    );
    whole.split(split)
}
