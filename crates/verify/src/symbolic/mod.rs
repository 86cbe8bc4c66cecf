//! The symbolic engine: the same model as the explicit search, its sets of states as binary
//! decision diagrams (`biodivine-lib-bdd`), for behaviours of many free inputs and small
//! machines, where the states are too many to store one by one but their sets are small as
//! diagrams.
//!
//! - **Its steps are the explicit search's ringlets.** Each machine's ringlet is run by
//!   `ringlet.rs` itself on an *open* world (its own control known, every stored slot and
//!   every other machine's mode chosen where first read), once per leaf of its choices: a leaf
//!   is a cube of what was read and the constants it wrote, met with what the other machines'
//!   clocks allow of its due tests (`clocks.rs`, the one rule the open world cannot read). The
//!   image of a set under a leaf is that set and the cube, the written fields forgotten and
//!   set; no relation over primed variables is built, and no second meaning of a ringlet is
//!   written.
//! - **Fields** are the packed state's: whose turn, each machine's state, mode, just-entered,
//!   started-this-round, time and clock-order bits, every stored slot and `saw()` value as the
//!   index of its value among those it can hold, and a bit for each free type chosen when read
//!   (posted yet). Those values are found first by the same ringlets, to a fixpoint; a slot
//!   whose values keep growing (a counter) makes the engine decline.
//! - **The first ringlet** (where a free type may still be never posted) is taken by the
//!   explicit stepper: the search starts from its successors.
//! - **Breadth first by layers**, so the first layer that meets what a property looks for
//!   gives the shortest counterexample; it is rebuilt backwards through the layers and then
//!   replayed forwards by the explicit stepper, so it reads exactly as the explicit search's.
//! - **Liveness** once the search is complete: fair cycles as a fixpoint, the lasso walked by
//!   the explicit stepper ([`liveness`]).
//! - It declines (and `auto` explores explicitly) where a free type is stored (a property
//!   names it) or where a slot's values are unbounded.

mod clocks;
mod liveness;

use crate::model::Storage;
use crate::outcome::{PropertyOutcome, Stop};
use crate::property::{Property, Term};
use crate::ringlet::{
    due_masks, initial_worlds, Choice, ControlWrites, OpenLeaf, OpenRead, StepGenerator, UNKNOWN,
};
use crate::search::Search;
use crate::values::{ValueId, NEVER};
use crate::world::POSTED;
use crate::world::{Control, Status, SystemState};
use biodivine_lib_bdd::{
    Bdd, BddPartialValuation, BddValuation, BddVariable, BddVariableSet, BddVariableSetBuilder,
};

/// At most this many values a slot may hold for the engine to encode it.
const MAX_VALUES: usize = 256;

/// At most this many leaves one ringlet from one control may have (the product of the values
/// of what it reads, cut short where a label is decided early).
const MAX_LEAVES: usize = 4096;

fn too_many_leaves(model: &Search, k: usize) -> Declined {
    Declined(format!(
        "a ringlet of {} reads more than {MAX_LEAVES} combinations of values",
        model.machines[k].name
    ))
}

/// Why the symbolic engine does not take a behaviour.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Declined(pub String);

/// A world's component as decision-diagram variables: its value's index, in binary.
#[derive(Clone, Debug)]
struct Field {
    bits: Vec<BddVariable>,
}

impl Field {
    fn set(&self, index: usize, cube: &mut BddPartialValuation) {
        for (b, var) in self.bits.iter().enumerate() {
            cube.set_value(*var, index >> b & 1 == 1);
        }
    }

    fn get(&self, valuation: &BddValuation) -> usize {
        self.bits
            .iter()
            .enumerate()
            .map(|(b, var)| usize::from(valuation.value(*var)) << b)
            .sum()
    }
}

/// A machine's control as fields.
#[derive(Clone, Debug)]
struct ControlFields {
    state: Field,
    status: Field,
    just_entered: Field,
    fresh: Field,
    time: Field,
    /// [`Control::arrived`] and [`Control::order`] (`clocks.rs`): no bits for a machine whose
    /// clocks are not ordered, and no `arrived` for the last that is (none reads it).
    arrived: Field,
    order: Field,
    /// [`Control::left_due`] and [`Control::left_wait`]: no bits where nothing reads them.
    left_due: Field,
    left_wait: Field,
}

/// Every component of a world as fields, and the values each stored one can hold.
struct Encoding {
    vars: BddVariableSet,
    turn: Field,
    machines: Vec<ControlFields>,
    /// Per slot: its field when stored.
    slots: Vec<Option<Field>>,
    saw: Vec<Field>,
    /// Per slot (stored ones): the values it can hold, in the order of their indices.
    domains: Vec<Vec<ValueId>>,
    saw_domains: Vec<Vec<ValueId>>,
}

/// Bits that number `count` values (as the explicit engine's fields do).
fn bits_for(count: usize) -> usize {
    usize::from(crate::world::bits_for(count.saturating_sub(1) as u64))
}

fn status_index(s: Status) -> usize {
    match s {
        Status::Running => 0,
        Status::Suspended => 1,
        Status::Dormant => 2,
    }
}

const STATUSES: [Status; 3] = [Status::Running, Status::Suspended, Status::Dormant];

/// The turn field's value for [`crate::world::FIRST_TURN`]: after every machine's and "past
/// the last".
fn turn_index(model: &Search, turn: u8) -> usize {
    if turn == crate::world::FIRST_TURN {
        model.machines.len() + 1
    } else {
        usize::from(turn)
    }
}

