//! Starting a loaded behaviour on a whiteboard: experts and sensor wrappers first (so every
//! label has its expert before the first ring), then the machines; their events merged into one
//! trace.

use crate::branch::Branch;
use crate::checkpoint::{self, Checkpoint, CheckpointPlan, Kept};
use crate::error::BehaviourError;
use crate::load::Behaviour;
use crate::manifest::Schedule;
use crate::manifest::{SensorKind, Simulator};
use crate::replaced::Replaced;
use crate::runners::{machine_runners, Driving};
use proclaim_board::{Pattern, Whiteboard};
use proclaim_experts::{
    ButtonWrapper, FallWrapper, FunctionExpert, GameControllerReceiver, Impersonator,
    ReasonerExpert, ReceiverConfig, Script, When,
};
use proclaim_gcsim::{default_game, play, GameEvent, SimConfig};
use proclaim_lower::RingletPlan;
use proclaim_runner::{Event, Hosts, Ringlet, RoundCounter, Rounds, RoundsEnd, Shared, Stepper};
use rustc_hash::{FxHashMap, FxHashSet};
use std::future::Future;
use std::net::SocketAddr;
use std::pin::Pin;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::Duration;
use tokio::sync::mpsc;
use tokio::task::JoinSet;

#[derive(Clone, Default)]
pub struct LaunchOptions {
    /// Answer from this script instead of the manifest's impersonator. Experts give up the
    /// atoms the script names and sensor wrappers answering one are left out (`replaced.rs`),
    /// so the machines cannot tell the impersonator from them.
    pub script: Option<Script>,
    /// Never start the GameController simulator (listen for a real GameController).
    pub no_simulator: bool,
    pub halt_on_timeout: bool,
    pub hosts: Hosts,
    /// Ring only when stepped (`proclaim run --step`).
    pub stepper: Option<Stepper>,
    /// An impersonator that asks a person (`proclaim run --ask`); its atoms replace the
    /// behaviour's own, as a script's do.
    pub person: Option<Impersonator>,
    /// Report every ringlet, where and when it began, once it has run ([`Running::ringlets`]):
    /// a recording that a replay can post outside messages back into at the same places.
    pub ringlets: bool,
    /// Experts of the embedding program (a Python callable per label, say). Their atoms
    /// replace the behaviour's own, as a script's do; the script's impersonator, when it
    /// answers one of them too, is left out.
    pub experts: Vec<FunctionExpert>,
    /// End at the first still round after the script's last step (`RoundsEnd::Still`,
    /// [`Running::end`]) when nothing else can post: only theories and the script answer (no
    /// person, sensor, program or embedding expert) and the script has no `step N:` lines. For a
    /// run with no end given, alone on its board (`proclaim run` with no `--for`).
    pub end_when_still: bool,
    /// Write the run down as this says ([`Running::checkpoints`] receives each checkpoint).
    pub checkpoints: Option<CheckpointPlan>,
    /// Take the run up where this checkpoint left it.
    pub resume: Option<Arc<Checkpoint>>,
    /// Replay this recording up to the branch's round, then go on live from there: what came
    /// from outside is the recording's until then (the modules that posted it are left out),
    /// and paused there when stepped.
    pub branch: Option<Arc<Branch>>,
}

impl LaunchOptions {
    /// What the machines' runners take of these options.
    pub(crate) fn driving(&self) -> Driving<'_> {
        Driving {
            hosts: &self.hosts,
            halt_on_timeout: self.halt_on_timeout,
            stepper: self.stepper.as_ref(),
        }
    }

    /// The script the run plays: the one given (empty: none at all), else the manifest's.
    pub(crate) fn script_played<'b>(&'b self, behaviour: &'b Behaviour) -> Option<&'b Script> {
        self.script.as_ref().or(behaviour.script.as_ref())
    }
}

/// Machine → its final states (those with no way out).
type Finals = FxHashMap<String, FxHashSet<i64>>;
/// The machines running from the start, and the state each is in.
type Positions = FxHashMap<String, Option<i64>>;

