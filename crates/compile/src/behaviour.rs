//! A behaviour planned for compiling, in stages: what a compiled program cannot have is refused
//! (with its file and line), the theories are tabulated, the variables get slots, and each
//! machine's states become a plan of conditions and steps (`plan.rs`) that a printer writes in
//! its language: `compile_behaviour` prints C, `compile_behaviour_rust` a Cargo project.

use crate::activity::{conversion, Activity, Variable, Variables};
use crate::c::c_identifier;
use crate::plan::{
    Answer, BoardValue, Condition, Conversion, Drawing, Input, MachinePlan, Output, Plan,
    PlannedTheory, StatePlan, Step, Suppressed, TransitionPlan,
};
use crate::refusal::{refuse, Language, Refusal};
use crate::tabulate::{compile, Domain};
use proclaim_behaviour::{Behaviour, Schedule, MANIFEST};
use proclaim_fsm::control::running_type;
use proclaim_fsm::names::Names;
use proclaim_fsm::{Action, BinOp, Expr, Statement, UnOp, TIME_TESTS};
use proclaim_lower::RingletPlan;
use std::collections::HashMap;

/// The files of a compiled behaviour: name (a path relative to the output folder) and text.
pub struct CBehaviour {
    pub files: Vec<(String, String)>,
}

/// Compiles `behaviour` to freestanding C (its theories over true/false/unknown inputs, its
/// machines as code) with the host harness `main.c`.
pub fn compile_behaviour(behaviour: &Behaviour) -> Result<CBehaviour, Refusal> {
    let plan = plan_behaviour(behaviour, Language::C)?;
    Ok(CBehaviour {
        files: crate::print_c::behaviour_files(&plan),
    })
}

/// The files of a behaviour compiled to a Cargo project: path in the project and text.
pub struct RustBehaviour {
    pub files: Vec<(String, String)>,
}

/// Compiles `behaviour` to a Cargo project whose machines are Rust code. It carries its own copy
/// of `proclaim-runtime` and builds with crates from crates.io alone; given `whiteboard` (the
/// root of this repository, [`source_repository`]) it can run on a whiteboard too (`--monitor`,
/// `--listen`, `--connect`), depending by path on that repository's `proclaim-host-board`.
pub fn compile_behaviour_rust(
    behaviour: &Behaviour,
    whiteboard: Option<&std::path::Path>,
) -> Result<RustBehaviour, Refusal> {
    let plan = plan_behaviour(behaviour, Language::Rust)?;
    Ok(RustBehaviour {
        files: crate::print_rust::project_files(&plan, whiteboard),
    })
}

/// The root of the repository this crate was built from, whose crates a compiled Rust
/// behaviour on a whiteboard depends on by path; `None` when it is not on this machine.
pub fn source_repository() -> Option<std::path::PathBuf> {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    root.join("crates/runner/Cargo.toml")
        .exists()
        .then(|| root.canonicalize().unwrap_or(root))
}

