//! One step of the model: one ringlet of the machine whose turn it is, under §3.1's round
//! schedule, with every choice the environment has along the way.
//!
//! A step: find the next running machine in manifest order from `turn` (passing the end starts
//! a new round: machines started during the last one may now ring); if its state was just
//! entered, run OnEntry; take the **snapshot**: the time tests of the state that are not yet
//! due may come due (constant ones of a clock in order of duration, none of a positive
//! duration whose clock this arrival started, as the other machines' clocks allow:
//! [`crate::clocks`]), and a free type that OnEntry read or
//! posted may change (the world may move between OnEntry and the snapshot); remember what the
//! properties' `saw()` read; try the transitions in priority order (labels a reasoner answers
//! are its answers on the snapshot's inputs, whiteboard values read from here on are the
//! snapshot's with the machine's own later postings on top, variables are live); on the first that holds run OnExit and make the target
//! current, else run Internal. Finally the environment sets every free type to any value of
//! its domain: that is what the next snapshot, of whichever machine, will see, and what a
//! property speaking of the world now sees after this step.
//!
//! A free type the search does not store ([`Storage::ChosenWhenRead`]) is the same world seen
//! lazily: its value is chosen where the ringlet first reads it, once in OnEntry and once from
//! the snapshot on (as the environment could have set it before either), and a machine reads
//! back what it posted to it; the choices are walked as a tree ([`Choices`]). A free type may
//! stay never posted (a silent sensor) until the environment first posts it, and never after:
//! a stored one by its value, one chosen when read by one bit of the state ([`crate::world::POSTED`]).
//!
//! Control postings (`Name: On`, `suspend("Name")`) act when the posting ringlet ends, in the
//! order posted, as the runner obeys them between ringlets: `NameIsRunning` read later in the
//! same ringlet is still the old mode (a machine started this round rings from the next).
//! A `reload` reads the same file again (files do not change while a behaviour is verified):
//! the machine enters its initial state again; a `reread` changes nothing. Host functions, `say`,
//! `print` and the sleeps have no effect on what machines read, and are skipped.

use crate::arith::{self, convert, text};
use crate::choices::Choices;
use crate::model::Storage;
use crate::model::{Name, SlotId, SlotKind};
use crate::reasoner::{input, Input};
use crate::search::Search;
use crate::values::{ValueId, NEVER};
use crate::world::{Control, Status, SystemState, FIRST_TURN, POSTED};
use proclaim_board::Value;
use proclaim_fsm::control::Command;
use proclaim_fsm::{Action, Expr, TIME_TESTS};
use proclaim_lower::builtin::{builtin, Builtin, Content};
use proclaim_lower::Evaluate;
use proclaim_lower::{walk_to_end, Effects, Next, RingletPlan, RingletRun};
use std::convert::Infallible;

/// Which of the environment's options a step took: the leaf of its ringlet's choices (time
/// tests, free types read) and the environment's move after the ringlet (every stored free
/// type). Replaying a step with its choice gives the same successor.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Choice {
    pub snapshot: u64,
    pub environment: u64,
}

/// What the environment did in a step, for counterexamples.
#[derive(Clone, Debug, Default)]
pub struct Detail {
    /// Time tests of the ringing machine's state that came due at the snapshot.
    pub timers: Vec<usize>,
    /// Stored free types set between OnEntry and the snapshot.
    pub at_snapshot: Vec<(SlotId, ValueId)>,
    /// Free types chosen where the ringlet read them, in the order it read them.
    pub read: Vec<(SlotId, ValueId)>,
    /// Free types chosen where read that the ringlet posted itself, each after how many of
    /// `read`: a later read of the value they held before is a change the environment made,
    /// to be told again.
    pub posted: Vec<(usize, SlotId, ValueId)>,
    /// Stored free types that changed after the ringlet.
    pub environment: Vec<(SlotId, ValueId)>,
}

pub struct Successor {
    pub world: SystemState,
    pub choice: Choice,
    pub machine: usize,
    /// A new round began with this step.
    pub wrapped: bool,
    /// The state the ringlet began in.
    pub from: usize,
    /// Which of that state's transitions fired (its position in priority order).
    pub fired: Option<usize>,
    pub detail: Option<Detail>,
}

/// The initial worlds: every machine at its initial state (running or dormant as the manifest
/// says), variables at zero, every stored free type at each value of its initial domain (in
/// mixed radix, the first free slot the fastest).
pub fn initial_worlds<'a>(model: &'a Search) -> impl Iterator<Item = SystemState> + 'a {
    let base = SystemState {
        turn: FIRST_TURN,
        machines: model
            .machines
            .iter()
            .map(|m| Control {
                state: m.initial as u16,
                status: if m.start {
                    Status::Running
                } else {
                    Status::Dormant
                },
                just_entered: true,
                fresh: false,
                time: 0,
                arrived: false,
                order: 0,
                left_due: 0,
                left_wait: 0,
            })
            .collect(),
        values: {
            let mut values = model.values.borrow_mut();
            model
                .slots
                .iter()
                .zip(&model.storage)
                .map(|(s, storage)| match storage {
                    Storage::ChosenWhenRead => NEVER,
                    Storage::Stored | Storage::Unread => values.intern_option(s.initial.as_ref()),
                })
                .collect()
        },
        saw: vec![NEVER; model.saw.len()],
    };
    let free: Vec<(SlotId, Vec<ValueId>)> = {
        let mut values = model.values.borrow_mut();
        model
            .stored_free_slots()
            .map(|(slot, d)| {
                (
                    slot,
                    d.initial
                        .iter()
                        .map(|v| values.intern_option(v.as_ref()))
                        .collect(),
                )
            })
            .collect()
    };
    let count: u64 = free.iter().map(|(_, d)| d.len() as u64).product();
    (0..count).map(move |mut index| {
        let mut w = base.clone();
        for (slot, domain) in &free {
            let n = domain.len() as u64;
            w.values[*slot] = domain[(index % n) as usize];
            index /= n;
        }
        w
    })
}

