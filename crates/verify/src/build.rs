//! A loaded behaviour lowered into its model (spec §6): its machines' states, transitions and
//! time tests; every storage place a run has numbered as a slot; which slots the environment
//! sets freely, from the finite domains of [`crate::domain`] over [`crate::flow`]'s facts; and
//! the reasoners whose answers labels ask for. [`Model::build`] is the one entry.
//!
//! Names resolve as `proclaim_fsm::names` decides for every reader: a name a machine declares
//! is its own, then externs, then globals (every other name some activity assigns); any other
//! name is a reasoner's answer when a theory outputs it, `NameIsRunning`
//! when it speaks of a machine, and otherwise a whiteboard type.

use crate::arith::zero;
use crate::domain::{sound_domains, Domains};
use crate::flow::Facts;
use crate::kind::ValueKind;
use crate::model::{
    FreeDomain, MachineModel, Model, Name, Slot, SlotId, SlotKind, StateModel, Storage,
    TheoryModel, TimeTest, TransitionModel,
};
use crate::reasoner::ReasonerSeed;
use proclaim_behaviour::{modules, Behaviour, DeclaredRange, ModuleKind};
use proclaim_board::Value;
use proclaim_fsm::control::{running_type, Command};
use proclaim_fsm::names::Names;
use proclaim_fsm::{Action, Expr, Machine, Statement, TIME_TESTS};
use rustc_hash::{FxHashMap, FxHashSet};

/// What the activities and labels of the behaviour read and write, gathered once.
#[derive(Default)]
struct Uses {
    /// Names read by labels and activities that are no variable, in first-use order.
    read: Vec<String>,
    /// Types machines post (postings, `post()` with a literal type, extern assignments).
    written: FxHashSet<String>,
}

/// The types that get a message slot, in slot order: what machines read, externs, reasoner
/// inputs, and the types the properties name.
fn message_types(
    uses: &Uses,
    externs: &FxHashSet<String>,
    theory_inputs: &[Vec<String>],
    property_exprs: &[&Expr],
    known_types: &FxHashSet<String>,
) -> Vec<String> {
    let mut wanted: Vec<String> = uses.read.clone();
    let mut sorted_externs: Vec<&String> = externs.iter().collect();
    sorted_externs.sort();
    wanted.extend(sorted_externs.into_iter().cloned());
    for inputs in theory_inputs {
        wanted.extend(inputs.iter().cloned());
    }
    for e in property_exprs {
        e.visit_names(&mut |n, _| {
            if known_types.contains(n) {
                wanted.push(n.to_string());
            }
        });
    }
    wanted
}

impl Model {
    /// The model of `behaviour`. `property_names` are the names the properties read, so a
    /// type only a property mentions (`Magnetron`, which the machine posts and no machine
    /// reads) gets a slot; `property_exprs` add the constants they compare with to the
    /// environment's domains.
    pub fn build(behaviour: &Behaviour, property_exprs: &[&Expr]) -> Model {
        let machine_names: Vec<&str> = behaviour
            .machines
            .iter()
            .map(|m| m.machine.name.as_str())
            .collect();
        let mut slots = Slots::default();
        let names = Names::of(behaviour.machines.iter().map(|m| &m.machine));
        let externs: FxHashSet<String> = names.externs.iter().cloned().collect();
        let locals_of = slots.declare_locals(behaviour, &names);
        slots.declare_globals(&names);
        let (mut theories, theory_inputs) = slots.reasoners(behaviour);
        for (i, name) in machine_names.iter().enumerate() {
            slots
                .names
                .entry(running_type(name))
                .or_insert(Name::Running(i));
        }

        let mut uses = Uses::default();
        for (i, m) in behaviour.machines.iter().enumerate() {
            gather_uses(
                &m.machine,
                &locals_of[i],
                &slots.names,
                &machine_names,
                &mut uses,
            );
        }
        let (outside, known_types) = posters(behaviour, &uses, &externs);

        let wanted = message_types(
            &uses,
            &externs,
            &theory_inputs,
            property_exprs,
            &known_types,
        );
        for ty in wanted {
            if !slots.names.contains_key(&ty) && !machine_names.contains(&ty.as_str()) {
                let external = externs.contains(&ty);
                slots.message(ty, external);
            }
        }
        for (t, inputs) in theory_inputs.iter().enumerate() {
            theories[t].inputs = inputs
                .iter()
                .map(|ty| (ty.clone(), slots.names.get(ty).copied()))
                .collect();
        }
        let Slots {
            slots: mut all_slots,
            names,
        } = slots;
        let hints = free_environment(
            &mut all_slots,
            behaviour,
            &theory_inputs,
            property_exprs,
            &outside,
            &uses,
        );

        let machines = machine_models(behaviour, locals_of);
        let clock_ranks = crate::clocks::ranks(&machines);
        let mut model = Model {
            clock_durations: crate::clocks::durations(&machines, &clock_ranks),
            clock_ranks,
            machines,
            storage: vec![Storage::Stored; all_slots.len()],
            slots: all_slots,
            theories,
            names,
            known_types,
            saw: Vec::new(),
            ring_period: behaviour.ring_period,
            inexact: Vec::new(),
        };
        sound_free_values(&mut model, behaviour, property_exprs, &hints);
        model
    }
}

