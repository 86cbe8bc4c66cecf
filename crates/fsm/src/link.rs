//! Machines that start one another with arguments and wait on their outcomes, linked across
//! the machines of a behaviour (`docs/spec/behaviour.md` §3.3): what a machine's file alone
//! cannot say, lowered to the globals every back end already runs. A start `Dive:
//! restart(side = x)` becomes `Dive_side = x;` for each parameter, `Dive_landed = 0;` for each
//! outcome (a machine started again has no outcome yet, even before its first ringlet), then
//! the command; a label's `Dive.landed` reads `Dive_landed`; a machine with outcomes clears
//! them on arrival in its initial state, and the manifest's parameters of a machine that
//! starts with the behaviour are set first of that arrival.

use crate::code::{Expr, Statement};
use crate::control::Command;
use crate::interface::{fits, global_of, is_name, Interface};
use crate::model::{Action, ActivityOf, Machine, StateId};
use crate::start::{start_of, Start};

/// How the manifest starts a machine: with the behaviour or not, and the parameters it gives.
#[derive(Clone, Debug, Default)]
pub struct Launch {
    pub start: bool,
    pub params: Vec<(String, Expr)>,
}

/// Why machines do not fit together: in `machine` (an index into what [`link`] was given), at
/// `line` of its file, or of the manifest where `line` is `None`.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub struct LinkProblem {
    pub machine: usize,
    pub line: Option<usize>,
    pub message: String,
}

/// Lowers every start of a machine of the behaviour, every read of an outcome and the
/// manifest's parameters, and says what does not fit; `launches[i]` is how the manifest starts
/// `machines[i]`.
pub fn link(machines: &mut [Machine], launches: &[Launch]) -> Vec<LinkProblem> {
    let interfaces: Vec<(String, Interface)> = machines
        .iter()
        .map(|m| (m.name.clone(), m.interface.clone()))
        .collect();
    let mut linker = Linker {
        interfaces: &interfaces,
        problems: Vec::new(),
        given: vec![None; machines.len()],
        caller: String::new(),
        quiet: false,
    };
    linker.names();
    for (i, machine) in machines.iter_mut().enumerate() {
        linker.clashes(i, machine);
        linker.caller = machine.name.clone();
        linker.machine(i, machine);
    }
    for (i, machine) in machines.iter_mut().enumerate() {
        let launch = launches.get(i).cloned().unwrap_or_default();
        linker.launch(i, machine, &launch);
    }
    let mut problems = linker.problems;
    problems.sort();
    problems.dedup();
    problems
}

struct Linker<'i> {
    interfaces: &'i [(String, Interface)],
    problems: Vec<LinkProblem>,
    /// The first machine that starts each one with arguments, if one does.
    given: Vec<Option<String>>,
    /// The machine being linked: an argument reads its parameters as its globals.
    caller: String,
    /// Lowering a composite's activity again in a flat state that runs it: its problems were
    /// said once, at the composite.
    quiet: bool,
}