impl Encoding {
    /// The fields in the order of their variables: the turn, then machine by machine its
    /// control, the slots it is the first to write and its `saw()` values, then the slots no
    /// machine writes. A slot beside its writer keeps the diagrams of "a sensor and the
    /// variable it mirrors" small.
    fn new(model: &Search, domains: Domains) -> Self {
        let mut builder = BddVariableSetBuilder::new();
        let mut count = 0usize;
        let mut field = |builder: &mut BddVariableSetBuilder, values: usize| {
            let bits = (0..bits_for(values))
                .map(|_| {
                    count += 1;
                    builder.make_variable(&format!("v{count}"))
                })
                .collect();
            Field { bits }
        };
        let turn = field(&mut builder, model.machines.len() + 2);
        let mut machines = Vec::new();
        let mut slots: Vec<Option<Field>> = vec![None; model.slots.len()];
        let mut saw: Vec<Option<Field>> = vec![None; model.saw.len()];
        let ordered = model.clock_ranks.iter().flatten().count();
        let durations = model.clock_durations.len() + 1;
        for (k, m) in model.machines.iter().enumerate() {
            let tests = m.most_time_tests();
            let ranked = model.clock_ranks[k].is_some();
            let heard = crate::clocks::heard_later(&model.clock_ranks, k);
            machines.push(ControlFields {
                state: field(&mut builder, m.states.len()),
                status: field(&mut builder, 3),
                just_entered: field(&mut builder, 2),
                fresh: field(&mut builder, 2),
                time: field(&mut builder, 1 << tests),
                arrived: field(&mut builder, if heard { 2 } else { 1 }),
                order: field(&mut builder, if ranked { 1 << ordered } else { 1 }),
                left_due: field(&mut builder, if heard { durations } else { 1 }),
                left_wait: field(&mut builder, if heard { durations } else { 1 }),
            });
            for slot in 0..model.slots.len() {
                if model.storage[slot] != Storage::Unread && domains.writer[slot] == Some(k) {
                    slots[slot] = Some(field(&mut builder, domains.slots[slot].len()));
                }
            }
            for (j, _) in model.saw_of(k) {
                saw[j] = Some(field(&mut builder, domains.saw[j].len()));
            }
        }
        for slot in 0..model.slots.len() {
            if model.storage[slot] != Storage::Unread && slots[slot].is_none() {
                slots[slot] = Some(field(&mut builder, domains.slots[slot].len()));
            }
        }
        Encoding {
            vars: builder.build(),
            turn,
            machines,
            slots,
            saw: saw
                .into_iter()
                .map(|f| f.unwrap_or(Field { bits: Vec::new() }))
                .collect(),
            domains: domains.slots,
            saw_domains: domains.saw,
        }
    }

    fn index_of(domain: &[ValueId], v: ValueId) -> usize {
        domain.iter().position(|&d| d == v).unwrap_or(0)
    }

    fn set_control(&self, m: usize, c: &Control, cube: &mut BddPartialValuation) {
        self.set_ringing_control(m, c, cube);
        let f = &self.machines[m];
        f.arrived.set(usize::from(c.arrived), cube);
        f.order.set(usize::from(c.order), cube);
    }

    /// The control a ringlet of machine `m` starts from as its steps know it: all but its
    /// clock-order bits, which are the world's ([`clocks`]).
    fn set_ringing_control(&self, m: usize, c: &Control, cube: &mut BddPartialValuation) {
        let f = &self.machines[m];
        f.state.set(usize::from(c.state), cube);
        f.status.set(status_index(c.status), cube);
        f.just_entered.set(usize::from(c.just_entered), cube);
        f.fresh.set(usize::from(c.fresh), cube);
        f.time.set(usize::from(c.time), cube);
        f.left_due.set(usize::from(c.left_due), cube);
        f.left_wait.set(usize::from(c.left_wait), cube);
    }

    /// The cube of one whole world.
    fn world(&self, model: &Search, w: &SystemState) -> BddPartialValuation {
        let mut cube = BddPartialValuation::empty();
        self.turn.set(turn_index(model, w.turn), &mut cube);
        for (m, c) in w.machines.iter().enumerate() {
            self.set_control(m, c, &mut cube);
        }
        for (slot, field) in self.slots.iter().enumerate() {
            if let Some(field) = field {
                field.set(
                    Self::index_of(&self.domains[slot], w.values[slot]),
                    &mut cube,
                );
            }
        }
        for (j, field) in self.saw.iter().enumerate() {
            field.set(Self::index_of(&self.saw_domains[j], w.saw[j]), &mut cube);
        }
        cube
    }

    /// Whether every stored value of `w` has an index (a world the encoding can hold).
    fn holds(&self, w: &SystemState) -> bool {
        self.slots
            .iter()
            .enumerate()
            .all(|(slot, f)| f.is_none() || self.domains[slot].contains(&w.values[slot]))
            && w.saw
                .iter()
                .enumerate()
                .all(|(j, v)| self.saw_domains[j].contains(v))
    }

    /// Whether world `w` is in `set`.
    fn contains(&self, model: &Search, set: &Bdd, w: &SystemState) -> bool {
        self.holds(w) && set.eval_in(&self.full_valuation(&self.world(model, w)))
    }

    fn mk(&self, cube: &BddPartialValuation) -> Bdd {
        self.vars.mk_conjunctive_clause(cube)
    }

    fn full_valuation(&self, cube: &BddPartialValuation) -> BddValuation {
        let mut v = BddValuation::all_false(self.vars.num_vars());
        for var in self.vars.variables() {
            if let Some(b) = cube.get_value(var) {
                v.set_value(var, b);
            }
        }
        v
    }
}

/// One leaf of machine `k`'s ringlet, as the engine applies it.
struct Step {
    machine: usize,
    /// Which of the machine's controls it starts from: the steps of one control stand together
    /// (`steps_of`), and the image meets the set with that control once for all of them.
    control: usize,
    /// The states with that control: the cube of the machine's control alone.
    control_set: Bdd,
    /// The cube it needs: the machine's control and what it read.
    needs: Bdd,
    /// The fields it writes, and their values.
    writes: BddPartialValuation,
    written: Vec<BddVariable>,
    /// What it writes as a set, met with after the written fields are forgotten.
    written_set: Bdd,
    /// Where `needs` is one cube (one leaf), the image of a state set under the step in three
    /// operations on diagrams no larger than the set: `needs` as assignments (the set
    /// restricted to them; empty for a step of several leaves), the written fields it does not
    /// read (forgotten), and the cube of what it needs and does not write with what it writes
    /// (met).
    reads: Vec<(BddVariable, bool)>,
    forgets: Vec<BddVariable>,
    after: Bdd,
    /// What the other machines' clocks allow of its due tests ([`clocks::guard`]), `needs`
    /// met with it: restricted to `reads`, for the image of one leaf.
    guard: Option<Bdd>,
    fired: Option<usize>,
}

/// A path from initial world number `.0`: each step's world and the choice it took.
pub type Path = (usize, Vec<(SystemState, Choice)>);

/// What the engine found.
pub struct SymbolicOutcome {
    /// Per property: the path to what it looks for.
    pub targets: Vec<Option<Path>>,
    pub stopped: Stop,
    pub states: f64,
    pub steps: usize,
    pub bytes: usize,
    /// Per machine, per state: ever current; per machine, per transition: ever fired (only
    /// meaningful once every state was reached).
    pub entered: Vec<Vec<bool>>,
    pub fired: Vec<Vec<bool>>,
    /// The nearest state from which no transition can ever fire again while a running machine
    /// is not in a final state, with the path to it (looked for only once every state was
    /// reached, as the explicit search does).
    pub deadlock: Option<(Path, SystemState)>,
    /// Per property: a liveness property's outcome, once the search is complete.
    pub liveness: Vec<Option<PropertyOutcome>>,
}

