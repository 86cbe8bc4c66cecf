//! What verify's findings call unreachable in a random behaviour (states never entered,
//! transitions that never fire), and whether one of a run's events reaches it.

use proclaim_behaviour::Behaviour;
use proclaim_fsm::Machine;
use proclaim_runner::Event;
use proclaim_verify::{Finding, Report};

/// The "never" findings, each as a run's event can name it.
pub(super) struct Unreachable {
    /// `Machine.State`.
    entered: Vec<String>,
    /// `Machine: From -> To on label`, only where no other written transition reads alike.
    fires: Vec<String>,
    /// A chart's transition as written: machine, where it was written, its line.
    lines: Vec<(String, String, usize)>,
}

impl Unreachable {
    pub(super) fn of(report: &Report, behaviour: &Behaviour) -> Unreachable {
        let mut entered = Vec::new();
        let mut fires = Vec::new();
        let mut lines = Vec::new();
        for f in &report.findings {
            match f {
                Finding::NeverEntered { machine, state } => {
                    entered.push(format!("{machine}.{state}"))
                }
                Finding::NeverFires {
                    machine,
                    from,
                    to,
                    label,
                    line,
                } => {
                    fires.push(format!("{machine}: {from} -> {to} on {label}"));
                    // In a chart, a transition as written is known by where it was written and
                    // its line, and a flat transition that fires credits every written one it
                    // joins (`lib.rs`'s findings).
                    if *line > 0 {
                        lines.push((machine.clone(), from.clone(), *line));
                    }
                }
                Finding::Deadlock { .. } => {}
            }
        }
        // A run's event names a transition by its states and label alone: where one of several
        // alike may fire (a label written twice), the event cannot tell which, so none is held.
        let said = fires.clone();
        fires.retain(|t| said.iter().filter(|s| *s == t).count() == alike(behaviour, t));
        Unreachable {
            entered,
            fires,
            lines,
        }
    }

    /// What the event reached that verify called unreachable, if anything.
    pub(super) fn reached_by(&self, e: &Event, behaviour: &Behaviour) -> Option<String> {
        match e {
            Event::Entered { machine, state, .. } => (state.split(", "))
                .map(|atomic| format!("{machine}.{atomic}"))
                .find(|s| self.entered.contains(s))
                .map(|s| format!("entered {s}")),
            Event::Fired {
                machine,
                from,
                to,
                label,
                ..
            } => match chart(behaviour, machine) {
                Some(m) => self.written_fired(m, *from, *to, label),
                None => {
                    let name = |id| state_name(behaviour, machine, id);
                    let t = format!("{machine}: {} -> {} on {label}", name(*from), name(*to));
                    self.fires.contains(&t).then_some(format!("fired {t}"))
                }
            },
            _ => None,
        }
    }

    /// A chart's firing, credited to the transition written and every one it joins.
    fn written_fired(&self, m: &Machine, from: i64, to: i64, label: &str) -> Option<String> {
        let arms: Vec<_> = (m.transitions.iter())
            .filter(|t| t.source == from && t.target == to)
            .filter(|t| t.shown().to_string() == label)
            .collect();
        let written = |c: Option<usize>, source: i64| {
            let composite = c.and_then(|c| m.composites.get(c));
            composite.map_or_else(
                || {
                    m.state(source)
                        .map_or_else(|| format!("#{source}"), |s| s.name.clone())
                },
                |c| c.name.clone(),
            )
        };
        // Several arms alike: the event cannot tell which fired.
        let [t] = arms.as_slice() else {
            return None;
        };
        let joined =
            (t.joined.iter().filter(|j| j.2)).map(|&(c, line, _)| (written(c, t.source), line));
        std::iter::once((written(t.composite, t.source), t.line))
            .chain(joined)
            .find(|(w, line)| self.lines.contains(&(m.name.clone(), w.clone(), *line)))
            .map(|(w, line)| format!("fired {}: the transition of {w} at line {line}", m.name))
    }
}

/// How many written transitions read as `t` does.
fn alike(behaviour: &Behaviour, t: &str) -> usize {
    let written = behaviour.machines.iter().flat_map(|m| {
        let name = |id| m.machine.state(id).map_or("", |s| s.name.as_str());
        m.machine.transitions.iter().map(move |x| {
            let (from, to) = (name(x.source), name(x.target));
            format!("{}: {from} -> {to} on {}", m.machine.name, x.label)
        })
    });
    written.filter(|w| w == t).count()
}

/// The machine, where it is a chart.
fn chart<'a>(behaviour: &'a Behaviour, machine: &str) -> Option<&'a Machine> {
    let m = behaviour
        .machines
        .iter()
        .find(|m| m.machine.name == machine);
    m.map(|m| &m.machine).filter(|m| !m.composites.is_empty())
}

fn state_name(behaviour: &Behaviour, machine: &str, id: i64) -> String {
    let m = behaviour
        .machines
        .iter()
        .find(|m| m.machine.name == machine);
    m.and_then(|m| m.machine.state(id))
        .map_or_else(|| format!("#{id}"), |s| s.name.clone())
}