impl Linker<'_> {
    fn problem(&mut self, machine: usize, line: Option<usize>, message: String) {
        if self.quiet {
            return;
        }
        self.problems.push(LinkProblem {
            machine,
            line,
            message,
        });
    }

    fn interface(&self, machine: &str) -> Option<(usize, &Interface)> {
        let i = self.interfaces.iter().position(|(n, _)| n == machine)?;
        Some((i, &self.interfaces[i].1))
    }

    /// Each parameter and outcome its own global: two of one name (`Dive`'s `left_side` and
    /// `Dive_left`'s `side`), or a machine whose name is no identifier, cannot be lowered.
    fn names(&mut self) {
        let mut seen: Vec<(String, String)> = Vec::new();
        for (i, (owner, interface)) in self.interfaces.iter().enumerate() {
            let declared = (interface.params.iter().map(|p| (&p.name, p.line)))
                .chain(interface.outcomes.iter().map(|o| (&o.name, o.line)));
            for (name, line) in declared {
                let global = global_of(owner, name);
                let message = if !is_name(owner) {
                    format!("`{owner}` declares parameters or outcomes, which need a machine named by letters, digits and `_` (they become globals such as `{global}`)")
                } else if let Some((_, theirs)) = seen.iter().find(|(g, _)| *g == global) {
                    format!("`{owner}`'s `{name}` and {theirs} both become the global `{global}`: rename one")
                } else {
                    seen.push((global, format!("`{owner}`'s `{name}`")));
                    continue;
                };
                self.problems.push(LinkProblem {
                    machine: i,
                    line: Some(line),
                    message,
                });
            }
        }
    }

    /// A global that another machine's parameter or outcome becomes, set by this one's code.
    fn clashes(&mut self, i: usize, machine: &Machine) {
        for (j, (owner, interface)) in self.interfaces.iter().enumerate() {
            let names = interface.params.iter().map(|p| &p.name);
            for name in names.chain(interface.outcomes.iter().map(|o| &o.name)) {
                let global = global_of(owner, name);
                let in_state = machine.states.iter().find(|s| {
                    s.on_entry
                        .iter()
                        .chain(&s.on_exit)
                        .chain(&s.internal)
                        .any(|a| sets(a, &global))
                });
                let in_transition = machine
                    .transitions
                    .iter()
                    .find(|t| t.leaving.iter().flatten().any(|a| sets(a, &global)));
                let line = in_state.map(|s| s.line).or(in_transition.map(|t| t.line));
                if let (true, Some(line)) = (j != i, line) {
                    let message = format!("`{}` sets `{global}`, the global that `{owner}`'s `{name}` becomes: call the variable something else", machine.name);
                    self.problem(i, Some(line), message);
                }
            }
        }
    }

    fn machine(&mut self, i: usize, machine: &mut Machine) {
        // A chart's composites keep their activities as written for what draws them: lowered
        // the same way, so they stay the flat states' leading parts, and their problems said
        // there, once, not in each flat state that runs them.
        let Copies { written, leaving } = copies(machine);
        for c in &mut machine.composites {
            for list in [&mut c.on_entry, &mut c.on_exit, &mut c.internal] {
                self.actions(i, c.line, list, &[]);
            }
        }
        for (state, quiet) in machine.states.iter_mut().zip(&written) {
            let line = state.line;
            let lists = [&mut state.on_entry, &mut state.on_exit, &mut state.internal];
            for (list, quiet) in lists.into_iter().zip(quiet) {
                self.actions(i, line, list, quiet);
            }
        }
        for (t, quiet) in machine.transitions.iter_mut().zip(&leaving) {
            let line = t.line;
            if let Some(list) = &mut t.leaving {
                self.actions(i, line, list, quiet);
            }
            let mut wrong = Vec::new();
            t.rename_label(&mut |n| self.outcome(n, &mut wrong));
            for message in wrong {
                self.problem(i, Some(line), message);
            }
        }
    }

    /// A name `Dive.landed` where `Dive` is a machine of the behaviour: its outcome's global.
    fn outcome(&self, name: &str, wrong: &mut Vec<String>) -> Option<String> {
        let (owner, outcome) = name.split_once('.')?;
        let (_, interface) = self.interface(owner)?;
        if interface.outcome(outcome).is_some() {
            return Some(global_of(owner, outcome));
        }
        let names = interface.outcome_names();
        wrong.push(match names.as_slice() {
            [] => format!("`{name}`: machine `{owner}` announces no outcomes (a final state announces one with `outcome NAME`)"),
            _ => match proclaim_syntax::nearest(names.iter().copied(), outcome) {
                Some(near) => format!("`{name}`: `{owner}` has no outcome `{outcome}`; did you mean `{owner}.{near}`?"),
                None => format!("`{name}`: `{owner}` has no outcome `{outcome}` (its outcomes: {})", names.join(", ")),
            },
        });
        None
    }

    /// Lowers `list`, its problems said at `line`, but not for the actions `quiet` marks.
    fn actions(&mut self, i: usize, line: usize, list: &mut Vec<Action>, quiet: &[bool]) {
        let mut out = Vec::with_capacity(list.len());
        for (k, action) in std::mem::take(list).into_iter().enumerate() {
            self.quiet = quiet.get(k).copied().unwrap_or(false);
            match action {
                Action::Post { ty, content } => match self.interface(&ty) {
                    Some((j, _)) => out.extend(self.post(i, line, j, ty, content)),
                    None => out.push(Action::Post { ty, content }),
                },
                Action::Statement(mut s) => {
                    let mut wrong = Vec::new();
                    s.visit(&mut |inner| {
                        if let Statement::Assign { name, .. } = inner {
                            let outcome = name.split_once('.').filter(|(m, _)| self.interface(m).is_some());
                            if let Some((m, o)) = outcome {
                                wrong.push(format!("`{name} = …`: `{m}`'s outcome `{o}` is announced by its final states (`outcome {o}`), never set"));
                            }
                        }
                    });
                    s.rename(&mut |n| self.outcome(n, &mut wrong));
                    for message in wrong {
                        self.problem(i, Some(line), message);
                    }
                    let call = matches!(s, Statement::Expr(_));
                    self.statement(i, line, &mut s);
                    match s {
                        // A command on a line of its own stays one: the compiled targets
                        // queue a fixed number of commands, so none may sit in a block.
                        Statement::Block(body) if call => {
                            out.extend(body.into_iter().map(Action::Statement));
                        }
                        s => out.push(Action::Statement(s)),
                    }
                }
                other => out.push(other),
            }
        }
        self.quiet = false;
        *list = out;
    }

    /// A posting to machine `j`: a command, alone or with arguments.
    fn post(
        &mut self,
        i: usize,
        line: usize,
        j: usize,
        ty: String,
        content: String,
    ) -> Vec<Action> {
        let start = match start_of(&content) {
            Some(Ok(start)) => start,
            Some(Err(message)) => {
                self.problem(i, Some(line), format!("`{ty}: …`: {message}"));
                return vec![Action::Post { ty, content }];
            }
            None => match Command::parse(&content) {
                Some(command) => Start {
                    command,
                    arguments: Vec::new(),
                },
                None => return vec![Action::Post { ty, content }],
            },
        };
        let interface = &self.interfaces[j].1;
        let written_alone = start.arguments.is_empty() && !content.contains('(');
        if start.command != Command::Restart || interface.is_empty() {
            let message = match start.command {
                Command::On | Command::Restart if !interface.is_empty() => Some(format!("`{ty}` takes parameters or announces outcomes: start it with `{ty}: restart(…)` (`On` does nothing to a machine already running, which would then run with other arguments, or keep an outcome its caller waits on)")),
                _ if !start.arguments.is_empty() && interface.params.is_empty() => Some(format!("`{ty}: {content}`: `{ty}` takes no parameters")),
                _ if !start.arguments.is_empty() => Some(format!("`{ty}: {content}`: only `restart` gives a machine its parameters")),
                _ => None,
            };
            if let Some(message) = message {
                self.problem(i, Some(line), message);
            }
            // The command alone, as written when it was written alone.
            let word = if written_alone {
                content
            } else {
                start.command.word().to_string()
            };
            return vec![Action::Post { ty, content: word }];
        }
        let mut out = self.arguments(i, line, j, &start);
        let interface = &self.interfaces[j].1;
        for o in &interface.outcomes {
            out.push(assign(global_of(&ty, &o.name), Expr::Int(0)));
        }
        out.push(Action::Post {
            ty,
            content: start.command.word().to_string(),
        });
        out
    }

    /// The assignments a restart of machine `j` makes of its arguments, each read as the
    /// starting machine reads its code, in the order the parameters were declared; what is
    /// missing, unknown or of the wrong kind is a problem.
    fn arguments(&mut self, i: usize, line: usize, j: usize, start: &Start) -> Vec<Action> {
        let (ty, interface) = (&self.interfaces[j].0, &self.interfaces[j].1);
        let mut problems = Vec::new();
        for (name, value) in &start.arguments {
            match interface.param(name) {
                Some(p) if !fits(&p.ty, value) => problems.push(format!(
                    "`{ty}`'s `{name}` is {}, which `{value}` is not",
                    p.ty.name()
                )),
                Some(_) => {}
                None => problems.push(
                    match proclaim_syntax::nearest(
                        interface.params.iter().map(|p| p.name.as_str()),
                        name,
                    ) {
                        Some(near) => {
                            format!("`{ty}` has no parameter `{name}`; did you mean `{near}`?")
                        }
                        None => format!("`{ty}` has no parameter `{name}`"),
                    },
                ),
            }
        }
        let missing = interface.missing_from(&start.arguments);
        if !missing.is_empty() {
            let list: Vec<String> = missing.iter().map(|p| format!("{p} = …")).collect();
            problems.push(format!(
                "`{ty}` takes {}: start it with `{ty}: restart({})`",
                missing.join(", "),
                list.join(", ")
            ));
        }
        let mut out = Vec::new();
        let mut assigned: Vec<String> = Vec::new();
        for p in &interface.params {
            if let Some((_, value)) = start.arguments.iter().find(|(n, _)| *n == p.name) {
                let mut value = value.clone();
                let mut wrong = Vec::new();
                value.rename(&mut |n| self.read(n, &mut wrong));
                problems.extend(wrong);
                // The arguments are assigned one after another: one may not read a parameter
                // an earlier one has just set (a machine restarting itself, `b = a, a = b`).
                let mut early = Vec::new();
                value.visit_names(&mut |n, _| {
                    if assigned.iter().any(|a| a == n) {
                        early.push(n.to_string());
                    }
                });
                if !early.is_empty() {
                    problems.push(format!("`{ty}: restart(…)`: the argument for `{}` reads `{}`, which an argument before it has already set: copy them to variables of the machine's own first", p.name, early.join("`, `")));
                }
                let global = global_of(ty, &p.name);
                out.push(assign(global.clone(), value));
                assigned.push(global);
            }
        }
        if !start.arguments.is_empty() && self.given[j].is_none() {
            self.given[j] = Some(self.caller.clone());
        }
        for message in problems {
            self.problem(i, Some(line), message);
        }
        out
    }

    /// A name an argument reads: the starting machine's own parameter, or an outcome.
    fn read(&self, name: &str, wrong: &mut Vec<String>) -> Option<String> {
        let own = self
            .interface(&self.caller)
            .is_some_and(|(_, i)| i.param(name).is_some());
        if own {
            return Some(global_of(&self.caller, name));
        }
        self.outcome(name, wrong)
    }

    /// A command to a machine inside a statement (`restart("Dive");`, `post("Dive", "On")`):
    /// cleared outcomes before a restart; what a statement cannot give is a problem.
    fn statement(&mut self, i: usize, line: usize, s: &mut Statement) {
        match s {
            Statement::Block(body) => body.iter_mut().for_each(|s| self.statement(i, line, s)),
            Statement::For { body, .. } => self.statement(i, line, body),
            Statement::Expr(Expr::Call {
                function,
                arguments,
                ..
            }) => {
                let Some((target, word)) = commanded(function, arguments) else {
                    return;
                };
                let Some((_, interface)) = self.interface(&target) else {
                    return;
                };
                let message = match start_of(&word) {
                    Some(_) => Some(format!("`{target}`: arguments are given on a line of its own, `{target}: restart(…)`, not by a statement")),
                    None if interface.is_empty() => None,
                    None => match Command::parse(&word) {
                        Some(Command::On) => Some(format!("`{target}` takes parameters or announces outcomes: start it with `{target}: restart(…)` (`On` does nothing to a machine already running)")),
                        Some(Command::Restart) if !interface.params.is_empty() => Some(format!("`{target}` takes parameters, which a statement cannot give: restart it on a line of its own, `{target}: restart(…)`")),
                        _ => None,
                    },
                };
                if let Some(message) = message {
                    self.problem(i, Some(line), message);
                    return;
                }
                if Command::parse(&word) == Some(Command::Restart) && !interface.outcomes.is_empty()
                {
                    let mut block: Vec<Statement> = interface
                        .outcomes
                        .iter()
                        .map(|o| Statement::Assign {
                            name: global_of(&target, &o.name),
                            value: Expr::Int(0),
                        })
                        .collect();
                    block.push(s.clone());
                    *s = Statement::Block(block);
                }
            }
            _ => {}
        }
    }
}