/// A behaviour running: its trace, and what it takes for it to be over.
pub struct Running {
    pub events: mpsc::UnboundedReceiver<Event>,
    /// Every ringlet, once it has run, when asked for ([`LaunchOptions::ringlets`]) and the
    /// machines run in rounds.
    pub ringlets: Option<mpsc::UnboundedReceiver<Ringlet>>,
    /// The round under way (0 under `schedule = "concurrent"`).
    pub round: RoundCounter,
    /// The variables the machines share (globals and externs).
    pub shared: Arc<Shared>,
    /// How the round schedule ended, once it has (never under `schedule = "concurrent"`): its
    /// events are in `events` by then.
    pub end: tokio::sync::watch::Receiver<Option<RoundsEnd>>,
    /// What was started or left out, and where sockets listen, for the person running it.
    pub notes: Vec<String>,
    /// The moment the run's times count from (a resumed run's began before it was taken up).
    pub epoch: tokio::time::Instant,
    /// The checkpoints asked for ([`LaunchOptions::checkpoints`]), as they are taken.
    pub checkpoints: Option<mpsc::UnboundedReceiver<Checkpoint>>,
    tasks: JoinSet<()>,
    finals: Finals,
    top: Positions,
    halted: FxHashSet<String>,
    /// Machines whose final state's OnEntry has run.
    finished: FxHashSet<String>,
}

impl Running {
    /// Follows an event; true once every top-level machine is in a final state or halted.
    pub fn observe(&mut self, event: &Event) -> bool {
        match event {
            Event::Entered { machine, id, .. } => {
                if let Some(at) = self.top.get_mut(machine) {
                    *at = Some(*id);
                }
            }
            Event::Finished { machine, .. } => {
                self.finished.insert(machine.clone());
            }
            Event::Halted { machine, .. } => {
                self.halted.insert(machine.clone());
            }
            _ => {}
        }
        self.is_over()
    }

    pub fn is_over(&self) -> bool {
        self.top.iter().all(|(machine, at)| {
            self.halted.contains(machine)
                || (self.finished.contains(machine)
                    && at.is_some_and(|id| {
                        self.finals.get(machine).is_some_and(|f| f.contains(&id))
                    }))
        })
    }

    /// Every event until every top-level machine is in a final state or halted, or `limit`
    /// passes; whether it ended by itself.
    pub async fn follow(&mut self, limit: Duration) -> (Vec<Event>, bool) {
        self.follow_rounds(limit, u64::MAX).await
    }

    /// [`Running::follow`], ending too before the first event of a round after `last_round`:
    /// a behaviour whose rounds follow each other at one moment for ever never lets `limit`
    /// of virtual time pass.
    pub async fn follow_rounds(&mut self, limit: Duration, last_round: u64) -> (Vec<Event>, bool) {
        let deadline = tokio::time::Instant::now() + limit;
        let mut events = Vec::new();
        while let Ok(Some(event)) = tokio::time::timeout_at(deadline, self.events.recv()).await {
            if event.round() > last_round {
                return (events, false);
            }
            let over = self.observe(&event);
            events.push(event);
            if over {
                return (events, true);
            }
        }
        (events, false)
    }

    /// Where a run taken up from `checkpoint` is: which top-level machines are in which
    /// state, which finished and which halted (what its events would have said).
    fn taken_up(&mut self, checkpoint: &Checkpoint, behaviour: &Behaviour) {
        for kept in &checkpoint.schedule.machines {
            let name = &kept.name;
            if kept.over {
                self.halted.insert(name.clone());
            }
            let machine = behaviour.machines.iter().find(|m| m.machine.name == *name);
            let (Some(machine), Some(entered)) = (machine, &kept.last_entered) else {
                continue;
            };
            // The state its last `Entered` event named: by name, or the current one's id when
            // the name repeats.
            let named: Vec<i64> = machine
                .machine
                .states
                .iter()
                .filter(|s| s.name == *entered)
                .map(|s| s.id)
                .collect();
            let state = match named.as_slice() {
                [only] => Some(*only),
                _ => kept
                    .state_in(&machine.machine)
                    .filter(|_| kept.state == *entered),
            };
            let Some(state) = state else {
                continue;
            };
            if let Some(at) = self.top.get_mut(name) {
                *at = Some(state);
            }
            if self.finals.get(name).is_some_and(|f| f.contains(&state)) {
                self.finished.insert(name.clone());
            }
        }
    }

    /// Stops everything it started.
    pub async fn stop(mut self) {
        self.tasks.abort_all();
        while self.tasks.join_next().await.is_some() {}
    }
}

type Task = Pin<Box<dyn Future<Output = ()> + Send>>;

/// One module to start, with the atoms it answers.
struct Module {
    name: String,
    answers: Vec<String>,
    task: Task,
}

