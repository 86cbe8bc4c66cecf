//! One machine running on the whiteboard: its rings, its control commands, its reloads.

use crate::event::{Answerer, Event};
use crate::host::Hosts;
use crate::label::{dependencies, prove, value, Context};
use crate::step::Stepper;
use proclaim_board::{Kind, ModuleDecl, Pattern, Value, Whiteboard};
use proclaim_fsm::{Action, Argument, Label, Machine, StateId};
use rustc_hash::FxHashSet;
use std::sync::Arc;
use std::time::Duration;
use tokio::sync::mpsc;
use tokio::time::Instant;

#[derive(Clone, Debug)]
pub struct RunOptions {
    /// The longest wait between rings when no message a label depends on arrives.
    pub ring_period: Duration,
    /// How long a label waits for its expert before it counts as false.
    pub answer_timeout: Duration,
    /// Running from the start (a top-level machine), or dormant until `Name: On`.
    pub start_running: bool,
    /// Stop the machine for good when an expert fails to answer in time, instead of counting the
    /// label false (for tests and bring-up, where a silent expert is a bug).
    pub halt_on_timeout: bool,
    /// Ring only when stepped (model simulation); between rings, wait for the next step instead
    /// of a message or the ring period.
    pub stepper: Option<Stepper>,
}

impl Default for RunOptions {
    fn default() -> RunOptions {
        RunOptions {
            ring_period: Duration::from_millis(100),
            answer_timeout: Duration::from_secs(1),
            start_running: true,
            halt_on_timeout: false,
            stepper: None,
        }
    }
}

/// Reads the machine's file again, for `reload` and `reread`: the new machine, or why not.
pub type Loader = Arc<dyn Fn() -> Result<Machine, String> + Send + Sync>;

pub struct MachineRunner {
    machine: Machine,
    hosts: Hosts,
    options: RunOptions,
    loader: Option<Loader>,
    events: Option<mpsc::UnboundedSender<Event>>,
}

/// Where a running machine is.
struct Position {
    running: bool,
    current: StateId,
    just_entered: bool,
    entered_at: Instant,
}

impl MachineRunner {
    pub fn new(machine: Machine, hosts: Hosts, options: RunOptions) -> MachineRunner {
        MachineRunner {
            machine,
            hosts,
            options,
            loader: None,
            events: None,
        }
    }

    /// How to read the machine again when `Name: reload` or `Name: reread` is posted.
    pub fn with_loader(mut self, loader: Loader) -> MachineRunner {
        self.loader = Some(loader);
        self
    }

    /// The events of this machine from now on.
    pub fn events(&mut self) -> mpsc::UnboundedReceiver<Event> {
        let (tx, rx) = mpsc::unbounded_channel();
        self.events = Some(tx);
        rx
    }

    /// Sends this machine's events into a channel shared with others (a behaviour's trace).
    pub fn events_into(&mut self, sender: mpsc::UnboundedSender<Event>) {
        self.events = Some(sender);
    }

    /// What it posts, reads and waits on, for the registry.
    pub fn declaration(&self) -> ModuleDecl {
        declaration(&self.machine, &self.machine.name)
    }

    fn emit(&self, event: Event) {
        if let Some(tx) = &self.events {
            let _ = tx.send(event);
        }
    }

    /// Runs until the whiteboard is gone or the machine halts (abort the task to stop it).
    pub async fn run(self, board: Whiteboard) {
        let span = tracing::info_span!("machine", name = %self.machine.name);
        tracing::Instrument::instrument(self.serve(board), span).await
    }