/// The machine a call commands and the word it posts: `restart("Dive")` → `restart`,
/// `post("Dive", "On")` → `On`.
fn commanded(function: &str, arguments: &[Expr]) -> Option<(String, String)> {
    match (function, arguments) {
        (f, [Expr::Str(m)]) => Some((m.clone(), Command::from_function(f)?.word().to_string())),
        ("post", [Expr::Str(m), Expr::Str(word)]) => Some((m.clone(), word.clone())),
        _ => None,
    }
}

/// Whether an action (a statement in it, however deep) sets `name`.
fn sets(action: &Action, name: &str) -> bool {
    let Action::Statement(s) = action else {
        return false;
    };
    let mut found = false;
    s.visit(&mut |inner| {
        if let Statement::Assign { name: n, .. } | Statement::Declare { name: n, .. } = inner {
            found |= n == name;
        }
    });
    found
}

fn assign(name: String, value: Expr) -> Action {
    Action::Statement(Statement::Assign { name, value })
}

impl Linker<'_> {
    /// The manifest's parameters of machine `i`: every one for a machine that starts with the
    /// behaviour, none for one that does not, set first of the arrival in its initial state;
    /// that arrival clears its outcomes too (so each is a global from the start, 0 until
    /// announced).
    fn launch(&mut self, i: usize, machine: &mut Machine, launch: &Launch) {
        let interface = &self.interfaces[i].1;
        let name = machine.name.clone();
        let mut problems = Vec::new();
        for (p, value) in &launch.params {
            match interface.param(p) {
                None => problems.push(format!(
                    "the manifest gives `{name}` a parameter `{p}` it does not declare"
                )),
                Some(param) if !fits(&param.ty, value) => problems.push(format!(
                    "the manifest gives `{name}`'s `{p}` {value}, which is no {}",
                    param.ty.name()
                )),
                Some(_) => {}
            }
        }
        if !launch.start && !launch.params.is_empty() {
            problems.push(format!("the manifest gives `{name}` parameters but starts it with `start = false`: whoever starts it gives them (`{name}: restart(…)`)"));
        }
        if let Some(starter) = self.given[i]
            .as_ref()
            .filter(|_| launch.start && !launch.params.is_empty())
        {
            problems.push(format!("`{name}` is given its parameters by the manifest and by `{starter}`, which starts it: give them in one place"));
        }
        let missing = interface.missing_from(&launch.params);
        if launch.start && !missing.is_empty() {
            let list: Vec<String> = missing.iter().map(|p| format!("{p} = …")).collect();
            problems.push(format!("`{name}` starts with the behaviour and takes {}: give them in its `[[machine]]` entry (`params = {{ {} }}`), or start it from a machine with `start = false`", missing.join(", "), list.join(", ")));
        }
        for message in problems {
            self.problem(i, None, message);
        }
        let clears: Vec<Action> = interface
            .outcomes
            .iter()
            .map(|o| assign(global_of(&name, &o.name), Expr::Int(0)))
            .collect();
        let sets: Vec<Action> = interface
            .params
            .iter()
            .filter(|_| launch.start)
            .filter_map(|p| {
                let (_, value) = launch.params.iter().find(|(n, _)| *n == p.name)?;
                Some(assign(global_of(&name, &p.name), value.clone()))
            })
            .collect();
        // Every way into the initial state is an arrival in it (a chart has a flat state for
        // each set of composites a move enters, all of one name).
        let initial = machine.state(machine.initial).map(|s| s.name.clone());
        let ways: Vec<StateId> = (machine.states.iter())
            .filter(|s| Some(&s.name) == initial.as_ref())
            .map(|s| s.id)
            .collect();
        for id in ways {
            arrive_with(machine, id, clears.clone());
            // The parameters before anything of the machine runs, its composites' OnEntry too.
            if let Some(state) = machine.states.iter_mut().find(|s| s.id == id) {
                state.on_entry.splice(0..0, sets.iter().cloned());
            }
        }
    }
}