/// The values a free type may take: once posted, and while still never posted (never posted
/// first: staying silent is the first choice).
#[derive(Clone, Debug, Default)]
struct ReadDomain {
    values: Vec<ValueId>,
    initial: Vec<ValueId>,
}

impl ReadDomain {
    fn of(values: &mut crate::values::Values, d: &crate::model::FreeDomain) -> ReadDomain {
        ReadDomain {
            values: d.values.iter().map(|v| values.intern(v)).collect(),
            initial: d
                .initial
                .iter()
                .map(|v| values.intern_option(v.as_ref()))
                .collect(),
        }
    }

    /// What the type may hold next, given whether it was ever posted.
    fn now(&self, posted: bool) -> &[ValueId] {
        if posted {
            &self.values
        } else {
            &self.initial
        }
    }
}

/// The steps of the model.
pub struct StepGenerator<'m> {
    model: &'m Search<'m>,
    /// Set once a state had more successors than [`MAX_SUCCESSORS`] (the search must then stop
    /// and say so: the list it got is cut short).
    overflowed: std::cell::Cell<bool>,
    /// Stored free slots and their domains as value numbers.
    free: Vec<(SlotId, ReadDomain)>,
    /// Per slot: its domain when it is chosen when read (empty otherwise).
    read_domains: Vec<ReadDomain>,
}