/// The plan of `behaviour`, or the first thing in it a compiled program cannot have.
pub(crate) fn plan_behaviour(behaviour: &Behaviour, target: Language) -> Result<Plan, Refusal> {
    refuse_what_no_target_has(behaviour)?;
    let (theories, outputs, inputs) = plan_theories(behaviour)?;
    let outside = outputs
        .iter()
        .filter(|o| matches!(o.answer, Answer::Outside { .. }))
        .count();
    let sensors = sensor_atoms(behaviour);
    let names = Names::of(behaviour.machines.iter().map(|m| &m.machine));
    let mut externs = plan_externs(behaviour, &names, &outputs)?;
    let (slots, own, globals) = plan_slots(behaviour, &names)?;
    plan_board_reads(behaviour, &own, &globals, &outputs, &mut externs);
    let machine_names: Vec<String> = behaviour
        .machines
        .iter()
        .map(|m| m.machine.name.clone())
        .collect();
    let input_types: Vec<String> = inputs.iter().map(|i| i.ty.clone()).collect();
    let mut counters = Counters {
        longest_text: 1,
        loops: 0,
        commands: 0,
        composites: Vec::new(),
    };
    let mut machines = Vec::new();
    for (m, loaded) in behaviour.machines.iter().enumerate() {
        let seen = Seen {
            file: behaviour.files.show(&loaded.file),
            variables: Variables {
                own: own[m].clone(),
                board: externs
                    .iter()
                    .enumerate()
                    .map(|(number, b)| (b.name.clone(), (number, b.bound)))
                    .collect(),
                globals: globals.clone(),
            },
            machines: &machine_names,
            inputs: &input_types,
            outputs: &outputs,
            target,
        };
        let composites_from = counters.composites.len();
        counters
            .composites
            .extend(loaded.machine.composites.iter().map(|_| m));
        machines.push(plan_machine(loaded, &seen, composites_from, &mut counters)?);
    }
    let period_ms = period_ms(behaviour)?;
    let suppressed = plan_suppressed(behaviour)?;
    Ok(Plan {
        name: behaviour.name.clone(),
        theories,
        outputs,
        inputs,
        outside,
        sensors,
        script: own_script(behaviour),
        slots,
        externs,
        machines,
        period_ms,
        answer_timeout_ms: u64::try_from(behaviour.answer_timeout.as_millis()).unwrap_or(u64::MAX),
        longest_text: counters.longest_text,
        commands: counters.commands,
        suppressed,
        composites: counters.composites,
        ranges: (behaviour.ranges.iter())
            .map(|r| (r.ty.clone(), r.low, r.high))
            .collect(),
    })
}

/// The manifest's `[suppress]` in name order (the order the runner releases holds in), each
/// hold in whole milliseconds (a target's clock counts milliseconds).
fn plan_suppressed(behaviour: &Behaviour) -> Result<Vec<Suppressed>, Refusal> {
    let mut suppressed = Vec::new();
    for (ty, hold) in &behaviour.suppress {
        if hold.as_micros() % 1000 != 0 {
            return Err(refuse(
                &behaviour.files.show(MANIFEST),
                manifest_line(behaviour, &[ty.as_str()]),
                format!("the hold of `{ty}` is not whole milliseconds"),
            ));
        }
        suppressed.push(Suppressed {
            ty: ty.clone(),
            hold_ms: hold.as_millis() as u64,
        });
    }
    suppressed.sort_by(|a, b| a.ty.cmp(&b.ty));
    Ok(suppressed)
}

/// The manifest's line that starts with one of `starts`, for a refusal to point at.
fn manifest_line(behaviour: &Behaviour, starts: &[&str]) -> usize {
    behaviour
        .files
        .read(MANIFEST)
        .unwrap_or_default()
        .lines()
        .position(|l| starts.iter().any(|s| l.trim_start().starts_with(s)))
        .map_or(1, |i| i + 1)
}

/// Refuses the manifest's parts that no target runs. A Prolog or program expert is no such part:
/// a compiled program takes its atoms from the run's script, as a sensor's, which is how
/// `proclaim run --virtual-clock` runs it too (a process on the real clock is left out when the
/// script sets its atoms).
fn refuse_what_no_target_has(behaviour: &Behaviour) -> Result<(), Refusal> {
    if behaviour.manifest.schedule != Schedule::Rounds {
        return Err(refuse(
            &behaviour.files.show(MANIFEST),
            manifest_line(behaviour, &["schedule"]),
            "schedule = \"concurrent\"".into(),
        ));
    }
    Ok(())
}

/// The ring period in whole milliseconds (a target's clock counts milliseconds).
fn period_ms(behaviour: &Behaviour) -> Result<u64, Refusal> {
    if behaviour.ring_period.as_micros() % 1000 != 0 {
        return Err(refuse(
            &behaviour.files.show(MANIFEST),
            manifest_line(behaviour, &["ring_period"]),
            "a ring period that is not whole milliseconds".into(),
        ));
    }
    Ok(behaviour.ring_period.as_millis() as u64)
}