/// The labels `options` answer from outside. A later replacer takes a label from an earlier
/// one: a person, then the script, then the embedding program.
fn replaced(behaviour: &Behaviour, options: &LaunchOptions) -> Replaced {
    let mut replaced = Replaced::default();
    if let Some(person) = &options.person {
        replaced.take(person.declaration().answers, "a person answers");
    }
    if let Some(script) = options.script_played(behaviour) {
        replaced.take(script.atoms(), "the script impersonates");
    }
    for expert in &options.experts {
        replaced.take(
            expert.declaration().answers,
            "the embedding program answers",
        );
    }
    replaced
}

/// Starts the behaviour on `board` (taken up from a checkpoint when `options` say). Fails when
/// a socket cannot be opened, or a checkpoint cannot be taken or taken up.
pub async fn launch(
    behaviour: &Behaviour,
    board: &Whiteboard,
    options: LaunchOptions,
) -> Result<Running, BehaviourError> {
    let resume = options.resume.clone();
    // The trace's times count from here, as the impersonator's script times do, so `at 1s`
    // shows as 1.000 s; a resumed run's from where its checkpoint's did.
    let epoch = match resume.as_deref() {
        Some(c) => {
            checkpoint::take_up(c, options.script_played(behaviour), board, &ours(behaviour))?
        }
        None => tokio::time::Instant::now(),
    };
    let mut kept = Kept::new(options.checkpoints.is_some(), resume.clone());
    let (tx, events) = mpsc::unbounded_channel();
    let shared = behaviour.shared_variables();
    let mut rounds = rounds_of(behaviour, &options, &tx, epoch, &shared);
    if let Some(branch) = &options.branch {
        rounds = branch.feeding(rounds, behaviour)?;
    }
    let round = rounds
        .as_ref()
        .map_or_else(RoundCounter::default, Rounds::counter);
    let mut notes = Vec::new();
    let (modules, machines_started) = modules(
        behaviour,
        board,
        &options,
        (&tx, epoch, &round),
        (&mut kept, &mut notes),
    )
    .await?;
    kept.refuse_unheld(behaviour, modules.iter().map(|m| m.name.as_str()))?;
    let silent = silent_from(behaviour, &options, &modules);
    let (mut rounds, checkpoints) =
        kept.schedule(rounds, behaviour, &options, board, &mut notes)?;
    let ringlets = rounds
        .as_mut()
        .filter(|_| options.ringlets)
        .map(Rounds::ringlets);
    let rounds = match (rounds, silent) {
        (Some(rounds), Some(from)) => Some(rounds.ends_when_still(from)),
        (rounds, _) => rounds,
    };
    let mut tasks = JoinSet::new();
    start_modules(board, modules, &mut tasks).await;
    let (ended, end) = tokio::sync::watch::channel(None);
    match rounds {
        Some(rounds) => {
            let board = board.clone();
            tasks.spawn(async move {
                let _ = ended.send(Some(rounds.run(board).await));
            });
        }
        None => {
            for runner in machine_runners(behaviour, options.driving(), &tx, epoch, &shared) {
                tasks.spawn(runner.run(board.clone()));
            }
        }
    }
    machines_started.notify_one();
    let (finals, top) = finals_and_top(behaviour);
    let mut running = Running {
        events,
        ringlets,
        round,
        shared,
        end,
        notes,
        epoch,
        checkpoints,
        tasks,
        finals,
        top,
        halted: FxHashSet::default(),
        finished: FxHashSet::default(),
    };
    if let Some(c) = resume {
        running.taken_up(&c, behaviour);
    }
    Ok(running)
}

/// The modules of this run whose postings a checkpoint's board holds as its own: the machines,
/// the theories and the script's impersonator.
fn ours(behaviour: &Behaviour) -> Vec<String> {
    let machines = behaviour.machines.iter().map(|m| m.machine.name.clone());
    let theories = behaviour.theories.iter().map(|t| t.name.clone());
    machines
        .chain(theories)
        .chain(["impersonator".to_string()])
        .collect()
}