impl<'m> StepGenerator<'m> {
    pub fn new(model: &'m Search<'m>) -> StepGenerator<'m> {
        let mut values = model.values.borrow_mut();
        let free = model
            .stored_free_slots()
            .map(|(slot, d)| (slot, ReadDomain::of(&mut values, d)))
            .collect();
        let mut read_domains = vec![ReadDomain::default(); model.slots.len()];
        for (slot, d) in model.free_slots() {
            if model.storage[slot] == Storage::ChosenWhenRead {
                read_domains[slot] = ReadDomain::of(&mut values, d);
            }
        }
        StepGenerator {
            model,
            overflowed: std::cell::Cell::new(false),
            free,
            read_domains,
        }
    }

    /// What stored free type `slot`, now holding `current`, may hold next.
    fn domain(&self, slot: SlotId, current: ValueId) -> &[ValueId] {
        self.free
            .iter()
            .find(|(s, _)| *s == slot)
            .map_or(&[], |(_, d)| d.now(current != NEVER))
    }

    /// The machine that rings next from `world` and the world as it is when it starts (a new
    /// round clears "started this round"); `None` when no machine can ring any more.
    pub(crate) fn next_machine(&self, world: &SystemState) -> Option<(usize, SystemState, bool)> {
        let n = self.model.machines.len();
        let mut w = world.clone();
        let mut k = if w.turn == FIRST_TURN {
            0
        } else {
            usize::from(w.turn)
        };
        let mut wrapped = false;
        for _ in 0..=2 * n {
            if k >= n {
                if wrapped {
                    return None;
                }
                k = 0;
                wrapped = true;
                for c in &mut w.machines {
                    c.fresh = false;
                    c.arrived = false;
                    (c.left_due, c.left_wait) = (0, 0);
                }
            }
            if self.can_ring(&w, k) {
                return Some((k, w, wrapped));
            }
            k += 1;
        }
        None
    }

    /// Running, not started this round, and not finished (a final state whose OnEntry ran).
    fn can_ring(&self, w: &SystemState, k: usize) -> bool {
        let c = &w.machines[k];
        c.status == Status::Running
            && !c.fresh
            && (c.just_entered || !self.model.machines[k].states[usize::from(c.state)].is_final())
    }

    /// Every successor of `world`, with what the environment did when `detail` is asked for:
    /// the ringing machine's ringlet once for every leaf of its choices (the free types it
    /// reads, the snapshot's time tests and stored free types), then every move of the
    /// environment.
    pub fn successors(&self, world: &SystemState, detail: bool, out: &mut Vec<Successor>) {
        let Some((k, start, wrapped)) = self.next_machine(world) else {
            return;
        };
        let mut choices = Choices::default();
        let mut leaf = 0u64;
        let before = out.len();
        loop {
            let ringlet = self.ringlet(&start, k, wrapped, &mut choices, leaf, detail);
            self.environment_moves(&ringlet, detail, out);
            leaf += 1;
            if out.len() - before > MAX_SUCCESSORS {
                self.overflowed.set(true);
                break;
            }
            if !choices.advance() {
                break;
            }
        }
    }

    /// Whether some state had more successors than [`MAX_SUCCESSORS`]: what was made of it
    /// is cut short, so no absence may be claimed.
    pub(crate) fn overflowed(&self) -> bool {
        self.overflowed.get()
    }

    /// Machine `k`'s ringlet from `start` along the current path of `choices`.
    #[allow(clippy::too_many_arguments)]
    fn ringlet(
        &self,
        start: &SystemState,
        k: usize,
        wrapped: bool,
        choices: &mut Choices,
        leaf: u64,
        detail: bool,
    ) -> Ringlet {
        self.ringlet_on(start, k, wrapped, choices, leaf, detail, None)
            .0
    }

    /// [`StepGenerator::ringlet`], on an open world when `open` is given (handed back after):
    /// the steps [`RingletRun`] gives, each done on the model.
    #[allow(clippy::too_many_arguments)]
    fn ringlet_on<'c>(
        &'c self,
        start: &SystemState,
        k: usize,
        wrapped: bool,
        choices: &'c mut Choices,
        leaf: u64,
        detail: bool,
        open: Option<Open<'c>>,
    ) -> (Ringlet, Option<Open<'c>>) {
        let from = usize::from(start.machines[k].state);
        let mut chosen = Chosen {
            choices,
            domains: &self.read_domains,
            now: Vec::new(),
            entry: Vec::new(),
            log: detail.then(Vec::new),
            posted: detail.then(Vec::new),
            open,
        };
        let mut exec = RingletInterpreter {
            model: self.model,
            world: start.clone(),
            machine: k,
            snapshot: None,
            touched: None,
            deferred: Vec::new(),
            chosen: &mut chosen,
        };
        let (fired, snapshot) = self.steps(&mut exec, from, detail);
        for (target, command) in std::mem::take(&mut exec.deferred) {
            exec.obey(target, command);
        }
        let mut world = exec.world;
        world.turn = (k + 1) as u8;
        let ringlet = Ringlet {
            world,
            machine: k,
            wrapped,
            from,
            fired,
            leaf,
            due: snapshot.due,
            timers: snapshot.timers,
            at_snapshot: snapshot.values,
            read: chosen.log.unwrap_or_default(),
            posted: chosen.posted.unwrap_or_default(),
        };
        (ringlet, chosen.open)
    }

    /// The steps [`RingletRun`] gives for the ringing machine's state `from`, each done on
    /// `exec`'s world: the transition that fired (its place in the model's), and what the
    /// snapshot chose.
    fn steps(
        &self,
        exec: &mut RingletInterpreter<'_, '_>,
        from: usize,
        detail: bool,
    ) -> (Option<usize>, Snapshot) {
        let k = exec.machine;
        let machine = &self.model.machines[k];
        let state = &machine.states[from];
        let plan = RingletPlan::of_state(&machine.machine, &machine.machine.states[from]);
        let mut run = RingletRun::new(plan, exec.world.machines[k].just_entered);
        let mut snapshot = Snapshot::default();
        let mut fired = None;
        let mut arrived = false;
        loop {
            match run.next_step() {
                Next::Arrive(actions) => {
                    exec.touched = Some(Vec::new());
                    exec.run(actions);
                    exec.world.machines[k].just_entered = false;
                    arrived = true;
                    // On an open world the other machines' bits are unknown: the symbolic
                    // engine writes this arrival itself (`symbolic/clocks.rs`).
                    if exec.chosen.open.is_none() {
                        let model = self.model;
                        crate::clocks::arrive(
                            &model.machines,
                            &model.clock_ranks,
                            &mut exec.world,
                            k,
                        );
                    }
                }
                Next::Snapshot => snapshot = self.snapshot(exec, detail, arrived),
                Next::Try(arm) => {
                    let modelled = state.modelled(arm);
                    let holds = modelled.is_some_and(|t| exec.truth(&state.transitions[t].label));
                    run.proved(holds);
                }
                Next::Leave(arm) => {
                    exec.run(arm.leaving());
                    // Only a modelled transition is proved (above).
                    if let Some(t) = state.modelled(arm) {
                        fired = Some(t);
                        // It stays as it is: not entered again, its due tests still due.
                        if arm.stays() {
                            continue;
                        }
                        let target = state.transitions[t].target;
                        let c = &mut exec.world.machines[k];
                        if crate::clocks::heard_later(&self.model.clock_ranks, k) {
                            let durations = &self.model.clock_durations;
                            (c.left_due, c.left_wait) =
                                crate::clocks::left(durations, state, c.time);
                        }
                        let kept = kept_time(
                            &state.time_tests,
                            c.time,
                            &machine.states[target].time_tests,
                            &arm.transition.enters,
                        );
                        c.time = implied_time(&machine.states[target], kept);
                        c.state = target as u16;
                        c.just_entered = true;
                    }
                }
                Next::Stay(actions) => exec.run(actions),
                Next::Done(_) => return (fired, snapshot),
            }
        }
    }

    /// The ringlet's snapshot, after its arrival (when `arrived`): the time tests that come due
    /// and the values of the stored free types its arrival read or posted, as the choice's
    /// branch makes them; then what the machine `saw`.
    fn snapshot(
        &self,
        exec: &mut RingletInterpreter<'_, '_>,
        detail: bool,
        arrived: bool,
    ) -> Snapshot {
        let k = exec.machine;
        let mut touched = exec.touched.take().unwrap_or_default();
        touched.retain(|s| {
            self.model.slots[*s].free.is_some() && self.model.storage[*s] == Storage::Stored
        });
        touched.sort_unstable();
        touched.dedup();
        exec.chosen.entry = std::mem::take(&mut exec.chosen.now);
        let w = &mut exec.world;
        let from = usize::from(w.machines[k].state);
        let state = &self.model.machines[k].states[from];
        let tests = &state.time_tests;
        let mut masks = due_masks(state, w.machines[k].time);
        if arrived {
            let (fresh, due) = (fresh_time(state), w.machines[k].time);
            masks.retain(|m| m & fresh & !due == 0);
        }
        // On an open world the symbolic engine meets each leaf with the same rule as a diagram.
        if exec.chosen.open.is_none() {
            self.agreeing(w, k, &mut masks);
        }
        let touched_domains: Vec<&[ValueId]> = touched
            .iter()
            .map(|s| self.domain(*s, w.values[*s]))
            .collect();
        let snapshot_count =
            masks.len() * touched_domains.iter().map(|d| d.len()).product::<usize>();
        let mut index = exec.chosen.choices.branch(snapshot_count);
        let mask = masks[index % masks.len()];
        index /= masks.len();
        let old_mask = w.machines[k].time;
        w.machines[k].time = mask;
        let mut taken = Snapshot {
            due: mask,
            ..Snapshot::default()
        };
        for (slot, domain) in touched.iter().zip(&touched_domains) {
            let n = domain.len();
            let v = rotated(domain, w.values[*slot], index % n);
            index /= n;
            // Only what changed: the first choice leaves a value as it was, and a script
            // would be told it cannot say a change that did not happen.
            if detail && v != w.values[*slot] {
                taken.values.push((*slot, v));
            }
            w.values[*slot] = v;
        }
        if detail {
            taken.timers = (0..tests.len())
                .filter(|i| mask & !old_mask & (1 << i) != 0)
                .collect();
        }
        exec.snapshot = Some(exec.world.values.clone());
        for (j, e) in self.model.saw_of(k) {
            let v = exec.value(e);
            let id = self.model.values.borrow_mut().intern_option(v.as_ref());
            exec.world.saw[j] = id;
        }
        taken
    }

    /// `masks` of machine `k` cut to those the other machines' clocks in `w` allow
    /// ([`crate::clocks::agrees`]). Every real moment agrees with itself, so some set of due
    /// tests always agrees.
    fn agreeing(&self, w: &SystemState, k: usize, masks: &mut Vec<u16>) {
        let model = self.model;
        let agrees = |m: &u16| {
            let durations = &model.clock_durations;
            crate::clocks::agrees(&model.machines, &model.clock_ranks, durations, w, k, *m)
        };
        if masks.iter().any(agrees) {
            masks.retain(agrees);
        } else {
            let name = &model.machines[k].name;
            debug_assert!(false, "no due tests of {name} agree with the other clocks");
        }
    }

    /// Every leaf of machine `k`'s ringlet from `control` on an open world whose stored slots
    /// take the values of `domains` (after the first ringlet, in a round already begun); false
    /// (and `out` incomplete) past `limit` leaves.
    pub(crate) fn open_leaves(
        &self,
        k: usize,
        control: Control,
        domains: &[Vec<ValueId>],
        limit: usize,
        out: &mut Vec<OpenLeaf>,
    ) -> bool {
        let model = self.model;
        let unknown_control = Control {
            state: 0,
            status: Status::Running,
            just_entered: false,
            fresh: false,
            time: 0,
            arrived: false,
            order: 0,
            left_due: 0,
            left_wait: 0,
        };
        let mut start = SystemState {
            turn: k as u8,
            machines: vec![unknown_control; model.machines.len()],
            values: model
                .storage
                .iter()
                .map(|s| match s {
                    Storage::Stored | Storage::ChosenWhenRead => UNKNOWN,
                    Storage::Unread => NEVER,
                })
                .collect(),
            saw: vec![NEVER; model.saw.len()],
        };
        start.machines[k] = control;
        let mut choices = Choices::default();
        loop {
            let mut status_known = vec![false; model.machines.len()];
            status_known[k] = true;
            let open = Open {
                domains,
                reads: Vec::new(),
                status_known,
                control_writes: vec![ControlWrites::default(); model.machines.len()],
            };
            let (ringlet, open) =
                self.ringlet_on(&start, k, false, &mut choices, 0, false, Some(open));
            if let Some(open) = open {
                out.push(OpenLeaf {
                    reads: open.reads,
                    after: ringlet.world,
                    control_writes: open.control_writes,
                    fired: ringlet.fired,
                    due: ringlet.due,
                });
            }
            if out.len() >= limit {
                return false;
            }
            if !choices.advance() {
                return true;
            }
        }
    }

    /// After a ringlet, one successor for every value each stored free type may take.
    fn environment_moves(&self, ringlet: &Ringlet, detail: bool, out: &mut Vec<Successor>) {
        let w = &ringlet.world;
        let domains: Vec<(SlotId, &[ValueId])> = self
            .free
            .iter()
            .map(|(slot, d)| (*slot, d.now(w.values[*slot] != NEVER)))
            .collect();
        let environment_count: u64 = domains.iter().map(|(_, d)| d.len() as u64).product();
        for environment_choice in 0..environment_count {
            let mut next = w.clone();
            let mut index = environment_choice;
            let mut changed = Vec::new();
            for &(slot, domain) in &domains {
                let n = domain.len() as u64;
                let v = rotated(domain, w.values[slot], (index % n) as usize);
                index /= n;
                if detail && next.values[slot] != v {
                    changed.push((slot, v));
                }
                next.values[slot] = v;
            }
            out.push(Successor {
                world: next,
                choice: Choice {
                    snapshot: ringlet.leaf,
                    environment: environment_choice,
                },
                machine: ringlet.machine,
                wrapped: ringlet.wrapped,
                from: ringlet.from,
                fired: ringlet.fired,
                detail: detail.then(|| Detail {
                    timers: ringlet.timers.clone(),
                    at_snapshot: ringlet.at_snapshot.clone(),
                    read: ringlet.read.clone(),
                    posted: ringlet.posted.clone(),
                    environment: changed,
                }),
            });
        }
    }
}