type PlannedTheories = (Vec<PlannedTheory>, Vec<Output>, Vec<Input>);

/// The line a theory's refusal points at: its first clause fact's, the one thing a theory
/// written for a behaviour is refused for, else the first.
fn refused_line(behaviour: &Behaviour, loaded: &proclaim_behaviour::LoadedTheory) -> usize {
    let span = loaded.theory.axioms().iter().find_map(|c| c.span);
    match (span, behaviour.files.read(&loaded.file)) {
        (Some(span), Ok(text)) => {
            let at = (span.start as usize).min(text.len());
            text[..at].matches('\n').count() + 1
        }
        _ => 1,
    }
}

/// Each theory tabulated over true/false/unknown inputs; its outputs and the posting types of
/// its inputs.
fn plan_theories(behaviour: &Behaviour) -> Result<PlannedTheories, Refusal> {
    let mut theories = Vec::new();
    let mut outputs: Vec<Output> = Vec::new();
    let mut inputs = Vec::new();
    let mut offset = 0;
    for (t, loaded) in behaviour.theories.iter().enumerate() {
        let file = behaviour.files.show(&loaded.file);
        let compiled = compile(&loaded.theory, loaded.limits, Domain::Ternary)
            .map_err(|e| refuse(&file, refused_line(behaviour, loaded), e.to_string()))?;
        for (index, atom) in compiled.inputs.iter().enumerate() {
            let ty = loaded
                .mapping
                .get(atom)
                .cloned()
                .unwrap_or_else(|| atom.clone());
            inputs.push(Input {
                ty,
                variable: offset + 2 * index,
                group: group_of(&loaded.theory, &compiled.inputs, index)
                    .map(|other| offset + 2 * other)
                    .collect(),
            });
        }
        for (index, name) in compiled.outputs.iter().enumerate() {
            if outputs.iter().any(|x| &x.name == name) {
                let what = format!("output `{name}` answered by two theories");
                return Err(refuse(&file, 1, what));
            }
            outputs.push(Output {
                name: name.clone(),
                answer: Answer::Theory {
                    theory: t,
                    index,
                    offset,
                },
                expert: loaded.name.clone(),
            });
        }
        offset += compiled.variables();
        let prefix = format!("theory_{}", c_identifier(&loaded.name));
        theories.push(PlannedTheory { compiled, prefix });
    }
    // The atoms the manifest's script or a sensor answers and no theory answers or reads come
    // from outside: from a run's script, as the interpreter's impersonator answers them then.
    let mut scripted: Vec<String> = behaviour
        .script
        .as_ref()
        .map(|s| s.atoms())
        .unwrap_or_default();
    scripted.extend(
        sensor_atoms(behaviour)
            .into_iter()
            .flat_map(|(_, atoms)| atoms),
    );
    scripted.sort();
    scripted.dedup();
    for atom in scripted {
        // A theory's input the script sets is both: the theory reads it, and a label asking it
        // is answered by the impersonator.
        if outputs.iter().any(|o| o.name == atom) {
            continue;
        }
        inputs.push(Input {
            ty: atom.clone(),
            variable: offset,
            group: Vec::new(),
        });
        outputs.push(Output {
            name: atom,
            answer: Answer::Outside { variable: offset },
            expert: "impersonator".into(),
        });
        offset += 2;
    }
    Ok((theories, outputs, inputs))
}

/// The places in `inputs` (a compiled theory's, in declaration order) of the other atoms of
/// input `index`'s group; none for an input of its own.
fn group_of<'a>(
    theory: &'a proclaim_cdl::Theory,
    inputs: &'a [String],
    index: usize,
) -> impl Iterator<Item = usize> + 'a {
    let group = theory.inputs().iter().find(|g| {
        g.atoms
            .iter()
            .any(|&a| theory.atom_name(a) == inputs[index])
    });
    group
        .into_iter()
        .flat_map(|g| g.atoms.iter())
        .filter_map(move |&a| inputs.iter().position(|name| name == theory.atom_name(a)))
        .filter(move |&other| other != index)
}