/// Every module but the machines, each answering what nobody answers from outside; and what
/// holds the script's timed steps back until the machines have started.
async fn modules(
    behaviour: &Behaviour,
    board: &Whiteboard,
    options: &LaunchOptions,
    trace: (
        &mpsc::UnboundedSender<Event>,
        tokio::time::Instant,
        &RoundCounter,
    ),
    (kept, notes): (&mut Kept, &mut Vec<String>),
) -> Result<(Vec<Module>, Arc<tokio::sync::Notify>), BehaviourError> {
    let replaced = replaced(behaviour, options);
    let mut modules = experts(behaviour, board, &replaced, notes, kept);
    // A branch's outside is its recording: no sensor is even opened (one may listen on a port
    // the robot holds).
    let sim_note = match &options.branch {
        None => sensors(behaviour, board, options, &replaced, &mut modules, notes).await?,
        Some(branch) => {
            if !behaviour.sensors.is_empty() {
                notes.push(format!(
                    "left out the sensor wrappers: the recording says what came from outside until round {}",
                    branch.of.round
                ));
            }
            None
        }
    };
    // The script's timed steps wait for the machines, so that one timed for the first round's
    // moment comes at that round's start (`docs/spec/behaviour.md` §3.1, between rounds).
    let machines_started = Arc::new(tokio::sync::Notify::new());
    impersonators(
        behaviour,
        board,
        options,
        trace,
        (&mut modules, &machines_started, kept),
        notes,
    );
    embedded_experts(board, options, &mut modules, notes);
    // A simulator with no receiver left to listen plays to nobody.
    if !modules.iter().any(|m| m.name == "gamecontroller") {
        modules.retain(|m| m.name != "gc-sim");
    } else {
        notes.extend(sim_note);
    }
    modules.extend(range_watch(behaviour, board, trace, kept));
    if let Some(branch) = &options.branch {
        branched(behaviour, board, branch, &mut modules, notes);
    }
    Ok((modules, machines_started))
}

/// A branch's modules: the theories, and the recording for what came from outside before the
/// branch's round (a sensor, the script, a person or a program posted it then; after it, only
/// whoever posts to the board does).
fn branched(
    behaviour: &Behaviour,
    board: &Whiteboard,
    branch: &Branch,
    modules: &mut Vec<Module>,
    notes: &mut Vec<String>,
) {
    let round = branch.of.round;
    modules.retain(|m| {
        let ours = m.name == "ranges" || behaviour.theories.iter().any(|t| t.name == m.name);
        if !ours {
            notes.push(format!(
                "left out {}: the recording says what came from outside until round {round}",
                m.name
            ));
        }
        ours
    });
    if let Some((atoms, task)) = branch.answers(behaviour, board) {
        notes.push(format!(
            "the recording answers {} until round {round}; then nothing does",
            atoms.join(", ")
        ));
        modules.push(Module {
            name: "recording".into(),
            answers: atoms,
            task: Box::pin(task),
        });
    }
}

/// From when (since the epoch) nothing but the experts' answers can reach the machines, if
/// `options` ask to end at a still round and only theories and a timed script are started.
fn silent_from(
    behaviour: &Behaviour,
    options: &LaunchOptions,
    modules: &[Module],
) -> Option<Duration> {
    // A branch's recording answers only what the branch replays.
    let ours = |m: &Module| {
        matches!(m.name.as_str(), "impersonator" | "script" | "recording")
            || behaviour.theories.iter().any(|t| t.name == m.name)
    };
    if !options.end_when_still || options.person.is_some() || !modules.iter().all(ours) {
        return None;
    }
    let played = options
        .script_played(behaviour)
        .filter(|_| options.branch.is_none());
    let steps = played.map_or(&[][..], |s| &s.steps[..]);
    steps
        .iter()
        .try_fold(Duration::ZERO, |last, step| match step.when {
            When::Start => Some(last),
            When::At(at) => Some(last.max(at)),
            When::Step(_) => None,
        })
}

/// The experts the embedding program gives: each takes over the atoms it answers from the
/// behaviour's own.
fn embedded_experts(
    board: &Whiteboard,
    options: &LaunchOptions,
    modules: &mut Vec<Module>,
    notes: &mut Vec<String>,
) {
    for expert in &options.experts {
        let answers = expert.declaration().answers;
        leave_out(modules, &answers, "the embedding program answers", notes);
        modules.push(Module {
            name: expert.name().to_string(),
            answers,
            task: Box::pin(expert.clone().run(board.clone())),
        });
    }
}

