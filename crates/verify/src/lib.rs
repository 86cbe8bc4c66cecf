//! Explicit-state verification of a behaviour (`docs/spec/behaviour.md` §6): its machines
//! under §3.1's round schedule, the environment free, reasoners answering from their theories,
//! time abstracted; `never`, `always` and `reachable` properties with shortest counterexamples;
//! `eventually`, `leads_to` and `always_eventually` over infinite runs, time passing, with lasso
//! counterexamples ([`liveness`]); states never entered, transitions that never fire, and
//! deadlock.
//!
//! - [`Model`]: the behaviour as slots (variables, whiteboard types), machines and reasoners;
//!   free types take values from a finite domain ([`domain`] says why that is sound and where
//!   it is not exact).
//! - One step is one **ringlet** of the machine whose turn it is ([`ringlet`]), not a whole
//!   round: a property must be able to see the world between two machines' ringlets (the door
//!   opening while the pump waits its turn), and counterexamples then say who moved.
//! - Time: a state's `timeout`/`after`/`after_ms` tests may come due at any snapshot after it
//!   was entered (a composite's transition's after the composite was: the moves inside it keep
//!   them; constant ones of one clock in order of duration, none of a positive duration in the
//!   ringlet that started its clock) and stay due until it is left: every real run is a path
//!   of the model, so a `never` that holds here holds in every run.
//! - [`explore`]: breadth-first, states packed into a byte arena ([`world`]), a hash table of
//!   state numbers, parents for the shortest path. Our own search rather than `stateright`'s:
//!   its checkers keep each state as a Rust value (here a `Vec` per machine and slot: ten times
//!   the bytes of the packed form), identify states by 64-bit fingerprints (a collision
//!   silently hides states), and its actions would have to carry the environment's choices as
//!   values; a model whose steps are "one ringlet and everything the environment may do" and
//!   whose state is a few dozen bytes fits a plain BFS over packed bytes better.
//! - [`promela`]: the same model written as Promela, for SPIN to check the same properties.
//! - Unbounded counters are cut by the state budget: the outcome is then incomplete, never a
//!   hang. Nothing here reads files or prints: the command line does.

/// The activity language's operators: the runner's own, so the model computes as the robot does.
pub use proclaim_lower::arith;
mod acceptance;
mod build;
mod choices;
mod chunked;
mod clocks;
mod components;
mod confirm;
pub mod domain;
mod edges;
mod error;
mod explore;
mod flow;
pub mod follow;
mod found_memo;
pub mod kind;
mod lasso;
mod liveness;
pub mod model;
mod outcome;
pub mod promela;
mod promela_clocks;
pub mod property;
mod race;
/// The conformance test's random behaviours, for the tests of the search's memos.
#[cfg(test)]
#[path = "../tests/common/random_behaviour.rs"]
#[allow(dead_code)]
mod random_behaviour;
mod reasoner;
pub mod reduce;
mod refine;
pub mod ringlet;
mod script;
pub mod search;
mod seen;
mod state_table;
mod step_memo;
mod symbolic;
mod trace;
mod values;
pub mod world;

pub use error::{PropertyError, VerifyError};
pub use explore::Progress;
pub use model::Model;
pub use outcome::{
    Assignment, Finding, Inexact, PropertyOutcome, Report, Run, SearchStats, Stop, Trace,
    TraceStep, Verdict,
};
pub use proclaim_behaviour::PropertyKind;
pub use promela::{to_promela, Claim, EmitError, Promela};
pub use property::{Property, PropertySource};
pub use reduce::Reductions;
pub use script::{lasso_script, to_script, unroll, LOOP_REPEATS};
pub use trace::render;

use proclaim_behaviour::Behaviour;
use search::Search;

/// Which engine explores.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SearchEngine {
    /// The explicit search alone for its first [`AUTO_EXPLICIT_STATES`] states; where that
    /// decides nothing, the symbolic engine beside it on a second thread, the first to decide
    /// answering (`race.rs`).
    #[default]
    Auto,
    /// States one by one (`explore.rs`).
    Explicit,
    /// Sets of states as decision diagrams (`symbolic.rs`).
    Symbolic,
}