/// The manifest's `[impersonator]` script: its file as shown and its text.
fn own_script(behaviour: &Behaviour) -> Option<(String, String)> {
    let file = &behaviour.manifest.impersonator.as_ref()?.script;
    let text = behaviour.files.read(file).ok()?;
    Some((behaviour.files.show(file), text))
}

/// Each module of the behaviour whose atoms a compiled program takes from its script (a sensor
/// wrapper, a Prolog or program expert: its name) and the atoms it answers.
fn sensor_atoms(behaviour: &Behaviour) -> Vec<(String, Vec<String>)> {
    proclaim_behaviour::modules(behaviour)
        .into_iter()
        .filter(|m| {
            matches!(
                m.kind,
                proclaim_behaviour::ModuleKind::Sensor(_)
                    | proclaim_behaviour::ModuleKind::Program { .. }
            )
        })
        .map(|m| (m.decl.name.clone(), m.decl.answers.clone()))
        .collect()
}

/// The behaviour's whiteboard variables ([`Names::externs`]); one that is also a theory's
/// answer, a machine's name or a type under subsumption is refused where it is bound (a
/// compiled program keeps those apart).
fn plan_externs(
    behaviour: &Behaviour,
    names: &Names,
    outputs: &[Output],
) -> Result<Vec<BoardValue>, Refusal> {
    for loaded in &behaviour.machines {
        let file = behaviour.files.show(&loaded.file);
        for state in &loaded.machine.states {
            for s in state_statements(&loaded.machine, state) {
                let Statement::Extern { name, .. } = s else {
                    continue;
                };
                if let Some(clash) = board_clash(behaviour, outputs, name) {
                    let what = format!("`extern {name}`, which is also {clash} (a compiled behaviour keeps a whiteboard variable's value apart from those)");
                    return Err(refuse(&file, state.line, what));
                }
            }
        }
    }
    Ok(names
        .externs
        .iter()
        .map(|name| BoardValue {
            name: name.clone(),
            bound: true,
            status_of: None,
        })
        .collect())
}

/// What a whiteboard type read as a value is besides, that a compiled program keeps apart: a
/// theory's answer (its expert's postings), a machine's name (its control commands), or a type
/// under subsumption.
fn board_clash(behaviour: &Behaviour, outputs: &[Output], name: &str) -> Option<&'static str> {
    if outputs
        .iter()
        .any(|o| o.name == name && matches!(o.answer, Answer::Theory { .. }))
    {
        Some("a theory's answer")
    } else if behaviour.machines.iter().any(|m| m.machine.name == name) {
        Some("a machine's name")
    } else if behaviour.suppress.iter().any(|(ty, _)| ty == name) {
        Some("a type under subsumption")
    } else {
        None
    }
}

