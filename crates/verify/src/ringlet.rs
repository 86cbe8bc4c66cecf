//! One step of the model: one ringlet of the machine whose turn it is, under §3.1's round
//! schedule, with every choice the environment has along the way.
//!
//! A step: find the next running machine in manifest order from `turn` (passing the end starts
//! a new round: machines started during the last one may now ring); if its state was just
//! entered, run OnEntry; take the **snapshot**: the time tests of the state that are not yet
//! due may come due (constant ones in order of duration), and a free type that OnEntry read or
//! posted may change (the world may move between OnEntry and the snapshot); remember what the
//! properties' `saw()` read; try the transitions in priority order (labels a reasoner answers
//! are its answers on the snapshot's inputs, whiteboard values read from here on are the
//! snapshot's with the machine's own later postings on top, variables are live); on the first that holds run OnExit and make the target
//! current, else run Internal. Finally the environment sets every free type to any value of
//! its domain: that is what the next snapshot, of whichever machine, will see, and what a
//! property speaking of the world now sees after this step.
//!
//! Control postings (`Name: On`, `suspend("Name")`) act when the posting ringlet ends, in the
//! order posted, as the runner obeys them between ringlets: `NameIsRunning` read later in the
//! same ringlet is still the old mode (a machine started this round rings from the next). `reload` and `reread`
//! change nothing: files do not change while a behaviour is verified. Host functions, `say`,
//! `print` and the sleeps have no effect on what machines read, and are skipped.

use crate::arith::{self, convert, text};
use crate::model::{Model, Name, SlotId, SlotKind};
use crate::reasoner::{input, Input};
use crate::values::{ValueId, NEVER};
use crate::world::{Control, Status, World};
use proclaim_board::Value;
use proclaim_fsm::control::Command;
use proclaim_fsm::{Action, Expr, Statement, TIME_TESTS};
use proclaim_runner::{Evaluate, LOOP_LIMIT};

/// Which of the environment's options a step took: the snapshot's (time tests, types OnEntry
/// touched) and the one after the ringlet (every free type). Replaying a step with its choice
/// gives the same successor.
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
    /// Free types set between OnEntry and the snapshot.
    pub at_snapshot: Vec<(SlotId, ValueId)>,
    /// Free types that changed after the ringlet.
    pub environment: Vec<(SlotId, ValueId)>,
}

pub struct Successor {
    pub world: World,
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
/// says), variables at zero, every free type at each value of its initial domain.
pub fn initial_worlds(model: &Model) -> Vec<World> {
    let base = World {
        turn: 0,
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
            })
            .collect(),
        values: {
            let mut values = model.values.borrow_mut();
            model
                .slots
                .iter()
                .map(|s| values.intern_option(s.initial.as_ref()))
                .collect()
        },
        saw: vec![NEVER; model.saw.len()],
    };
    let free: Vec<(SlotId, Vec<ValueId>)> = {
        let mut values = model.values.borrow_mut();
        model
            .free_slots()
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
    (0..count)
        .map(|mut index| {
            let mut w = base.clone();
            for (slot, domain) in &free {
                let n = domain.len() as u64;
                w.values[*slot] = domain[(index % n) as usize];
                index /= n;
            }
            w
        })
        .collect()
}

/// The steps of the model.
pub struct Stepper<'m> {
    model: &'m Model,
    /// Free slots and their domains as value numbers.
    free: Vec<(SlotId, Vec<ValueId>)>,
}

