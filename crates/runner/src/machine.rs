//! One machine running on the whiteboard.

use crate::event::Event;
use crate::host::Hosts;
use crate::label::{dependencies, prove, value, Context};
use proclaim_board::{Kind, ModuleDecl, Pattern, Value, Whiteboard};
use proclaim_fsm::{Action, Argument, Label, Machine, StateId};
use rustc_hash::FxHashSet;
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
}

impl Default for RunOptions {
    fn default() -> RunOptions {
        RunOptions {
            ring_period: Duration::from_millis(100),
            answer_timeout: Duration::from_secs(1),
            start_running: true,
        }
    }
}

pub struct MachineRunner {
    machine: Machine,
    hosts: Hosts,
    options: RunOptions,
    events: Option<mpsc::UnboundedSender<Event>>,
}

impl MachineRunner {
    pub fn new(machine: Machine, hosts: Hosts, options: RunOptions) -> MachineRunner {
        MachineRunner {
            machine,
            hosts,
            options,
            events: None,
        }
    }

    /// The events of this machine from now on.
    pub fn events(&mut self) -> mpsc::UnboundedReceiver<Event> {
        let (tx, rx) = mpsc::unbounded_channel();
        self.events = Some(tx);
        rx
    }

    /// What it posts, reads and waits on, for the registry.
    pub fn declaration(&self) -> ModuleDecl {
        let m = &self.machine;
        let mut posts: Vec<String> = vec![format!("{}IsRunning", m.name)];
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
        let mut reads: Vec<String> = vec![m.name.clone()];
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
        ModuleDecl::new(&m.name)
            .posts(posts)
            .reads(reads)
            .waits_on(waits)
    }

    fn emit(&self, event: Event) {
        if let Some(tx) = &self.events {
            let _ = tx.send(event);
        }
    }

    /// Runs until the whiteboard is gone (forever, in practice: abort the task to stop it).
    pub async fn run(self, board: Whiteboard) {
        let span = tracing::info_span!("machine", name = %self.machine.name);
        tracing::Instrument::instrument(self.serve(board), span).await
    }

    async fn serve(self, board: Whiteboard) {
        let name = self.machine.name.clone();
        board.declare(&name, Kind::Signal);
        board.register(self.declaration());
        let start = Instant::now();
        let mut running = self.options.start_running;
        let mut current = self.machine.initial;
        let mut just_entered = true;
        let mut entered_at = Instant::now();
        let mut unknown: FxHashSet<String> = FxHashSet::default();
        let running_type = format!("{name}IsRunning");
        board.post(&name, &running_type, running);
        let mut watch = self.subscribe(&board, current);
        let mut watched = current;
        // A command taken while dormant, applied on the next turn of the loop.
        let mut woken_by: Option<proclaim_board::Message> = None;
        loop {
            // Control commands: consumed here, in order.
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
                let was = running;
                match command.as_str() {
                    "On" | "on" | "restart" => {
                        running = true;
                        current = self.machine.initial;
                        just_entered = true;
                    }
                    "Off" | "off" | "suspend" => running = false,
                    "resume" => running = true,
                    other => {
                        tracing::warn!(machine = %name, command = other, "unknown control command")
                    }
                }
                if running != was {
                    board.post(&name, &running_type, running);
                }
            }
            if !running {
                // Dormant: only a control command wakes the machine.
                woken_by = board.wait_for(&name, 0, Duration::from_secs(3600)).await;
                continue;
            }
            if just_entered {
                just_entered = false;
                entered_at = Instant::now();
                if watched != current {
                    watch = self.subscribe(&board, current);
                    watched = current;
                }
                let Some(state) = self.machine.state(current) else {
                    return;
                };
                self.emit(Event::Entered {
                    machine: name.clone(),
                    state: state.name.clone(),
                    id: current,
                    at: start.elapsed(),
                });
                self.act(&board, &state.on_entry.clone(), &mut unknown)
                    .await;
            }
            let mut fired = None;
            for t in self.machine.outgoing(current) {
                let mut answered = Vec::new();
                let mut cx = Context {
                    board: &board,
                    module: &name,
                    in_state: entered_at.elapsed(),
                    answer_timeout: self.options.answer_timeout,
                    answered: &mut answered,
                };
                let proved = prove(&t.label, &mut cx).await;
                for (atom, value, by) in answered {
                    self.emit(Event::Answered {
                        machine: name.clone(),
                        atom,
                        value,
                        by,
                        at: start.elapsed(),
                    });
                }
                if proved {
                    fired = Some((t.target, t.label.to_string()));
                    break;
                }
            }
            let Some(state) = self.machine.state(current) else {
                return;
            };
            match fired {
                Some((target, label)) => {
                    self.act(&board, &state.on_exit, &mut unknown).await;
                    self.emit(Event::Fired {
                        machine: name.clone(),
                        from: current,
                        to: target,
                        label,
                        at: start.elapsed(),
                    });
                    current = target;
                    just_entered = true;
                }
                None => {
                    self.act(&board, &state.internal.clone(), &mut unknown)
                        .await;
                    // Answers to this ring's own queries are not news.
                    while watch.try_next().is_some() {}
                    let wait = self
                        .until_next_timeout(&board, current, entered_at)
                        .min(self.options.ring_period);
                    let _ = tokio::time::timeout(wait, watch.next()).await;
                }
            }
        }
    }

    /// Messages a label of `state` depends on, and the machine's own control type.
    fn subscribe(&self, board: &Whiteboard, state: StateId) -> proclaim_board::Subscription {
        let mut types = vec![self.machine.name.clone()];
        for t in self.machine.outgoing(state) {
            dependencies(&t.label, &mut types);
        }
        board.subscribe_pattern(Pattern::Any(types))
    }

    /// How long until a `timeout()` label of the state comes due (long when none).
    fn until_next_timeout(
        &self,
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
        for t in self.machine.outgoing(state) {
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

    async fn act(&self, board: &Whiteboard, actions: &[Action], unknown: &mut FxHashSet<String>) {
        for action in actions {
            match action {
                Action::Post { ty, content } => {
                    board.post(&self.machine.name, ty, Value::parse(content));
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
                                tracing::warn!(machine = %self.machine.name, function = %function, "host function not registered; skipped");
                                self.emit(Event::UnknownFunction {
                                    machine: self.machine.name.clone(),
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