/// Every machine's model, in manifest order, each with its own variables.
fn machine_models(
    behaviour: &Behaviour,
    locals_of: Vec<FxHashMap<String, SlotId>>,
) -> Vec<MachineModel> {
    (behaviour.machines.iter())
        .zip(locals_of)
        .map(|(m, locals)| machine_model(&m.machine, m.start, locals))
        .collect()
}

fn machine_model(
    machine: &Machine,
    start: bool,
    locals: FxHashMap<String, SlotId>,
) -> MachineModel {
    let index_of = |id| machine.states.iter().position(|s| s.id == id);
    let states = machine
        .states
        .iter()
        .map(|s| {
            let transitions: Vec<TransitionModel> = machine
                .transitions
                .iter()
                .enumerate()
                .filter(|(_, t)| t.source == s.id)
                .filter_map(|(index, t)| {
                    Some(TransitionModel {
                        index,
                        target: index_of(t.target)?,
                        label: t.label.clone(),
                    })
                })
                .collect();
            let time_tests = time_tests_of(&transitions);
            let arrival_enters = machine.arrival_enters(s);
            StateModel {
                name: s.name.clone(),
                transitions,
                time_order: time_order(&time_tests, machine, &arrival_enters),
                time_tests,
                arrival_enters,
            }
        })
        .collect::<Vec<StateModel>>();
    let mut clocks = vec![None];
    for t in states.iter().flat_map(|s| &s.time_tests) {
        if !clocks.contains(&t.clock) {
            clocks.push(t.clock);
        }
    }
    MachineModel {
        name: machine.name.clone(),
        initial: index_of(machine.initial).unwrap_or(0),
        machine: machine.clone(),
        states,
        start,
        locals,
        clocks,
    }
}

/// The time tests of a state's labels, each once a clock: by clock, and in each constant tests
/// first, shortest first, so that "which are due" is a prefix of them.
fn time_tests_of(transitions: &[TransitionModel]) -> Vec<TimeTest> {
    let mut time_tests: Vec<TimeTest> = Vec::new();
    for t in transitions {
        for (function, arguments, clock) in t.label.time_tests() {
            let call = Expr::Call {
                function: function.to_string(),
                arguments: arguments.to_vec(),
                clock,
            };
            if time_tests.iter().any(|u| u.call == call) {
                continue;
            }
            let unit = TIME_TESTS
                .iter()
                .find(|(f, _)| *f == function)
                .map_or(1.0, |(_, unit)| *unit);
            // Exact or not at all: the durations order the tests, so one rounded (a fraction
            // of a microsecond) or wrapped (past u64) would order two wrongly; such a test is
            // left free, as a computed one is.
            let micros = match arguments {
                [Expr::Duration(us)] => Some(*us),
                [Expr::Int(n)] => ((*n).max(0) as u64).checked_mul(unit as u64),
                [Expr::Float(x)] => {
                    let us = (x * unit).max(0.0);
                    (us.fract() == 0.0 && us < u64::MAX as f64).then_some(us as u64)
                }
                _ => None,
            };
            time_tests.push(TimeTest {
                call,
                micros,
                clock,
            });
        }
    }
    time_tests.sort_by_key(|t| (t.clock, t.micros.map_or(u64::MAX, |m| m)));
    time_tests
}