impl<'m> Stepper<'m> {
    pub fn new(model: &'m Model) -> Stepper<'m> {
        let mut values = model.values.borrow_mut();
        let free = model
            .free_slots()
            .map(|(slot, d)| (slot, d.values.iter().map(|v| values.intern(v)).collect()))
            .collect();
        Stepper { model, free }
    }

    fn domain(&self, slot: SlotId) -> &[ValueId] {
        self.free
            .iter()
            .find(|(s, _)| *s == slot)
            .map_or(&[], |(_, d)| d.as_slice())
    }

    /// The machine that rings next from `world` and the world as it is when it starts (a new
    /// round clears "started this round"); `None` when no machine can ring any more.
    fn next_machine(&self, world: &World) -> Option<(usize, World, bool)> {
        let n = self.model.machines.len();
        let mut w = world.clone();
        let mut k = usize::from(w.turn);
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
    fn can_ring(&self, w: &World, k: usize) -> bool {
        let c = &w.machines[k];
        c.status == Status::Running
            && !c.fresh
            && (c.just_entered || !self.model.machines[k].states[usize::from(c.state)].is_final())
    }

    /// Every successor of `world`, with what the environment did when `detail` is asked for:
    /// the ringing machine's OnEntry, then for every snapshot it may take (the free types its
    /// OnEntry touched at each value, the state's timers at each mask that can be due) the rest
    /// of its ringlet, then every move of the environment.
    pub fn successors(&self, world: &World, detail: bool, out: &mut Vec<Successor>) {
        let Some((k, start, wrapped)) = self.next_machine(world) else {
            return;
        };
        let machine = &self.model.machines[k];
        let from = usize::from(start.machines[k].state);
        let (entered, touched, deferred) = self.on_entry(start, k);

        let tests = &machine.states[from].time_tests;
        let masks = time_masks(tests, entered.machines[k].time);
        let touched_domains: Vec<&[ValueId]> = touched.iter().map(|s| self.domain(*s)).collect();
        let snapshot_count = masks.len() as u64
            * touched_domains
                .iter()
                .map(|d| d.len() as u64)
                .product::<u64>();

        for snapshot_choice in 0..snapshot_count {
            let mut w = entered.clone();
            let mut index = snapshot_choice;
            let mask = masks[(index % masks.len() as u64) as usize];
            index /= masks.len() as u64;
            let old_mask = w.machines[k].time;
            w.machines[k].time = mask;
            let mut at_snapshot = Vec::new();
            for (slot, domain) in touched.iter().zip(&touched_domains) {
                let n = domain.len() as u64;
                let v = rotated(domain, w.values[*slot], (index % n) as usize);
                index /= n;
                if detail {
                    at_snapshot.push((*slot, v));
                }
                w.values[*slot] = v;
            }
            let fired = self.rest_of_ringlet(&mut w, k, deferred.clone());
            let ringlet = Ringlet {
                machine: k,
                wrapped,
                from,
                fired,
                snapshot_choice,
                timers: if detail {
                    (0..tests.len())
                        .filter(|i| mask & !old_mask & (1 << i) != 0)
                        .collect()
                } else {
                    Vec::new()
                },
                at_snapshot,
            };
            self.environment_moves(&w, &ringlet, detail, out);
        }
    }

    /// Machine `k`'s OnEntry, where it has just entered its state: the world after it, the free
    /// types it read or posted (sorted), and the commands it posted (to which machine).
    fn on_entry(&self, start: World, k: usize) -> (World, Vec<SlotId>, Vec<(usize, Command)>) {
        let mut entered = start;
        let mut touched: Vec<SlotId> = Vec::new();
        let mut deferred = Vec::new();
        if entered.machines[k].just_entered {
            let state =
                &self.model.machines[k].machine.states[usize::from(entered.machines[k].state)];
            let mut exec = Exec {
                model: self.model,
                world: &mut entered,
                machine: k,
                snapshot: None,
                touched: Some(Vec::new()),
                deferred: Vec::new(),
            };
            exec.run(&state.on_entry);
            touched = exec.touched.take().unwrap_or_default();
            deferred = std::mem::take(&mut exec.deferred);
            entered.machines[k].just_entered = false;
        }
        touched.retain(|s| self.model.slots[*s].free.is_some());
        touched.sort_unstable();
        touched.dedup();
        (entered, touched, deferred)
    }

    /// The rest of machine `k`'s ringlet on its snapshot `w`: what it `saw`, the first
    /// transition whose label holds (then OnExit and the move) or else Internal, then the
    /// commands it posted, obeyed as the ringlet ends. Returns the transition that fired.
    fn rest_of_ringlet(
        &self,
        w: &mut World,
        k: usize,
        deferred: Vec<(usize, Command)>,
    ) -> Option<usize> {
        let machine = &self.model.machines[k];
        let from = usize::from(w.machines[k].state);
        let state = &machine.machine.states[from];
        let snapshot: Vec<ValueId> = w.values.clone();
        let mut exec = Exec {
            model: self.model,
            world: w,
            machine: k,
            snapshot: Some(snapshot),
            touched: None,
            deferred,
        };
        for (j, (m, e)) in self.model.saw.iter().enumerate() {
            if *m == k {
                let v = exec.value(e);
                let id = self.model.values.borrow_mut().intern_option(v.as_ref());
                exec.world.saw[j] = id;
            }
        }
        let fired = machine.states[from]
            .transitions
            .iter()
            .position(|t| exec.truth(&t.label));
        match fired {
            Some(t) => {
                exec.run(&state.on_exit);
                let c = &mut exec.world.machines[k];
                c.state = machine.states[from].transitions[t].target as u16;
                c.just_entered = true;
                c.time = 0;
            }
            None => exec.run(&state.internal),
        }
        for (target, command) in std::mem::take(&mut exec.deferred) {
            control(self.model, exec.world, target, command);
        }
        w.turn = (k + 1) as u8;
        fired
    }

    /// After a ringlet ending in `w`, one successor for every value each free type may take.
    fn environment_moves(
        &self,
        w: &World,
        ringlet: &Ringlet,
        detail: bool,
        out: &mut Vec<Successor>,
    ) {
        let environment_count: u64 = self.free.iter().map(|(_, d)| d.len() as u64).product();
        for environment_choice in 0..environment_count {
            let mut next = w.clone();
            let mut index = environment_choice;
            let mut changed = Vec::new();
            for (slot, domain) in &self.free {
                let n = domain.len() as u64;
                let v = rotated(domain, w.values[*slot], (index % n) as usize);
                index /= n;
                if detail && next.values[*slot] != v {
                    changed.push((*slot, v));
                }
                next.values[*slot] = v;
            }
            out.push(Successor {
                world: next,
                choice: Choice {
                    snapshot: ringlet.snapshot_choice,
                    environment: environment_choice,
                },
                machine: ringlet.machine,
                wrapped: ringlet.wrapped,
                from: ringlet.from,
                fired: ringlet.fired,
                detail: detail.then(|| Detail {
                    timers: ringlet.timers.clone(),
                    at_snapshot: ringlet.at_snapshot.clone(),
                    environment: changed,
                }),
            });
        }
    }
}

/// One ringlet as its successors share it: which machine rang from which state, on which
/// snapshot, and what fired.
struct Ringlet {
    machine: usize,
    wrapped: bool,
    from: usize,
    fired: Option<usize>,
    snapshot_choice: u64,
    /// With detail only: the time tests that came due.
    timers: Vec<usize>,
    /// With detail only: the values the free types had at the snapshot.
    at_snapshot: Vec<(SlotId, ValueId)>,
}

/// The `i`-th value of `domain` counted from `current` (when it is in the domain), so that
/// choice 0 leaves the value as it is: among paths of one length, the search meets first the
/// one in which the world changes least, and counterexamples say only what matters.
fn rotated(domain: &[ValueId], current: ValueId, i: usize) -> ValueId {
    let start = domain.iter().position(|&v| v == current).unwrap_or(0);
    domain[(start + i) % domain.len()]
}

/// The time bits a state's tests may have at a snapshot, given those already due: a due test
/// stays due, and constant tests (first in the list, shortest first) come due in order.
pub(crate) fn time_masks(tests: &[crate::model::TimeTest], due: u16) -> Vec<u16> {
    let n = tests.len();
    let constant = tests.iter().take_while(|t| t.micros.is_some()).count();
    let all = (1u32 << n) - 1;
    (0..=all)
        .map(|m| m as u16)
        .filter(|m| m & due == due)
        .filter(|m| {
            let prefix = m & ((1u32 << constant) - 1) as u16;
            prefix & (prefix.wrapping_add(1)) == 0
        })
        .collect()
}

/// Applies a control command to machine `k` as gufsm's `SuspensibleMachine` (and the runner)
/// does; a machine that starts is "fresh": it rings from the next round on.
fn control(model: &Model, world: &mut World, k: usize, command: Command) {
    let initial = model.machines[k].initial as u16;
    let c = &mut world.machines[k];
    match (command, c.status) {
        (Command::On | Command::Resume, Status::Running) => {}
        (Command::Restart, _) | (Command::On | Command::Resume, Status::Dormant) => {
            *c = Control {
                state: initial,
                status: Status::Running,
                just_entered: true,
                fresh: true,
                time: 0,
            };
        }
        (Command::On | Command::Resume, Status::Suspended) => {
            c.status = Status::Running;
            c.just_entered = true;
            c.fresh = true;
            c.time = 0;
        }
        (Command::Suspend, Status::Running) => c.status = Status::Suspended,
        (Command::Suspend, _) => {}
        (Command::Off, _) => c.status = Status::Dormant,
        (Command::Reload | Command::Reread, _) => {}
    }
}

/// Runs activities and evaluates expressions for machine `machine` over a world.
struct Exec<'a> {
    model: &'a Model,
    world: &'a mut World,
    machine: usize,
    /// Whiteboard values as the snapshot took them (from the snapshot to the ringlet's end).
    snapshot: Option<Vec<ValueId>>,
    /// While OnEntry runs: the whiteboard types it reads or posts.
    touched: Option<Vec<SlotId>>,
    /// Commands posted (target machine, command), obeyed when the ringlet ends.
    deferred: Vec<(usize, Command)>,
}

/// The runner's walk over an expression, on the model: names resolve to slots and answers, a
/// time test is due where the step's choice made it so.
impl Evaluate for Exec<'_> {
    fn read(&mut self, name: &str) -> Option<Value> {
        let resolved = self.model.resolve(Some(self.machine), name)?;
        self.name_value(resolved)
    }