/// Puts `sets` into the OnEntry of flat state `id` after what the composites it arrives
/// through run (so a chart's drawing still tells theirs from its own).
fn arrive_with(machine: &mut Machine, id: StateId, sets: Vec<Action>) {
    if sets.is_empty() {
        return;
    }
    let Some(at) = machine.states.iter().position(|s| s.id == id) else {
        return;
    };
    let mut around = Vec::new();
    let mut inside = machine.composite_of(&machine.states[at]);
    while let Some(c) = inside {
        around.push(c);
        inside = machine.composites[c].parent;
    }
    let entered = machine.states[at].arrives_through.min(around.len());
    let lead: usize = around[..entered]
        .iter()
        .map(|&c| machine.composites[c].on_entry.len())
        .sum();
    let entry = &mut machine.states[at].on_entry;
    let lead = lead.min(entry.len());
    entry.splice(lead..lead, sets);
}

/// Which actions of each flat state's activities (entry, exit, internal) and of each
/// transition's leaving are copies of what a composite wrote (or, leaving, of the source's
/// OnExit), found before anything is lowered.
struct Copies {
    written: Vec<[Vec<bool>; 3]>,
    leaving: Vec<Vec<bool>>,
}

fn copies(machine: &Machine) -> Copies {
    let written = machine
        .states
        .iter()
        .map(|s| {
            let sections: [(&Vec<Action>, ActivityOf); 3] = [
                (&s.on_entry, |c| &c.on_entry),
                (&s.on_exit, |c| &c.on_exit),
                (&s.internal, |c| &c.internal),
            ];
            sections.map(|(list, section)| {
                let from = |a| machine.composite_writing(s, a, section).is_some();
                list.iter().map(from).collect()
            })
        })
        .collect();
    let leaving = machine
        .transitions
        .iter()
        .map(|t| {
            let source = machine.state(t.source);
            let exits = |a: &Action| {
                source.is_some_and(|s| {
                    s.on_exit.contains(a)
                        || machine.composite_writing(s, a, |c| &c.on_exit).is_some()
                })
            };
            t.leaving.iter().flatten().map(exits).collect()
        })
        .collect();
    Copies { written, leaving }
}
