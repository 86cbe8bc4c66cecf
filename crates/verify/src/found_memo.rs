//! What the explicit search checks of each state it finds (which machine states it enters,
//! which properties look for it), remembered by the bits of its packed record those read: the
//! machines' controls for the first, the fields a property's expression names for the second.
//! Most new states then need no unpacking.

use crate::model::Name;
use crate::property::{Property, Term};
use crate::search::Search;
use crate::world::{Layout, Status, SystemState};
use rustc_hash::{FxHashMap, FxHashSet};

/// The most keys each table keeps; past it, states are unpacked and checked as they come.
const MAX_KEYS: usize = 1 << 16;

pub(crate) struct FoundMemo<'m> {
    model: &'m Search<'m>,
    properties: &'m [Property],
    /// Every machine's control.
    controls: u128,
    /// Controls whose entered states are marked.
    marked: FxHashSet<u128>,
    /// Per property: the bits its expression reads, and whether it looks for a state by them.
    targets: Vec<(u128, FxHashMap<u128, bool>)>,
}

impl<'m> FoundMemo<'m> {
    pub fn new(
        model: &'m Search<'m>,
        properties: &'m [Property],
        layout: &Layout,
    ) -> FoundMemo<'m> {
        let mut memo = FoundMemo {
            model,
            properties,
            controls: 0,
            marked: FxHashSet::default(),
            targets: Vec::new(),
        };
        memo.relayout(layout);
        memo
    }

    /// Forgets everything, for records packed with `layout` (a field widened).
    pub fn relayout(&mut self, layout: &Layout) {
        self.controls = (0..self.model.machines.len()).fold(0, |m, k| m | layout.control_mask(k));
        self.marked.clear();
        self.targets = self
            .properties
            .iter()
            .map(|p| {
                (
                    term_mask(self.model, layout, p.term()),
                    FxHashMap::default(),
                )
            })
            .collect();
    }

    /// Bytes the tables hold.
    pub fn bytes(&self) -> usize {
        self.marked.capacity() * (std::mem::size_of::<u128>() + 1)
            + self
                .targets
                .iter()
                .map(|(_, t)| t.capacity() * (std::mem::size_of::<(u128, bool)>() + 1))
                .sum::<usize>()
    }

    /// Marks what the new state `id`, packed as `record`, enters, in `entered`, and which
    /// properties not yet decided look for it, in `found`; `world` is where it is unpacked when
    /// it must be.
    pub fn check(
        &mut self,
        layout: &Layout,
        record: u128,
        world: &mut SystemState,
        entered: &mut [Vec<bool>],
        found: &mut [Option<u32>],
        id: u32,
    ) {
        let bytes = &record.to_le_bytes()[..layout.bytes()];
        let mut unpacked = false;
        let mut unpack = |world: &mut SystemState| {
            if !std::mem::replace(&mut unpacked, true) {
                layout.unpack_into(bytes, world);
            }
        };
        let controls = record & self.controls;
        if !self.marked.contains(&controls) {
            unpack(world);
            for (k, c) in world.machines.iter().enumerate() {
                if c.status != Status::Dormant {
                    entered[k][usize::from(c.state)] = true;
                }
            }
            if self.marked.len() < MAX_KEYS {
                self.marked.insert(controls);
            }
        }
        for (p, (mask, known)) in self.targets.iter_mut().enumerate() {
            if found[p].is_some() {
                continue;
            }
            let key = record & *mask;
            let target = match known.get(&key) {
                Some(&target) => target,
                None => {
                    unpack(world);
                    let target = self.properties[p].is_target(self.model, world);
                    if known.len() < MAX_KEYS {
                        known.insert(key, target);
                    }
                    target
                }
            };
            if target {
                found[p] = Some(id);
            }
        }
        if cfg!(debug_assertions) {
            unpack(world);
            for (k, c) in world.machines.iter().enumerate() {
                let marked = c.status == Status::Dormant || entered[k][usize::from(c.state)];
                assert!(marked, "a remembered control left a state unmarked");
            }
            for (p, property) in self.properties.iter().enumerate() {
                let target = property.is_target(self.model, world);
                assert!(
                    !target || found[p].is_some(),
                    "a remembered property missed"
                );
                assert!(
                    target || found[p] != Some(id),
                    "a remembered property misfound"
                );
            }
        }
    }
}

/// The bits of a record `term` reads.
fn term_mask(model: &Search, layout: &Layout, term: &Term) -> u128 {
    match term {
        Term::Const(_) => 0,
        Term::Slot(slot) => layout.slot_mask(*slot),
        Term::Answer { theory, .. } => {
            let mut asked = vec![false; model.theories.len()];
            theory_mask(model, layout, *theory, &mut asked)
        }
        Term::Running(m) | Term::InState { machine: m, .. } => layout.control_mask(*m),
        Term::Saw(i) => layout.saw_mask(*i),
        Term::Not(t) | Term::Neg(t) => term_mask(model, layout, t),
        Term::And(l, r) | Term::Or(l, r) | Term::Binary(_, l, r) => {
            term_mask(model, layout, l) | term_mask(model, layout, r)
        }
        Term::Function(_, args) => args.iter().fold(0, |m, a| m | term_mask(model, layout, a)),
    }
}

/// The bits of a record a reasoner's inputs read.
fn theory_mask(model: &Search, layout: &Layout, theory: usize, asked: &mut [bool]) -> u128 {
    if std::mem::replace(&mut asked[theory], true) {
        return 0;
    }
    model.theories[theory]
        .inputs
        .iter()
        .filter_map(|(_, name)| *name)
        .fold(0, |m, name| {
            m | match name {
                Name::Slot(slot) => layout.slot_mask(slot),
                Name::Running(k) => layout.control_mask(k),
                Name::Answer { theory, .. } => theory_mask(model, layout, theory, asked),
            }
        })
}
