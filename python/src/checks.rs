//! What `Behaviour(...)` checks of the callables it is given against the machines, so that a
//! typo is an error with a suggestion rather than a label answered by nobody: an expert for a
//! label no machine asks and a host function no machine calls are errors; a host function a
//! machine calls that no callable answers is a warning (`proclaim.BehaviourWarning`, which
//! `warnings.simplefilter("error", proclaim.BehaviourWarning)` makes an error), since a
//! behaviour may well be run without its hardware.

use proclaim_behaviour::LoadedMachine;
use proclaim_fsm::{Action, Command, Expr, Statement, BUILTIN_FUNCTIONS};
use proclaim_lower::RingletPlan;
use proclaim_runner::Shared;
use std::collections::BTreeMap;

/// A problem with the callables given: where (a machine's file and line, or the argument) and
/// what.
pub(crate) struct Problem {
    pub(crate) file: String,
    pub(crate) line: usize,
    pub(crate) message: String,
}

/// What the callables given do not match: errors, then warnings.
#[derive(Default)]
pub(crate) struct Findings {
    pub(crate) errors: Vec<Problem>,
    pub(crate) warnings: Vec<Problem>,
}

/// Every label atom some machine asks an expert about, with the first machine file asking it.
fn asked(machines: &[LoadedMachine], shared: &Shared) -> BTreeMap<String, (String, usize)> {
    let mut out = BTreeMap::new();
    for loaded in machines {
        for transition in &loaded.machine.transitions {
            for atom in proclaim_runner::asked(&transition.label, &loaded.machine, shared) {
                out.entry(atom.to_string())
                    .or_insert_with(|| (loaded.file.clone(), transition.line));
            }
        }
    }
    out
}

/// The function a statement calls for its effect, when it is a host function: a call standing
/// alone that is neither built in nor a sub-machine control.
fn host_call(statement: &Statement) -> Option<&str> {
    match statement {
        Statement::Expr(Expr::Call { function, .. })
            if !BUILTIN_FUNCTIONS.contains(&function.as_str())
                && Command::from_function(function).is_none() =>
        {
            Some(function)
        }
        _ => None,
    }
}

/// Every host function some machine's activities call, with the first file and line calling it.
fn called(machines: &[LoadedMachine]) -> BTreeMap<String, (String, usize)> {
    let mut out = BTreeMap::new();
    for loaded in machines {
        for state in &loaded.machine.states {
            let plan = RingletPlan::of_state(&loaded.machine, state);
            for action in plan.activities().into_iter().flatten() {
                let mut functions = Vec::new();
                match action {
                    Action::Call { function, .. } => functions.push(function.as_str()),
                    Action::Statement(statement) => statement.visit(&mut |s| {
                        functions.extend(host_call(s));
                    }),
                    Action::Post { .. } | Action::Code(_) => {}
                }
                for function in functions {
                    if function != "msleep" && function != "sleep" {
                        out.entry(function.to_string())
                            .or_insert_with(|| (loaded.file.clone(), state.line));
                    }
                }
            }
        }
    }
    out
}

fn did_you_mean<'a>(known: impl IntoIterator<Item = &'a str>, name: &str) -> String {
    proclaim_syntax::nearest(known, name)
        .map(|close| format!("; did you mean `{close}`?"))
        .unwrap_or_default()
}

/// The experts' labels and the host functions given, against what `machines` ask and call.
pub(crate) fn check(
    machines: &[LoadedMachine],
    shared: &Shared,
    experts: &[String],
    hosts: &[String],
) -> Findings {
    let mut findings = Findings::default();
    let asked = asked(machines, shared);
    for label in experts.iter().filter(|l| !asked.contains_key(*l)) {
        findings.errors.push(Problem {
            file: "experts".into(),
            line: 0,
            message: format!(
                "experts[{label:?}]: no machine asks `{label}`{}",
                did_you_mean(asked.keys().map(String::as_str), label)
            ),
        });
    }
    let called = called(machines);
    for host in hosts.iter().filter(|h| !called.contains_key(*h)) {
        findings.errors.push(Problem {
            file: "hosts".into(),
            line: 0,
            message: format!(
                "hosts[{host:?}]: no machine calls `{host}`{}",
                did_you_mean(called.keys().map(String::as_str), host)
            ),
        });
    }
    for (function, (file, line)) in &called {
        if !hosts.contains(function) {
            findings.warnings.push(Problem {
                file: file.clone(),
                line: *line,
                message: format!(
                    "{file}:{line}: the machine calls the host function `{function}`, which no \
                     callable in hosts answers: the call is skipped{}",
                    did_you_mean(hosts.iter().map(String::as_str), function)
                ),
            });
        }
    }
    findings
}