/// Numbers every value a slot or `saw()` of `model` can hold, without a search: the values of
/// the initial worlds and the first ringlets, then whatever a ringlet of any machine writes
/// from values already numbered, to a fixpoint (as [`check`] finds its fields' values).
/// Declines where a slot's values keep growing.
pub fn number_values(model: &Search) -> Result<(), Declined> {
    let stepper = StepGenerator::new(model);
    let first = first_ringlets(model, &stepper)?;
    value_domains(model, &stepper, &first.initial, &first.steps).map(|_| ())
}

/// The initial worlds and their first ringlets, which the explicit stepper takes (a free type
/// may still be never posted there).
struct FirstRinglets {
    initial: Vec<SystemState>,
    /// Per initial world, its successors and the choice that made each.
    steps: Vec<Vec<(SystemState, Choice)>>,
    /// Per machine, per transition: fired by a first ringlet.
    fired: Vec<Vec<bool>>,
    /// Per initial world: some first ringlet from it fires a transition.
    fires: Vec<bool>,
}

fn first_ringlets(model: &Search, stepper: &StepGenerator<'_>) -> Result<FirstRinglets, Declined> {
    let initial: Vec<SystemState> = initial_worlds(model).collect();
    let mut first = FirstRinglets {
        steps: Vec::new(),
        fired: model.per_transition(),
        fires: Vec::new(),
        initial: Vec::new(),
    };
    let mut successors = Vec::new();
    for w in &initial {
        successors.clear();
        stepper.successors(w, false, &mut successors);
        first
            .fires
            .push(successors.iter().any(|s| s.fired.is_some()));
        for s in &successors {
            if let Some(t) = s.fired {
                let index = model.machines[s.machine].states[s.from].transitions[t].index;
                first.fired[s.machine][index] = true;
            }
        }
        first
            .steps
            .push(successors.drain(..).map(|s| (s.world, s.choice)).collect());
    }
    if stepper.overflowed() {
        return Err(Declined(format!(
            "a first ringlet has more than {} successors",
            crate::ringlet::MAX_SUCCESSORS
        )));
    }
    first.initial = initial;
    Ok(first)
}

/// Per property, the first initial world it looks for, if any (layers 0 and 1 are the explicit
/// stepper's).
fn initial_targets(
    model: &Search,
    properties: &[Property],
    initial: &[SystemState],
) -> Vec<Option<Path>> {
    properties
        .iter()
        .map(|property| {
            let i = initial.iter().position(|w| property.is_target(model, w))?;
            Some((i, Vec::new()))
        })
        .collect()
}

/// Why the engine does not take this model, if it does not.
fn declines(model: &Search) -> Result<(), Declined> {
    if let Some((slot, _)) = model.stored_free_slots().next() {
        return Err(Declined(format!(
            "a property names the free type `{}`",
            model.slots[slot].name
        )));
    }
    Ok(())
}

/// Checks `properties` of `model` symbolically, or says why it does not.
pub fn check(
    model: &Search,
    properties: &[Property],
    max_memory: usize,
) -> Result<SymbolicOutcome, Declined> {
    declines(model)?;
    let stepper = StepGenerator::new(model);
    let FirstRinglets {
        initial,
        steps: first_steps,
        fired: first_fired,
        fires: initial_fires,
    } = first_ringlets(model, &stepper)?;
    let domains = value_domains(model, &stepper, &initial, &first_steps)?;
    let enc = Encoding::new(model, domains);
    let steps = steps_of(model, &stepper, &enc)?;
    let guards = Guards::new(model, &enc);
    let targets: Vec<Bdd> = properties
        .iter()
        .map(|p| target_set(model, &enc, p))
        .collect::<Result<_, _>>()?;

    let mut outcome = SymbolicOutcome {
        targets: initial_targets(model, properties, &initial),
        stopped: Stop::Explored,
        states: 0.0,
        steps: 0,
        bytes: 0,
        entered: model.per_state(),
        fired: first_fired,
        deadlock: None,
        liveness: vec![None; properties.len()],
    };
    let searched = Searched {
        model,
        stepper: &stepper,
        enc: &enc,
        steps: &steps,
        guards: &guards,
        initial: &initial,
        first_steps: &first_steps,
    };
    let (mut reached, mut layer) = first_layers(model, &enc, &initial, &first_steps);
    let mut layers = vec![layer.clone()];
    let decidable = !properties.is_empty();
    loop {
        for (p, target) in targets.iter().enumerate() {
            if outcome.targets[p].is_none() && !layer.and(target).is_false() {
                outcome.targets[p] = Some(
                    searched
                        .rebuild(&layers, target)
                        .map_or((0, Vec::new()), |(path, _)| path),
                );
            }
        }
        if decidable && outcome.targets.iter().all(Option::is_some) {
            outcome.stopped = Stop::Decided;
            break;
        }
        let next = image(&enc, &steps, &guards, &layer).and_not(&reached);
        if next.is_false() {
            break;
        }
        reached = reached.or(&next);
        layers.push(next.clone());
        layer = next;
        let nodes: usize = layers.iter().map(Bdd::size).sum::<usize>() + reached.size();
        outcome.bytes = nodes * 12;
        if !within_budget(model, outcome.bytes, max_memory)? {
            outcome.stopped = Stop::MemoryBudget;
            break;
        }
    }
    outcome.states = reached.cardinality();
    outcome.steps = layers.len();
    mark_entered_and_fired(model, &enc, &guards, &steps, &reached, &mut outcome);
    if outcome.stopped == Stop::Explored {
        outcome.deadlock = searched.deadlock(&layers, &reached, &initial_fires);
        for (p, property) in properties.iter().enumerate() {
            if property.source.kind.is_liveness() {
                outcome.liveness[p] = Some(searched.liveness(property, &layers, &reached)?);
            }
        }
    }
    Ok(outcome)
}

/// Goes on unless a racing engine has answered (`race.rs`): then this one declines.
fn go_on(model: &Search) -> Result<(), Declined> {
    if model.overtaken() {
        return Err(Declined("the explicit search answered first".into()));
    }
    Ok(())
}

/// Whether diagrams of `bytes` are within the budget (less what a racing engine holds, which
/// hears of them); declines once the racing engine has answered.
fn within_budget(model: &Search, bytes: usize, max_memory: usize) -> Result<bool, Declined> {
    go_on(model)?;
    model.hold(bytes);
    Ok(bytes <= model.memory_budget(max_memory))
}