/// A reasoner expert per theory, then the Prolog and program experts, each answering what is
/// not answered from outside.
fn experts(
    behaviour: &Behaviour,
    board: &Whiteboard,
    replaced: &Replaced,
    notes: &mut Vec<String>,
    kept: &mut Kept,
) -> Vec<Module> {
    let mut modules = Vec::new();
    for t in &behaviour.theories {
        let expert =
            ReasonerExpert::new(&t.name, t.theory.clone(), &t.mapping).with_limits(t.limits);
        let answers = replaced.narrow(&t.name, &expert.declaration().answers, notes);
        if !answers.is_empty() {
            let expert = kept.theory(&t.name, expert.answering_only(&answers));
            modules.push(Module {
                name: t.name.clone(),
                answers,
                task: Box::pin(expert.run(board.clone())),
            });
        }
    }
    for p in &behaviour.programs {
        let answers = replaced.narrow(&p.name, &p.answers, notes);
        if !answers.is_empty() {
            let program = crate::programs::LoadedProgram {
                answers: answers.clone(),
                ..p.clone()
            };
            modules.push(Module {
                name: p.name.clone(),
                answers,
                task: Box::pin(program.expert(behaviour.files.folder()).run(board.clone())),
            });
        }
    }
    modules
}

/// The sensor wrappers of the manifest, but those whose labels are answered from outside
/// (left out before they open a socket); what the GameController simulator will play, if it
/// plays.
async fn sensors(
    behaviour: &Behaviour,
    board: &Whiteboard,
    options: &LaunchOptions,
    replaced: &Replaced,
    modules: &mut Vec<Module>,
    notes: &mut Vec<String>,
) -> Result<Option<String>, BehaviourError> {
    let mut sim_note = None;
    for sensor in &behaviour.sensors {
        let mut wrapper = |name: String, answers: Vec<String>, task: Task| {
            if !replaced.leaves_out(&name, &answers, notes) {
                modules.push(Module {
                    name,
                    answers,
                    task,
                });
            }
        };
        match sensor.entry.kind {
            SensorKind::Gamecontroller => {
                let declared = GameControllerReceiver::declaration_for(&ReceiverConfig::default());
                if !replaced.leaves_out("gamecontroller", &declared.answers, notes) {
                    sim_note = gamecontroller(sensor, board, options, modules, notes).await?;
                }
            }
            SensorKind::ChestButton => {
                let b = ButtonWrapper::chest();
                let (name, answers) = (b.name.clone(), b.declaration().answers);
                wrapper(name, answers, Box::pin(b.run(board.clone())));
            }
            SensorKind::FootBumpers => {
                for left in [true, false] {
                    let b = ButtonWrapper::foot(left);
                    let (name, answers) = (b.name.clone(), b.declaration().answers);
                    wrapper(name, answers, Box::pin(b.run(board.clone())));
                }
            }
            SensorKind::Fall => {
                let f = FallWrapper::default();
                let (name, answers) = (f.name.clone(), f.declaration().answers);
                wrapper(name, answers, Box::pin(f.run(board.clone())));
            }
        }
    }
    Ok(sim_note)
}

/// The GameController receiver on its socket, and the simulator playing to it unless a real
/// GameController is listened for; the simulator's note.
async fn gamecontroller(
    sensor: &crate::load::LoadedSensor,
    board: &Whiteboard,
    options: &LaunchOptions,
    modules: &mut Vec<Module>,
    notes: &mut Vec<String>,
) -> Result<Option<String>, BehaviourError> {
    let e = &sensor.entry;
    let mut sim_note = None;
    let simulate = !options.no_simulator && e.simulator != Some(Simulator::On(false));
    let bind: SocketAddr = match (simulate, e.port) {
        (true, None) => ([127, 0, 0, 1], 0).into(),
        (true, Some(port)) => ([127, 0, 0, 1], port).into(),
        (false, port) => ([0, 0, 0, 0], port.unwrap_or(3838)).into(),
    };
    let home = 18;
    let receiver = GameControllerReceiver::bind(ReceiverConfig {
        bind,
        team: e.team.or(simulate.then_some(home)),
        player: e.player.unwrap_or(1),
        ..ReceiverConfig::default()
    })
    .await
    .map_err(|error| BehaviourError::Socket {
        what: format!("cannot listen for the GameController on {bind}"),
        error,
    })?;
    let at = receiver
        .local_addr()
        .map_err(|error| BehaviourError::Socket {
            what: "the GameController socket has no address".into(),
            error,
        })?;
    let answers = receiver.declaration().answers;
    let board = board.clone();
    modules.push(Module {
        name: "gamecontroller".into(),
        answers,
        task: Box::pin(async move {
            if let Err(error) = receiver.run(board).await {
                tracing::error!(%error, "the GameController receiver stopped");
            }
        }),
    });
    if simulate {
        let (module, note) = simulator(sensor, at, home);
        modules.push(module);
        sim_note = Some(note);
    } else {
        notes.push(format!("listening for the GameController on {at}"));
    }
    Ok(sim_note)
}