    async fn serve(self, board: Whiteboard) {
        // The name it answers to stays the one it started with, whatever a reload says.
        let name = self.machine.name.clone();
        let mut machine = self.machine.clone();
        board.declare(&name, Kind::Signal);
        board.register(self.declaration());
        let start = Instant::now();
        let mut at = Position {
            running: self.options.start_running,
            current: machine.initial,
            just_entered: true,
            entered_at: Instant::now(),
        };
        let mut unknown: FxHashSet<String> = FxHashSet::default();
        let running_type = format!("{name}IsRunning");
        board.post(&name, &running_type, at.running);
        let mut watch = subscribe(&machine, &name, &board, at.current);
        let mut watched = Some(at.current);
        // A command taken while dormant, applied on the next turn of the loop.
        let mut woken_by: Option<proclaim_board::Message> = None;
        let mut last_step = 0;
        loop {
            // Control commands: consumed here, between rings, in order.
            while let Some(command) = woken_by.take().or_else(|| board.latest(&name)) {
                let command = match &command.value {
                    Value::Str(s) => s.clone(),
                    other => other.to_string(),
                };
                self.emit(Event::Control {
                    machine: name.clone(),
                    command: command.clone(),
                    at: start.elapsed(),
                });
                let was = at.running;
                match command.as_str() {
                    "On" | "on" | "restart" => {
                        at.running = true;
                        at.current = machine.initial;
                        at.just_entered = true;
                    }
                    "Off" | "off" | "suspend" => at.running = false,
                    "resume" => at.running = true,
                    "reload" | "reread" => {
                        if self.reload(
                            &mut machine,
                            &mut at,
                            command == "reread",
                            &board,
                            &name,
                            start,
                        ) {
                            watched = None;
                        }
                    }
                    other => {
                        tracing::warn!(machine = %name, command = other, "unknown control command")
                    }
                }
                if at.running != was {
                    board.post(&name, &running_type, at.running);
                }
            }
            if !at.running {
                // Dormant: only a control command wakes the machine.
                woken_by = board.wait_for(&name, 0, Duration::from_secs(3600)).await;
                continue;
            }
            if let Some(stepper) = &self.options.stepper {
                // A command may arrive while waiting; it is applied before the ring.
                tokio::select! {
                    step = stepper.wait(last_step) => last_step = step,
                    command = board.wait_for(&name, 0, Duration::from_secs(3600)) => {
                        woken_by = command;
                        continue;
                    }
                }
            }
            if watched != Some(at.current) {
                watch = subscribe(&machine, &name, &board, at.current);
                watched = Some(at.current);
            }
            let Some(state) = machine.state(at.current) else {
                return;
            };
            if at.just_entered {
                at.just_entered = false;
                at.entered_at = Instant::now();
                self.emit(Event::Entered {
                    machine: name.clone(),
                    state: state.name.clone(),
                    id: at.current,
                    at: start.elapsed(),
                });
                self.act(&board, &name, &state.on_entry, &mut unknown, start)
                    .await;
            }
            let mut fired = None;
            for t in machine.outgoing(at.current) {
                let mut answered = Vec::new();
                let mut cx = Context {
                    board: &board,
                    module: &name,
                    in_state: at.entered_at.elapsed(),
                    answer_timeout: self.options.answer_timeout,
                    answered: &mut answered,
                };
                let proved = prove(&t.label, &mut cx).await;
                let mut silent = None;
                for (atom, value, by) in answered {
                    if by == Answerer::TimedOut && silent.is_none() {
                        silent = Some(atom.clone());
                    }
                    self.emit(Event::Answered {
                        machine: name.clone(),
                        atom,
                        value,
                        by,
                        at: start.elapsed(),
                    });
                }
                if let Some(atom) = silent.filter(|_| self.options.halt_on_timeout) {
                    self.emit(Event::Halted {
                        machine: name.clone(),
                        reason: format!(
                            "no expert answered `{atom}` within {:?} (in state {})",
                            self.options.answer_timeout, state.name
                        ),
                        at: start.elapsed(),
                    });
                    board.post(&name, &running_type, false);
                    return;
                }
                if proved {
                    fired = Some((t.target, t.label.to_string()));
                    break;
                }
            }
            match fired {
                Some((target, label)) => {
                    self.emit(Event::Fired {
                        machine: name.clone(),
                        from: at.current,
                        to: target,
                        label,
                        at: start.elapsed(),
                    });
                    self.act(&board, &name, &state.on_exit, &mut unknown, start)
                        .await;
                    at.current = target;
                    at.just_entered = true;
                    if let Some(stepper) = &self.options.stepper {
                        stepper.ring_done(&name, last_step);
                    }
                }
                None => {
                    self.act(&board, &name, &state.internal, &mut unknown, start)
                        .await;
                    if let Some(stepper) = &self.options.stepper {
                        stepper.ring_done(&name, last_step);
                        continue;
                    }
                    // Answers to this ring's own queries are not news.
                    while watch.try_next().is_some() {}
                    let wait = until_next_timeout(&machine, &board, at.current, at.entered_at)
                        .min(self.options.ring_period);
                    let _ = tokio::time::timeout(wait, watch.next()).await;
                }
            }
        }
    }