impl SearchEngine {
    pub fn word(self) -> &'static str {
        match self {
            SearchEngine::Auto => "auto",
            SearchEngine::Explicit => "explicit",
            SearchEngine::Symbolic => "symbolic",
        }
    }
}

/// How many states the automatic choice lets the explicit search store alone before the
/// symbolic engine starts beside it.
pub const AUTO_EXPLICIT_STATES: usize = 20_000;

/// How far to explore, and how.
#[derive(Clone, Copy, Debug)]
pub struct Options {
    /// Stop once this many states are stored (the outcome is then incomplete where the
    /// question is not settled).
    pub max_states: usize,
    /// Stop before the search's tables would hold more than this many bytes (likewise).
    pub max_memory: usize,
    pub reductions: Reductions,
    pub engine: SearchEngine,
    /// Order the clocks of different machines (§6, time; `clocks.rs`) for every property: no
    /// run that needs one machine's longer test due before another's shorter one started no
    /// later, at the price of states (the order of the machines' arrivals). Off, the search is
    /// unordered and the verdicts a run decided are checked again ordered (`refine.rs`).
    /// [`to_promela`] writes the ordered model either way.
    pub clock_order: bool,
}

impl Default for Options {
    fn default() -> Options {
        Options {
            max_states: 1_000_000,
            max_memory: 2 << 30,
            reductions: Reductions::default(),
            engine: SearchEngine::Auto,
            clock_order: false,
        }
    }
}

impl Options {
    fn limits(&self) -> explore::Limits {
        explore::Limits {
            max_states: self.max_states,
            max_memory: self.max_memory,
            stop_when_decided: self.reductions.stop_when_decided,
            rival_after: usize::MAX,
            memo: true,
        }
    }
}

/// The properties a behaviour's manifest declares.
pub fn manifest_properties(behaviour: &Behaviour) -> Vec<PropertySource> {
    behaviour
        .manifest
        .properties
        .iter()
        .map(|p| PropertySource {
            name: p.name.clone(),
            kind: p.kind,
            expression: p.expression.clone(),
            fair: p.fair.iter().cloned().collect(),
        })
        .collect()
}

/// Verifies `properties` of `behaviour`. Bad properties (every one) or a behaviour beyond the
/// packed state's widths are errors; anything else is a [`Report`].
pub fn verify(
    behaviour: &Behaviour,
    properties: &[PropertySource],
    options: Options,
) -> Result<Report, VerifyError> {
    verify_with_progress(behaviour, properties, options, &mut |_| {})
}

/// [`verify`], telling `progress` how far the search got as it goes (a long search's bar).
pub fn verify_with_progress(
    behaviour: &Behaviour,
    properties: &[PropertySource],
    options: Options,
    progress: &mut dyn FnMut(Progress),
) -> Result<Report, VerifyError> {
    checked(behaviour, properties, options, progress, &[])
}

/// [`verify_with_progress`], where each property the search leaves undecided is decided by
/// its run in `found` if that run follows through the model (`confirm.rs`).
fn checked(
    behaviour: &Behaviour,
    properties: &[PropertySource],
    options: Options,
    progress: &mut dyn FnMut(Progress),
    found: &[Option<confirm::Found>],
) -> Result<Report, VerifyError> {
    // The first search's model is let go before a second one is built.
    let (report, ordered) = {
        let (mut model, compiled) = prepare(behaviour, properties, options.clock_order)?;
        model.storage = reduce::storage(&model, &compiled, options.reductions);
        check_stored_free(&model)?;
        let report = search(&model, &compiled, options, progress)?;
        let mut report = undecided_where_inexact(report, &model);
        if options.clock_order {
            if !found.is_empty() {
                let search = Search::new(&model);
                let budget = (options.max_states, options.max_memory);
                confirm::confirm(&search, &compiled, &mut report.properties, found, budget);
            }
            return Ok(report);
        }
        let ordered = (model.machines.iter().zip(clocks::ranks(&model.machines)))
            .filter(|(_, r)| r.is_some())
            .map(|(m, _)| m.name.clone())
            .collect();
        (report, ordered)
    };
    let mut again = |properties: &[PropertySource], options, found: &[Option<confirm::Found>]| {
        checked(behaviour, properties, options, progress, found)
    };
    let mut follows = |run: &Run| deadlock_followed(behaviour, properties, options, run);
    refine::check_ordered(
        report,
        properties,
        ordered,
        options,
        &mut again,
        &mut follows,
    )
}

