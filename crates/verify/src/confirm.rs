//! A run found with the clocks of different machines unordered, followed through the model with
//! them ordered (§6, time; `refine.rs`), for a property whose ordered search ran out, or for a
//! deadlock found: the ordered model may be far too large to search, but a run of the first
//! model is one path to follow. The follower keeps the *set* of ordered worlds that fit the
//! run's, step by step, each reached by real steps of the ordered model.
//! - A counterexample or witness is followed loosely: each step of a machine without ordered
//!   clocks is held to the run's (that machine, the others without, the free values), while the
//!   machines with ordered clocks ring or not as the schedule has them; a world at the end that
//!   is the property's target decides it, the way with fewest firings of those machines shown.
//! - A deadlock likewise, to a world that shows the run's last exactly: from it no transition
//!   can ever fire again unordered, so none can ordered (its steps are some of those).
//! - A lasso is followed exactly (its loop's verdict rests on every machine), round its loop
//!   until a set of worlds at the loop's start comes back, which makes a loop of ordered worlds.
//!
//! A run not followed, or one that would hold more worlds than the search's budget, decides
//! nothing.

use crate::clocks;
use crate::outcome::{PropertyOutcome, Trace, Verdict};
use crate::property::Property;
use crate::ringlet::{initial_worlds, Choice, StepGenerator};
use crate::search::Search;
use crate::seen::{Names, Run, Seen, Shown};
use crate::trace::{names, seen, trace_of};
use crate::world::{Control, SystemState};
use proclaim_behaviour::PropertyKind;
use rustc_hash::{FxHashMap, FxHashSet};

/// How often a lasso's loop is followed round before its start's worlds must have come back.
const MOST_LAPS: usize = 64;

