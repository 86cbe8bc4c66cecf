//! A machine's parameters and outcomes as the native format writes them (`param side: int`,
//! `outcome saved, missed`, a final state's `outcome saved`), lowered where the file alone
//! says what they mean: the machine reads a parameter as the global `Dive_side`, and a final
//! state announcing an outcome sets the global `Dive_saved` to 1 as it is entered. What a
//! start of the machine elsewhere gives and resets is the behaviour's (`crate::link`).

use super::{Body, Lowering};
use crate::code::{Expr, Statement, VarType};
use crate::interface::{global_of, start_of, DeclaredOutcome, Param};
use crate::model::{Action, Machine};

impl Lowering<'_> {
    /// `param NAME: TYPE`.
    pub(super) fn param(&mut self, text: &str, at: usize) {
        let Some((name, ty)) = text.split_once(':') else {
            self.error(
                at,
                format!(
                    "`param {text}`: a parameter is `param NAME: TYPE`, as in `param side: int`"
                ),
            );
            return;
        };
        let (name, ty) = (name.trim(), ty.trim());
        if !is_name(name) {
            self.error(
                at,
                format!(
                    "`{name}` cannot name a parameter: letters, digits and `_`, not first a digit"
                ),
            );
            return;
        }
        let Some(ty) = VarType::keyword(ty) else {
            self.error(
                at,
                format!("`{ty}` is no type a parameter can have: int, bool, char, float or double"),
            );
            return;
        };
        if self.interface.param(name).is_some() {
            self.error(at, format!("parameter `{name}` is declared twice"));
            return;
        }
        let line = self.lines.line(at);
        self.interface.params.push(Param {
            name: name.to_string(),
            ty,
            line,
        });
    }

    /// `outcome NAME, NAME…`.
    pub(super) fn outcomes(&mut self, text: &str, at: usize) {
        let line = self.lines.line(at);
        for name in text.split(',').map(str::trim) {
            if !is_name(name) {
                self.error(at, format!("`{name}` cannot name an outcome: letters, digits and `_`, not first a digit (`outcome saved, missed`)"));
            } else if self.interface.outcome(name).is_some() || self.interface.param(name).is_some()
            {
                self.error(at, format!("`{name}` is declared twice"));
            } else {
                self.interface.outcomes.push(DeclaredOutcome {
                    name: name.to_string(),
                    line,
                });
            }
        }
    }

    /// A state's `outcome NAME`: it must be final and the outcome declared; entering it sets
    /// the outcome's global, last of its OnEntry.
    pub(super) fn announce(&mut self, state: &str, (name, at): (String, usize), body: &mut Body) {
        if !body.whens.is_empty() || !body.states.is_empty() {
            self.error(at, format!("state `{state}` announces outcome `{name}`, so it is final: it can have no transitions and hold no states"));
            return;
        }
        if self.interface.outcome(&name).is_none() {
            let declared: Vec<&str> = self
                .interface
                .outcomes
                .iter()
                .map(|o| o.name.as_str())
                .collect();
            let message = match proclaim_syntax::nearest(declared.iter().copied(), &name) {
                Some(near) => format!("`{name}` is not an outcome of this machine; did you mean `{near}`?"),
                None if declared.is_empty() => format!("`{name}` is not an outcome of this machine: declare it at the top (`outcome {name}`)"),
                None => format!("`{name}` is not an outcome of this machine (its outcomes: {})", declared.join(", ")),
            };
            self.error(at, message);
            return;
        }
        body.entry.push(Action::Statement(Statement::Assign {
            name: global_of(&self.machine, &name),
            value: Expr::Int(1),
        }));
    }

    /// A posting with arguments (`Dive: On(side = 1)`) must read as a command and its
    /// arguments; which machine takes them is the behaviour's to say.
    pub(super) fn check_start(&mut self, content: &str, at: usize) {
        if let Some(Err(message)) = start_of(content) {
            self.error(at, message);
        }
    }

    /// The machine reads its parameters as the globals they are: refused where it declares
    /// one of their names or sets one.
    pub(super) fn lower_params(&mut self, machine: &mut Machine) {
        machine.interface = std::mem::take(&mut self.interface);
        if machine.interface.params.is_empty() {
            return;
        }
        let params: Vec<String> = machine
            .interface
            .params
            .iter()
            .map(|p| p.name.clone())
            .collect();
        let name = machine.name.clone();
        let mut to = |n: &str| params.iter().any(|p| p == n).then(|| global_of(&name, n));
        let mut misuse = Vec::new();
        for state in &mut machine.states {
            for action in state
                .on_entry
                .iter_mut()
                .chain(&mut state.on_exit)
                .chain(&mut state.internal)
            {
                if let Action::Statement(s) = action {
                    s.visit(&mut |inner| {
                        if let Statement::Assign { name: n, .. }
                        | Statement::Declare { name: n, .. } = inner
                        {
                            if params.contains(n) {
                                misuse.push((state.line, n.clone()));
                            }
                        }
                    });
                    s.rename(&mut to);
                }
            }
        }
        for t in &mut machine.transitions {
            t.label.rename(&mut to);
            for action in t.leaving.iter_mut().flatten() {
                if let Action::Statement(s) = action {
                    s.rename(&mut to);
                }
            }
        }
        misuse.sort();
        misuse.dedup();
        for (line, n) in misuse {
            self.error_at_line(line, format!("`{n}` is a parameter of `{name}`: whoever starts it sets it, so the machine cannot set or declare it (copy it to a variable of its own: `int s; s = {n};`)"));
        }
    }
}

fn is_name(text: &str) -> bool {
    text.starts_with(|c: char| c.is_alphabetic() || c == '_')
        && text.chars().all(|c| c.is_alphanumeric() || c == '_')
}