    fn call(&mut self, function: &str, arguments: &[Expr]) -> Option<Value> {
        if TIME_TESTS.iter().any(|(f, _)| *f == function) {
            return Some(Value::Bool(self.time_due(function, arguments)));
        }
        let args: Vec<Option<Value>> = arguments.iter().map(|a| self.value(a)).collect();
        arith::function(function, &args)
    }
}

impl Exec<'_> {
    fn is_message(&self, slot: SlotId) -> bool {
        matches!(self.model.slots[slot].kind, SlotKind::Message { .. })
    }

    fn slot_value(&mut self, slot: SlotId) -> Option<Value> {
        let message = self.is_message(slot);
        if message {
            if let Some(t) = &mut self.touched {
                t.push(slot);
            }
        }
        let id = match (&self.snapshot, message) {
            (Some(snapshot), true) => snapshot[slot],
            _ => self.world.values[slot],
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
            Name::Running(m) => Some(Value::Bool(
                self.world.machines[m].status == Status::Running,
            )),
        }
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
        t.reasoner.borrow_mut().answers(&inputs)[output]
    }

    /// Whether a time test of the current state is due; a time test that no label of the
    /// state has (one in an activity) is never due.
    fn time_due(&self, function: &str, arguments: &[Expr]) -> bool {
        let c = &self.world.machines[self.machine];
        let state = &self.model.machines[self.machine].states[usize::from(c.state)];
        let this_call = |call: &Expr| matches!(call, Expr::Call { function: f, arguments: a } if f == function && a == arguments);
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
                Action::Statement(s) => self.exec(s),
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
        if let Some(Name::Slot(slot)) = self.model.names.get(ty) {
            if self.is_message(*slot) {
                if let Some(t) = &mut self.touched {
                    t.push(*slot);
                }
                let id = self.model.values.borrow_mut().intern(&value);
                self.world.values[*slot] = id;
                // A machine reads back what it posted itself after its snapshot, as the
                // runner's `seen.rs` does.
                if let Some(snapshot) = &mut self.snapshot {
                    snapshot[*slot] = id;
                }
            }
        }
    }

    /// Assigns as gufsm did: the machine's own variable, else an extern (posted), else a
    /// global.
    fn assign(&mut self, name: &str, value: Value) {
        match self.model.resolve(Some(self.machine), name) {
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

    fn exec(&mut self, statement: &Statement) {
        match statement {
            Statement::Declare {
                name,
                value: Some(value),
                ..
            }
            | Statement::Assign { name, value } => {
                let v = self.value(value).unwrap_or(Value::Int(0));
                self.assign(name, v);
            }
            Statement::Declare { value: None, .. } | Statement::Extern { .. } => {}
            Statement::Expr(Expr::Call {
                function,
                arguments,
            }) => self.call(function, arguments),
            Statement::Expr(other) => {
                self.value(other);
            }
            Statement::Block(body) => body.iter().for_each(|s| self.exec(s)),
            Statement::For {
                init,
                condition,
                step,
                body,
            } => {
                if let Some(init) = init {
                    self.exec(init);
                }
                let mut rounds = 0;
                while condition.as_ref().is_none_or(|c| self.truth(c)) && rounds < LOOP_LIMIT {
                    rounds += 1;
                    self.exec(body);
                    if let Some(step) = step {
                        self.exec(step);
                    }
                }
            }
        }
    }

    fn text_of(&mut self, e: &Expr) -> String {
        text(&self.value(e).unwrap_or(Value::Int(0)))
    }

    /// A call standing as a statement: the runner's built-ins that post; everything else
    /// (printing, sleeping, host functions) changes nothing a machine reads.
    fn call(&mut self, function: &str, arguments: &[Expr]) {
        match (function, arguments.len()) {
            ("post", 2) => {
                let ty = self.text_of(&arguments[0]);
                let v = self.value(&arguments[1]).unwrap_or(Value::Int(0));
                self.post(&ty, v);
            }
            ("post", 3) => {
                let ty = self.text_of(&arguments[0]);
                let parts: Vec<String> = arguments[1..]
                    .iter()
                    .map(|a| self.text_of(a))
                    .filter(|t| !t.is_empty())
                    .collect();
                self.post(&ty, Value::Str(parts.join(" ")));
            }
            ("post_int", 2) => {
                let ty = self.text_of(&arguments[0]);
                let v = match self.value(&arguments[1]).unwrap_or(Value::Int(0)) {
                    Value::Int(i) => Value::Int(i),
                    other => Value::Int(other.as_f64().unwrap_or(0.0) as i64),
                };
                self.post(&ty, v);
            }
            ("postv" | "post_v", n) if n >= 2 => {
                let ty = self.text_of(&arguments[0]);
                let values = arguments[1..]
                    .iter()
                    .map(|a| self.value(a).unwrap_or(Value::Int(0)))
                    .collect();
                self.post(&ty, Value::List(values));
            }
            (f, 1) if Command::from_function(f).is_some() => {
                let ty = self.text_of(&arguments[0]);
                let command = Command::from_function(f).unwrap_or(Command::On);
                self.post(&ty, Value::Str(command.word().into()));
            }
            ("say", 1) => {
                let t = self.text_of(&arguments[0]);
                self.post("Say", Value::Str(t));
            }
            ("speech", 1) => {
                let t = self.text_of(&arguments[0]);
                self.post("Speech", Value::Str(t));
            }
            _ => {
                // Arguments are still evaluated: they may read (and so touch) free types.
                for a in arguments {
                    self.value(a);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::TimeTest;

    fn tests(micros: &[Option<u64>]) -> Vec<TimeTest> {
        micros
            .iter()
            .map(|&m| TimeTest {
                call: Expr::Call {
                    function: "timeout".into(),
                    arguments: vec![],
                },
                micros: m,
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
}
