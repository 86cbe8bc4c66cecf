//! A machine's parameters and outcomes as the native format writes them (`param side: int`,
//! `outcome saved, missed`, a final state's `outcome saved`), lowered where the file alone
//! says what they mean: the machine reads a parameter as the global `Dive_side`, and a final
//! state announcing an outcome sets the global `Dive_saved` to 1 as it is entered. What a
//! start of the machine elsewhere gives and resets is the behaviour's (`crate::link`).

use super::{Body, Lowering};
use crate::code::{Expr, Statement, VarType};
use crate::interface::{global_of, is_name, DeclaredOutcome, Param};
use crate::model::{Action, Machine};
use proclaim_syntax::FileDiagnostic;

/// Names the activity language reads as truth values, never a parameter's or an outcome's.
const LITERALS: [&str; 4] = ["true", "false", "TRUE", "FALSE"];

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
        if !is_name(name) || LITERALS.contains(&name) {
            self.error(
                at,
                format!(
                    "`{name}` cannot name a parameter: letters, digits and `_`, not first a digit, and no truth value"
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
        if self.interface.param(name).is_some() || self.interface.outcome(name).is_some() {
            self.error(at, format!("`{name}` is declared twice (a parameter and an outcome become one global, `{}`)", global_of(&self.machine, name)));
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
        if text.trim().is_empty() {
            let message =
                "`outcome` names the outcomes a final state can announce: `outcome saved, missed`";
            self.error(at, message.into());
            return;
        }
        for name in text.split(',').map(str::trim) {
            if !is_name(name) || LITERALS.contains(&name) {
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
        if name.contains(',') || name.is_empty() {
            let message =
                format!("state `{state}` announces one outcome, by its name (`outcome landed`)");
            self.error(at, message);
            return;
        }
        if !body.whens.is_empty() || !body.states.is_empty() {
            self.error(at, format!("state `{state}` announces outcome `{name}`, so it is final: it can have no transitions and hold no states"));
            return;
        }
        if self.interface.outcome(&name).is_none() {
            let declared = self.interface.outcome_names();
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
        self.announced.push(name);
    }

    /// A statement of the machine may not set or declare a parameter (whoever starts the
    /// machine sets it), nor the global a parameter or an outcome becomes (an outcome is set by
    /// the state announcing it).
    pub(super) fn check_sets(&mut self, statements: &[Statement], at: usize) {
        let mut wrong = Vec::new();
        for statement in statements {
            statement.visit(&mut |s| {
                if let Statement::Assign { name, .. }
                | Statement::Declare { name, .. }
                | Statement::Extern { name, .. } = s
                {
                    wrong.extend(self.set_by_whom(name));
                }
            });
        }
        for message in wrong {
            self.error(at, message);
        }
    }

    fn set_by_whom(&self, name: &str) -> Option<String> {
        let machine = &self.machine;
        if let Some(p) = self.interface.param(name) {
            return Some(format!("`{}` is a parameter of `{machine}`: whoever starts it sets it, so the machine cannot set or declare it (copy it to a variable of its own: `int s; s = {};`)", p.name, p.name));
        }
        let param = self
            .interface
            .params
            .iter()
            .find(|p| global_of(machine, &p.name) == name);
        if let Some(p) = param {
            return Some(format!(
                "`{name}` is what parameter `{}` becomes: whoever starts `{machine}` sets it",
                p.name
            ));
        }
        let outcome = self
            .interface
            .outcomes
            .iter()
            .find(|o| global_of(machine, &o.name) == name);
        outcome.map(|o| format!("`{name}` is outcome `{}`: a final state announces it (`outcome {}`), nothing sets it", o.name, o.name))
    }

    /// The machine reads its parameters as the globals they are.
    pub(super) fn lower_params(&mut self, machine: &mut Machine) {
        machine.interface = std::mem::take(&mut self.interface);
        for o in &machine.interface.outcomes {
            if !self.announced.contains(&o.name) {
                let message = format!("outcome `{}` is announced by no state (a final state says `outcome {}`), so whoever waits on it waits for ever", o.name, o.name);
                let mut d = FileDiagnostic::error(self.file, o.line, message);
                d.severity = proclaim_syntax::Severity::Warning;
                self.diagnostics.push(d);
            }
        }
        let params: Vec<String> = machine
            .interface
            .params
            .iter()
            .map(|p| p.name.clone())
            .collect();
        if params.is_empty() {
            return;
        }
        let name = machine.name.clone();
        machine.rename(&mut |n| params.iter().any(|p| p == n).then(|| global_of(&name, n)));
    }
}