/// What a finished search keeps to answer with paths: the model, its steps as the explicit
/// stepper and as diagrams, and the first ringlets (the explicit stepper's).
struct Searched<'a, 'm> {
    model: &'m Search<'m>,
    stepper: &'a StepGenerator<'m>,
    enc: &'a Encoding,
    steps: &'a [Step],
    guards: &'a Guards,
    initial: &'a [SystemState],
    first_steps: &'a [Vec<(SystemState, Choice)>],
}

impl Searched<'_, '_> {
    /// The nearest deadlock of a complete search: a reached state, not live, where a running
    /// machine is not in a final state. Live: some ringlet that fires a transition can still be
    /// reached from it (a backward fixpoint from the states where one can fire).
    fn deadlock(
        &self,
        layers: &[Bdd],
        reached: &Bdd,
        initial_fires: &[bool],
    ) -> Option<(Path, SystemState)> {
        let (enc, guards) = (self.enc, self.guards);
        let firing = self.steps.iter().filter(|s| s.fired.is_some());
        let mut live = preimage(enc, firing, guards, &enc.vars.mk_true(), reached);
        let mut initial_set = enc.vars.mk_false();
        for w in self.initial {
            initial_set = initial_set.or(&enc.mk(&enc.world(self.model, w)));
        }
        // Only a state where a machine waits and nothing fires can be a deadlock, and the first
        // ringlets are the explicit stepper's, so an initial world that waits and fires nothing
        // is judged by where they lead. The fixpoint stops once all of those are known live.
        let dead_here = reached
            .and_not(&live)
            .and_not(&initial_set)
            .and(&waiting_set(self.model, enc));
        let mut first_successors = enc.vars.mk_false();
        for (i, w) in self.initial.iter().enumerate() {
            if !initial_fires[i] && !crate::explore::waiting(self.model, w).is_empty() {
                for (s, _) in &self.first_steps[i] {
                    first_successors = first_successors.or(&enc.mk(&enc.world(self.model, s)));
                }
            }
        }
        let mut undecided = dead_here.or(&first_successors).and_not(&live);
        let mut frontier = live.clone();
        while !frontier.is_false() && !undecided.is_false() {
            let before = preimage(enc, self.steps, guards, &frontier, &reached.and_not(&live));
            live = live.or(&before);
            undecided = undecided.and_not(&before);
            frontier = before;
        }
        for (i, w) in self.initial.iter().enumerate() {
            let live_here = initial_fires[i]
                || self.first_steps[i]
                    .iter()
                    .any(|(s, _)| enc.contains(self.model, &live, s));
            if !live_here && !crate::explore::waiting(self.model, w).is_empty() {
                return Some(((i, Vec::new()), w.clone()));
            }
        }
        let dead = dead_here.and_not(&live);
        let nearest = layers
            .iter()
            .position(|layer| !layer.and(&dead).is_false())?;
        self.rebuild(&layers[..=nearest], &dead)
    }
}

/// The states where some running machine is not in a final state.
fn waiting_set(model: &Search, enc: &Encoding) -> Bdd {
    let field_is = |f: &Field, i: usize| {
        let mut cube = BddPartialValuation::empty();
        f.set(i, &mut cube);
        enc.mk(&cube)
    };
    let mut waiting = enc.vars.mk_false();
    for (k, m) in model.machines.iter().enumerate() {
        let f = &enc.machines[k];
        let mut unfinished = enc.vars.mk_false();
        for (s, state) in m.states.iter().enumerate() {
            if !state.is_final() {
                unfinished = unfinished.or(&field_is(&f.state, s));
            }
        }
        let running = field_is(&f.status, status_index(Status::Running));
        waiting = waiting.or(&running.and(&unfinished));
    }
    waiting
}

/// The states of the initial worlds, and those of the first ringlets' successors not among
/// them (the first layer the symbolic search grows).
fn first_layers(
    model: &Search,
    enc: &Encoding,
    initial: &[SystemState],
    first_steps: &[Vec<(SystemState, Choice)>],
) -> (Bdd, Bdd) {
    let mut reached = enc.vars.mk_false();
    for w in initial {
        reached = reached.or(&enc.mk(&enc.world(model, w)));
    }
    let mut layer = enc.vars.mk_false();
    for (w, _) in first_steps.iter().flatten() {
        layer = layer.or(&enc.mk(&enc.world(model, w)));
    }
    let layer = layer.and_not(&reached);
    (reached.or(&layer), layer)
}

/// Marks every state some machine is in within `reached`, and every transition some step from
/// `reached` fires.
fn mark_entered_and_fired(
    model: &Search,
    enc: &Encoding,
    guards: &Guards,
    steps: &[Step],
    reached: &Bdd,
    outcome: &mut SymbolicOutcome,
) {
    for (k, m) in model.machines.iter().enumerate() {
        for s in 0..m.states.len() {
            let mut cube = BddPartialValuation::empty();
            enc.machines[k].state.set(s, &mut cube);
            let here = reached.and(&enc.mk(&cube)).and_not(&guards.dormant[k]);
            outcome.entered[k][s] = !here.is_false();
        }
    }
    let ringing = ringing_sets(guards, reached);
    for step in steps {
        let Some(t) = step.fired else { continue };
        let k = step.machine;
        let enabled = ringing[k]
            .iter()
            .any(|from| !from.and(&step.needs).is_false());
        if enabled {
            let state = first_state(enc, k, &step.needs);
            let index = model.machines[k].states[state].transitions[t].index;
            outcome.fired[k][index] = true;
        }
    }
}

/// Per machine, the states of `set` in which it rings, as its ringlet sees them: without a
/// new round, and with one (the fresh bits cleared).
fn ringing_sets(guards: &Guards, set: &Bdd) -> Vec<[Bdd; 2]> {
    (0..guards.next.len())
        .map(|k| {
            let direct = set.and(&guards.next[k]);
            let here = set.and(&guards.next_wrapped[k]);
            let wrapped = if here.is_false() {
                here
            } else {
                here.exists(&guards.fresh_vars).and(&guards.none_fresh)
            };
            [direct, wrapped]
        })
        .collect()
}

/// The state of machine `k` a step's cube needs.
fn first_state(enc: &Encoding, k: usize, needs: &Bdd) -> usize {
    needs
        .sat_witness()
        .map_or(0, |v| enc.machines[k].state.get(&v))
}