/// The [`StateModel::time_order`] of a state's `tests`, whose arrival enters the composites
/// `arrival_enters`. Clock `a` started no later than clock `b` when `b` is the state's own or
/// one its arrival started (an arrival is the latest start of all the clocks it finds
/// running), or `a` is a composite around `b` (a move into a composite enters what holds it
/// first or at once). A real run's moment is one for a whole ringlet, so a test of `a` is
/// then at least as old as one of `b`.
fn time_order(tests: &[TimeTest], machine: &Machine, arrival_enters: &[usize]) -> Vec<(u8, u8)> {
    let around = |x: usize, y: usize| {
        let mut inner = machine.composites.get(y).and_then(|c| c.parent);
        while let Some(p) = inner {
            if p == x {
                return true;
            }
            inner = machine.composites.get(p).and_then(|c| c.parent);
        }
        false
    };
    let no_later = |a: Option<usize>, b: Option<usize>| match (a, b) {
        (_, None) => true,
        (_, Some(y)) if arrival_enters.contains(&y) => true,
        (Some(x), Some(y)) => around(x, y),
        (None, Some(_)) => false,
    };
    let mut order = Vec::new();
    for (j, later) in tests.iter().enumerate() {
        for (i, earlier) in tests.iter().enumerate() {
            let (Some(d), Some(c)) = (later.micros, earlier.micros) else {
                continue;
            };
            if earlier.clock != later.clock && c <= d && no_later(earlier.clock, later.clock) {
                order.push((j as u8, i as u8));
            }
        }
    }
    order
}

/// Gives every free slot the domain that keeps each test of its value ([`crate::flow`],
/// [`sound_domains`]), and notes where none can.
fn sound_free_values(
    model: &mut Model,
    behaviour: &Behaviour,
    property_exprs: &[&Expr],
    hints: &Domains,
) {
    let files: Vec<String> = behaviour.machines.iter().map(|m| m.file.clone()).collect();
    let facts = crate::flow::analyse(model, &files, property_exprs);
    let (domains, inexact) = sound_domains(&model.slots, &facts, hints);
    for (slot, domain) in model.slots.iter_mut().zip(domains) {
        if slot.free.is_some() {
            slot.free = domain;
        }
    }
    let exact = exact_ranges(&mut model.slots, &facts, &behaviour.ranges);
    model.inexact = facts.inexact;
    for i in inexact {
        if !model.inexact.contains(&i) {
            model.inexact.push(i);
        }
    }
    model.inexact.retain(|i| !exact.contains(&i.value));
}

/// Gives every free type with a declared range each value of it (and "never posted"), where
/// it is compared with no free type that has none: then every value the world may post is in
/// the model, whatever the behaviour does with it. Returns the types made exact.
fn exact_ranges(slots: &mut [Slot], facts: &Facts, ranges: &[DeclaredRange]) -> Vec<String> {
    let range_of: Vec<Option<&DeclaredRange>> = slots
        .iter()
        .map(|s| ranges.iter().find(|r| r.ty == s.name))
        .collect();
    let declared = |slot: SlotId| range_of[slot];
    // A declared type whose copies are compared with an undeclared one's keeps the intervals
    // they share: its own values alone would not order the other's.
    let mut shared_with_undeclared: Vec<SlotId> = Vec::new();
    let mut grown = true;
    while grown {
        grown = false;
        for &(a, b) in &facts.pairs {
            for (x, y) in [(a, b), (b, a)] {
                let taints = declared(y).is_none() || shared_with_undeclared.contains(&y);
                if taints && !shared_with_undeclared.contains(&x) {
                    shared_with_undeclared.push(x);
                    grown = true;
                }
            }
        }
    }
    let mut exact = Vec::new();
    for (id, slot) in slots.iter_mut().enumerate() {
        if slot.free.is_none() || shared_with_undeclared.contains(&id) {
            continue;
        }
        if let Some(range) = declared(id) {
            exact.push(slot.name.clone());
            slot.free = Some(FreeDomain::of(range.values().collect()));
        }
    }
    exact
}