/// Adds to `board` every other whiteboard type a machine reads: a name in an expression that
/// is no variable of that machine, a label atom the script or a module answers from outside
/// (also a value on the board), and a label atom nobody answers (the runner reads its newest
/// posting then: a machine's `NameIsRunning`, a type a machine posts, or nothing at all). A
/// name that clashes (`board_clash`) is left out, so that reading it is refused where it is
/// read.
fn plan_board_reads(
    behaviour: &Behaviour,
    own: &[HashMap<String, Variable>],
    globals: &HashMap<String, Variable>,
    outputs: &[Output],
    board: &mut Vec<BoardValue>,
) {
    for (m, loaded) in behaviour.machines.iter().enumerate() {
        let mut read = |name: &str, asked: bool| {
            // A theory's answer is its expert's alone; an atom from outside is also a value on
            // the board, whose postings are news to a ringlet that read the snapshot without
            // asking it.
            let answered = asked
                && outputs
                    .iter()
                    .any(|o| o.name == name && matches!(o.answer, Answer::Theory { .. }));
            if answered
                || own[m].contains_key(name)
                || globals.contains_key(name)
                || board.iter().any(|b| b.name == name)
                || board_clash(behaviour, outputs, name).is_some()
            {
                return;
            }
            let status_of = behaviour
                .machines
                .iter()
                .position(|other| running_type(&other.machine.name) == name);
            board.push(BoardValue {
                name: name.to_string(),
                bound: false,
                status_of,
            });
        };
        for state in &loaded.machine.states {
            for s in state_statements(&loaded.machine, state) {
                for e in s.expressions() {
                    e.visit_names(&mut |name, _| read(name, false));
                }
            }
        }
        for t in &loaded.machine.transitions {
            t.label
                .visit_names(&mut |name, condition| read(name, condition));
        }
    }
}

type Slots = (
    Vec<bool>,
    Vec<HashMap<String, Variable>>,
    HashMap<String, Variable>,
);

/// Slots: each machine's own variables, then the globals ([`Names`]). An own variable starts
/// as its first declared type and converts to its last; a type no target has is refused
/// where it is declared.
fn plan_slots(behaviour: &Behaviour, names: &Names) -> Result<Slots, Refusal> {
    for loaded in &behaviour.machines {
        let file = behaviour.files.show(&loaded.file);
        for state in &loaded.machine.states {
            for s in state_statements(&loaded.machine, state) {
                if let Statement::Declare { ty, .. } = s {
                    conversion(ty).map_err(|what| refuse(&file, state.line, what))?;
                }
            }
        }
    }
    // Every declared type converts: one that does not was refused above.
    let converts = |ty| conversion(ty).unwrap_or(Conversion::Kept);
    let mut slots: Vec<bool> = Vec::new();
    let mut own: Vec<HashMap<String, Variable>> = Vec::new();
    for variables in &names.own {
        let mut mine: HashMap<String, Variable> = HashMap::new();
        for v in variables {
            let variable = Variable {
                slot: slots.len(),
                conversion: converts(&v.last),
            };
            mine.insert(v.name.clone(), variable);
            slots.push(converts(&v.first) == Conversion::Truth);
        }
        own.push(mine);
    }
    let mut globals: HashMap<String, Variable> = HashMap::new();
    for name in &names.globals {
        let variable = Variable {
            slot: slots.len(),
            conversion: Conversion::Kept,
        };
        globals.insert(name.clone(), variable);
        slots.push(false);
    }
    Ok((slots, own, globals))
}

/// What one machine's activities and labels see while they are planned.
struct Seen<'a> {
    file: String,
    variables: Variables,
    machines: &'a [String],
    inputs: &'a [String],
    outputs: &'a [Output],
    target: Language,
}

/// What grows across the whole behaviour as it is planned.
struct Counters {
    longest_text: usize,
    loops: usize,
    commands: usize,
    /// Each composite state's machine, numbered across the behaviour.
    composites: Vec<usize>,
}

/// Machine `loaded`, whose composite states are numbered from `composites_from`.
fn plan_machine(
    loaded: &proclaim_behaviour::LoadedMachine,
    seen: &Seen<'_>,
    composites_from: usize,
    counters: &mut Counters,
) -> Result<MachinePlan, Refusal> {
    let machine = &loaded.machine;
    if let Some(u) = machine.unread.first() {
        let what = format!("the label `{}` that did not read", u.label);
        return Err(refuse(&seen.file, u.line, what));
    }
    let states = machine
        .states
        .iter()
        .map(|state| plan_state(machine, state, seen, composites_from, counters))
        .collect::<Result<_, _>>()?;
    Ok(MachinePlan {
        name: machine.name.clone(),
        initial: machine.initial,
        start: loaded.start,
        priority: loaded.priority,
        states,
        drawing: Drawing {
            transitions: machine
                .transitions
                .iter()
                .map(|t| (t.source, t.target, t.shown().to_string(), t.stays))
                .collect(),
            dot: proclaim_fsm::to_dot(machine),
        },
    })
}