/// One ringlet as its successors share it: which machine rang from which state, along which
/// leaf of its choices, and what fired.
struct Ringlet {
    world: SystemState,
    machine: usize,
    wrapped: bool,
    from: usize,
    fired: Option<usize>,
    leaf: u64,
    /// The time tests due at its snapshot.
    due: u16,
    /// With detail only: the time tests that came due.
    timers: Vec<usize>,
    /// With detail only: the values the stored free types had at the snapshot.
    at_snapshot: Vec<(SlotId, ValueId)>,
    /// With detail only: the free types chosen where they were read.
    read: Vec<(SlotId, ValueId)>,
    /// With detail only: what it posted to them, each after how many reads.
    posted: Vec<(usize, SlotId, ValueId)>,
}

/// What a ringlet's snapshot chose: the time tests due, and with detail only those that came
/// due and the values the stored free types had.
#[derive(Default)]
struct Snapshot {
    /// The time tests due at it.
    due: u16,
    timers: Vec<usize>,
    values: Vec<(SlotId, ValueId)>,
}

/// The free types a ringlet chooses where it reads them: each phase (OnEntry, then from the
/// snapshot on) chooses a type at its first read and reads back what the machine posted to it.
struct Chosen<'c> {
    choices: &'c mut Choices,
    domains: &'c [ReadDomain],
    /// This phase's values.
    now: Vec<(SlotId, ValueId)>,
    /// OnEntry's values, from the snapshot on: the value a snapshot choice starts from, so that
    /// its first branch leaves it unchanged.
    entry: Vec<(SlotId, ValueId)>,
    /// With detail: every value chosen, in order.
    log: Option<Vec<(SlotId, ValueId)>>,
    /// With detail: every value the ringlet posted to a type chosen where read, each after
    /// how many of `log`.
    posted: Option<Vec<(usize, SlotId, ValueId)>>,
    /// Where the ringlet runs on a world only partly known.
    open: Option<Open<'c>>,
}