/// The simulator playing the manifest's game (or the built-in one, its penalty for this robot)
/// to the receiver at `at`, and the note saying so.
fn simulator(sensor: &crate::load::LoadedSensor, at: SocketAddr, home: u8) -> (Module, String) {
    let e = &sensor.entry;
    let player = e.player.unwrap_or(1);
    let game = sensor.game.clone().unwrap_or_else(|| {
        // The built-in game's penalty is for this robot, so it is seen.
        let mut game = default_game(home, 5);
        for (_, event) in &mut game.events {
            if let GameEvent::Penalise { player: p, .. } | GameEvent::Unpenalise { player: p, .. } =
                event
            {
                *p = player;
            }
        }
        game
    });
    let config = SimConfig {
        to: at,
        home,
        ..SimConfig::default()
    };
    let note = format!(
        "GameController simulator: a game of {:.0} s to {at}",
        game.length().as_secs_f64()
    );
    let module = Module {
        name: "gc-sim".into(),
        answers: Vec::new(),
        task: Box::pin(async move {
            if let Err(error) = play(&game, &config, |_| {}).await {
                tracing::error!(%error, "the GameController simulator stopped");
            }
        }),
    };
    (module, note)
}

/// A person at the terminal and the script, each leaving out the modules that answer what it
/// answers.
fn impersonators(
    behaviour: &Behaviour,
    board: &Whiteboard,
    options: &LaunchOptions,
    (tx, epoch, round): (
        &mpsc::UnboundedSender<Event>,
        tokio::time::Instant,
        &RoundCounter,
    ),
    (modules, machines_started, kept): (&mut Vec<Module>, &Arc<tokio::sync::Notify>, &mut Kept),
    notes: &mut Vec<String>,
) {
    let script = options.script_played(behaviour).cloned();
    if let Some(person) = &options.person {
        let asked = person.declaration().answers;
        leave_out(modules, &asked, "a person answers", notes);
        modules.push(Module {
            name: person.declaration().name,
            answers: asked,
            task: Box::pin(person.clone().run(board.clone())),
        });
    }
    if let Some(script) = script {
        let scripted = script.atoms();
        leave_out(modules, &scripted, "the script impersonates", notes);
        let imp = Impersonator::new("impersonator", Vec::<String>::new(), script.clone())
            .timed_after(machines_started.clone());
        // An atom the script sets only later is false until then.
        for atom in &scripted {
            if !script
                .steps
                .iter()
                .any(|s| s.atom == *atom && s.when == proclaim_experts::When::Start)
            {
                imp.set(atom, false);
            }
        }
        // Taken up from a checkpoint, every atom is what the script had said by then.
        let imp = kept.script(&script, imp, epoch);
        // What the script sets shows in the trace (a theory's inputs change no machine's state,
        // yet explain why an answer changed).
        let said = board.subscribe_pattern(Pattern::Any(scripted.clone()));
        let shown = (
            kept.script_shown(board, &scripted),
            kept.follower(&scripted, board),
        );
        modules.push(Module {
            name: "script".into(),
            answers: Vec::new(),
            task: Box::pin(show_script(said, shown, tx.clone(), epoch, round.clone())),
        });
        modules.push(Module {
            name: "impersonator".into(),
            answers: scripted,
            task: Box::pin(imp.run(board.clone())),
        });
    }
}

/// The machines of a behaviour in one round schedule, unless it asks for `concurrent`.
fn rounds_of(
    behaviour: &Behaviour,
    options: &LaunchOptions,
    tx: &mpsc::UnboundedSender<Event>,
    epoch: tokio::time::Instant,
    shared: &Arc<Shared>,
) -> Option<Rounds> {
    if behaviour.manifest.schedule == Schedule::Concurrent {
        return None;
    }
    let rounds = Rounds::new(machine_runners(
        behaviour,
        options.driving(),
        tx,
        epoch,
        shared,
    ));
    Some(match &options.stepper {
        Some(stepper) => rounds.stepped_by(stepper.clone()),
        None => rounds,
    })
}

