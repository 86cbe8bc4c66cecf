//! One machine running on the whiteboard: its rings, its control commands, its reloads.

use crate::activity::{ActivityContext, SharedSuppressor};
use crate::eval::{Clocks, Env};
use crate::event::{Answerer, Event, Reporter};
use crate::feed::{QueryHook, RoundCounter};
use crate::host::Hosts;
use crate::label::{dependencies, next_time_test, prove, reads_globals, Context};
use crate::seen::Seen;
use crate::step::Stepper;
use crate::variables::{Locals, Scope, Shared};
use proclaim_board::{Kind, Message, ModuleDecl, Pattern, Subscription, Value, Whiteboard};
use proclaim_fsm::control::{running_type, Command};
use proclaim_fsm::{Action, FileDiagnostic, Label, Machine, StateId};
use proclaim_lower::{Arm, Next, RingletPlan, RingletRun};
use rustc_hash::FxHashSet;
use std::sync::Arc;
use std::time::Duration;
use tokio::sync::{mpsc, watch};
use tokio::time::Instant;

#[derive(Clone)]
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
    /// The variables this machine shares with the others of its behaviour
    /// ([`Shared::for_machines`]); a machine given none shares with nobody.
    pub shared: Option<Arc<Shared>>,
    /// The moment event times count from, the same for every machine of a behaviour so that
    /// their merged trace is in time order; the machine's start when not given.
    pub epoch: Option<Instant>,
    /// The machine's subsumption layer: every posting it makes carries this priority (0, the
    /// default, is the bottom layer).
    pub priority: u32,
    /// The behaviour's suppressed types, shared by its machines (one per behaviour): a
    /// posting to one of them is shown or suppressed by it at the schedule's moment. What
    /// takes over when a hold runs out is posted by the round schedule ([`crate::Rounds`]);
    /// a machine on a task of its own only has its postings judged.
    pub suppressor: Option<SharedSuppressor>,
}

impl Default for RunOptions {
    fn default() -> RunOptions {
        RunOptions {
            ring_period: Duration::from_millis(100),
            answer_timeout: Duration::from_secs(1),
            start_running: true,
            halt_on_timeout: false,
            stepper: None,
            shared: None,
            epoch: None,
            priority: 0,
            suppressor: None,
        }
    }
}

/// Reads the machine's file again, for `reload` and `reread`: the new machine, or every problem
/// of the file, each at its place.
pub type Loader = Arc<dyn Fn() -> Result<Machine, Vec<FileDiagnostic>> + Send + Sync>;

pub struct MachineRunner {
    machine: Machine,
    hosts: Hosts,
    options: RunOptions,
    loader: Option<Loader>,
    events: Option<mpsc::UnboundedSender<Event>>,
}

/// Whether a machine rings: gufsm's `SuspensibleMachine` states.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Status {
    Running,
    /// Parked by `suspend`; the current state is where `resume` goes back to.
    Suspended,
    /// Not started, or stopped by `Off`: `On` starts from the initial state.
    Dormant,
}