fn plan_state(
    machine: &proclaim_fsm::Machine,
    state: &proclaim_fsm::State,
    seen: &Seen<'_>,
    composites_from: usize,
    counters: &mut Counters,
) -> Result<StatePlan, Refusal> {
    let mut activity = Activity {
        file: &seen.file,
        line: state.line,
        state: &state.name,
        variables: &seen.variables,
        machines: seen.machines,
        inputs: seen.inputs,
        target: seen.target,
        longest_text: &mut counters.longest_text,
        loops: &mut counters.loops,
        commands: &mut counters.commands,
    };
    let plan = RingletPlan::of_state(machine, state);
    let entry = activity.actions(plan.arriving())?;
    let (leavings, leaves) = plan_leavings(&plan, &mut activity)?;
    let staying = activity.actions(plan.staying())?;
    let mut labels = Labels {
        outputs: seen.outputs,
        read: Vec::new(),
        due: Vec::new(),
        composites_from,
        reads_globals: false,
        reads_externs: Vec::new(),
    };
    let mut transitions = Vec::new();
    for (arm, leaving) in plan.arms().zip(leaves) {
        let t = arm.transition;
        activity.line = t.line;
        transitions.push(TransitionPlan {
            condition: labels.condition(&t.label, &mut activity)?,
            target: t.target,
            label: t.shown().to_string(),
            leaving,
            enters: t.enters.iter().map(|c| composites_from + c).collect(),
            stays: arm.stays(),
        });
    }
    let Labels {
        mut read,
        due,
        reads_globals,
        mut reads_externs,
        ..
    } = labels;
    read.sort_unstable();
    read.dedup();
    reads_externs.sort_unstable();
    reads_externs.dedup();
    Ok(StatePlan {
        id: state.id,
        name: state.name.clone(),
        entry,
        leavings,
        staying,
        is_final: plan.is_final(),
        transitions,
        reads: read,
        due_ms: due,
        reads_globals,
        reads_externs,
    })
}

/// What `plan`'s arms run as they fire, each activity planned once (arms that leave by the
/// same activity share its steps), and the place of each arm's among them.
fn plan_leavings(
    plan: &RingletPlan<'_>,
    activity: &mut Activity<'_>,
) -> Result<(Vec<Vec<Step>>, Vec<usize>), Refusal> {
    let mut planned: Vec<&[Action]> = Vec::new();
    let mut leavings = Vec::new();
    let mut leaves = Vec::new();
    for arm in plan.arms() {
        match planned.iter().position(|l| std::ptr::eq(*l, arm.leaving())) {
            Some(at) => leaves.push(at),
            None => {
                leaves.push(leavings.len());
                leavings.push(activity.actions(arm.leaving())?);
                planned.push(arm.leaving());
            }
        }
    }
    Ok((leavings, leaves))
}

/// What a state's labels read, gathered as they are planned: the theory outputs they ask, the
/// times their time tests come due, whether they read a global, and the whiteboard variables
/// they read.
struct Labels<'a> {
    outputs: &'a [Output],
    read: Vec<usize>,
    due: Vec<(u64, Option<usize>)>,
    /// Where the machine's composites begin among the behaviour's: a time test's clock (the
    /// machine's composite) is numbered across the behaviour.
    composites_from: usize,
    reads_globals: bool,
    reads_externs: Vec<usize>,
}