/// A deadlock's `run`, found with the clocks of different machines unordered, followed
/// through the model of `behaviour` and `properties` with them ordered (`confirm.rs`).
fn deadlock_followed(
    behaviour: &Behaviour,
    properties: &[PropertySource],
    options: Options,
    run: &Run,
) -> Result<Option<Trace>, VerifyError> {
    let (mut model, compiled) = prepare(behaviour, properties, true)?;
    model.storage = reduce::storage(&model, &compiled, options.reductions);
    let budget = (options.max_states, options.max_memory);
    Ok(confirm::deadlock(&Search::new(&model), run, budget))
}

/// What a search claims is absent (a `never` that holds, a state never entered) is only
/// true when the free values' domains keep every test (spec §6, "Free values"): where they
/// do not, such a verdict is undecided and such a finding left out, with the reasons. What
/// a search found (a counterexample, a witness, a lasso) is a run with real values and
/// stands.
fn undecided_where_inexact(mut report: Report, model: &Model) -> Report {
    if model.inexact.is_empty() {
        return report;
    }
    for p in &mut report.properties {
        let absent = match p.verdict {
            Verdict::Holds => p.kind != PropertyKind::Reachable.word(),
            Verdict::Fails => p.kind == PropertyKind::Reachable.word(),
            Verdict::Incomplete => false,
        };
        if absent {
            p.verdict = Verdict::Incomplete;
        }
    }
    report.findings.clear();
    report.inexact = model.inexact.clone();
    report
}

fn search(
    model: &Model,
    compiled: &[Property],
    options: Options,
    progress: &mut dyn FnMut(Progress),
) -> Result<Report, VerifyError> {
    let (model, compiled) = (model, compiled);
    match options.engine {
        SearchEngine::Explicit => {
            Ok(explicit(&Search::new(model), compiled, options.limits(), progress).0)
        }
        SearchEngine::Symbolic => symbolic(&Search::new(model), compiled, options)
            .map_err(|declined| VerifyError::SymbolicDeclined(declined.0)),
        SearchEngine::Auto => Ok(race(model, compiled, options, progress)),
    }
}

/// The explicit search alone on a small graph; beyond its first [`AUTO_EXPLICIT_STATES`]
/// states undecided, or after it ran out of memory, the symbolic engine beside it, the first
/// to decide answering (`race.rs`). Where neither decides, the explicit search's report.
fn race(
    model: &Model,
    compiled: &[Property],
    options: Options,
    progress: &mut dyn FnMut(Progress),
) -> Report {
    let race = race::Race::new(options.max_memory);
    std::thread::scope(|scope| {
        let rival = scope.spawn(|| {
            if !race.wait_for_start() {
                return None;
            }
            let search = Search::racing(model, &race, race::Side::Symbolic);
            let report = symbolic(&search, compiled, options).ok();
            let decided = report.as_ref().is_some_and(decided);
            race.finish(race::Side::Symbolic, decided);
            report.filter(|_| decided)
        });
        let search = Search::racing(model, &race, race::Side::Explicit);
        let limits = explore::Limits {
            rival_after: AUTO_EXPLICIT_STATES,
            ..options.limits()
        };
        let (explicit, overtaken) = explicit(&search, compiled, limits, progress);
        let explicit_decided = !overtaken && decided(&explicit);
        if !overtaken && explicit.stats.stopped == Stop::StateBudget {
            // `--max-states` bounds the search asked for: no engine starts after it.
            race.no_rival();
        }
        race.finish(race::Side::Explicit, explicit_decided);
        let symbolic = rival
            .join()
            .unwrap_or_else(|p| std::panic::resume_unwind(p));
        // Where both decided, the explicit search's report, as without the race.
        match symbolic {
            Some(report) if !explicit_decided => report,
            _ => explicit,
        }
    })
}

/// Whether a report's search reached its end or settled every property.
fn decided(report: &Report) -> bool {
    matches!(report.stats.stopped, Stop::Explored | Stop::Decided)
}