/// Records what a machine's labels and activities read (names that are no variable of the
/// machine) and which types it posts.
fn gather_uses(
    machine: &Machine,
    locals: &FxHashMap<String, SlotId>,
    names: &FxHashMap<String, Name>,
    machine_names: &[&str],
    uses: &mut Uses,
) {
    let mut read = |n: &str| {
        if !locals.contains_key(n)
            && !machine_names.contains(&n)
            && !uses.read.iter().any(|r| r == n)
            && !matches!(
                names.get(n),
                Some(Name::Answer { .. } | Name::Running(_) | Name::Slot(_))
            )
        {
            uses.read.push(n.to_string());
        }
    };
    for t in &machine.transitions {
        t.label.visit_names(&mut |n, _| read(n));
    }
    for s in machine.statements() {
        for e in s.expressions() {
            e.visit_names(&mut |n, _| read(n));
        }
    }
    for a in machine.actions() {
        if let Action::Post { ty, .. } = a {
            if !machine_names.contains(&ty.as_str()) {
                uses.written.insert(ty.clone());
            }
        }
    }
    for s in machine.statements() {
        match s {
            Statement::Assign { name, .. } if !locals.contains_key(name) => {
                uses.written.insert(name.clone());
            }
            Statement::Expr(Expr::Call {
                function,
                arguments,
                ..
            }) if matches!(function.as_str(), "post" | "post_int" | "postv" | "post_v")
                || Command::from_function(function).is_some() =>
            {
                if let Some(Expr::Str(ty)) = arguments.first() {
                    uses.written.insert(ty.clone());
                }
            }
            _ => {}
        }
    }
}

/// The slots being numbered and what each name resolves to, while a model is built.
#[derive(Default)]
struct Slots {
    slots: Vec<Slot>,
    names: FxHashMap<String, Name>,
}

impl Slots {
    /// Each machine's own variables ([`Names::own`]): each starts at its first declared
    /// type's zero and converts to its last.
    fn declare_locals(
        &mut self,
        behaviour: &Behaviour,
        names: &Names,
    ) -> Vec<FxHashMap<String, SlotId>> {
        let mut locals_of = Vec::new();
        for (i, (m, own)) in behaviour.machines.iter().zip(&names.own).enumerate() {
            let mut locals: FxHashMap<String, SlotId> = FxHashMap::default();
            for variable in own {
                locals.insert(variable.name.clone(), self.slots.len());
                self.slots.push(Slot {
                    name: format!("{}.{}", m.machine.name, variable.name),
                    kind: SlotKind::Local {
                        machine: i,
                        ty: variable.last.clone(),
                    },
                    initial: Some(zero(&variable.first)),
                    free: None,
                    value_kind: ValueKind::Any,
                });
            }
            locals_of.push(locals);
        }
        locals_of
    }

    /// The behaviour's globals ([`Names::globals`]), starting at 0.
    fn declare_globals(&mut self, names: &Names) {
        for name in &names.globals {
            self.names
                .insert(name.clone(), Name::Slot(self.slots.len()));
            self.slots.push(Slot {
                name: name.clone(),
                kind: SlotKind::Global,
                initial: Some(Value::Int(0)),
                free: None,
                value_kind: ValueKind::Any,
            });
        }
    }

    /// The reasoners: their answers become names; each one's inputs (whiteboard types it
    /// reads) are returned beside it, to be given slots.
    fn reasoners(&mut self, behaviour: &Behaviour) -> (Vec<TheoryModel>, Vec<Vec<String>>) {
        let mut theories = Vec::new();
        let mut theory_inputs = Vec::new();
        for t in &behaviour.theories {
            let reasoner = ReasonerSeed::new(t);
            let decl = reasoner.start().declaration();
            for (o, atom) in decl.answers.iter().enumerate() {
                self.names.entry(atom.clone()).or_insert(Name::Answer {
                    theory: theories.len(),
                    output: o,
                });
            }
            theory_inputs.push(
                decl.reads
                    .iter()
                    .filter(|r| r.as_str() != proclaim_board::QUERY_TYPE)
                    .cloned()
                    .collect(),
            );
            theories.push(TheoryModel {
                name: t.name.clone(),
                inputs: Vec::new(),
                outputs: decl.answers.clone(),
                reasoner,
            });
        }
        (theories, theory_inputs)
    }

