//! The explicit search's memo of steps, over packed records: most ringlets repeat (a machine
//! in one state, on the few values it reads, does the same thing whatever the rest of the world
//! holds), so a step is made once through `ringlet.rs` and then replayed on every record that
//! agrees with it on what the step can read.
//!
//! What a step can read is found from the text, once a machine state: the ringing machine's
//! control, every slot its state's activities, labels and `saw()`s name (with the inputs of the
//! reasoners they ask), the control of every machine they name (a mode read, a command), every
//! machine whose clocks are ordered against its own (`clocks.rs`), and every stored free type
//! (the environment moves from its value). Its successors are then the record with those bits
//! and the ones it writes (whose turn, `saw()`, "started this round" and the clock flags on a
//! new round) replaced, leaf by leaf, in the order the ringlet made them. A state whose code
//! computes the type it posts to is never memoised, nor one whose step was seen writing outside
//! what it names; in debug builds every replayed step is made again and compared.

use crate::model::{Name, SlotId};
use crate::ringlet::{StepGenerator, Successor};
use crate::search::Search;
use crate::world::{Layout, TooNarrow};
use proclaim_fsm::{Action, Expr, Statement};
use proclaim_lower::builtin::{builtin, Builtin, Target};
use proclaim_lower::RingletPlan;
use rustc_hash::FxHashMap;

/// The most successors the memo keeps before it starts afresh (so its memory stays bounded).
const MAX_LEAVES: usize = 1 << 18;

/// One successor of a packed state.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Step {
    pub record: u128,
    pub machine: usize,
    /// The state the ringlet began in.
    pub from: usize,
    /// Which of that state's transitions fired (its position in priority order).
    pub fired: Option<usize>,
}

/// What a machine's ringlet in one state can read or write besides its own control: slots and
/// other machines' controls.
#[derive(Debug, Default)]
struct Footprint {
    slots: Vec<SlotId>,
    machines: Vec<usize>,
}

/// A machine state's footprint as bits of a record: what the step's successors depend on
/// (`key`) and what they may differ in (`write`, besides the "started this round" and clock
/// flags a new round clears).
#[derive(Clone, Copy, Debug)]
struct Masks {
    key: u128,
    write: u128,
}

/// The successors of one key: the bits they write, kept in `leaves[start..start + len]`.
#[derive(Clone, Copy, Debug)]
struct Entry {
    write: u128,
    start: u32,
    len: u32,
}

#[derive(Clone, Copy, Debug)]
struct Leaf {
    bits: u128,
    fired: Option<u32>,
}

pub(crate) struct StepMemo<'m> {
    model: &'m Search<'m>,
    /// Per machine, per state: its footprint, `None` where its code computes a posting's type.
    footprints: Vec<Vec<Option<Footprint>>>,
    /// The footprints as bits of the current layout.
    masks: Vec<Vec<Option<Masks>>>,
    /// Per machine: where its state number lies in a record.
    state_fields: Vec<(u32, u128)>,
    /// Whose turn it is and every machine's control: what decides who rings next.
    schedule_mask: u128,
    /// Every machine's "started this round" flag and the clock flags a new round clears.
    all_fresh: u128,
    /// Who rings next (and whether a new round begins), by the bits that decide it.
    schedule: FxHashMap<u128, Option<(u32, bool)>>,
    /// Keyed by the bits of the footprint, the ringing machine and whether a round began.
    entries: FxHashMap<(u128, u32), Entry>,
    leaves: Vec<Leaf>,
    /// Machine states whose step was seen writing outside its footprint.
    unmemoised: Vec<Vec<bool>>,
    successors: Vec<Successor>,
}