/// The model of `behaviour` and its properties compiled against it: what [`verify`] explores
/// and [`promela`] writes out.
pub(crate) fn prepare(
    behaviour: &Behaviour,
    properties: &[PropertySource],
    clock_order: bool,
) -> Result<(Model, Vec<Property>), VerifyError> {
    if !behaviour.suppress.is_empty() {
        let types = behaviour
            .suppress
            .iter()
            .map(|(ty, _)| ty.clone())
            .collect();
        return Err(VerifyError::Suppression(types));
    }
    let mut errors = Vec::new();
    let mut parsed = Vec::new();
    for p in properties {
        match property::parse(p) {
            Ok(e) => parsed.push((p, e)),
            Err(e) => errors.push(e),
        }
    }
    let exprs: Vec<&proclaim_fsm::Expr> = parsed.iter().flat_map(|(_, e)| e.exprs()).collect();
    let mut model = Model::build(behaviour, &exprs);
    if !clock_order {
        model.unorder_clocks();
    }
    let mut compiled = Vec::new();
    for (source, expr) in &parsed {
        match Property::compile(&mut model, source, expr) {
            Ok(p) => compiled.push(p),
            Err(e) => errors.push(e),
        }
    }
    if !errors.is_empty() {
        return Err(VerifyError::Properties(errors));
    }
    check_widths(&model)?;
    Ok((model, compiled))
}

fn check_widths(model: &Model) -> Result<(), VerifyError> {
    if model.machines.len() > 254 {
        return Err(VerifyError::TooLarge(format!(
            "{} machines (at most 254)",
            model.machines.len()
        )));
    }
    for m in &model.machines {
        if m.states.len() > usize::from(u16::MAX) {
            return Err(VerifyError::TooLarge(format!(
                "machine {} has {} states (at most {})",
                m.name,
                m.states.len(),
                u16::MAX
            )));
        }
        if let Some(s) = m.states.iter().find(|s| s.time_tests.len() > 15) {
            return Err(VerifyError::TooLarge(format!(
                "state {}.{} has {} time tests (at most 15)",
                m.name,
                s.name,
                s.time_tests.len()
            )));
        }
    }
    Ok(())
}

/// The environment's moves are numbered in a `u32`: the free types every state stores (those
/// the properties name, or all of them without the reduction) must have fewer joint values.
pub(crate) fn check_stored_free(model: &Model) -> Result<(), VerifyError> {
    let choices = model
        .stored_free_slots()
        .try_fold(1u64, |n, (_, d)| n.checked_mul(d.initial.len() as u64));
    if choices.is_none_or(|n| n > u64::from(u32::MAX)) {
        return Err(VerifyError::TooLarge(
            "the free whiteboard types stored in every state have over 2^32 joint values (name fewer in properties)".into(),
        ));
    }
    Ok(())
}

/// A property's verdict from whether what it looks for was found and whether every state was.
fn verdict(kind: PropertyKind, found: bool, complete: bool) -> Verdict {
    match (kind, found, complete) {
        (PropertyKind::Reachable, true, _) => Verdict::Holds,
        (_, true, _) => Verdict::Fails,
        (_, false, false) => Verdict::Incomplete,
        (PropertyKind::Reachable, false, true) => Verdict::Fails,
        (_, false, true) => Verdict::Holds,
    }
}

fn outcome(
    property: &Property,
    found: bool,
    complete: bool,
    trace: Option<Trace>,
) -> PropertyOutcome {
    PropertyOutcome {
        name: property.source.name.clone(),
        kind: property.source.kind.word().to_string(),
        expression: property.source.expression.clone(),
        fair: property.source.fair.clone(),
        verdict: verdict(property.source.kind, found, complete),
        trace,
        cycle: None,
        unconfirmed: false,
        followed: false,
    }
}