    /// A slot for whiteboard type `ty`, never posted at first.
    fn message(&mut self, ty: String, external: bool) {
        self.names.insert(ty.clone(), Name::Slot(self.slots.len()));
        self.slots.push(Slot {
            kind: SlotKind::Message { external },
            name: ty,
            initial: None,
            free: None,
            value_kind: ValueKind::Any,
        });
    }
}

/// The types something outside the machines and reasoners posts, and every type anything
/// declares, reads or writes.
fn posters(
    behaviour: &Behaviour,
    uses: &Uses,
    externs: &FxHashSet<String>,
) -> (FxHashSet<String>, FxHashSet<String>) {
    let mut outside: FxHashSet<String> = FxHashSet::default();
    let mut known_types: FxHashSet<String> = FxHashSet::default();
    for module in modules(behaviour) {
        let inside = matches!(
            module.kind,
            ModuleKind::Machine { .. } | ModuleKind::Theory { .. }
        );
        for ty in module.decl.posts.iter().chain(&module.decl.answers) {
            known_types.insert(ty.clone());
            if !inside {
                outside.insert(ty.clone());
            }
        }
        for ty in module.decl.reads.iter().chain(&module.decl.waits_on) {
            known_types.insert(ty.clone());
        }
    }
    known_types.extend(uses.read.iter().cloned());
    known_types.extend(uses.written.iter().cloned());
    known_types.extend(externs.iter().cloned());
    (outside, known_types)
}

/// The environment: a whiteboard type is free when something outside posts it, or when nothing
/// inside writes it at all (spec §6), and takes the values its domain gathers.
fn free_environment(
    slots: &mut [Slot],
    behaviour: &Behaviour,
    theory_inputs: &[Vec<String>],
    property_exprs: &[&Expr],
    outside: &FxHashSet<String>,
    uses: &Uses,
) -> Domains {
    let mut domains = Domains::default();
    for m in &behaviour.machines {
        domains.gather_machine(&m.machine);
    }
    if let Some(script) = &behaviour.script {
        for step in &script.steps {
            domains.add(&step.atom, proclaim_experts::script_value(&step.value));
        }
    }
    for inputs in theory_inputs {
        for ty in inputs {
            domains.add(ty, Value::Bool(false));
            domains.add(ty, Value::Bool(true));
        }
    }
    // The kind of a type is what the behaviour gives it; the properties' constants then
    // widen what the environment tries (a property may ask about a value no machine names).
    for slot in slots.iter_mut() {
        if let SlotKind::Message { .. } = slot.kind {
            slot.value_kind = domains.kind(&slot.name);
        }
    }
    for e in property_exprs {
        domains.gather_expr(e);
    }
    for slot in slots.iter_mut() {
        if let SlotKind::Message { .. } = slot.kind {
            if outside.contains(&slot.name) || !uses.written.contains(&slot.name) {
                slot.free = Some(domains.of_constants(&slot.name));
            }
        }
    }
    domains
}

#[cfg(test)]
mod tests {
    use super::*;
    use proclaim_behaviour::{load, Embedded};
    use proclaim_fsm::VarType;
    use std::sync::Arc;

