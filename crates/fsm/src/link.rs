//! Machines that start one another with arguments and wait on their outcomes, linked across
//! the machines of a behaviour (`docs/spec/behaviour.md` §3.3): what a machine's file alone
//! cannot say, lowered to the globals every back end already runs. A start `Dive: On(side =
//! x)` becomes `Dive_side = x;` for each parameter, `Dive_saved = 0;` for each outcome (a
//! machine started again has no outcome yet, even before its first ringlet), then the command;
//! a label's `Dive.saved` reads `Dive_saved`; the manifest's parameters of a machine that
//! starts with the behaviour are set first of its initial state's OnEntry.

use crate::code::{Expr, Statement};
use crate::control::Command;
use crate::interface::{global_of, start_of, Interface};
use crate::model::{Action, Machine};

/// How the manifest starts a machine: with the behaviour or not, and the parameters it gives.
#[derive(Clone, Debug, Default)]
pub struct Launch {
    pub start: bool,
    pub params: Vec<(String, Expr)>,
}

/// Why machines do not fit together: in `machine` (an index into what [`link`] was given), at
/// `line` of its file, or of the manifest where `line` is `None`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LinkProblem {
    pub machine: usize,
    pub line: Option<usize>,
    pub message: String,
}

/// Lowers every start of a machine with parameters or outcomes, every label reading an
/// outcome and the manifest's parameters, and says what does not fit; `launches[i]` is how
/// the manifest starts `machines[i]`.
pub fn link(machines: &mut [Machine], launches: &[Launch]) -> Vec<LinkProblem> {
    let interfaces: Vec<(String, Interface)> = machines
        .iter()
        .map(|m| (m.name.clone(), m.interface.clone()))
        .collect();
    if interfaces.iter().all(|(_, i)| i.is_empty()) {
        return Vec::new();
    }
    let mut linker = Linker {
        interfaces: &interfaces,
        problems: Vec::new(),
        given: vec![false; machines.len()],
    };
    for (i, machine) in machines.iter_mut().enumerate() {
        linker.clashes(i, machine);
        linker.machine(i, machine);
    }
    for (i, machine) in machines.iter_mut().enumerate() {
        let launch = launches.get(i).cloned().unwrap_or_default();
        linker.launch(i, machine, &launch);
    }
    linker.problems
}

struct Linker<'i> {
    interfaces: &'i [(String, Interface)],
    problems: Vec<LinkProblem>,
    /// Whether some machine starts each one with arguments.
    given: Vec<bool>,
}