/// What one ring did.
pub(crate) enum RingOutcome {
    Moved,
    Stayed,
    /// The machine stopped for good, or its state vanished.
    Over,
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
        let shared = self.shared();
        declaration(&self.machine, &self.machine.name, &shared)
    }

    /// The machine it runs (as it was given: a reload changes the running copy only).
    pub fn machine(&self) -> &Machine {
        &self.machine
    }

    /// The behaviour's suppressor, which the schedule asks between ringlets what takes over.
    pub(crate) fn suppressor(&self) -> Option<SharedSuppressor> {
        self.options.suppressor.clone()
    }

    pub(crate) fn shared(&self) -> Arc<Shared> {
        self.options
            .shared
            .clone()
            .unwrap_or_else(|| Shared::for_machines([&self.machine]))
    }

    /// Runs until the whiteboard is gone or the machine halts (abort the task to stop it).
    pub async fn run(self, board: Whiteboard) {
        let span = tracing::info_span!("machine", name = %self.machine.name);
        tracing::Instrument::instrument(self.serve(board), span).await
    }

    async fn serve(self, board: Whiteboard) {
        // On its own task, a machine's rounds are its own ringlets.
        let mut run = RunningMachine::new(&self, board, RoundCounter::default(), true);
        // A command taken while waiting, applied on the next turn of the loop.
        let mut woken_by: Option<Message> = None;
        loop {
            // Control commands: consumed here, between rings, in order.
            while let Some(command) = woken_by.take().or_else(|| run.board.latest(&run.name)) {
                run.control(&command);
            }
            if run.status != Status::Running || run.is_done() {
                woken_by = run
                    .board
                    .wait_for(&run.name, 0, Duration::from_secs(3600))
                    .await;
                continue;
            }
            if let Some(stepper) = &self.options.stepper {
                // A command may arrive while waiting; it is applied before the ring.
                tokio::select! {
                    step = stepper.wait(run.last_step) => run.last_step = step,
                    command = run.board.wait_for(&run.name, 0, Duration::from_secs(3600)) => {
                        woken_by = command;
                        continue;
                    }
                }
            }
            run.reporter.round.advance();
            match run.ring().await {
                RingOutcome::Over => {
                    if let Some(stepper) = &self.options.stepper {
                        stepper.note_due(&run.name, None);
                    }
                    return;
                }
                RingOutcome::Moved => {
                    if let Some(stepper) = &self.options.stepper {
                        stepper.note_due(&run.name, run.due_at());
                        stepper.ring_done(&run.name, run.last_step);
                    }
                    // A machine whose labels are all true at once (over variables, `TRUE`)
                    // would otherwise never give the other machines a turn, nor stop when told;
                    // this yields once the task has used up its share (tokio's budget).
                    tokio::task::consume_budget().await;
                }
                RingOutcome::Stayed => match &self.options.stepper {
                    Some(stepper) => {
                        stepper.note_due(&run.name, run.due_at());
                        stepper.ring_done(&run.name, run.last_step);
                        if !stepper.is_paused() {
                            run.wait_between_rings().await;
                        }
                    }
                    None => run.wait_between_rings().await,
                },
            }
        }
    }
}

/// A machine while it runs: where it is and what it holds.
pub(crate) struct RunningMachine<'r> {
    runner: &'r MachineRunner,
    pub(crate) board: Whiteboard,
    /// The name it answers to: the one it started with, whatever a reload says.
    pub(crate) name: String,
    running_type: String,
    /// Shared with the ring that runs it, so a ring borrows no copy of its state.
    pub(crate) machine: Arc<Machine>,
    pub(crate) status: Status,
    pub(crate) current: StateId,
    pub(crate) just_entered: bool,
    pub(crate) entered_at: Instant,
    /// When it entered each composite state (`Machine::composites`), which the time tests of
    /// that composite's transitions count from; `None` while a move into it has not arrived.
    pub(crate) composites_entered: Vec<Option<Instant>>,
    /// The state it last arrived in (its OnEntry run), by name: what its events last said.
    pub(crate) last_entered: Option<String>,
    /// The round's moment, while a round schedule runs one (time tests and times in state
    /// are read against it, so every machine of a round sees one time); the clock otherwise.
    pub(crate) round_time: Option<Instant>,
    pub(crate) locals: Locals,
    pub(crate) shared: Arc<Shared>,
    pub(crate) globals_changed: watch::Receiver<u64>,
    pub(crate) unknown: FxHashSet<String>,
    pub(crate) reporter: Reporter,
    /// What this ringlet reads of the board (its snapshot once OnEntry has run).
    pub(crate) seen: Seen,
    /// The atoms the last ringlet asked and their answers (an answer arriving is no news to
    /// the machine that asked for it).
    pub(crate) asked: Vec<(String, bool)>,
    /// The count of changes of globals when the last ringlet took its snapshot.
    pub(crate) globals_seen: u64,
    /// Under a feed (a replay): told before each query this ringlet asks.
    pub(crate) query_hook: Option<QueryHook>,
    /// Queries asked of experts in this ringlet so far.
    queries: usize,
    /// What the current state's labels read (messages), and whether they read globals.
    reads: Option<(StateId, Vec<String>, bool)>,
    /// On a task of its own: a subscription to what the current state's labels read.
    watch: Option<(StateId, Subscription)>,
    last_step: u64,
}