    /// A variable declared twice starts at its first type's zero and converts to its last,
    /// as the runner has it (`proclaim_fsm::names`).
    #[test]
    fn a_variable_declared_twice_starts_as_first_declared() {
        let files = Embedded {
            name: "twice",
            files: &[
                ("behaviour.toml", "[[machine]]\nfile = \"D.machine\"\n"),
                (
                    "D.machine",
                    "machine D\ninitial S\nstate S {\n    entry { int n; bool n; g = 1; }\n}\n",
                ),
            ],
        };
        let behaviour = load("twice", Arc::new(files)).expect("loads");
        let model = Model::build(&behaviour, &[]);
        let n = model.resolve(Some(0), "n").expect("n is D's own");
        let Name::Slot(n) = n else {
            panic!("n is a variable: {n:?}");
        };
        assert_eq!(model.slots[n].initial, Some(Value::Int(0)));
        assert!(
            matches!(
                &model.slots[n].kind,
                SlotKind::Local {
                    ty: VarType::Bool,
                    ..
                }
            ),
            "{:?}",
            model.slots[n].kind
        );
        assert_eq!(model.resolve(Some(0), "g"), model.resolve(None, "g"));
    }

    /// A composite is entered no later than the states inside it: where P and A were entered
    /// together, P's 3 s are never up before A's 1 s; where A was entered again inside P, they
    /// may be.
    #[test]
    fn a_composites_clock_is_never_younger_than_its_states() {
        let files = Embedded {
            name: "older",
            files: &[
                ("behaviour.toml", "[[machine]]\nfile = \"M.machine\"\n"),
                (
                    "M.machine",
                    "machine M\ninitial P\nstate P {\n    when after(3s) -> LATE\n    state A {\n        when after(1s) -> B\n    }\n    state B {\n        when after(5s) -> A\n    }\n}\nstate LATE { }\n",
                ),
            ],
        };
        let behaviour = load("older", Arc::new(files)).expect("loads");
        let model = Model::build(&behaviour, &[]);
        let a: Vec<&StateModel> = (model.machines[0].states.iter())
            .filter(|s| s.name == "P.A")
            .collect();
        let [with_p, inside_p] = a[..] else {
            panic!("A once entered with P and once inside it: {a:?}");
        };
        let (with_p, inside_p) = match with_p.arrival_enters.is_empty() {
            true => (inside_p, with_p),
            false => (with_p, inside_p),
        };
        // Bit 0 is A's 1 s (its own clock's tests come first), bit 1 P's 3 s.
        let due = crate::ringlet::due_masks;
        assert_eq!(due(with_p, 0), vec![0b00, 0b01, 0b11]);
        assert_eq!(due(inside_p, 0), vec![0b00, 0b01, 0b10, 0b11]);
        // A due set against the order (only a state taken from outside the model could have
        // one) is made whole at the next snapshot.
        assert_eq!(due(with_p, 0b10), vec![0b11]);
    }

    /// The domain `[ranges]` gives a free type: every value of the range, unless its copies
    /// are compared with those of a type that has no range (then both keep their intervals).
    #[test]
    fn a_declared_range_is_every_value_unless_compared_with_an_undeclared_type() {
        let domain = |ranges: &str| {
            let manifest = format!("[[machine]]\nfile = \"K.machine\"\n[ranges]\n{ranges}");
            let files: &'static [(&str, &str)] = Box::leak(Box::new([
                ("behaviour.toml", &*Box::leak(manifest.into_boxed_str())),
                (
                    "K.machine",
                    "machine K\ninitial W\nstate W {\n    internal { extern a; extern b; x = a; y = b; }\n    when x > y && x > 3 -> KICK\n}\nstate KICK { }\n",
                ),
            ]));
            let files = Embedded {
                name: "kick",
                files,
            };
            let behaviour = load("kick", Arc::new(files)).expect("loads");
            let model = Model::build(&behaviour, &[]);
            let values = |name: &str| {
                let Some(Name::Slot(slot)) = model.resolve(None, name) else {
                    panic!("{name} is a slot");
                };
                model.slots[slot].free.clone().expect("free").values
            };
            (values("a"), values("b"))
        };
        let every = |low: i64, high: i64| (low..=high).map(Value::Int).collect::<Vec<_>>();
        let (a, b) = domain("a = \"0..5\"\nb = \"-2..2\"\n");
        assert_eq!((a, b), (every(0, 5), every(-2, 2)));
        let (a, _) = domain("a = \"0..5\"\n");
        assert_ne!(
            a,
            every(0, 5),
            "b has no range: a keeps the intervals it shares with b"
        );
    }
}