/// A stored slot's value not known before a ringlet of the symbolic engine runs.
pub(crate) const UNKNOWN: ValueId = ValueId::MAX;

/// At most this many successors of one state (a ringlet whose reads of free values multiply
/// past it would hold the search on one state for ever, in ever more memory).
pub(crate) const MAX_SUCCESSORS: usize = 100_000;

/// What a ringlet on an open world found out by reading.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum OpenRead {
    Slot(SlotId, ValueId),
    Status(usize, Status),
}

/// A world only partly known (the symbolic engine's): the ringing machine's control is, every
/// other machine's mode and every stored slot are chosen where the ringlet first reads them,
/// from the values they can hold.
pub(crate) struct Open<'d> {
    /// Per slot, the values it can hold.
    pub domains: &'d [Vec<ValueId>],
    pub reads: Vec<OpenRead>,
    pub status_known: Vec<bool>,
    /// Per machine, what commands to it wrote.
    pub control_writes: Vec<ControlWrites>,
}

/// One leaf of a ringlet on an open world: what it read, and the world after it (a stored slot
/// still [`UNKNOWN`] was neither read nor written).
pub(crate) struct OpenLeaf {
    pub reads: Vec<OpenRead>,
    pub after: SystemState,
    pub control_writes: Vec<ControlWrites>,
    pub fired: Option<usize>,
    /// The time tests due at its snapshot.
    pub due: u16,
}

impl Chosen<'_> {
    /// The value of `slot` in this phase: chosen at its first read, from what it may hold
    /// given whether the environment has `posted` it.
    fn value(&mut self, slot: SlotId, posted: bool) -> ValueId {
        if let Some(&(_, v)) = self.now.iter().find(|(s, _)| *s == slot) {
            return v;
        }
        let before = self.entry.iter().find(|(s, _)| *s == slot).map(|&(_, v)| v);
        let domain = self.domains[slot].now(posted);
        let branch = self.choices.branch(domain.len());
        let v = match before {
            Some(before) => rotated(domain, before, branch),
            None => domain[branch % domain.len()],
        };
        self.now.push((slot, v));
        if let Some(log) = &mut self.log {
            log.push((slot, v));
        }
        v
    }

    fn post(&mut self, slot: SlotId, value: ValueId) {
        match self.now.iter_mut().find(|(s, _)| *s == slot) {
            Some(entry) => entry.1 = value,
            None => self.now.push((slot, value)),
        }
        if let Some(posted) = &mut self.posted {
            let reads = self.log.as_ref().map_or(0, Vec::len);
            posted.push((reads, slot, value));
        }
    }
}

/// The `i`-th value of `domain` counted from `current` (when it is in the domain), so that
/// choice 0 leaves the value as it is: among paths of one length, the search meets first the
/// one in which the world changes least, and counterexamples say only what matters.
fn rotated(domain: &[ValueId], current: ValueId, i: usize) -> ValueId {
    let start = domain.iter().position(|&v| v == current).unwrap_or(0);
    domain[(start + i) % domain.len()]
}

/// The time bits a state's tests may have at a snapshot, given those already due: a due test
/// stays due, and the constant tests of one clock (first in its part of the list, shortest
/// first) come due in order.
pub(crate) fn time_masks(tests: &[crate::model::TimeTest], due: u16) -> Vec<u16> {
    let n = tests.len();
    // Each clock's part of the list: where it starts and how many constant tests it begins with.
    let mut parts: Vec<(usize, usize)> = Vec::new();
    for (i, t) in tests.iter().enumerate() {
        if i == 0 || tests[i - 1].clock != t.clock {
            parts.push((i, 0));
        }
        if let Some(part) = parts
            .last_mut()
            .filter(|p| i - p.0 == p.1 && t.micros.is_some())
        {
            part.1 += 1;
        }
    }
    let all = (1u32 << n) - 1;
    (0..=all)
        .map(|m| m as u16)
        .filter(|m| m & due == due)
        .filter(|m| {
            parts.iter().all(|&(start, constant)| {
                let prefix = (u32::from(*m) >> start) & ((1u32 << constant) - 1);
                prefix & (prefix + 1) == 0
            })
        })
        .collect()
}

/// The sets of `state`'s time tests that may be due at a snapshot, given those already `due`:
/// [`time_masks`], and across clocks [`crate::model::StateModel::time_order`]. Never empty:
/// every test due is one of them, whatever `due` was.
pub(crate) fn due_masks(state: &crate::model::StateModel, due: u16) -> Vec<u16> {
    let masks = time_masks(&state.time_tests, due);
    let ordered = |m: &u16| {
        (state.time_order.iter())
            .all(|&(later, earlier)| m & (1 << later) == 0 || m & (1 << earlier) != 0)
    };
    masks.into_iter().filter(ordered).collect()
}

/// `due` with every test of `state` it implies due as well: a constant test no longer than a
/// due one of its clock, and the earlier of each pair of
/// [`crate::model::StateModel::time_order`] whose later is due. Those are due in every run, so
/// a move that keeps a composite's due tests into a state whose labels test more of its clocks
/// (an `in()` the state left folded away) arrives with them, and every set of due tests a
/// world holds is one [`due_masks`] lists (the symbolic engine's steps are made from those).
pub(crate) fn implied_time(state: &crate::model::StateModel, due: u16) -> u16 {
    let tests = &state.time_tests;
    let mut closed = due;
    loop {
        let mut next = closed;
        for (j, t) in tests.iter().enumerate() {
            let Some(d) = t.micros.filter(|_| closed & (1 << j) != 0) else {
                continue;
            };
            for (i, u) in tests.iter().enumerate() {
                if u.clock == t.clock && u.micros.is_some_and(|c| c <= d) {
                    next |= 1 << i;
                }
            }
        }
        for &(later, earlier) in &state.time_order {
            if next & (1 << later) != 0 {
                next |= 1 << earlier;
            }
        }
        if next == closed {
            return closed;
        }
        closed = next;
    }
}