impl<'r> RunningMachine<'r> {
    /// The machine at its start, saying on the board whether it runs; a machine taken up
    /// from a checkpoint (`announce` false) finds that on the board already.
    pub(crate) fn new(
        runner: &'r MachineRunner,
        board: Whiteboard,
        round: RoundCounter,
        announce: bool,
    ) -> RunningMachine<'r> {
        let name = runner.machine.name.clone();
        let shared = runner.shared();
        board.declare(&name, Kind::Signal);
        board.register(declaration(&runner.machine, &name, &shared));
        let status = if runner.options.start_running {
            Status::Running
        } else {
            Status::Dormant
        };
        let running_type = running_type(&name);
        if announce {
            board.post(&name, &running_type, status == Status::Running);
        }
        RunningMachine {
            runner,
            name,
            running_type,
            machine: Arc::new(runner.machine.clone()),
            status,
            current: runner.machine.initial,
            just_entered: true,
            entered_at: Instant::now(),
            composites_entered: vec![None; runner.machine.composites.len()],
            last_entered: None,
            round_time: None,
            locals: Locals::declared(&runner.machine),
            globals_changed: shared.changes(),
            shared,
            unknown: FxHashSet::default(),
            reporter: Reporter {
                sender: runner.events.clone(),
                epoch: runner.options.epoch.unwrap_or_else(Instant::now),
                round,
            },
            seen: Seen::default(),
            asked: Vec::new(),
            globals_seen: 0,
            query_hook: None,
            queries: 0,
            reads: None,
            watch: None,
            last_step: 0,
            board,
        }
    }

    /// What a label reads: each time test counts on its own clock.
    fn env(&self) -> Env<'_> {
        Env {
            board: &self.board,
            seen: &self.seen,
            locals: &self.locals,
            shared: &self.shared,
            clocks: self.clocks(),
        }
    }

    /// Its state's arrival and its composites' entries (a composite entered with its state
    /// when the move into it has not arrived yet).
    fn clocks(&self) -> Clocks<'_> {
        Clocks {
            now: self.now(),
            entered_at: self.entered_at,
            composites: &self.composites_entered,
        }
    }

    /// Now, as the machine's time tests read it.
    fn now(&self) -> Instant {
        self.round_time.unwrap_or_else(Instant::now)
    }

    /// Obeys one control command; whether it started the machine anew (from dormant, from
    /// suspended, or again from its initial state).
    pub(crate) fn control(&mut self, message: &Message) -> bool {
        let word = match &message.value {
            Value::Str(s) => s.clone(),
            other => other.to_string(),
        };
        self.reporter.emit(|at, round| Event::Control {
            machine: self.name.clone(),
            command: word.clone(),
            at,
            round,
        });
        let Some(command) = Command::parse(&word) else {
            tracing::warn!(machine = %self.name, command = %word, "unknown control command");
            return false;
        };
        let was = self.status;
        let mut started = false;
        match (command, self.status) {
            (Command::On | Command::Resume, Status::Running) => {}
            (Command::Restart, _) | (Command::On | Command::Resume, Status::Dormant) => {
                self.status = Status::Running;
                self.current = self.machine.initial;
                self.just_entered = true;
                started = true;
            }
            // Back into the state it left, as a transition would enter it.
            (Command::On | Command::Resume, Status::Suspended) => {
                self.status = Status::Running;
                self.just_entered = true;
                started = true;
            }
            (Command::Suspend, Status::Running) => self.status = Status::Suspended,
            (Command::Suspend, _) => {}
            (Command::Off, _) => self.status = Status::Dormant,
            (Command::Reload | Command::Reread, _) => {
                self.reload(command == Command::Reread);
            }
        }
        if started {
            // Into its state as from outside: every composite around it is entered again.
            self.composites_entered.fill(None);
        }
        if (was == Status::Running) != (self.status == Status::Running) {
            self.board.post(
                &self.name,
                &self.running_type,
                self.status == Status::Running,
            );
        }
        started
    }

    /// Stops the machine for good, saying why in the trace (as `halt_on_timeout` does).
    pub(crate) fn halt(&mut self, why: &str) {
        let state = self
            .machine
            .state(self.current)
            .map_or_else(|| "?".to_string(), |s| s.name.clone());
        self.reporter.emit(|at, round| Event::Halted {
            machine: self.name.clone(),
            reason: format!("{why} (in state {state})"),
            at,
            round,
        });
        self.board.post(&self.name, &self.running_type, false);
    }

    /// Whether the machine's run is over for now: its state has no way out and its OnEntry
    /// has run (§3: it rings no more until a command moves it).
    pub(crate) fn is_done(&self) -> bool {
        !self.just_entered
            && RingletPlan::of(&self.machine, self.current).is_none_or(|plan| plan.is_final())
    }

    /// One ringlet (§3.1): OnEntry if just entered, then the snapshot, the transitions in
    /// priority order, OnExit and a move on the first proved, Internal when none was.
    pub(crate) async fn ring(&mut self) -> RingOutcome {
        let ring = self.ringlet().await;
        self.seen.release();
        ring
    }

    async fn ringlet(&mut self) -> RingOutcome {
        let machine = self.machine.clone();
        let Some(plan) = RingletPlan::of(&machine, self.current) else {
            return RingOutcome::Over;
        };
        let state = plan.state();
        // Changes of globals from here on wake the wait after this ring.
        self.globals_changed.borrow_and_update();
        let mut run = RingletRun::new(plan, self.just_entered);
        loop {
            match run.next_step() {
                Next::Arrive(actions) => self.arrive(&plan, actions).await,
                Next::Snapshot => {
                    self.seen.take();
                    self.globals_seen = *self.globals_changed.borrow();
                    self.asked.clear();
                    self.queries = 0;
                }
                Next::Try(arm) => match self.prove(arm, &state.name).await {
                    Some(proved) => run.proved(proved),
                    None => return RingOutcome::Over,
                },
                Next::Leave(arm) => self.leave(arm, &state.name).await,
                Next::Stay(actions) => self.act(&state.name, actions).await,
                Next::Done(Some(_)) => return RingOutcome::Moved,
                Next::Done(None) => return RingOutcome::Stayed,
            }
        }
    }

    /// Whether `arm`'s label is proved; `None` when the machine halts because no expert
    /// answered in time (and was asked to halt then).
    async fn prove(&mut self, arm: Arm<'_>, state: &str) -> Option<bool> {
        let mut answered = Vec::new();
        let proved = {
            let mut cx = Context {
                env: Env {
                    board: &self.board,
                    seen: &self.seen,
                    locals: &self.locals,
                    shared: &self.shared,
                    clocks: Clocks {
                        now: self.round_time.unwrap_or_else(Instant::now),
                        entered_at: self.entered_at,
                        composites: &self.composites_entered,
                    },
                },
                module: &self.name,
                answer_timeout: self.runner.options.answer_timeout,
                answered: &mut answered,
                hook: self.query_hook.as_ref(),
                queries: &mut self.queries,
            };
            prove(arm.label(), &mut cx).await
        };
        let Some(atom) = self.report_answers(answered) else {
            return Some(proved);
        };
        self.reporter.emit(|at, round| Event::Halted {
            machine: self.name.clone(),
            reason: format!(
                "no expert answered `{atom}` within {:?} (in state {state})",
                self.runner.options.answer_timeout
            ),
            at,
            round,
        });
        self.board.post(&self.name, &self.running_type, false);
        None
    }

    /// `arm` fired: the event, what it runs leaving, and the move to its target (none for one
    /// that stays).
    async fn leave(&mut self, arm: Arm<'_>, state: &str) {
        let (from, to) = (self.current, arm.target());
        let label = arm.transition.shown().to_string();
        tracing::debug!(from = %state, to, %label, "transition fired");
        self.reporter.emit(|at, round| Event::Fired {
            machine: self.name.clone(),
            from,
            to,
            label,
            at,
            round,
        });
        self.act(state, arm.leaving()).await;
        if arm.stays() {
            return;
        }
        self.current = arm.target();
        self.just_entered = true;
        for &c in &arm.transition.enters {
            if let Some(entered) = self.composites_entered.get_mut(c) {
                *entered = None;
            }
        }
    }

    /// Arriving in `plan`'s state: its arrival activities, and the end of the run for a state
    /// with no way out.
    async fn arrive(&mut self, plan: &RingletPlan<'_>, actions: &[Action]) {
        let state = plan.state();
        self.just_entered = false;
        self.entered_at = self.now();
        for entered in &mut self.composites_entered {
            entered.get_or_insert(self.entered_at);
        }
        self.last_entered = Some(state.name.clone());
        let id = self.current;
        self.reporter.emit(|at, round| Event::Entered {
            machine: self.name.clone(),
            state: state.name.clone(),
            id,
            at,
            round,
        });
        self.act(&state.name, actions).await;
        if plan.is_final() {
            self.reporter.emit(|at, round| Event::Finished {
                machine: self.name.clone(),
                state: state.name.clone(),
                at,
                round,
            });
        }
    }

    /// Reports a ring's answers; the first atom no expert answered in time, when that halts
    /// the machine.
    fn report_answers(&mut self, answered: Vec<(String, bool, Answerer)>) -> Option<String> {
        let mut silent = None;
        for (atom, value, by) in answered {
            self.asked.push((atom.clone(), value));
            if by == Answerer::TimedOut && silent.is_none() {
                silent = Some(atom.clone());
            }
            self.reporter.emit_read(|at, round| Event::Answered {
                machine: self.name.clone(),
                atom,
                value,
                by,
                at,
                round,
            });
        }
        silent.filter(|_| self.runner.options.halt_on_timeout)
    }

    async fn act(&mut self, state: &str, actions: &[Action]) {
        let now = self.now();
        ActivityContext {
            board: &self.board,
            seen: &mut self.seen,
            machine: &self.name,
            state,
            entered_at: self.entered_at,
            now,
            hosts: &self.runner.hosts,
            shared: &self.shared,
            locals: &mut self.locals,
            unknown: &mut self.unknown,
            reporter: &self.reporter,
            priority: self.runner.options.priority,
            suppressor: self.runner.options.suppressor.as_ref(),
        }
        .run(actions)
        .await
    }

    /// The current state's transitions, in the order its ringlet tries them.
    fn arms(&self) -> impl Iterator<Item = Arm<'_>> + '_ {
        RingletPlan::of(&self.machine, self.current)
            .into_iter()
            .flat_map(|plan| plan.arms())
    }

    /// What the current state's labels read: the message types (its own name among them, for
    /// control commands) and whether they read a global. Worked out once per state.
    pub(crate) fn reads(&mut self) -> (&[String], bool) {
        if self
            .reads
            .as_ref()
            .is_none_or(|(s, _, _)| *s != self.current)
        {
            let mut types = vec![self.name.clone()];
            let mut globals = false;
            let scope = Scope {
                locals: &self.locals,
                shared: &self.shared,
            };
            for arm in self.arms() {
                dependencies(arm.label(), scope, &mut types);
                globals |= reads_globals(arm.label(), scope);
            }
            self.reads = Some((self.current, types, globals));
        }
        let (_, types, globals) = self.reads.as_ref().expect("worked out above");
        (types, *globals)
    }

    /// How long until the current state's next time test comes due, at most the ring period.
    pub(crate) fn next_due(&self) -> Duration {
        let period = self.runner.options.ring_period;
        self.next_time_test().map_or(period, |due| due.min(period))
    }

    /// How long until the soonest time test of the current state's labels comes due, if one
    /// is still to come.
    pub(crate) fn next_time_test(&self) -> Option<Duration> {
        self.arms()
            .filter_map(|arm| next_time_test(arm.label(), &mut self.env()))
            .min()
    }

    /// When the current state's next time test comes due, if it runs, has arrived in its
    /// state (a move's time starts when it arrives) and one is still to come.
    pub(crate) fn due_at(&self) -> Option<Instant> {
        let running = self.status == Status::Running && !self.just_entered;
        let due = self.next_time_test().filter(|_| running)?;
        Some(self.now() + due)
    }

    /// Waits until a message a label of the state reads arrives, a global it reads changes,
    /// its next time test comes due, or the ring period passes.
    async fn wait_between_rings(&mut self) {
        if self.watch.as_ref().is_none_or(|(s, _)| *s != self.current) {
            let types = self.reads().0.to_vec();
            let subscription = self.board.subscribe_pattern(Pattern::Any(types));
            self.watch = Some((self.current, subscription));
        }
        let wait = self.next_due();
        let reads_globals = self.reads().1;
        let Some((_, watch)) = self.watch.as_mut() else {
            return;
        };
        // Answers to this ring's own queries are not news.
        while watch.try_next().is_some() {}
        let globals = &mut self.globals_changed;
        tokio::select! {
            biased;
            _ = watch.next() => {}
            _ = globals.changed(), if reads_globals => {}
            _ = tokio::time::sleep(wait) => {}
        }
    }

    /// When it entered each composite of `new`, read in place of its machine: each keeps its
    /// entry by path when the state is `kept` (started afresh, it enters them all again); one
    /// the new machine adds counts from its state's entry (from the arrival, when a move into
    /// the state has not arrived yet).
    fn composites_reloaded(&self, new: &Machine, kept: bool) -> Vec<Option<Instant>> {
        let added = (!self.just_entered).then_some(self.entered_at);
        new.composites
            .iter()
            .map(|c| {
                let old = (self.machine.composites.iter()).position(|o| o.name == c.name);
                match old.and_then(|o| self.composites_entered.get(o)) {
                    _ if !kept => None,
                    Some(entered) => *entered,
                    None => added,
                }
            })
            .collect()
    }

    /// Reads the machine again. `reread` keeps the current state when the new machine still
    /// has it (by name when the name is unique, else by id); otherwise the machine starts again
    /// from its initial state. Variables it still declares keep their values. A failure changes
    /// nothing.
    fn reload(&mut self, keep_state: bool) {
        let loaded = match &self.runner.loader {
            // The event is text, one problem a line, as the trace and the terminal show it.
            Some(load) => load().map_err(|problems| {
                problems
                    .iter()
                    .map(ToString::to_string)
                    .collect::<Vec<_>>()
                    .join("\n")
            }),
            None => Err("the machine has no file to read again".to_string()),
        };
        let new = match loaded {
            Ok(new) => new,
            Err(error) => {
                // The event reaches whoever runs the machine; a warning here would say it twice.
                tracing::debug!(machine = %self.name, %error, "reload failed; the machine runs on unchanged");
                self.reporter.emit(|at, round| Event::ReloadFailed {
                    machine: self.name.clone(),
                    error,
                    at,
                    round,
                });
                return;
            }
        };
        let kept = keep_state
            .then(|| self.machine.state(self.current))
            .flatten()
            .and_then(|old| {
                let same_name: Vec<_> = new.states.iter().filter(|s| s.name == old.name).collect();
                match same_name.as_slice() {
                    [only] => Some(only.id),
                    _ => same_name.iter().find(|s| s.id == old.id).map(|s| s.id),
                }
            });
        match kept {
            Some(id) => self.current = id,
            None => {
                self.current = new.initial;
                self.just_entered = true;
            }
        }
        self.composites_entered = self.composites_reloaded(&new, kept.is_some());
        self.shared.register(&new);
        self.locals = self.locals.reloaded(&new);
        self.machine = Arc::new(new);
        self.reads = None;
        self.watch = None;
        self.board
            .register(declaration(&self.machine, &self.name, &self.shared));
        let state = self
            .machine
            .state(self.current)
            .map_or_else(String::new, |s| s.name.clone());
        self.reporter.emit(|at, round| Event::Reloaded {
            machine: self.name.clone(),
            state,
            at,
            round,
        });
    }
}