/// The states never entered and the transitions that never fire, of a complete search. A
/// nested state lowers to a flat state for each way into it, and a composite's transition to a
/// copy for each state inside it (`docs/spec/behaviour.md` §3.2): each is said of what was
/// written, once, and only when no flat state or copy of it was entered or fired.
fn never_findings(model: &Model, entered: &[Vec<bool>], fired: &[Vec<bool>]) -> Vec<Finding> {
    let mut findings = Vec::new();
    for (k, m) in model.machines.iter().enumerate() {
        // Each atomic state as written: a flat state of regions is one of each region's.
        let chart = !m.machine.composites.is_empty();
        let states = m
            .machine
            .states
            .iter()
            .zip(&entered[k])
            .flat_map(|(s, &e)| {
                let line = if chart { 0 } else { s.line };
                let paths = m.machine.atomic_paths(s);
                paths.into_iter().map(move |p| ((p.to_string(), line), e))
            });
        for state in once_each(states) {
            findings.push(Finding::NeverEntered {
                machine: m.name.clone(),
                state: state.0,
            });
        }
        let name = |id| {
            m.machine
                .state(id)
                .map_or_else(|| format!("#{id}"), |s| s.name.clone())
        };
        // Where a transition was written: its composite (or a region's state), else its state.
        let from_of = |composite: Option<usize>, source| {
            composite
                .and_then(|c| m.machine.composites.get(c))
                .map_or_else(|| name(source), |c| c.name.clone())
        };
        // A transition as written fired if any arm that fires it did, joined with another
        // region's or alone; it is shown as its arm that fires it alone shows it.
        let mut credited: std::collections::HashSet<(String, usize)> = Default::default();
        for (t, &f) in m.machine.transitions.iter().zip(&fired[k]) {
            if f && !t.joined.is_empty() {
                credited.insert((from_of(t.composite, t.source), t.line));
                for &(c, line, fires) in &t.joined {
                    if fires {
                        credited.insert((from_of(c, t.source), line));
                    }
                }
            }
        }
        let regions = m.machine.composites.iter().any(|c| c.parallel);
        let to_of = |t: &proclaim_fsm::Transition| shown_target(&m.machine, t, regions);
        // In a state of regions a transition as written is one finding wherever its arms go
        // (a composite's move back into itself goes to each combination it was in): it is
        // shown going where its first arm goes.
        let mut first_to: std::collections::HashMap<(String, usize), String> = Default::default();
        let transitions = (m.machine.transitions.iter().zip(&fired[k]))
            .filter(|(t, _)| t.joined.is_empty())
            .map(|(t, &f)| {
                let from = from_of(t.composite, t.source);
                let fired = f || credited.contains(&(from.clone(), t.line));
                let to = match regions {
                    // One that stays is one finding, wherever its copies are.
                    _ if t.stays => from.clone(),
                    true => (first_to.entry((from.clone(), t.line)))
                        .or_insert_with(|| to_of(t))
                        .clone(),
                    false => to_of(t),
                };
                ((from, to, t.shown().to_string(), t.line), fired)
            })
            .collect::<Vec<_>>();
        for (from, to, label, line) in once_each(transitions.into_iter()) {
            findings.push(Finding::NeverFires {
                machine: m.name.clone(),
                from,
                to,
                label,
                line,
            });
        }
    }
    findings
}

/// Where a never-fires finding says transition `t` goes: in a state of regions, the state it
/// enters that its source was not in (its region's), or its own for a move back into it,
/// however the other regions stand; else its target.
fn shown_target(
    machine: &proclaim_fsm::Machine,
    t: &proclaim_fsm::Transition,
    regions: bool,
) -> String {
    let name = |id| {
        machine
            .state(id)
            .map_or_else(|| format!("#{id}"), |s| s.name.clone())
    };
    let (Some(a), Some(b)) = (machine.state(t.source), machine.state(t.target)) else {
        return name(t.target);
    };
    let before = machine.atomic_paths(a);
    let after = machine.atomic_paths(b);
    let own = t.composite.and_then(|c| machine.composites.get(c));
    match after.iter().find(|p| !before.contains(p)) {
        Some(p) if regions => p.to_string(),
        None if regions => own
            .filter(|c| c.atomic)
            .map_or_else(|| name(t.target), |c| c.name.clone()),
        _ => name(t.target),
    }
}

