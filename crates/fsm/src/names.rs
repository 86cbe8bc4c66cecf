//! How the names in a behaviour's activities resolve, decided here once for every reader (the
//! runner, the checker, the code generators). gufsm looked a name up in three tables in turn:
//! the machine's own variables (declared anywhere in it), then the behaviour's whiteboard
//! variables (`extern`, bound for every machine by any one of them), then the globals (names
//! some activity assigns that are neither the assigning machine's own nor an extern). Any other
//! name an expression reads is a whiteboard value, or an atom to ask an expert about.

use crate::code::{Statement, VarType};
use crate::model::Machine;
use std::collections::HashSet;

/// One of a machine's own variables.
#[derive(Clone, Debug, PartialEq)]
pub struct Own {
    pub name: String,
    /// The first declaration's type: the variable starts at its zero (gufsm made it when it
    /// read that declaration).
    pub first: VarType,
    /// The last declaration's type: what a value assigned to it converts to.
    pub last: VarType,
}

/// A machine's own variables, in the order first declared.
pub fn own_variables(machine: &Machine) -> Vec<Own> {
    let mut own: Vec<Own> = Vec::new();
    for s in machine.statements() {
        let Statement::Declare { ty, name, .. } = s else {
            continue;
        };
        match own.iter_mut().find(|o| o.name == *name) {
            Some(o) => o.last = ty.clone(),
            None => own.push(Own {
                name: name.clone(),
                first: ty.clone(),
                last: ty.clone(),
            }),
        }
    }
    own
}

/// The names `machine` binds to the whiteboard (`extern x`), in order, once each.
pub fn externs_of(machine: &Machine) -> Vec<&str> {
    let mut seen = HashSet::new();
    machine
        .statements()
        .into_iter()
        .filter_map(|s| match s {
            Statement::Extern { name, .. } => Some(name.as_str()),
            _ => None,
        })
        .filter(|name| seen.insert(*name))
        .collect()
}

/// The globals `machine`'s activities assign, in order, once each: the names it assigns that
/// are not its own and not externs of the behaviour.
pub fn globals_of<'m>(
    machine: &'m Machine,
    own: &[Own],
    is_extern: impl Fn(&str) -> bool,
) -> Vec<&'m str> {
    let mut seen = HashSet::new();
    machine
        .statements()
        .into_iter()
        .filter_map(|s| match s {
            Statement::Assign { name, .. } => Some(name.as_str()),
            _ => None,
        })
        .filter(|name| !own.iter().any(|o| o.name == *name) && !is_extern(name))
        .filter(|name| seen.insert(*name))
        .collect()
}

/// Every name of a behaviour's machines, resolved.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Names {
    /// Per machine (in the order given), its own variables.
    pub own: Vec<Vec<Own>>,
    /// The whiteboard variables, in the order first bound.
    pub externs: Vec<String>,
    /// The globals, in the order first assigned (machine by machine).
    pub globals: Vec<String>,
}

/// What a name is in one machine's activities.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Resolved {
    Own,
    Extern,
    Global,
    /// A whiteboard value read by name, or an atom to ask about.
    Other,
}

impl Names {
    pub fn of<'a>(machines: impl IntoIterator<Item = &'a Machine>) -> Names {
        let machines: Vec<&Machine> = machines.into_iter().collect();
        let mut names = Names {
            own: machines.iter().map(|m| own_variables(m)).collect(),
            ..Names::default()
        };
        // Externs first: a name any machine binds to the whiteboard is no global anywhere.
        for m in &machines {
            for name in externs_of(m) {
                if !names.externs.iter().any(|e| e == name) {
                    names.externs.push(name.to_string());
                }
            }
        }
        for (m, own) in machines.iter().zip(&names.own) {
            for name in globals_of(m, own, |n| names.externs.iter().any(|e| e == n)) {
                if !names.globals.iter().any(|g| g == name) {
                    names.globals.push(name.to_string());
                }
            }
        }
        names
    }

    /// What `name` is in machine `machine`'s activities.
    pub fn resolve(&self, machine: usize, name: &str) -> Resolved {
        if self.own[machine].iter().any(|o| o.name == name) {
            Resolved::Own
        } else if self.externs.iter().any(|e| e == name) {
            Resolved::Extern
        } else if self.globals.iter().any(|g| g == name) {
            Resolved::Global
        } else {
            Resolved::Other
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parse_machine;

    fn machine(text: &str) -> Machine {
        let mut imported = parse_machine("M.machine", text);
        assert!(!imported.has_errors(), "{:?}", imported.diagnostics);
        imported.machines.remove(0)
    }

    #[test]
    fn own_then_extern_then_global_as_gufsm_looked_them_up() {
        let a = machine(
            "machine A\ninitial S\nstate S {\n  entry { int n; bool n; extern ball; n = 1; g = 2; ball = 3; }\n}\n",
        );
        let b =
            machine("machine B\ninitial S\nstate S {\n  entry { n = 4; g = 5; h = ball; }\n}\n");
        let names = Names::of([&a, &b]);
        assert_eq!(
            names.own[0],
            vec![Own {
                name: "n".into(),
                first: VarType::Int,
                last: VarType::Bool,
            }]
        );
        assert_eq!(names.externs, vec!["ball"]);
        // `n` is A's own, so A's assignment makes no global; B's does.
        assert_eq!(names.globals, vec!["g", "n", "h"]);
        assert_eq!(names.resolve(0, "n"), Resolved::Own);
        assert_eq!(names.resolve(1, "n"), Resolved::Global);
        assert_eq!(names.resolve(1, "ball"), Resolved::Extern);
        assert_eq!(names.resolve(1, "door"), Resolved::Other);
    }
}