/// The time tests of a state that are never due at the snapshot of a ringlet that arrived in
/// it: those of a positive constant duration whose clock the arrival started (its own, or a
/// composite it entered), since the round's moment is the arrival's (§3.1).
pub(crate) fn fresh_time(state: &crate::model::StateModel) -> u16 {
    state.time_mask(|t| t.micros.is_some_and(|us| us > 0) && state.arrival_starts(t.clock))
}

/// Which due time tests of a state a move keeps, as (bit in `from`'s tests, bit in `to`'s):
/// those of a composite it stays in, which it does not enter again.
pub(crate) fn kept_time_bits(
    from: &[crate::model::TimeTest],
    to: &[crate::model::TimeTest],
    enters: &[usize],
) -> Vec<(usize, usize)> {
    from.iter()
        .enumerate()
        .filter(|(_, t)| t.clock.is_some_and(|c| !enters.contains(&c)))
        .filter_map(|(i, t)| {
            let j = to.iter().position(|u| u.call == t.call)?;
            Some((i, j))
        })
        .collect()
}

/// The time bits after a move from a state whose tests had `due`: see [`kept_time_bits`].
fn kept_time(
    from: &[crate::model::TimeTest],
    due: u16,
    to: &[crate::model::TimeTest],
    enters: &[usize],
) -> u16 {
    kept_time_bits(from, to, enters)
        .into_iter()
        .filter(|(i, _)| due & (1 << i) != 0)
        .fold(0, |kept, (_, j)| kept | (1 << j))
}

/// Which fields of a machine's control a command wrote.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct ControlWrites {
    /// Its mode.
    pub status: bool,
    /// Just entered and the time bits (it starts or enters again).
    pub entry: bool,
    /// Started this round (it starts: a reload enters again without starting).
    pub fresh: bool,
    /// Its state (it starts afresh).
    pub state: bool,
}

impl ControlWrites {
    fn add(&mut self, other: ControlWrites) {
        self.status |= other.status;
        self.entry |= other.entry;
        self.fresh |= other.fresh;
        self.state |= other.state;
    }
}

/// Applies a control command to machine `k` as gufsm's `SuspensibleMachine` (and the runner)
/// does; a machine that starts is "fresh": it rings from the next round on. Returns what it
/// wrote.
fn control(model: &Search, world: &mut SystemState, k: usize, command: Command) -> ControlWrites {
    let initial = model.machines[k].initial as u16;
    let c = &mut world.machines[k];
    let all = ControlWrites {
        status: true,
        entry: true,
        fresh: true,
        state: true,
    };
    let status = ControlWrites {
        status: true,
        ..ControlWrites::default()
    };
    match (command, c.status) {
        (Command::On | Command::Resume, Status::Running) => ControlWrites::default(),
        (Command::Restart, _) | (Command::On | Command::Resume, Status::Dormant) => {
            *c = Control {
                state: initial,
                status: Status::Running,
                just_entered: true,
                fresh: true,
                time: 0,
                // Facts about its last arrival and this round, true until it arrives again
                // (`clocks.rs`).
                arrived: c.arrived,
                order: c.order,
                left_due: c.left_due,
                left_wait: c.left_wait,
            };
            all
        }
        (Command::On | Command::Resume, Status::Suspended) => {
            c.status = Status::Running;
            c.just_entered = true;
            c.fresh = true;
            c.time = 0;
            ControlWrites {
                state: false,
                ..all
            }
        }
        (Command::Suspend, Status::Running) => {
            c.status = Status::Suspended;
            status
        }
        (Command::Suspend, _) => ControlWrites::default(),
        (Command::Off, _) => {
            c.status = Status::Dormant;
            status
        }
        // The file read again is the one checked: `reload` starts the machine again at its
        // initial state, running or not, its variables kept; `reread` keeps its state.
        (Command::Reload, _) => {
            c.state = initial;
            c.just_entered = true;
            c.time = 0;
            ControlWrites {
                entry: true,
                state: true,
                ..ControlWrites::default()
            }
        }
        (Command::Reread, _) => ControlWrites::default(),
    }
}

/// One ringlet's interpreter: runs activities and evaluates expressions for machine `machine`
/// over a world.
struct RingletInterpreter<'a, 'c> {
    model: &'a Search<'a>,
    world: SystemState,
    machine: usize,
    /// Whiteboard values as the snapshot took them (from the snapshot to the ringlet's end).
    snapshot: Option<Vec<ValueId>>,
    /// While OnEntry runs: the whiteboard types it reads or posts.
    touched: Option<Vec<SlotId>>,
    /// Commands posted (target machine, command), obeyed when the ringlet ends.
    deferred: Vec<(usize, Command)>,
    chosen: &'a mut Chosen<'c>,
}

/// `proclaim-lower`'s walk over an expression, on the model: names resolve to slots and answers, a
/// time test is due where the step's choice made it so.
impl Evaluate for RingletInterpreter<'_, '_> {
    fn read(&mut self, name: &str) -> Option<Value> {
        let resolved = self.model.resolve(Some(self.machine), name)?;
        self.name_value(resolved)
    }

    fn call(&mut self, function: &str, arguments: &[Expr], clock: Option<usize>) -> Option<Value> {
        if TIME_TESTS.iter().any(|(f, _)| *f == function) {
            return Some(Value::Bool(self.time_due(function, arguments, clock)));
        }
        let args: Vec<Option<Value>> = arguments.iter().map(|a| self.value(a)).collect();
        arith::function(function, &args)
    }
}