/// The values every stored slot and `saw()` can hold: those of the initial worlds and of the
/// first ringlets, then whatever a ringlet of any machine can write from values already known,
/// to a fixpoint.
fn value_domains(
    model: &Search,
    stepper: &StepGenerator<'_>,
    initial: &[SystemState],
    first_steps: &[Vec<(SystemState, Choice)>],
) -> Result<Domains, Declined> {
    let mut domains: Vec<Vec<ValueId>> = vec![Vec::new(); model.slots.len()];
    let mut writer: Vec<Option<usize>> = vec![None; model.slots.len()];
    // A free type chosen when read is one bit: posted yet or not.
    for (slot, d) in domains.iter_mut().enumerate() {
        if model.storage[slot] == Storage::ChosenWhenRead {
            *d = vec![NEVER, POSTED];
        }
    }
    let mut saw_domains: Vec<Vec<ValueId>> = vec![Vec::new(); model.saw.len()];
    let add = |list: &mut Vec<ValueId>, v: ValueId| {
        if v != UNKNOWN && !list.contains(&v) {
            list.push(v);
        }
    };
    let worlds = initial
        .iter()
        .chain(first_steps.iter().flatten().map(|(w, _)| w));
    for w in worlds {
        for (slot, d) in domains.iter_mut().enumerate() {
            if model.storage[slot] == Storage::Stored {
                add(d, w.values[slot]);
            }
        }
        for (j, d) in saw_domains.iter_mut().enumerate() {
            add(d, w.saw[j]);
        }
    }
    let mut leaves = Vec::new();
    loop {
        let before: usize = domains.iter().chain(&saw_domains).map(Vec::len).sum();
        for k in 0..model.machines.len() {
            for control in controls(model, k) {
                leaves.clear();
                if !stepper.open_leaves(k, control, &domains, MAX_LEAVES, &mut leaves) {
                    return Err(too_many_leaves(model, k));
                }
                for leaf in &leaves {
                    for (slot, d) in domains.iter_mut().enumerate() {
                        if model.storage[slot] == Storage::Stored {
                            add(d, leaf.after.values[slot]);
                        }
                        if model.storage[slot] != Storage::Unread
                            && leaf.after.values[slot] != UNKNOWN
                        {
                            writer[slot].get_or_insert(k);
                        }
                    }
                    for (j, _) in model.saw_of(k) {
                        add(&mut saw_domains[j], leaf.after.saw[j]);
                    }
                }
            }
        }
        too_many_values(model, &domains, &saw_domains)?;
        let after: usize = domains.iter().chain(&saw_domains).map(Vec::len).sum();
        if after == before {
            break;
        }
    }
    for d in &mut domains {
        if d.is_empty() {
            d.push(NEVER);
        }
    }
    for d in &mut saw_domains {
        if d.is_empty() {
            d.push(NEVER);
        }
    }
    Ok(Domains {
        slots: domains,
        saw: saw_domains,
        writer,
    })
}

/// Declines domains grown past [`MAX_VALUES`].
fn too_many_values(
    model: &Search,
    domains: &[Vec<ValueId>],
    saw_domains: &[Vec<ValueId>],
) -> Result<(), Declined> {
    if let Some(slot) = domains.iter().position(|d| d.len() > MAX_VALUES) {
        return Err(Declined(format!(
            "`{}` takes more than {MAX_VALUES} values (a counter?)",
            model.slots[slot].name
        )));
    }
    if saw_domains.iter().any(|d| d.len() > MAX_VALUES) {
        return Err(Declined(format!(
            "a saw() of a property takes more than {MAX_VALUES} values"
        )));
    }
    Ok(())
}

/// The values every stored slot and `saw()` can hold, and the first machine that writes each
/// slot (where the encoding places it).
struct Domains {
    slots: Vec<Vec<ValueId>>,
    saw: Vec<Vec<ValueId>>,
    writer: Vec<Option<usize>>,
}

/// Every control machine `k` may ring from: each state, just entered (none of the time tests
/// of the clocks its arrival started due; those of a composite it stayed in may be) or not
/// (each set of due time tests that can be), running and not started this round.
fn controls(model: &Search, k: usize) -> Vec<Control> {
    let mut out = Vec::new();
    for (s, state) in model.machines[k].states.iter().enumerate() {
        let base = Control {
            state: s as u16,
            status: Status::Running,
            just_entered: true,
            fresh: false,
            time: 0,
            arrived: false,
            order: 0,
            left_due: 0,
            left_wait: 0,
        };
        let started = state.time_mask(|t| state.arrival_starts(t.clock));
        let masks = due_masks(state, 0);
        out.extend(
            masks
                .iter()
                .filter(|&&time| time & started == 0)
                .map(|&time| Control { time, ..base }),
        );
        if !state.is_final() {
            out.extend(masks.into_iter().map(|time| Control {
                just_entered: false,
                time,
                ..base
            }));
        }
    }
    out
}

/// Every leaf of every machine's ringlet, as cubes and writes.
fn steps_of(
    model: &Search,
    stepper: &StepGenerator<'_>,
    enc: &Encoding,
) -> Result<Vec<Step>, Declined> {
    let mut steps: Vec<Step> = Vec::new();
    let mut leaves: Vec<OpenLeaf> = Vec::new();
    for k in 0..model.machines.len() {
        for (c, control) in controls(model, k).into_iter().enumerate() {
            leaves.clear();
            if !stepper.open_leaves(k, control, &enc.domains, MAX_LEAVES, &mut leaves) {
                return Err(too_many_leaves(model, k));
            }
            let mut cube = BddPartialValuation::empty();
            enc.set_ringing_control(k, &control, &mut cube);
            let control_set = enc.mk(&cube);
            // Leaves that write the same and fire the same transition are one step whose
            // needs are theirs joined: one image instead of many.
            let from = steps.len();
            let arrivals = clocks::arrivals(model, k, &control);
            if leaves.len() * arrivals.len() > MAX_LEAVES {
                return Err(too_many_leaves(model, k));
            }
            // Leaves of one control share few sets of due tests: one guard each.
            let mut guards: Vec<((u16, usize), Bdd)> = Vec::new();
            for leaf in &leaves {
                for (a, copied) in arrivals.iter().enumerate() {
                    let guard = match guards.iter().find(|(key, _)| *key == (leaf.due, a)) {
                        Some((_, guard)) => guard.clone(),
                        None => {
                            let guard = clocks::guard(model, enc, k, &control, leaf.due, copied);
                            guards.push(((leaf.due, a), guard.clone()));
                            guard
                        }
                    };
                    let mut step = step_of(model, enc, k, &control, leaf, copied, &guard);
                    (step.control, step.control_set) = (c, control_set.clone());
                    match steps[from..].iter_mut().find(|s| s.same_effect(&step)) {
                        Some(same) => {
                            same.needs = same.needs.or(&step.needs);
                            same.reads.clear();
                        }
                        None => steps.push(step),
                    }
                }
            }
        }
    }
    Ok(steps)
}