impl Labels<'_> {
    /// A label as the runner proves it: a name standing as a condition is a variable's truth,
    /// else a theory output asked; `!`, `&&`, `||` over conditions; anything else (comparisons,
    /// arithmetic) a value's truth, computed on the spot.
    fn condition(
        &mut self,
        label: &Expr,
        activity: &mut Activity<'_>,
    ) -> Result<Condition, Refusal> {
        self.note_globals(label, activity);
        Ok(match label {
            Expr::Bool(b) => Condition::Constant(*b),
            Expr::Name(n) if activity.variables.is_variable(n) => {
                Condition::Truth(activity.value(label)?.0)
            }
            Expr::Name(_)
                if proclaim_fsm::team_words(label) == [proclaim_fsm::TeamWord::Quorum] =>
            {
                return Err(activity.team_refusal(label, "the team's quorum"));
            }
            Expr::Name(n) => {
                if let Some(k) = self.outputs.iter().position(|o| &o.name == n) {
                    self.read.push(k);
                    Condition::Ask(k)
                } else if let Some(number) = activity.variables.extern_number(n) {
                    Condition::AskPosted {
                        number,
                        atom: n.clone(),
                    }
                } else {
                    return Err(refuse(activity.file, activity.line, format!("the label atom `{n}`, which no theory, script or sensor answers and whose postings a compiled program does not keep (a machine's name or a type under subsumption)")));
                }
            }
            Expr::Unary {
                op: UnOp::Not,
                operand,
            } => Condition::Not(Box::new(self.condition(operand, activity)?)),
            Expr::Binary {
                op: op @ (BinOp::And | BinOp::Or),
                left,
                right,
            } => Condition::Both {
                and: *op == BinOp::And,
                left: Box::new(self.condition(left, activity)?),
                right: Box::new(self.condition(right, activity)?),
            },
            Expr::Call {
                function,
                arguments,
                clock,
            } if arguments.len() == 1 && TIME_TESTS.iter().any(|(t, _)| t == function) => {
                let clock = clock.map(|c| self.composites_from + c);
                self.time_test(label, function, &arguments[0], clock, activity)?
            }
            other => Condition::Truth(activity.value(other)?.0),
        })
    }

    /// A time test over a constant time in whole milliseconds.
    fn time_test(
        &mut self,
        label: &Expr,
        function: &str,
        argument: &Expr,
        clock: Option<usize>,
        activity: &Activity<'_>,
    ) -> Result<Condition, Refusal> {
        // The µs one unit of the argument stands for (1 for timeout, 1000 for after_ms).
        let unit = TIME_TESTS
            .iter()
            .find(|(t, _)| *t == function)
            .map_or(1, |(_, us)| *us as u64);
        let micros = match argument {
            Expr::Int(n) if *n >= 0 => (*n as u64).checked_mul(unit),
            Expr::Duration(d) => Some(*d),
            _ => None,
        };
        let Some(micros) = micros.filter(|us| us % 1000 == 0) else {
            return Err(refuse(activity.file, activity.line, format!("`{label}` (only a constant time in whole milliseconds: a target's clock counts milliseconds)")));
        };
        self.due.push((micros / 1000, clock));
        Ok(Condition::Elapsed {
            ms: micros / 1000,
            composite: clock,
        })
    }

    fn note_globals(&mut self, label: &Expr, activity: &Activity<'_>) {
        label.visit_names(&mut |name, _| {
            if matches!(activity.variables.lookup(name), Some((_, true))) {
                self.reads_globals = true;
            }
            if let Some(number) = activity.variables.extern_number(name) {
                self.reads_externs.push(number);
            }
        });
    }
}

/// The statements of a state's activities, those inside blocks and loops included.
fn state_statements<'m>(
    machine: &'m proclaim_fsm::Machine,
    state: &'m proclaim_fsm::State,
) -> Vec<&'m Statement> {
    let mut out = Vec::new();
    let activities = RingletPlan::of_state(machine, state).activities();
    for action in activities.into_iter().flatten() {
        if let Action::Statement(s) = action {
            s.visit(&mut |inner| out.push(inner));
        }
    }
    out
}