impl RingletInterpreter<'_, '_> {
    fn is_message(&self, slot: SlotId) -> bool {
        matches!(self.model.slots[slot].kind, SlotKind::Message { .. })
    }

    fn slot_value(&mut self, slot: SlotId) -> Option<Value> {
        let message = self.is_message(slot);
        let id = if self.model.storage[slot] == Storage::ChosenWhenRead {
            let mut posted = self.world.values[slot];
            if posted == UNKNOWN {
                posted = self.open_read(slot);
            }
            let id = self.chosen.value(slot, posted == POSTED);
            if id != NEVER {
                self.world.values[slot] = POSTED;
            }
            id
        } else {
            if message {
                if let Some(t) = &mut self.touched {
                    t.push(slot);
                }
            }
            let id = match (&self.snapshot, message) {
                (Some(snapshot), true) => snapshot[slot],
                _ => self.world.values[slot],
            };
            if id == UNKNOWN {
                self.open_read(slot)
            } else {
                id
            }
        };
        let value = self.model.values.borrow().get(id).cloned();
        match (value, &self.model.slots[slot].kind) {
            (None, SlotKind::Message { external: true }) => Some(Value::Int(0)),
            (v, _) => v,
        }
    }

    fn name_value(&mut self, name: Name) -> Option<Value> {
        match name {
            Name::Slot(slot) => self.slot_value(slot),
            Name::Answer { theory, output } => Some(Value::Bool(self.answer(theory, output, 0))),
            Name::Running(m) => Some(Value::Bool(self.status_of(m) == Status::Running)),
        }
    }

    /// A command this ringlet posted, obeyed as it ends; on an open world, what it wrote of
    /// another machine's control is noted.
    fn obey(&mut self, target: usize, command: Command) {
        if target != self.machine {
            self.status_of(target);
        }
        let writes = control(self.model, &mut self.world, target, command);
        if let Some(open) = &mut self.chosen.open {
            if target != self.machine {
                open.control_writes[target].add(writes);
            }
        }
    }

    /// Machine `m`'s mode; on an open world, chosen at its first read.
    fn status_of(&mut self, m: usize) -> Status {
        if let Some(open) = &mut self.chosen.open {
            if !open.status_known[m] {
                const MODES: [Status; 3] = [Status::Running, Status::Suspended, Status::Dormant];
                let status = MODES[self.chosen.choices.branch(MODES.len())];
                open.status_known[m] = true;
                open.reads.push(OpenRead::Status(m, status));
                self.world.machines[m].status = status;
            }
        }
        self.world.machines[m].status
    }

    /// A reasoner's answer on the inputs as this ringlet reads them.
    fn answer(&mut self, theory: usize, output: usize, depth: usize) -> bool {
        let t = &self.model.theories[theory];
        let inputs: Vec<Input> = t
            .inputs
            .iter()
            .map(|(_, name)| match name {
                Some(Name::Answer { theory, output }) if depth < 8 => {
                    Input::Value(self.answer(*theory, *output, depth + 1))
                }
                Some(n @ (Name::Slot(_) | Name::Running(_))) => input(self.name_value(*n).as_ref()),
                _ => Input::Unknown,
            })
            .collect();
        self.model.reasoner(theory).answers(&inputs)[output]
    }

    /// Whether a time test of the current state is due, counted on its clock; a time test
    /// that no label of the state has (one in an activity) is never due.
    fn time_due(&self, function: &str, arguments: &[Expr], clock: Option<usize>) -> bool {
        let c = &self.world.machines[self.machine];
        let state = &self.model.machines[self.machine].states[usize::from(c.state)];
        let this_call = |call: &Expr| matches!(call, Expr::Call { function: f, arguments: a, clock: k } if f == function && a == arguments && *k == clock);
        state
            .time_tests
            .iter()
            .position(|t| this_call(&t.call))
            .is_some_and(|i| c.time & (1 << i) != 0)
    }

    fn run(&mut self, actions: &[Action]) {
        for action in actions {
            match action {
                Action::Post { ty, content } => self.post(ty, Value::parse(content)),
                Action::Statement(s) => walk_to_end(s, self),
                // Host functions change nothing a machine reads; unread code does nothing.
                Action::Call { .. } | Action::Code(_) => {}
            }
        }
    }

    fn post(&mut self, ty: &str, value: Value) {
        if let Some(k) = self.model.machine_index(ty) {
            let word = match &value {
                Value::Str(s) => s.clone(),
                other => other.to_string(),
            };
            if let Some(command) = Command::parse(&word) {
                self.deferred.push((k, command));
            }
            return;
        }
        let Some(&Name::Slot(slot)) = self.model.names.get(ty) else {
            return;
        };
        if !self.is_message(slot) {
            return;
        }
        let id = match self.model.storage[slot] {
            Storage::Unread => return,
            Storage::ChosenWhenRead => {
                let id = self.model.values.borrow_mut().intern(&value);
                self.chosen.post(slot, id);
                self.world.values[slot] = POSTED;
                return;
            }
            Storage::Stored => self.model.values.borrow_mut().intern(&value),
        };
        if let Some(t) = &mut self.touched {
            t.push(slot);
        }
        self.world.values[slot] = id;
        // A machine reads back what it posted itself after its snapshot, as the runner's
        // `seen.rs` does.
        if let Some(snapshot) = &mut self.snapshot {
            snapshot[slot] = id;
        }
    }