    /// Reads the machine again. `reread` keeps the current state when the new machine still
    /// has it (by name when the name is unique, else by id); otherwise the machine starts again
    /// from its initial state. A failure changes nothing. Returns whether the machine changed.
    fn reload(
        &self,
        machine: &mut Machine,
        at: &mut Position,
        keep_state: bool,
        board: &Whiteboard,
        name: &str,
        start: Instant,
    ) -> bool {
        let loaded = match &self.loader {
            Some(load) => load(),
            None => Err("the machine has no file to read again".to_string()),
        };
        let new = match loaded {
            Ok(new) => new,
            Err(error) => {
                tracing::warn!(machine = %name, %error, "reload failed; the machine runs on unchanged");
                self.emit(Event::ReloadFailed {
                    machine: name.to_string(),
                    error,
                    at: start.elapsed(),
                });
                return false;
            }
        };
        let kept = keep_state
            .then(|| machine.state(at.current))
            .flatten()
            .and_then(|old| {
                let same_name: Vec<_> = new.states.iter().filter(|s| s.name == old.name).collect();
                match same_name.as_slice() {
                    [only] => Some(only.id),
                    _ => same_name.iter().find(|s| s.id == old.id).map(|s| s.id),
                }
            });
        match kept {
            Some(id) => at.current = id,
            None => {
                at.current = new.initial;
                at.just_entered = true;
            }
        }
        *machine = new;
        board.register(declaration(machine, name));
        self.emit(Event::Reloaded {
            machine: name.to_string(),
            state: machine
                .state(at.current)
                .map_or_else(String::new, |s| s.name.clone()),
            at: start.elapsed(),
        });
        true
    }

    async fn act(
        &self,
        board: &Whiteboard,
        name: &str,
        actions: &[Action],
        unknown: &mut FxHashSet<String>,
        start: Instant,
    ) {
        for action in actions {
            match action {
                Action::Post { ty, content } => {
                    board.post(name, ty, Value::parse(content));
                    self.emit(Event::Posted {
                        machine: name.to_string(),
                        ty: ty.clone(),
                        content: content.clone(),
                        at: start.elapsed(),
                    });
                }
                Action::Call { function, argument } => match (function.as_str(), argument) {
                    ("msleep", Some(Argument::Int(ms))) => {
                        tokio::time::sleep(Duration::from_millis((*ms).max(0) as u64)).await
                    }
                    ("sleep", Some(Argument::Int(s))) => {
                        tokio::time::sleep(Duration::from_secs((*s).max(0) as u64)).await
                    }
                    _ => match self.hosts.get(function) {
                        Some(f) => f(argument.as_ref()),
                        None => {
                            if unknown.insert(function.clone()) {
                                tracing::warn!(machine = %name, function = %function, "host function not registered; skipped");
                                self.emit(Event::UnknownFunction {
                                    machine: name.to_string(),
                                    function: function.clone(),
                                });
                            }
                        }
                    },
                },
                Action::Code(_) => {}
            }
        }
    }
}

/// What a machine posts, reads and waits on, registered under `name` (its own name, unless it
/// was renamed by a reload).
pub fn declaration(m: &Machine, name: &str) -> ModuleDecl {
    let mut posts: Vec<String> = vec![format!("{name}IsRunning")];
    for s in &m.states {
        for a in s.on_entry.iter().chain(&s.on_exit).chain(&s.internal) {
            if let Action::Post { ty, .. } = a {
                if !posts.contains(ty) {
                    posts.push(ty.clone());
                }
            }
        }
    }
    let mut waits: Vec<String> = Vec::new();
    let mut reads: Vec<String> = vec![name.to_string()];
    for t in &m.transitions {
        for atom in t.label.atoms() {
            if !waits.iter().any(|w| w == atom) {
                waits.push(atom.to_string());
            }
        }
        let mut deps = Vec::new();
        dependencies(&t.label, &mut deps);
        for d in deps {
            if !waits.contains(&d) && !reads.contains(&d) {
                reads.push(d);
            }
        }
    }
    ModuleDecl::new(name)
        .posts(posts)
        .reads(reads)
        .waits_on(waits)
}

/// Messages a label of `state` depends on, and the machine's own control type.
fn subscribe(
    machine: &Machine,
    name: &str,
    board: &Whiteboard,
    state: StateId,
) -> proclaim_board::Subscription {
    let mut types = vec![name.to_string()];
    for t in machine.outgoing(state) {
        dependencies(&t.label, &mut types);
    }
    board.subscribe_pattern(Pattern::Any(types))
}

/// How long until a `timeout()` label of the state comes due (long when none).
fn until_next_timeout(
    machine: &Machine,
    board: &Whiteboard,
    state: StateId,
    entered_at: Instant,
) -> Duration {
    fn timeouts<'a>(label: &'a Label, out: &mut Vec<&'a proclaim_fsm::Operand>) {
        match label {
            Label::Timeout(t) => out.push(t),
            Label::Not(l) => timeouts(l, out),
            Label::And(ls) | Label::Or(ls) => ls.iter().for_each(|l| timeouts(l, out)),
            _ => {}
        }
    }
    let mut limits = Vec::new();
    for t in machine.outgoing(state) {
        timeouts(&t.label, &mut limits);
    }
    let elapsed = entered_at.elapsed();
    limits
        .into_iter()
        .filter_map(|l| value(board, l))
        .map(|us| Duration::from_secs_f64(us.max(0.0) / 1e6))
        .filter(|due| *due > elapsed)
        .map(|due| due - elapsed)
        .min()
        .unwrap_or(Duration::from_secs(3600))
}