impl<'m> StepMemo<'m> {
    pub fn new(model: &'m Search<'m>, layout: &Layout) -> StepMemo<'m> {
        let footprints = (0..model.machines.len())
            .map(|k| {
                (0..model.machines[k].states.len())
                    .map(|s| footprint(model, k, s))
                    .collect()
            })
            .collect();
        let mut memo = StepMemo {
            model,
            footprints,
            masks: Vec::new(),
            state_fields: Vec::new(),
            schedule_mask: 0,
            all_fresh: 0,
            schedule: FxHashMap::default(),
            entries: FxHashMap::default(),
            leaves: Vec::new(),
            unmemoised: model.per_state(),
            successors: Vec::new(),
        };
        memo.relayout(layout);
        memo
    }

    /// Forgets every step and makes the masks anew, for records packed with `layout` (a field
    /// widened).
    pub fn relayout(&mut self, layout: &Layout) {
        let model = self.model;
        let machines = model.machines.len();
        let stored_free = model
            .stored_free_slots()
            .fold(0, |m, (slot, _)| m | layout.slot_mask(slot));
        self.masks = self
            .footprints
            .iter()
            .enumerate()
            .map(|(k, states)| {
                let saw = model.saw_of(k).fold(0, |m, (j, _)| m | layout.saw_mask(j));
                states
                    .iter()
                    .map(|footprint| {
                        let f = footprint.as_ref()?;
                        let key = f
                            .machines
                            .iter()
                            .fold(layout.control_mask(k) | stored_free, |m, &j| {
                                m | layout.control_mask(j)
                            });
                        let key = f.slots.iter().fold(key, |m, &s| m | layout.slot_mask(s));
                        Some(Masks {
                            key,
                            write: key | saw | layout.turn_mask(),
                        })
                    })
                    .collect()
            })
            .collect();
        self.state_fields = (0..machines).map(|k| layout.state_field(k)).collect();
        self.schedule_mask =
            (0..machines).fold(layout.turn_mask(), |m, k| m | layout.control_mask(k));
        self.all_fresh =
            (0..machines).fold(0, |m, k| m | layout.fresh_mask(k) | layout.round_mask(k));
        self.schedule.clear();
        self.forget();
    }

    /// Forgets every step made.
    fn forget(&mut self) {
        self.entries.clear();
        self.leaves.clear();
    }

    /// Bytes the memo holds.
    pub fn bytes(&self) -> usize {
        let entry = std::mem::size_of::<((u128, u32), Entry)>() + 1;
        let schedule = std::mem::size_of::<(u128, Option<(u32, bool)>)>() + 1;
        self.entries.capacity() * entry
            + self.schedule.capacity() * schedule
            + self.leaves.capacity() * std::mem::size_of::<Leaf>()
            + self.successors.capacity() * std::mem::size_of::<Successor>()
    }

    /// The successors of the state packed as `record` with `layout`, in the order
    /// [`StepGenerator::successors`] makes them, appended to `out`; or the field too narrow for
    /// one of them (`out` then holds a part of them).
    pub fn successors(
        &mut self,
        layout: &Layout,
        stepper: &StepGenerator,
        record: u128,
        out: &mut Vec<Step>,
    ) -> Result<(), TooNarrow> {
        let Some((k, wrapped)) = self.next_machine(layout, stepper, record) else {
            return Ok(());
        };
        let (shift, mask) = self.state_fields[k];
        let s = ((record >> shift) & mask) as usize;
        let masks = match self.masks[k].get(s) {
            Some(Some(masks)) if !self.unmemoised[k][s] => *masks,
            _ => return self.direct(layout, stepper, record, out),
        };
        let write = masks.write | if wrapped { self.all_fresh } else { 0 };
        let key = (record & masks.key, (k as u32) << 1 | u32::from(wrapped));
        let first = out.len();
        if let Some(entry) = self.entries.get(&key) {
            let kept = record & !entry.write;
            let leaves = &self.leaves[entry.start as usize..(entry.start + entry.len) as usize];
            out.extend(leaves.iter().map(|leaf| Step {
                record: kept | leaf.bits,
                machine: k,
                from: s,
                fired: leaf.fired.map(|f| f as usize),
            }));
            if cfg!(debug_assertions) {
                let mut made = Vec::new();
                self.direct(layout, stepper, record, &mut made)?;
                assert_eq!(
                    made,
                    out[first..],
                    "a replayed step differs from the ringlet's"
                );
            }
            return Ok(());
        }
        self.direct(layout, stepper, record, out)?;
        let made = &out[first..];
        if made
            .iter()
            .any(|step| step.record & !write != record & !write)
        {
            self.unmemoised[k][s] = true;
            return Ok(());
        }
        if self.leaves.len() + made.len() > MAX_LEAVES {
            self.forget();
        }
        let start = self.leaves.len() as u32;
        self.leaves.extend(made.iter().map(|step| Leaf {
            bits: step.record & write,
            fired: step.fired.map(|f| f as u32),
        }));
        self.entries.insert(
            key,
            Entry {
                write,
                start,
                len: made.len() as u32,
            },
        );
        Ok(())
    }

    /// The machine that rings next from `record` and whether a new round begins with it.
    fn next_machine(
        &mut self,
        layout: &Layout,
        stepper: &StepGenerator,
        record: u128,
    ) -> Option<(usize, bool)> {
        let key = record & self.schedule_mask;
        let next = *self.schedule.entry(key).or_insert_with(|| {
            let world = layout.unpack_record(record);
            stepper
                .next_machine(&world)
                .map(|(k, _, wrapped)| (k as u32, wrapped))
        });
        next.map(|(k, wrapped)| (k as usize, wrapped))
    }

    /// The successors made by the ringlet itself.
    fn direct(
        &mut self,
        layout: &Layout,
        stepper: &StepGenerator,
        record: u128,
        out: &mut Vec<Step>,
    ) -> Result<(), TooNarrow> {
        let world = layout.unpack_record(record);
        self.successors.clear();
        stepper.successors(&world, false, &mut self.successors);
        for s in &self.successors {
            out.push(Step {
                record: layout.pack_register(&s.world)?,
                machine: s.machine,
                from: s.from,
                fired: s.fired,
            });
        }
        Ok(())
    }
}