/// The most worlds a step of a loose follow keeps, those with fewest firings of machines with
/// ordered clocks first: a loose follow needs one way, not every one, and the machines it
/// lets do what they like would otherwise multiply its worlds.
const BEAM: usize = 256;

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
/// run follows through the model, decided by that run; no more worlds held at once than
/// `budget` states of the search would take.
pub(crate) fn confirm(
    model: &Search,
    properties: &[Property],
    outcomes: &mut [PropertyOutcome],
    found: &[Option<Found>],
    budget: (usize, usize),
) {
    for ((outcome, property), found) in outcomes.iter_mut().zip(properties).zip(found) {
        let Some(found) = found else { continue };
        if outcome.verdict != Verdict::Incomplete || found.way.worlds.is_empty() {
            continue;
        }
        let followed = match &found.cycle {
            None => follow_way(model, property, &found.way, budget).map(|trace| (trace, None)),
            Some(cycle) => follow_lasso(model, &found.way, cycle, budget)
                .map(|(way_in, round)| (way_in, Some(round))),
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

/// A deadlock's `run` followed loosely to a world that shows its last exactly, as the trace of
/// that ordered run; with no more worlds held at once than `budget` states of the search would
/// take.
pub(crate) fn deadlock(model: &Search, run: &Run, budget: (usize, usize)) -> Option<Trace> {
    let last = run.worlds.last()?;
    let exact = Fit::new(model, &run.names, true);
    loosely_to(model, run, budget, |w| exact.fits(&seen(model, w), last))
}

/// Which parts of a world the follower holds to the run's, and where each of the model's slots
/// and `saw()`s is in the run's (the run's model may have been built for more properties).
struct Fit {
    /// Whether every part is held, the turn too: else the turn is not, since a machine not held
    /// may ring where the run's did not, or not ring where it did.
    exact: bool,
    /// Per machine, whether it is held (all of them when following exactly).
    machines: Vec<bool>,
    /// Per slot, whether it is held, and where it is in the run.
    slots: Vec<(bool, Option<usize>)>,
    /// Per `saw()`, where it is in the run; `None` when they are not held.
    saw: Option<Vec<Option<usize>>>,
}

impl Fit {
    fn new(model: &Search, run: &Names, exact: bool) -> Fit {
        let here = names(model);
        let ranks = clocks::ranks(&model.machines);
        let free: FxHashSet<usize> = model.free_slots().map(|(slot, _)| slot).collect();
        Fit {
            exact,
            machines: ranks.iter().map(|r| exact || r.is_none()).collect(),
            slots: (places(&here.slots, &run.slots).into_iter().enumerate())
                .map(|(slot, place)| (exact || free.contains(&slot), place))
                .collect(),
            saw: exact.then(|| places(&here.saw, &run.saw)),
        }
    }

    /// Whether world `got` of this model fits world `run` of the run.
    fn fits(&self, got: &Seen, run: &Seen) -> bool {
        // A value this model does not keep fits any; one it keeps must be the run's too.
        let value = |v: &Shown, at: Option<usize>, run: &[Shown]| {
            *v == Shown::Unstored || at.and_then(|i| run.get(i)).is_some_and(|w| v.agrees(w))
        };
        (!self.exact || got.turn == run.turn)
            && got.machines.len() == run.machines.len()
            && (got.machines.iter().zip(&run.machines).zip(&self.machines))
                .all(|((a, b), &held)| !held || a == b)
            && (got.values.iter().zip(&self.slots))
                .all(|(v, &(held, at))| !held || value(v, at, &run.values))
            && self
                .saw
                .as_ref()
                .is_none_or(|saw| (got.saw.iter().zip(saw)).all(|(v, &at)| value(v, at, &run.saw)))
    }
}

/// Steps of a way, each the world it starts from and its choice.
type Steps = Vec<(SystemState, Choice)>;

/// Where each of `mine` is in `theirs`. Two slots may share a name (a machine's `Pump.level`
/// and a global written so): the same names in the same order map by place, else a name
/// repeated on either side maps to nothing.
fn places(mine: &[String], theirs: &[String]) -> Vec<Option<usize>> {
    if mine == theirs {
        return (0..mine.len()).map(Some).collect();
    }
    let once = |names: &[String], name: &String| {
        let mut at = (names.iter().enumerate()).filter(|(_, n)| *n == name);
        match (at.next(), at.next()) {
            (Some((i, _)), None) => Some(i),
            _ => None,
        }
    };
    (mine.iter())
        .map(|name| once(mine, name).and(once(theirs, name)))
        .collect()
}

/// How an ordered world of a step was reached.
#[derive(Clone)]
enum Came {
    /// The initial world of this number.
    Initial(usize),
    /// From node `parent` of the step before, by these steps (each the world it starts from
    /// and its choice): one when following exactly, else the steps of machines not held that
    /// the schedule puts before the run's next step, and that step.
    Steps { parent: usize, steps: Steps },
}

/// A world on the way from a node of the last layer, by `steps` (the last of `machine`), with
/// `fired` so far.
struct Going {
    parent: usize,
    steps: Steps,
    machine: usize,
    world: SystemState,
    fired: u32,
}

/// `g` in `layer`, unless a way to its world with no more firings is there already.
fn keep(layer: &mut Vec<Node>, met: &mut FxHashMap<SystemState, usize>, g: Going) {
    let came = Came::Steps {
        parent: g.parent,
        steps: g.steps,
    };
    match met.get(&g.world) {
        Some(&i) if layer[i].fired > g.fired => {
            layer[i].came = came;
            layer[i].fired = g.fired;
        }
        Some(_) => {}
        None => {
            met.insert(g.world.clone(), layer.len());
            layer.push(Node {
                world: g.world,
                came,
                fired: g.fired,
            });
        }
    }
}

/// An ordered world that fits a world of the run.
struct Node {
    world: SystemState,
    came: Came,
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
    /// Worlds held in all layers, and the most that may be.
    held: usize,
    most: usize,
}

impl<'a> Layers<'a> {
    /// The initial worlds that fit the run's first, with at most as many worlds held in all
    /// as `budget` (states, bytes) of the search would store.
    fn start(
        model: &'a Search<'a>,
        run: &Run,
        exact: bool,
        budget: (usize, usize),
    ) -> Option<Self> {
        let fit = Fit::new(model, &run.names, exact);
        let first = run.worlds.first()?;
        let layer: Vec<Node> = (initial_worlds(model).enumerate())
            .filter(|(_, w)| fit.fits(&seen(model, w), first))
            .map(|(i, world)| Node {
                world,
                came: Came::Initial(i),
                fired: 0,
            })
            .collect();
        // A node's world, and its key in a step's table of worlds met.
        let bytes = 2
            * (std::mem::size_of::<Node>()
                + model.machines.len() * std::mem::size_of::<Control>()
                + 4 * (model.slots.len() + model.saw.len()));
        (!layer.is_empty()).then(|| Layers {
            model,
            fit,
            ordered: (clocks::ranks(&model.machines).iter())
                .map(Option::is_some)
                .collect(),
            stepper: StepGenerator::new(model),
            held: layer.len(),
            most: budget.0.min(budget.1 / bytes),
            layers: vec![layer],
        })
    }

    /// The last layer's worlds, as the start of ways on.
    fn going(&self) -> Vec<Going> {
        let last = self.layers.last().expect("a first layer");
        (last.iter().enumerate())
            .map(|(parent, n)| Going {
                parent,
                steps: Vec::new(),
                machine: usize::MAX,
                world: n.world.clone(),
                fired: n.fired,
            })
            .collect()
    }

    /// The worlds `going` leads to by one step each, of a machine `by` allows; their firings of
    /// machines with ordered clocks counted.
    fn on(&self, going: Vec<Going>, by: impl Fn(usize) -> bool, out: &mut Vec<Going>) {
        let mut successors = Vec::new();
        for g in going {
            successors.clear();
            self.stepper.successors(&g.world, false, &mut successors);
            for s in successors.drain(..).filter(|s| by(s.machine)) {
                let mut steps = g.steps.clone();
                steps.push((g.world.clone(), s.choice));
                out.push(Going {
                    parent: g.parent,
                    steps,
                    machine: s.machine,
                    world: s.world,
                    fired: g.fired + u32::from(self.ordered[s.machine] && s.fired.is_some()),
                });
            }
        }
    }

    /// One step on, to the worlds that fit `next`: any step when following exactly (`by`
    /// none), else a step of machine `by` after the steps of machines not held that the
    /// schedule puts before it (fewer than there are machines). `false` where no world fits,
    /// or the worlds would pass the budget.
    fn step(&mut self, next: &Seen, by: Option<usize>) -> bool {
        let mut layer: Vec<Node> = Vec::new();
        let mut met: FxHashMap<SystemState, usize> = FxHashMap::default();
        let mut between: FxHashSet<SystemState> = FxHashSet::default();
        let mut going = self.going();
        let depth = if by.is_some() {
            self.model.machines.len()
        } else {
            0
        };
        for _ in 0..=depth {
            let mut stepped = Vec::new();
            self.on(going, |_| true, &mut stepped);
            going = Vec::new();
            for g in stepped {
                if by.is_none_or(|m| m == g.machine) {
                    if self.fit.fits(&seen(self.model, &g.world), next) {
                        keep(&mut layer, &mut met, g);
                    }
                } else if !self.fit.machines[g.machine] && between.insert(g.world.clone()) {
                    going.push(g);
                }
            }
            if self.held + layer.len() > self.most || between.len() > self.most {
                return false;
            }
        }
        if by.is_some() && layer.len() > BEAM {
            layer.sort_by_key(|n| n.fired);
            layer.truncate(BEAM);
        }
        self.held += layer.len();
        let going = !layer.is_empty();
        self.layers.push(layer);
        going
    }

    /// Follows `run` after its first world, exactly.
    fn follow(&mut self, run: &[Seen]) -> bool {
        run.iter().skip(1).all(|next| self.step(next, None))
    }

    /// Follows `run` loosely: each step of a machine held, after those of the others the
    /// schedule puts before it.
    fn follow_loosely(&mut self, run: &Run) -> bool {
        let held = self.fit.machines.clone();
        (run.rang.iter().zip(&run.worlds[1..]))
            .filter(|(&m, _)| held[m])
            .all(|(&m, next)| self.step(next, Some(m)))
    }

    /// A world that is a target: of the last layer, or one that at most `depth`
    /// steps of machines not held lead to; the one with fewest firings of machines with
    /// ordered clocks, then the nearest. Its node in the last layer, and the steps from it.
    fn target(
        &self,
        is_target: impl Fn(&SystemState) -> bool,
        depth: usize,
    ) -> Option<(usize, Steps)> {
        let mut best: Option<(u32, usize, Steps)> = None;
        let mut between: FxHashSet<SystemState> = FxHashSet::default();
        let mut going = self.going();
        for d in 0..=depth {
            for g in &going {
                let better = best.as_ref().is_none_or(|b| g.fired < b.0);
                if better && is_target(&g.world) {
                    best = Some((g.fired, g.parent, g.steps.clone()));
                }
            }
            if d == depth || between.len() > self.most {
                break;
            }
            let mut stepped = Vec::new();
            self.on(going, |k| !self.fit.machines[k], &mut stepped);
            going = (stepped.into_iter())
                .filter(|g| between.insert(g.world.clone()))
                .collect();
        }
        best.map(|(_, at, steps)| (at, steps))
    }

    /// The way to node `at` of layer `layer` from the layer `down_to`'s node it came from:
    /// that node, and each step's world and choice.
    fn way(&self, layer: usize, at: usize, down_to: usize) -> (usize, Steps) {
        let (mut layer, mut at) = (layer, at);
        let mut chunks = Vec::new();
        while layer > down_to {
            let Came::Steps { parent, steps } = &self.layers[layer][at].came else {
                unreachable!("only the first layer's worlds are initial");
            };
            chunks.push(steps);
            layer -= 1;
            at = *parent;
        }
        let steps = chunks.into_iter().rev().flatten().cloned().collect();
        (at, steps)
    }

    /// The way from an initial world to node `at` of layer `layer`, then `then`, replayed as a
    /// trace, and where `then` starts in it; `None` if the replay does not go all the way.
    fn trace(&self, layer: usize, at: usize, then: Steps) -> Option<(Trace, usize)> {
        let (first, mut steps) = self.way(layer, at, 0);
        let Came::Initial(initial) = self.layers[0][first].came else {
            unreachable!("the first layer's worlds are initial");
        };
        let split = steps.len();
        let last = match then.last() {
            Some((world, choice)) => self.after(world, *choice)?,
            None => self.layers[layer][at].world.clone(),
        };
        steps.extend(then);
        let length = steps.len();
        let trace = trace_of(self.model, initial, steps);
        // A replay that stops short would be a bug in the model; then the run decides nothing.
        let whole = trace.steps.len() == length
            && trace.run.worlds.last() == Some(&seen(self.model, &last));
        whole.then_some((trace, split))
    }

    /// The world step `choice` leads to from `world`.
    fn after(&self, world: &SystemState, choice: Choice) -> Option<SystemState> {
        let mut successors = Vec::new();
        self.stepper.successors(world, false, &mut successors);
        (successors.into_iter())
            .find(|s| s.choice == choice)
            .map(|s| s.world)
    }

    fn worlds(&self, layer: usize) -> FxHashMap<&SystemState, usize> {
        (self.layers[layer].iter().enumerate())
            .map(|(i, n)| (&n.world, i))
            .collect()
    }
}

/// A counterexample or witness: `way` followed loosely, then on by steps of machines not held
/// (as many as the run took after its last step of one held, and one a machine more) to a
/// world that is `property`'s target.
fn follow_way(
    model: &Search,
    property: &Property,
    way: &Run,
    budget: (usize, usize),
) -> Option<Trace> {
    loosely_to(model, way, budget, |w| property.is_target(model, w))
}

/// `way` followed loosely, then on by steps of machines not held (as many as the run took
/// after its last step of one held, and one a machine more) to a world `is_target` takes.
fn loosely_to(
    model: &Search,
    way: &Run,
    budget: (usize, usize),
    is_target: impl Fn(&SystemState) -> bool,
) -> Option<Trace> {
    let mut layers = Layers::start(model, way, false, budget)?;
    if !layers.follow_loosely(way) {
        return None;
    }
    let after = (way.rang.iter().rev())
        .take_while(|&&m| !layers.fit.machines[m])
        .count();
    let (at, then) = layers.target(is_target, after + model.machines.len())?;
    Some(layers.trace(layers.layers.len() - 1, at, then)?.0)
}

/// A lasso: `way` followed to the loop's start, then round `cycle` until the worlds at its
/// start are a set met at an earlier lap. Every world of that set was reached from one of it
/// by some laps, so walking back from one lands on a world met again: the ordered loop.
fn follow_lasso(
    model: &Search,
    way: &Run,
    cycle: &Run,
    budget: (usize, usize),
) -> Option<(Trace, Trace)> {
    // A lasso whose loop does not start where its way ends, or does not close, decides nothing.
    let (entry, start_of_loop) = (way.worlds.last()?, cycle.worlds.first());
    if start_of_loop.is_some_and(|s| s != entry) || cycle.worlds.last() != start_of_loop {
        return None;
    }
    let mut layers = Layers::start(model, way, true, budget)?;
    if !layers.follow(&way.worlds) {
        return None;
    }
    let start = layers.layers.len() - 1;
    if cycle.worlds.len() < 2 {
        return ended(&layers);
    }
    let lap = cycle.worlds.len() - 1;
    let set = |layers: &Layers, at: usize| -> FxHashSet<SystemState> {
        layers.layers[at].iter().map(|n| n.world.clone()).collect()
    };
    let mut starts = vec![set(&layers, start)];
    for laps in 1..=MOST_LAPS {
        if !layers.follow(&cycle.worlds) {
            return None;
        }
        let now = set(&layers, start + laps * lap);
        let Some(earlier) = starts.iter().position(|s| *s == now) else {
            // The sets kept to compare are worlds held too.
            layers.held += now.len();
            if layers.held > layers.most {
                return None;
            }
            starts.push(now);
            continue;
        };
        return close_loop(&layers, start + earlier * lap, start + laps * lap);
    }
    None
}

/// A lasso whose run ends where no machine can ring: the way to a world of the last layer where
/// none can either, and a loop of no steps.
fn ended(layers: &Layers) -> Option<(Trace, Trace)> {
    let last = layers.layers.len() - 1;
    let mut next = Vec::new();
    let at = (layers.layers[last].iter()).position(|n| {
        next.clear();
        layers.stepper.successors(&n.world, false, &mut next);
        next.is_empty()
    })?;
    let (way_in, _) = layers.trace(last, at, Vec::new())?;
    let stays = Trace {
        initially: Vec::new(),
        steps: Vec::new(),
        unposted: Vec::new(),
        run: Run::default(),
    };
    Some((way_in, stays))
}

/// With the worlds of layers `from` and `to` one set, the loop through them and the way to it.
fn close_loop(layers: &Layers, from: usize, to: usize) -> Option<(Trace, Trace)> {
    let at_to = layers.worlds(to);
    // Walking back from a world of `to` to `from` lands on a world of the set again.
    let mut met: Vec<&SystemState> = Vec::new();
    let mut backs: Vec<Steps> = Vec::new();
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
    // met[k+1] leads to met[k] by backs[k], so from met[repeat] (the last one walked back to)
    // forward through them in reverse.
    let loop_steps: Steps = backs[repeat..].iter().rev().flatten().cloned().collect();
    let from_at = layers.worlds(from)[met[repeat]];
    let (whole, split) = layers.trace(from, from_at, loop_steps)?;
    // The loop ends where it starts.
    if whole.run.worlds.get(split) != whole.run.worlds.last() {
        return None;
    }
    Some(whole.split(split))
}