/// Each machine's final states, and the machines running from the start.
pub(crate) fn finals_and_top(behaviour: &Behaviour) -> (Finals, Positions) {
    let mut finals = FxHashMap::default();
    let mut top = FxHashMap::default();
    for loaded in &behaviour.machines {
        let m = &loaded.machine;
        let dead_ends: FxHashSet<i64> = m
            .states
            .iter()
            .filter(|s| RingletPlan::of_state(m, s).is_final())
            .map(|s| s.id)
            .collect();
        finals.insert(m.name.clone(), dead_ends);
        if loaded.start {
            top.insert(m.name.clone(), None);
        }
    }
    (finals, top)
}

/// The watch that holds the run to the manifest's `[ranges]`, if it declares any.
fn range_watch(
    behaviour: &Behaviour,
    board: &Whiteboard,
    (tx, epoch, round): (
        &mpsc::UnboundedSender<Event>,
        tokio::time::Instant,
        &RoundCounter,
    ),
    kept: &mut Kept,
) -> Option<Module> {
    if behaviour.ranges.is_empty() {
        return None;
    }
    let types: Vec<String> = behaviour.ranges.iter().map(|r| r.ty.clone()).collect();
    let handled = kept.follower(&types, board);
    let machines = behaviour.machines.iter().map(|m| m.machine.name.clone());
    Some(Module {
        name: "ranges".into(),
        answers: Vec::new(),
        task: Box::pin(crate::range_watch::watch(
            board.subscribe_pattern(Pattern::Any(types)),
            behaviour.ranges.clone(),
            machines.collect(),
            (kept.range_warnings(), handled),
            (tx.clone(), epoch, round.clone()),
        )),
    })
}

/// Turns the impersonator's postings into trace events, each value once when it changes from
/// what was `last` shown (it also posts its answer to every query, which is no news).
async fn show_script(
    mut said: proclaim_board::Subscription,
    (mut last, handled): (FxHashMap<String, proclaim_board::Value>, Arc<AtomicU64>),
    trace: mpsc::UnboundedSender<Event>,
    epoch: tokio::time::Instant,
    round: RoundCounter,
) {
    while let Some(m) = said.next().await {
        handled.store(m.seq, Ordering::Relaxed);
        if &*m.module != "impersonator" || last.get(&*m.ty) == Some(&m.value) {
            continue;
        }
        last.insert(m.ty.to_string(), m.value.clone());
        let event = Event::Posted {
            machine: "impersonator".into(),
            ty: m.ty.to_string(),
            content: m.value.to_string(),
            priority: 0,
            round: round.get(),
            at: epoch.elapsed(),
        };
        if trace.send(event).is_err() {
            return;
        }
    }
}

/// Leaves out the modules that answer any of `atoms` (someone else answers them now), noting
/// each with `why` and the atoms.
fn leave_out(modules: &mut Vec<Module>, atoms: &[String], why: &str, notes: &mut Vec<String>) {
    modules.retain(|m| {
        let overlap: Vec<&str> = m
            .answers
            .iter()
            .filter(|a| atoms.contains(a))
            .map(String::as_str)
            .collect();
        if overlap.is_empty() {
            return true;
        }
        notes.push(format!("left out {}: {why} {}", m.name, overlap.join(", ")));
        false
    });
}

/// Starts every module, and waits until those that answer have registered.
async fn start_modules(board: &Whiteboard, modules: Vec<Module>, tasks: &mut JoinSet<()>) {
    let experts: Vec<String> = modules
        .iter()
        .filter(|m| !m.answers.is_empty())
        .map(|m| m.name.clone())
        .collect();
    for m in modules {
        tasks.spawn(m.task);
    }
    wait_registered(board, &experts).await;
}

/// Waits (briefly, bounded) until every expert has registered: they subscribe to queries first,
/// so from then on no query is missed.
async fn wait_registered(board: &Whiteboard, experts: &[String]) {
    for _ in 0..1000 {
        for _ in 0..8 {
            let registry = board.registry();
            if experts.iter().all(|e| registry.get(e).is_some()) {
                return;
            }
            tokio::task::yield_now().await;
        }
        tokio::time::sleep(Duration::from_millis(1)).await;
    }
    tracing::warn!("some experts did not register within a second");
}