/// The keys none of whose items happened, each once, in the order first met.
fn once_each<K: Eq + std::hash::Hash + Clone>(items: impl Iterator<Item = (K, bool)>) -> Vec<K> {
    let mut order: Vec<K> = Vec::new();
    let mut happened: std::collections::HashMap<K, bool> = Default::default();
    for (key, did) in items {
        match happened.get_mut(&key) {
            Some(any) => *any |= did,
            None => {
                order.push(key.clone());
                happened.insert(key, did);
            }
        }
    }
    order.into_iter().filter(|k| !happened[k]).collect()
}

/// The explicit search's report, and whether a racing engine answered first.
fn explicit(
    model: &Search,
    properties: &[Property],
    limits: explore::Limits,
    progress: &mut dyn FnMut(Progress),
) -> (Report, bool) {
    let graph = explore::explore(model, properties, limits, progress);
    let outcomes = properties
        .iter()
        .zip(&graph.targets)
        .map(|(p, target)| {
            if p.source.kind.is_liveness() {
                return liveness::outcome(model, &graph, p);
            }
            let trace = target.map(|id| trace::trace(model, &graph, id));
            outcome(p, target.is_some(), graph.complete, trace)
        })
        .collect();
    let mut findings = Vec::new();
    // Findings that say "never" are only true of a complete exploration.
    if graph.complete {
        findings = never_findings(model, &graph.entered, &graph.fired);
        if let Some(id) = graph.deadlock(model) {
            findings.push(Finding::Deadlock {
                waiting: waiting_names(model, &graph.world(id)),
                trace: trace::trace(model, &graph, id),
            });
        }
    }
    let stats = SearchStats {
        states: graph.len(),
        transitions: graph.edge_count(),
        complete: graph.complete,
        stopped: graph.stopped,
        bytes: graph.bytes(),
        bytes_per_state: graph.bytes_per_state(),
        packed_bytes_per_state: graph.packed_bytes_per_state() as f64,
        depth: graph.depth,
        values: model.values_met(),
        valuations: model.valuations(),
        engine: SearchEngine::Explicit.word(),
    };
    let report = Report {
        properties: outcomes,
        findings,
        stats,
        inexact: Vec::new(),
        unordered_clocks: Vec::new(),
        clocks_ordered: None,
    };
    (report, graph.overtaken)
}

/// `Machine.State` of each running machine of `world` not in a final state.
fn waiting_names(model: &Search, world: &world::SystemState) -> Vec<String> {
    explore::waiting(model, world)
        .into_iter()
        .map(|k| {
            let m = &model.machines[k];
            let state = &m.states[usize::from(world.machines[k].state)].name;
            format!("{}.{state}", m.name)
        })
        .collect()
}

/// The symbolic engine's report.
fn symbolic(
    model: &Search,
    properties: &[Property],
    options: Options,
) -> Result<Report, symbolic::Declined> {
    let found = symbolic::check(model, properties, options.max_memory)?;
    let complete = found.stopped == Stop::Explored;
    let outcomes = properties
        .iter()
        .zip(&found.targets)
        .zip(&found.liveness)
        .map(|((p, target), liveness)| {
            if let Some(outcome) = liveness {
                return outcome.clone();
            }
            let trace = target
                .as_ref()
                .map(|(initial, path)| trace::trace_of(model, *initial, path.iter().cloned()));
            outcome(p, target.is_some(), complete, trace)
        })
        .collect();
    let mut findings = Vec::new();
    if complete {
        findings = never_findings(model, &found.entered, &found.fired);
        if let Some(((initial, path), world)) = found.deadlock {
            findings.push(Finding::Deadlock {
                waiting: waiting_names(model, &world),
                trace: trace::trace_of(model, initial, path),
            });
        }
    }
    let states = found.states.min(usize::MAX as f64) as usize;
    Ok(Report {
        properties: outcomes,
        findings,
        stats: SearchStats {
            states,
            transitions: found.steps,
            complete,
            stopped: found.stopped,
            bytes: found.bytes,
            bytes_per_state: found.bytes as f64 / states.max(1) as f64,
            packed_bytes_per_state: 0.0,
            depth: found.steps,
            values: model.values_met(),
            valuations: model.valuations(),
            engine: SearchEngine::Symbolic.word(),
        },
        inexact: Vec::new(),
        unordered_clocks: Vec::new(),
        clocks_ordered: None,
    })
}