    /// Assigns as gufsm did: the machine's own variable, else an extern (posted), else a
    /// global.
    fn store(&mut self, name: &str, value: Value) {
        match self.model.resolve(Some(self.machine), name) {
            Some(Name::Slot(slot)) if self.model.storage[slot] == Storage::Unread => {}
            Some(Name::Slot(slot)) => match &self.model.slots[slot].kind {
                SlotKind::Local { ty, .. } => {
                    let v = convert(ty, value);
                    self.world.values[slot] = self.model.values.borrow_mut().intern(&v);
                }
                SlotKind::Global => {
                    self.world.values[slot] = self.model.values.borrow_mut().intern(&value);
                }
                SlotKind::Message { .. } => self.post(name, value),
            },
            _ => self.post(name, value),
        }
    }

    /// A stored slot of an open world read for the first time: each value of its domain in
    /// turn, as a choice, held from here on as if it had been there all along.
    fn open_read(&mut self, slot: SlotId) -> ValueId {
        let Some(open) = &mut self.chosen.open else {
            return UNKNOWN;
        };
        let domain = &open.domains[slot];
        if domain.is_empty() {
            return UNKNOWN;
        }
        let v = domain[self.chosen.choices.branch(domain.len())];
        open.reads.push(OpenRead::Slot(slot, v));
        self.world.values[slot] = v;
        if let Some(snapshot) = &mut self.snapshot {
            snapshot[slot] = v;
        }
        v
    }

    /// Whether `name` is a slot the search does not keep (nothing reads it).
    fn unread(&self, name: &str) -> bool {
        matches!(
            self.model.resolve(Some(self.machine), name),
            Some(Name::Slot(slot)) if self.model.storage[slot] == Storage::Unread
        )
    }

    fn text_of(&mut self, e: &Expr) -> String {
        text(&self.value(e).unwrap_or(Value::Int(0)))
    }

    /// The name of the state the ringing machine is in.
    fn state_name(&self) -> String {
        let state = self.world.machines[self.machine].state;
        self.model.machines[self.machine].states[usize::from(state)]
            .name
            .clone()
    }
}

/// The activity language's statements on the model: the same walk as the runner's.
impl Effects for RingletInterpreter<'_, '_> {
    type Pause = Infallible;

    fn assign(&mut self, name: &str, value: &Expr) {
        // What nothing reads is not computed: its reads would only branch.
        if self.unread(name) {
            return;
        }
        let v = self.value(value).unwrap_or(Value::Int(0));
        self.store(name, v);
    }

    /// A call standing as a statement ([`builtin`]): its postings; everything else (printing,
    /// sleeping, host functions) changes nothing a machine reads, but its arguments are still
    /// evaluated, as they may read (and so touch) free types.
    fn perform(&mut self, function: &str, arguments: &[Expr]) -> Option<Infallible> {
        match builtin(function, arguments) {
            Builtin::Post { to, content } => {
                let ty = to.name(|e| self.text_of(e));
                let state = match content {
                    Content::StateName => self.state_name(),
                    _ => String::new(),
                };
                let value = content.value(|e| self.value(e).unwrap_or(Value::Int(0)), &state);
                self.post(&ty, value);
            }
            _ => {
                for a in arguments {
                    self.value(a);
                }
            }
        }
        None
    }

    fn evaluate(&mut self, expr: &Expr) {
        self.value(expr);
    }

    fn holds(&mut self, condition: &Expr) -> bool {
        self.truth(condition)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::TimeTest;

    fn tests(micros: &[Option<u64>]) -> Vec<TimeTest> {
        clocked(&micros.iter().map(|&m| (None, m)).collect::<Vec<_>>())
    }

    /// Tests counted from the given clocks, each `timeout(its duration)`.
    fn clocked(tests: &[(Option<usize>, Option<u64>)]) -> Vec<TimeTest> {
        tests
            .iter()
            .map(|&(clock, m)| TimeTest {
                call: Expr::Call {
                    function: "timeout".into(),
                    arguments: vec![m.map_or(Expr::Name("n".into()), |m| Expr::Int(m as i64))],
                    clock,
                },
                micros: m,
                clock,
            })
            .collect()
    }

    #[test]
    fn time_tests_come_due_in_order_and_stay_due() {
        assert_eq!(time_masks(&[], 0), vec![0]);
        assert_eq!(time_masks(&tests(&[Some(1)]), 0), vec![0, 1]);
        assert_eq!(time_masks(&tests(&[Some(1)]), 1), vec![1]);
        // 1 s and 2 s: the 2 s test is never due before the 1 s one.
        assert_eq!(time_masks(&tests(&[Some(1), Some(2)]), 0), vec![0, 1, 3]);
        // A test whose duration is computed is free of the others.
        assert_eq!(time_masks(&tests(&[Some(1), None]), 0), vec![0, 1, 2, 3]);
        assert_eq!(time_masks(&tests(&[Some(1), None]), 2), vec![2, 3]);
    }

    #[test]
    fn each_clock_orders_its_own_tests_and_a_move_keeps_those_of_a_composite_it_stays_in() {
        // The state's 2 s test, then its composite's 1 s and 3 s: the composite's 3 s test
        // waits for its 1 s one, not for the state's.
        let inside = clocked(&[(None, Some(2)), (Some(0), Some(1)), (Some(0), Some(3))]);
        assert_eq!(
            time_masks(&inside, 0),
            vec![0, 1, 2, 3, 6, 7],
            "the composite's tests come due in their order, free of the state's"
        );
        // Its sibling in the composite has a test of its own and the composite's two.
        let sibling = clocked(&[(None, Some(5)), (Some(0), Some(1)), (Some(0), Some(3))]);
        assert_eq!(kept_time_bits(&inside, &sibling, &[]), vec![(1, 1), (2, 2)]);
        assert_eq!(kept_time(&inside, 0b111, &sibling, &[]), 0b110);
        assert_eq!(
            kept_time(&inside, 0b111, &sibling, &[0]),
            0,
            "entering the composite again restarts its clock"
        );
        // Out of the composite: nothing of it is kept.
        assert_eq!(kept_time(&inside, 0b111, &tests(&[Some(1)]), &[]), 0);
    }
}