/// The step of one leaf of machine `k`'s ringlet from `before`, and of one set of the flags
/// its arrival copies (`copied`, [`clocks::arrivals`]), whose due tests the other machines'
/// clocks allow where `guard` holds ([`clocks::guard`]).
fn step_of(
    model: &Search,
    enc: &Encoding,
    k: usize,
    before: &Control,
    leaf: &OpenLeaf,
    copied: &[(usize, bool)],
    guard: &Bdd,
) -> Step {
    let mut needs = BddPartialValuation::empty();
    enc.set_ringing_control(k, before, &mut needs);
    let mut read_values: Vec<(usize, ValueId)> = Vec::new();
    for read in &leaf.reads {
        match *read {
            OpenRead::Slot(slot, v) => {
                if let Some(f) = &enc.slots[slot] {
                    f.set(Encoding::index_of(&enc.domains[slot], v), &mut needs);
                }
                read_values.push((slot, v));
            }
            OpenRead::Status(m, status) => {
                enc.machines[m].status.set(status_index(status), &mut needs);
            }
        }
    }
    let mut writes = BddPartialValuation::empty();
    enc.turn.set(k + 1, &mut writes);
    enc.set_control(k, &leaf.after.machines[k], &mut writes);
    for (m, w) in leaf.control_writes.iter().enumerate() {
        if m == k || *w == ControlWrites::default() {
            continue;
        }
        let f = &enc.machines[m];
        let c = &leaf.after.machines[m];
        if w.status {
            f.status.set(status_index(c.status), &mut writes);
        }
        if w.entry {
            f.just_entered.set(usize::from(c.just_entered), &mut writes);
            f.time.set(usize::from(c.time), &mut writes);
        }
        if w.fresh {
            f.fresh.set(usize::from(c.fresh), &mut writes);
        }
        if w.state {
            f.state.set(usize::from(c.state), &mut writes);
        }
    }
    for (slot, field) in enc.slots.iter().enumerate() {
        let Some(field) = field else { continue };
        let v = leaf.after.values[slot];
        if v == UNKNOWN || read_values.contains(&(slot, v)) {
            continue;
        }
        field.set(Encoding::index_of(&enc.domains[slot], v), &mut writes);
    }
    for (j, _) in model.saw_of(k) {
        enc.saw[j].set(
            Encoding::index_of(&enc.saw_domains[j], leaf.after.saw[j]),
            &mut writes,
        );
    }
    clocks::needs_and_writes(model, enc, k, before, copied, &mut needs, &mut writes);
    let written: Vec<BddVariable> = enc
        .vars
        .variables()
        .into_iter()
        .filter(|v| writes.get_value(*v).is_some())
        .collect();
    let (reads, forgets, after) = taken_apart(enc, &needs, &writes, &written);
    Step {
        machine: k,
        // `steps_of` numbers the controls.
        control: 0,
        control_set: enc.vars.mk_true(),
        needs: enc.mk(&needs).and(guard),
        guard: (!guard.is_true()).then(|| guard.restrict(&reads)),
        written_set: enc.mk(&writes),
        writes,
        written,
        reads,
        forgets,
        after,
        fired: leaf.fired,
    }
}

impl Step {
    /// Whether `other`, of the same machine and control, writes what this writes and fires
    /// the same transition.
    fn same_effect(&self, other: &Step) -> bool {
        self.fired == other.fired
            && self.written == other.written
            && self
                .written
                .iter()
                .all(|v| self.writes.get_value(*v) == other.writes.get_value(*v))
    }

    /// What it writes, as the assignments a set is restricted to (a preimage's "after").
    fn written_values(&self) -> Vec<(BddVariable, bool)> {
        self.written
            .iter()
            .filter_map(|v| Some((*v, self.writes.get_value(*v)?)))
            .collect()
    }

    /// The states one ringlet along this step leads to from `from`.
    fn image(&self, from: &Bdd) -> Bdd {
        if self.reads.is_empty() {
            return from
                .and(&self.needs)
                .exists(&self.written)
                .and(&self.written_set);
        }
        // (from ∧ needs) with the written fields forgotten and set, taken apart: needs is a
        // cube, so meeting it is restricting to it and putting its literals back.
        let mut applied = from.restrict(&self.reads);
        if let Some(guard) = &self.guard {
            applied = applied.and(guard);
        }
        if applied.is_false() {
            return applied;
        }
        applied.exists(&self.forgets).and(&self.after)
    }
}

/// A step's `needs` and `writes` as the image applies them ([`Step::reads`]).
fn taken_apart(
    enc: &Encoding,
    needs: &BddPartialValuation,
    writes: &BddPartialValuation,
    written: &[BddVariable],
) -> (Vec<(BddVariable, bool)>, Vec<BddVariable>, Bdd) {
    let reads = enc
        .vars
        .variables()
        .into_iter()
        .filter_map(|v| Some((v, needs.get_value(v)?)))
        .collect();
    let forgets = written
        .iter()
        .copied()
        .filter(|v| needs.get_value(*v).is_none())
        .collect();
    let mut after = needs.clone();
    for v in written {
        after.unset_value(*v);
        if let Some(value) = writes.get_value(*v) {
            after.set_value(*v, value);
        }
    }
    (reads, forgets, enc.mk(&after))
}

/// The schedule as sets: where machine `k` rings next without and with a new round begun.
struct Guards {
    next: Vec<Bdd>,
    next_wrapped: Vec<Bdd>,
    dormant: Vec<Bdd>,
    fresh_vars: Vec<BddVariable>,
    /// No machine started this round.
    none_fresh: Bdd,
}