/// What a machine posts, reads and waits on, registered under `name` (its own name, unless it
/// was renamed by a reload). Labels' conditions that are no variable are waited on (asked of
/// experts); other names they read are read.
pub fn declaration(m: &Machine, name: &str, shared: &Shared) -> ModuleDecl {
    let locals = Locals::declared(m);
    let scope = Scope {
        locals: &locals,
        shared,
    };
    let mut posts: Vec<String> = vec![running_type(name)];
    let add = |list: &mut Vec<String>, ty: &str| {
        if !list.iter().any(|t| t == ty) {
            list.push(ty.to_string());
        }
    };
    // A control word written as a statement (`restart("Dive")`) posts the machine's type too.
    for a in m.actions() {
        for (ty, _) in a.literal_postings() {
            add(&mut posts, &ty);
        }
    }
    for s in m.statements() {
        if let proclaim_fsm::Statement::Extern { name, .. } = s {
            add(&mut posts, name);
        }
        for e in s.expressions() {
            for (function, arguments) in e.calls() {
                if let (true, Some(proclaim_fsm::Expr::Str(ty))) =
                    (posting_function(function), arguments.first())
                {
                    add(&mut posts, ty);
                }
            }
        }
    }
    let mut waits: Vec<String> = Vec::new();
    let mut reads: Vec<String> = vec![name.to_string()];
    for t in &m.transitions {
        for atom in asked(&t.label, m, shared) {
            add(&mut waits, atom);
        }
        let mut deps = Vec::new();
        dependencies(&t.label, scope, &mut deps);
        for d in deps {
            if !waits.contains(&d) {
                add(&mut reads, &d);
            }
        }
    }
    ModuleDecl::new(name)
        .posts(posts)
        .reads(reads)
        .waits_on(waits)
}

/// The propositions a label of `machine` asks experts about: names standing as conditions
/// that are no variable of the machine or its behaviour.
pub fn asked<'a>(label: &'a Label, machine: &Machine, shared: &Shared) -> Vec<&'a str> {
    let locals = Locals::declared(machine);
    let scope = Scope {
        locals: &locals,
        shared,
    };
    label
        .condition_names()
        .into_iter()
        .filter(|n| !scope.is_variable(n))
        .collect()
}

/// Built-ins whose first argument is the type they post to.
fn posting_function(function: &str) -> bool {
    matches!(function, "post" | "post_int" | "postv" | "post_v")
        || Command::from_function(function).is_some()
}
