//! A behaviour's machines linked (`proclaim_fsm::link`, `docs/spec/behaviour.md` §3.3) as they
//! load, and each one again as it is read anew (`reload`, `--watch`): a start gives the
//! parameters of the machine it starts and clears its outcomes, a label reads an outcome.

use crate::loaded::LoadedMachine;
use crate::manifest::MachineEntry;
use proclaim_fsm::{link, Expr, Launch, LinkProblem, Machine};
use proclaim_syntax::FileDiagnostic;
use std::sync::Arc;

/// What linking one machine read anew needs of the others: their names and interfaces.
struct Linking {
    stubs: Vec<Machine>,
    launches: Vec<Launch>,
    shown: Vec<String>,
    manifest: String,
}

/// Links the loaded machines (`entries[i]` the manifest's entry of `machines[i]`), reporting
/// what does not fit; each machine's loader links what it reads the same way.
pub(crate) fn link_loaded(
    machines: &mut [LoadedMachine],
    entries: &[&MachineEntry],
    shown: &dyn Fn(&str) -> String,
    manifest: &str,
    problems: &mut Vec<FileDiagnostic>,
) {
    let launches: Vec<Launch> = entries
        .iter()
        .map(|e| Launch {
            start: e.start,
            params: e
                .params
                .iter()
                .filter_map(|(n, v)| match value(v) {
                    Some(v) => Some((n.clone(), v)),
                    None => {
                        problems.push(FileDiagnostic::in_file(
                            manifest,
                            format!("`{}`'s parameter `{n} = {v}`: a parameter's value is a whole number, a fraction, a truth or a text", e.file),
                        ));
                        None
                    }
                })
                .collect(),
        })
        .collect();
    let linking = Arc::new(Linking {
        stubs: machines
            .iter()
            .map(|m| Machine {
                name: m.machine.name.clone(),
                interface: m.machine.interface.clone(),
                ..Machine::default()
            })
            .collect(),
        launches,
        shown: machines.iter().map(|m| shown(&m.file)).collect(),
        manifest: manifest.to_string(),
    });
    let mut linked: Vec<Machine> = machines.iter().map(|m| m.machine.clone()).collect();
    let found = link(&mut linked, &linking.launches);
    problems.extend(found.iter().map(|p| linking.diagnostic(p)));
    for (i, (m, linked)) in machines.iter_mut().zip(linked).enumerate() {
        m.machine = linked;
        let read = m.loader.clone();
        let linking = linking.clone();
        m.loader = Arc::new(move || linking.relink(i, read()?));
    }
}

/// A manifest's value as the activity language writes it, if it is one a parameter can take.
fn value(v: &toml::Value) -> Option<Expr> {
    Some(match v {
        toml::Value::Integer(i) => Expr::Int(*i),
        toml::Value::Float(x) => Expr::Float(*x),
        toml::Value::Boolean(b) => Expr::Bool(*b),
        toml::Value::String(s) => Expr::Str(s.clone()),
        _ => return None,
    })
}

impl Linking {
    fn diagnostic(&self, p: &LinkProblem) -> FileDiagnostic {
        match p.line {
            Some(line) => FileDiagnostic::error(&self.shown[p.machine], line, p.message.clone()),
            None => FileDiagnostic::in_file(&self.manifest, p.message.clone()),
        }
    }

    /// Machine `i` read anew, linked to the others as they were loaded. Its parameters and
    /// outcomes must be as they were: the machines that start it were linked to those.
    fn relink(&self, i: usize, machine: Machine) -> Result<Machine, Vec<FileDiagnostic>> {
        if machine.name != self.stubs[i].name {
            let message = format!(
                "the file now names its machine `{}`, not `{}`: the other machines start and read it by its old name, so run the behaviour again",
                machine.name, self.stubs[i].name
            );
            return Err(vec![FileDiagnostic::in_file(&self.shown[i], message)]);
        }
        if !machine.interface.same_as(&self.stubs[i].interface) {
            let message = format!(
                "`{}`'s parameters or outcomes changed: the machines that start it were read with the old ones, so run the behaviour again",
                machine.name
            );
            return Err(vec![FileDiagnostic::in_file(&self.shown[i], message)]);
        }
        let mut machines = self.stubs.clone();
        machines[i] = machine;
        // The others are stubs with nothing to lower: a problem found with one of them is this
        // machine's doing (a restart with arguments of a machine the manifest gives them).
        let found: Vec<FileDiagnostic> = link(&mut machines, &self.launches)
            .iter()
            .map(|p| self.diagnostic(p))
            .collect();
        if !found.is_empty() {
            return Err(found);
        }
        Ok(machines.swap_remove(i))
    }
}