/// What machine `k`'s ringlet in state `s` names, or `None` where it computes the type it posts
/// to.
fn footprint(model: &Search, k: usize, s: usize) -> Option<Footprint> {
    let mut gather = Gather {
        model,
        machine: k,
        footprint: Footprint::default(),
        theories: vec![false; model.theories.len()],
        computed_type: false,
    };
    let machine = &model.machines[k].machine;
    for actions in RingletPlan::of_state(machine, &machine.states[s]).activities() {
        gather.actions(actions);
    }
    for t in &model.machines[k].states[s].transitions {
        gather.expr(&t.label);
    }
    for (_, e) in model.saw_of(k) {
        gather.expr(e);
    }
    if gather.computed_type {
        return None;
    }
    let mut footprint = gather.footprint;
    // Its arrival and snapshot read and write the others' clock bits (`clocks.rs`).
    if model.clock_ranks[k].is_some() {
        (footprint.machines)
            .extend((0..model.machines.len()).filter(|&j| model.clock_ranks[j].is_some()));
    }
    footprint.slots.sort_unstable();
    footprint.slots.dedup();
    footprint.machines.sort_unstable();
    footprint.machines.dedup();
    Some(footprint)
}

/// Every name one machine state's code holds, resolved as its ringlet could resolve it.
struct Gather<'m> {
    model: &'m Search<'m>,
    machine: usize,
    footprint: Footprint,
    /// Reasoners whose inputs are already gathered.
    theories: Vec<bool>,
    /// Some posting's type is computed as the ringlet runs.
    computed_type: bool,
}

impl Gather<'_> {
    fn actions(&mut self, actions: &[Action]) {
        for action in actions {
            match action {
                Action::Post { ty, .. } => self.name(ty),
                Action::Statement(statement) => {
                    let mut inner = Vec::new();
                    statement.visit(&mut |s| inner.push(s));
                    for s in inner {
                        self.statement(s);
                    }
                }
                Action::Call { .. } | Action::Code(_) => {}
            }
        }
    }

    fn statement(&mut self, statement: &Statement) {
        match statement {
            Statement::Declare { name, .. }
            | Statement::Extern { name, .. }
            | Statement::Assign { name, .. } => self.name(name),
            Statement::Expr(_) | Statement::Block(_) | Statement::For { .. } => {}
        }
        for e in statement.expressions() {
            self.expr(e);
        }
    }

    fn expr(&mut self, e: &Expr) {
        match e {
            // A string may name a type posted to or a machine commanded.
            Expr::Name(n) | Expr::Str(n) => self.name(n),
            Expr::Unary { operand, .. } => self.expr(operand),
            Expr::Binary { left, right, .. } => {
                self.expr(left);
                self.expr(right);
            }
            Expr::Call {
                function,
                arguments,
                ..
            } => {
                if let Builtin::Post { to, .. } = builtin(function, arguments) {
                    match to {
                        Target::Named(Expr::Str(_)) => {}
                        Target::Named(_) => self.computed_type = true,
                        Target::Fixed(ty) => self.name(ty),
                    }
                }
                for a in arguments {
                    self.expr(a);
                }
            }
            Expr::Bool(_) | Expr::Int(_) | Expr::Float(_) | Expr::Duration(_) => {}
        }
    }

    /// `n` read, assigned or posted to, as the machine's own name or the behaviour's.
    fn name(&mut self, n: &str) {
        if let Some(m) = self.model.machine_index(n) {
            self.footprint.machines.push(m);
        }
        if let Some(name) = self.model.resolve(Some(self.machine), n) {
            self.resolved(name);
        }
        if let Some(&name) = self.model.names.get(n) {
            self.resolved(name);
        }
    }

    fn resolved(&mut self, name: Name) {
        match name {
            Name::Slot(slot) => self.footprint.slots.push(slot),
            Name::Running(m) => self.footprint.machines.push(m),
            Name::Answer { theory, .. } => {
                if std::mem::replace(&mut self.theories[theory], true) {
                    return;
                }
                let inputs: Vec<Name> = self.model.theories[theory]
                    .inputs
                    .iter()
                    .filter_map(|(_, name)| *name)
                    .collect();
                for input in inputs {
                    self.resolved(input);
                }
            }
        }
    }
}