impl Guards {
    fn new(model: &Search, enc: &Encoding) -> Guards {
        let n = model.machines.len();
        let field_is = |f: &Field, i: usize| {
            let mut cube = BddPartialValuation::empty();
            f.set(i, &mut cube);
            enc.mk(&cube)
        };
        let mut can_ring = Vec::new();
        let mut can_ring_wrapped = Vec::new();
        let mut dormant = Vec::new();
        for (k, m) in model.machines.iter().enumerate() {
            let f = &enc.machines[k];
            let running = field_is(&f.status, 0);
            let mut unfinished = field_is(&f.just_entered, 1);
            for (s, state) in m.states.iter().enumerate() {
                if !state.is_final() {
                    unfinished = unfinished.or(&field_is(&f.state, s));
                }
            }
            let wrapped = running.and(&unfinished);
            can_ring.push(wrapped.and(&field_is(&f.fresh, 0)));
            can_ring_wrapped.push(wrapped);
            dormant.push(field_is(&f.status, 2));
        }
        let mut next = Vec::new();
        let mut next_wrapped = Vec::new();
        for k in 0..n {
            // Without a new round: from a turn t <= k, nothing rings in t..k, k can.
            let mut direct = enc.vars.mk_false();
            for t in 0..=k {
                let mut none = field_is(&enc.turn, t);
                for ring in &can_ring[t..k] {
                    none = none.and_not(ring);
                }
                direct = direct.or(&none);
            }
            next.push(direct.and(&can_ring[k]));
            // With one: nothing rings from the turn to the end, then (fresh cleared) nothing
            // before k, and k can.
            let mut to_end = enc.vars.mk_false();
            for t in 0..=n {
                let mut none = field_is(&enc.turn, t);
                for ring in &can_ring[t..] {
                    none = none.and_not(ring);
                }
                to_end = to_end.or(&none);
            }
            let mut wrapped = to_end;
            for ring in &can_ring_wrapped[..k] {
                wrapped = wrapped.and_not(ring);
            }
            next_wrapped.push(wrapped.and(&can_ring_wrapped[k]));
        }
        // A new round clears "started this round" and what the clocks keep for a round.
        let fresh_vars: Vec<BddVariable> = enc
            .machines
            .iter()
            .flat_map(|f| {
                (f.fresh.bits.iter())
                    .chain(&f.arrived.bits)
                    .chain(&f.left_due.bits)
                    .chain(&f.left_wait.bits)
                    .copied()
            })
            .collect();
        let mut none_fresh = BddPartialValuation::empty();
        for v in &fresh_vars {
            none_fresh.set_value(*v, false);
        }
        Guards {
            next,
            next_wrapped,
            dormant,
            none_fresh: enc.mk(&none_fresh),
            fresh_vars,
        }
    }
}

/// Every state one ringlet leads to from `set`. The set is met with a machine's control once
/// for all the steps from that control, and the steps' images are joined pairwise, so no
/// operation but the last works on the whole image.
fn image(enc: &Encoding, steps: &[Step], guards: &Guards, set: &Bdd) -> Bdd {
    let ringing = ringing_sets(guards, set);
    let mut parts = Vec::new();
    let mut here: Vec<Bdd> = Vec::new();
    let mut group = None;
    for step in steps {
        if group != Some((step.machine, step.control)) {
            group = Some((step.machine, step.control));
            here = ringing[step.machine]
                .iter()
                .map(|from| from.and(&step.control_set))
                .filter(|from| !from.is_false())
                .collect();
        }
        for from in &here {
            let after = step.image(from);
            if !after.is_false() {
                parts.push(after);
            }
        }
    }
    union(parts).unwrap_or_else(|| enc.vars.mk_false())
}

/// The union of `parts`, joined in pairs so that each join meets diagrams of like size.
fn union(mut parts: Vec<Bdd>) -> Option<Bdd> {
    while parts.len() > 1 {
        let mut joined = Vec::with_capacity(parts.len().div_ceil(2));
        let mut pairs = parts.chunks_exact(2);
        for pair in &mut pairs {
            joined.push(pair[0].or(&pair[1]));
        }
        joined.extend(pairs.remainder().iter().cloned());
        parts = joined;
    }
    parts.pop()
}

/// Every state of `within` from which one ringlet leads into `set`. `within` is met first, so
/// a large `set` costs little when `within` is small.
fn preimage<'s>(
    enc: &Encoding,
    steps: impl IntoIterator<Item = &'s Step>,
    guards: &Guards,
    set: &Bdd,
    within: &Bdd,
) -> Bdd {
    if set.size() < within.size() {
        preimage_of_small(enc, steps, guards, set, within)
    } else {
        preimage_within_small(enc, steps, guards, set, within)
    }
}

/// [`preimage`] where `set` is the smaller: each step's predecessors of `set` alone (small
/// diagrams throughout), met with the schedule and `within` once per machine at the end.
fn preimage_of_small<'s>(
    enc: &Encoding,
    steps: impl IntoIterator<Item = &'s Step>,
    guards: &Guards,
    set: &Bdd,
    within: &Bdd,
) -> Bdd {
    let cleared: Vec<(BddVariable, bool)> = guards.fresh_vars.iter().map(|v| (*v, false)).collect();
    let machines = guards.next.len();
    let (mut direct, mut wrapped) = (vec![Vec::new(); machines], vec![Vec::new(); machines]);
    for step in steps {
        let after = set.restrict(&step.written_values());
        if after.is_false() {
            continue;
        }
        direct[step.machine].push(step.needs.and(&after));
        // From a new round: the fresh bits were cleared first, whatever they were.
        wrapped[step.machine].push(step.needs.restrict(&cleared).and(&after.restrict(&cleared)));
    }
    let mut parts = Vec::new();
    for (k, (direct, wrapped)) in direct.into_iter().zip(wrapped).enumerate() {
        if let Some(d) = union(direct) {
            parts.push(d.and(&guards.next[k]).and(within));
        }
        if let Some(w) = union(wrapped) {
            parts.push(w.and(&guards.next_wrapped[k]).and(within));
        }
    }
    union(parts).unwrap_or_else(|| enc.vars.mk_false())
}

/// [`preimage`] where `within` is the smaller: the schedule and `within` met with each
/// machine's control once, and `set` cut down to a step's writes only where it may start.
fn preimage_within_small<'s>(
    enc: &Encoding,
    steps: impl IntoIterator<Item = &'s Step>,
    guards: &Guards,
    set: &Bdd,
    within: &Bdd,
) -> Bdd {
    let direct: Vec<Bdd> = guards.next.iter().map(|g| g.and(within)).collect();
    let wrapped: Vec<Bdd> = guards.next_wrapped.iter().map(|g| g.and(within)).collect();
    // From a new round: the fresh bits were cleared first, whatever they were.
    let cleared: Vec<(BddVariable, bool)> = guards.fresh_vars.iter().map(|v| (*v, false)).collect();
    let mut parts = Vec::new();
    // Where each of the machine's ringlets may start, met with its control once for all the
    // steps from that control (they stand together).
    let mut group = None;
    let (mut direct_here, mut wrapped_here) = (enc.vars.mk_false(), enc.vars.mk_false());
    for step in steps {
        let k = step.machine;
        if group != Some((k, step.control)) {
            group = Some((k, step.control));
            direct_here = direct[k].and(&step.control_set);
            wrapped_here = wrapped[k].and(&step.control_set.restrict(&cleared));
        }
        if direct_here.is_false() && wrapped_here.is_false() {
            continue;
        }
        // Where the step may start (what the ringlet needs and reads; from a new round, of the
        // state with its fresh bits cleared): small where `within` is, so it goes first, and
        // `set` is cut down to what the step writes only where the step may start at all.
        let here = direct_here.and(&step.needs);
        let from_round = wrapped_here.and(&step.needs.restrict(&cleared));
        if here.is_false() && from_round.is_false() {
            continue;
        }
        let after = set.restrict(&step.written_values());
        if after.is_false() {
            continue;
        }
        if !here.is_false() {
            parts.push(here.and(&after));
        }
        if !from_round.is_false() {
            parts.push(from_round.and(&after.restrict(&cleared)));
        }
    }
    union(parts).unwrap_or_else(|| enc.vars.mk_false())
}