impl Linker<'_> {
    fn problem(&mut self, machine: usize, line: Option<usize>, message: String) {
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

    /// A global that a parameter or outcome becomes, set by a machine's own code elsewhere.
    fn clashes(&mut self, i: usize, machine: &Machine) {
        let mut set = Vec::new();
        for s in machine.statements() {
            if let Statement::Assign { name, .. } | Statement::Declare { name, .. } = s {
                set.push(name.clone());
            }
        }
        for (j, (owner, interface)) in self.interfaces.iter().enumerate() {
            if j == i {
                continue;
            }
            let names = interface.params.iter().map(|p| &p.name);
            for name in names.chain(interface.outcomes.iter().map(|o| &o.name)) {
                let global = global_of(owner, name);
                if set.contains(&global) {
                    self.problems.push(LinkProblem {
                        machine: i,
                        line: None,
                        message: format!("`{}` sets `{global}`, the global that `{owner}`'s `{name}` becomes: call the variable something else", machine.name),
                    });
                }
            }
        }
    }

    fn machine(&mut self, i: usize, machine: &mut Machine) {
        for state in &mut machine.states {
            let line = state.line;
            for list in [&mut state.on_entry, &mut state.on_exit, &mut state.internal] {
                self.actions(i, line, list);
            }
        }
        for t in &mut machine.transitions {
            let line = t.line;
            if let Some(list) = &mut t.leaving {
                self.actions(i, line, list);
            }
            let mut wrong = Vec::new();
            t.label.rename(&mut |n| self.outcome(n, &mut wrong));
            for message in wrong {
                self.problem(i, Some(line), message);
            }
        }
    }

    /// A name `Dive.saved` where `Dive` is a machine of the behaviour: its outcome's global.
    fn outcome(&self, name: &str, wrong: &mut Vec<String>) -> Option<String> {
        let (owner, outcome) = name.split_once('.')?;
        let (_, interface) = self.interface(owner)?;
        if interface.outcome(outcome).is_some() {
            return Some(global_of(owner, outcome));
        }
        let names: Vec<&str> = interface.outcomes.iter().map(|o| o.name.as_str()).collect();
        wrong.push(match names.as_slice() {
            [] => format!("`{name}`: machine `{owner}` announces no outcomes (a state announces one with `outcome NAME`)"),
            _ => match proclaim_syntax::nearest(names.iter().copied(), outcome) {
                Some(near) => format!("`{name}`: `{owner}` has no outcome `{outcome}`; did you mean `{owner}.{near}`?"),
                None => format!("`{name}`: `{owner}` has no outcome `{outcome}` (its outcomes: {})", names.join(", ")),
            },
        });
        None
    }

    fn actions(&mut self, i: usize, line: usize, list: &mut Vec<Action>) {
        let mut out = Vec::with_capacity(list.len());
        for action in std::mem::take(list) {
            match action {
                Action::Post { ty, content } => match self.interface(&ty) {
                    Some((j, _)) => out.extend(self.post(i, line, j, ty, content)),
                    None => out.push(Action::Post { ty, content }),
                },
                Action::Statement(mut s) => {
                    let mut wrong = Vec::new();
                    s.rename(&mut |n| self.outcome(n, &mut wrong));
                    for message in wrong {
                        self.problem(i, Some(line), message);
                    }
                    self.statement(i, line, &mut s);
                    out.push(Action::Statement(s));
                }
                other => out.push(other),
            }
        }
        *list = out;
    }

    /// A posting to machine `j`: a start gives its parameters and clears its outcomes.
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
            // Reported where the file was read.
            Some(Err(_)) => return vec![Action::Post { ty, content }],
            None => match Command::parse(&content) {
                Some(command) => crate::interface::Start {
                    command,
                    arguments: Vec::new(),
                },
                None => return vec![Action::Post { ty, content }],
            },
        };
        let interface = &self.interfaces[j].1;
        let starts = matches!(start.command, Command::On | Command::Restart);
        // What is posted: the command alone (as written, when it was written alone).
        let word = if start.arguments.is_empty() {
            content.clone()
        } else {
            start.command.word().to_string()
        };
        if !starts || (interface.is_empty() && start.arguments.is_empty()) {
            if !start.arguments.is_empty() {
                self.problem(i, Some(line), format!("`{ty}: {content}`: only `On` and `restart` start a machine, so only they take arguments"));
            }
            return vec![Action::Post { ty, content: word }];
        }
        let mut out = Vec::new();
        let mut problems = Vec::new();
        for (name, _) in &start.arguments {
            if interface.param(name).is_none() {
                let names = interface.params.iter().map(|p| p.name.as_str());
                problems.push(match proclaim_syntax::nearest(names, name) {
                    Some(near) => {
                        format!("`{ty}` has no parameter `{name}`; did you mean `{near}`?")
                    }
                    None if interface.params.is_empty() => {
                        format!("`{ty}` takes no parameters, so `{name}` cannot be given")
                    }
                    None => format!("`{ty}` has no parameter `{name}`"),
                });
            }
        }
        let missing: Vec<&str> = interface
            .params
            .iter()
            .filter(|p| !start.arguments.iter().any(|(n, _)| *n == p.name))
            .map(|p| p.name.as_str())
            .collect();
        if !missing.is_empty() {
            let list: Vec<String> = missing.iter().map(|p| format!("{p} = …")).collect();
            problems.push(format!(
                "`{ty}` takes {}: start it with `{ty}: {}({})`",
                missing.join(", "),
                start.command,
                list.join(", ")
            ));
        }
        for message in problems {
            self.problem(i, Some(line), message);
        }
        if !start.arguments.is_empty() {
            self.given[j] = true;
        }
        for p in &interface.params {
            if let Some((_, value)) = start.arguments.iter().find(|(n, _)| *n == p.name) {
                out.push(assign(global_of(&ty, &p.name), value.clone()));
            }
        }
        for o in &interface.outcomes {
            out.push(assign(global_of(&ty, &o.name), Expr::Int(0)));
        }
        out.push(Action::Post { ty, content: word });
        out
    }

    /// A start of a machine with an interface inside a statement (`start("Dive");`): its
    /// outcomes are cleared just before; it cannot give parameters.
    fn statement(&mut self, i: usize, line: usize, s: &mut Statement) {
        match s {
            Statement::Block(body) => body.iter_mut().for_each(|s| self.statement(i, line, s)),
            Statement::For { body, .. } => self.statement(i, line, body),
            Statement::Expr(Expr::Call {
                function,
                arguments,
            }) => {
                let Some(target) = started(function, arguments) else {
                    return;
                };
                let Some((_, interface)) = self.interface(&target) else {
                    return;
                };
                if !interface.params.is_empty() {
                    let params: Vec<String> = interface
                        .params
                        .iter()
                        .map(|p| format!("{} = …", p.name))
                        .collect();
                    let message = format!("`{target}` takes parameters, which a statement cannot give: start it on a line of its own, `{target}: On({})`", params.join(", "));
                    self.problem(i, Some(line), message);
                    return;
                }
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
            _ => {}
        }
    }

    /// The manifest's parameters of machine `i`: every one for a machine that starts with the
    /// behaviour, none for one that does not; set first of its initial state's OnEntry.
    fn launch(&mut self, i: usize, machine: &mut Machine, launch: &Launch) {
        let interface = &self.interfaces[i].1;
        let name = machine.name.clone();
        let mut problems = Vec::new();
        for (p, _) in &launch.params {
            if interface.param(p).is_none() {
                problems.push(format!(
                    "the manifest gives `{name}` a parameter `{p}` it does not declare"
                ));
            }
        }
        if !launch.start && !launch.params.is_empty() {
            problems.push(format!("the manifest gives `{name}` parameters but starts it with `start = false`: whoever starts it gives them (`{name}: On(…)`)"));
        }
        if launch.start && !launch.params.is_empty() && self.given[i] {
            problems.push(format!("`{name}` is given its parameters by the manifest and by a machine that starts it: give them in one place"));
        }
        let missing: Vec<&str> = interface
            .params
            .iter()
            .filter(|p| !launch.params.iter().any(|(n, _)| *n == p.name))
            .map(|p| p.name.as_str())
            .collect();
        if launch.start && !missing.is_empty() {
            let list: Vec<String> = missing.iter().map(|p| format!("{p} = …")).collect();
            problems.push(format!("`{name}` starts with the behaviour and takes {}: give them in its `[[machine]]` entry (`params = {{ {} }}`), or start it from a machine with `start = false`", missing.join(", "), list.join(", ")));
        }
        for message in problems {
            self.problem(i, None, message);
        }
        if !launch.start {
            return;
        }
        let sets: Vec<Action> = interface
            .params
            .iter()
            .filter_map(|p| {
                let (_, value) = launch.params.iter().find(|(n, _)| *n == p.name)?;
                Some(assign(global_of(&name, &p.name), value.clone()))
            })
            .collect();
        let initial = machine.initial;
        if let Some(state) = machine.states.iter_mut().find(|s| s.id == initial) {
            state.on_entry.splice(0..0, sets);
        }
    }
}

fn assign(name: String, value: Expr) -> Action {
    Action::Statement(Statement::Assign { name, value })
}

/// The machine a call starts from its initial state, if it starts one: `start("Dive")`,
/// `restart("Dive")`, `post("Dive", "On")`.
fn started(function: &str, arguments: &[Expr]) -> Option<String> {
    match (function, arguments) {
        (f, [Expr::Str(m)])
            if matches!(
                Command::from_function(f),
                Some(Command::On | Command::Restart)
            ) =>
        {
            Some(m.clone())
        }
        ("post", [Expr::Str(m), Expr::Str(word)])
            if matches!(Command::parse(word), Some(Command::On | Command::Restart)) =>
        {
            Some(m.clone())
        }
        _ => None,
    }
}