impl Searched<'_, '_> {
    /// The shortest path to `target` through `layers`, and the world it ends in: back through
    /// the layers to the first ringlets, then forwards with the explicit stepper, one successor
    /// inside each layer's part that leads on.
    fn rebuild(&self, layers: &[Bdd], target: &Bdd) -> Option<(Path, SystemState)> {
        let (model, enc) = (self.model, self.enc);
        let last = layers.len() - 1;
        let mut leads: Vec<Bdd> = vec![layers[last].and(target)];
        for j in (0..last).rev() {
            let before = preimage(enc, self.steps, self.guards, &leads[0], &layers[j]);
            leads.insert(0, before);
        }
        let inside = |set: &Bdd, w: &SystemState| enc.contains(model, set, w);
        for (i, w0) in self.initial.iter().enumerate() {
            let Some((w1, choice)) = self.first_steps[i]
                .iter()
                .find(|(w, _)| inside(&leads[0], w))
            else {
                continue;
            };
            let mut path = vec![(w0.clone(), *choice)];
            let mut at = w1.clone();
            let mut successors = Vec::new();
            for lead in &leads[1..] {
                successors.clear();
                self.stepper.successors(&at, false, &mut successors);
                let Some(s) = successors.iter().find(|s| inside(lead, &s.world)) else {
                    break;
                };
                path.push((at.clone(), s.choice));
                at = s.world.clone();
            }
            return Some(((i, path), at));
        }
        None
    }
}

/// The states a property looks for, over the fields its expression reads: every combination
/// of their values evaluated as the explicit search evaluates it.
fn target_set(model: &Search, enc: &Encoding, property: &Property) -> Result<Bdd, Declined> {
    if property.source.kind.is_liveness() {
        return Ok(enc.vars.mk_false());
    }
    set_where(model, enc, property.term(), &property.source.name, &|w| {
        property.is_target(model, w)
    })
}

/// The states where `holds` is true, over the fields `term` reads (`holds` reads no other):
/// every combination of their values evaluated as the explicit search evaluates it. `name`
/// (the property's) says which property reads too many.
fn set_where(
    model: &Search,
    enc: &Encoding,
    term: &Term,
    name: &str,
    holds: &dyn Fn(&SystemState) -> bool,
) -> Result<Bdd, Declined> {
    let mut fields: Vec<Component> = Vec::new();
    components(model, term, &mut fields, 0);
    fields.sort();
    fields.dedup();
    let sizes: Vec<usize> = fields
        .iter()
        .map(|c| match c {
            Component::Slot(slot) => enc.domains[*slot].len(),
            Component::Saw(j) => enc.saw_domains[*j].len(),
            Component::Control(m) => model.machines[*m].states.len() * 3,
        })
        .collect();
    let combinations = sizes.iter().try_fold(1usize, |n, s| n.checked_mul(*s));
    let Some(combinations) = combinations.filter(|&n| n <= 1 << 16) else {
        return Err(Declined(format!("`{name}` reads too many values at once")));
    };
    let mut world = SystemState {
        turn: 0,
        machines: vec![
            Control {
                state: 0,
                status: Status::Dormant,
                just_entered: false,
                fresh: false,
                time: 0,
                arrived: false,
                order: 0,
                left_due: 0,
                left_wait: 0,
            };
            model.machines.len()
        ],
        values: vec![NEVER; model.slots.len()],
        saw: vec![NEVER; model.saw.len()],
    };
    let mut set = enc.vars.mk_false();
    for mut index in 0..combinations {
        let mut cube = BddPartialValuation::empty();
        for (c, size) in fields.iter().zip(&sizes) {
            let i = index % size;
            index /= size;
            match c {
                Component::Slot(slot) => {
                    world.values[*slot] = enc.domains[*slot][i];
                    if let Some(f) = &enc.slots[*slot] {
                        f.set(i, &mut cube);
                    }
                }
                Component::Saw(j) => {
                    world.saw[*j] = enc.saw_domains[*j][i];
                    enc.saw[*j].set(i, &mut cube);
                }
                Component::Control(m) => {
                    let (state, status) = (i / 3, STATUSES[i % 3]);
                    world.machines[*m].state = state as u16;
                    world.machines[*m].status = status;
                    enc.machines[*m].state.set(state, &mut cube);
                    enc.machines[*m].status.set(i % 3, &mut cube);
                }
            }
        }
        if holds(&world) {
            set = set.or(&enc.mk(&cube));
        }
    }
    Ok(set)
}

/// A part of the world a property reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Component {
    Slot(usize),
    Saw(usize),
    /// A machine's state and mode.
    Control(usize),
}

fn components(model: &Search, term: &Term, out: &mut Vec<Component>, depth: usize) {
    match term {
        Term::Const(_) => {}
        Term::Slot(slot) => out.push(Component::Slot(*slot)),
        Term::Saw(j) => out.push(Component::Saw(*j)),
        Term::Running(m) => out.push(Component::Control(*m)),
        Term::InState { machine, .. } => out.push(Component::Control(*machine)),
        Term::Answer { theory, .. } => {
            for (_, name) in &model.theories[*theory].inputs {
                match name {
                    Some(crate::model::Name::Slot(slot)) => out.push(Component::Slot(*slot)),
                    Some(crate::model::Name::Running(m)) => out.push(Component::Control(*m)),
                    Some(crate::model::Name::Answer { theory, output }) if depth < 8 => {
                        components(
                            model,
                            &Term::Answer {
                                theory: *theory,
                                output: *output,
                            },
                            out,
                            depth + 1,
                        );
                    }
                    _ => {}
                }
            }
        }
        Term::Not(t) | Term::Neg(t) => components(model, t, out, depth),
        Term::And(l, r) | Term::Or(l, r) | Term::Binary(_, l, r) => {
            components(model, l, out, depth);
            components(model, r, out, depth);
        }
        Term::Function(_, args) => {
            for a in args {
                components(model, a, out, depth);
            }
        }
    }
}
