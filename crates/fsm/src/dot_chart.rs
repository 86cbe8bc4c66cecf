//! A machine with nested states drawn as it was written: each composite state a cluster
//! holding its states, each state once (not once per flat state it lowers to), a composite's
//! transition drawn once from its cluster's edge.

use crate::code::Statement;
use crate::dot_text::{escape, node, quote, show};
use crate::interface::global_of;
use crate::model::{Action, Machine, State, StateId, Transition};
use std::collections::HashMap;
use std::fmt::Write;

/// The states, clusters and transitions of a machine whose `composites` are not empty; node
/// names prefixed as `dot::body`'s.
pub(crate) fn chart_body(out: &mut String, machine: &Machine, prefix: &str, indent: &str) {
    let drawing = Drawing::new(machine, prefix);
    let _ = writeln!(out, "{indent}compound=true;");
    let _ = writeln!(out, "{indent}{prefix}start [shape=point, width=0.15];");
    let _ = writeln!(
        out,
        "{indent}{prefix}start -> {};",
        drawing.node(machine.initial)
    );
    drawing.cluster(out, None, indent);
    drawing.edges(out, indent);
}

/// The nodes `chart_body` draws each flat state as: one, or one a region of a parallel state
/// (§3.2), the first standing for the state (what a fired transition is drawn from and to).
pub(crate) fn state_nodes(machine: &Machine, prefix: &str) -> Vec<(StateId, Vec<String>)> {
    let drawing = Drawing::new(machine, prefix);
    machine
        .states
        .iter()
        .map(|s| (s.id, drawing.nodes(s)))
        .collect()
}

/// Each state's posted start, as `starting` finds them in a flat state's OnEntry, and the node
/// it is drawn from: the state as written that posts it (a region's state, or one inside the
/// composite that does), so a start is not drawn from another region's state.
pub(crate) fn start_nodes<'s>(
    machine: &'s Machine,
    prefix: &str,
    starting: impl Fn(&'s State) -> Vec<(&'s Action, String)>,
) -> Vec<(String, String)> {
    let drawing = Drawing::new(machine, prefix);
    let mut started = Vec::new();
    for state in &machine.states {
        for (action, started_machine) in starting(state) {
            let writer = machine.composite_writing(state, action, |c| &c.on_entry);
            let at = writer.and_then(|w| {
                let c = machine.composites.iter().position(|c| std::ptr::eq(c, w))?;
                Some(drawing.node_inside(state, c))
            });
            let from = at.unwrap_or_else(|| drawing.node(state.id));
            if !started.contains(&(from.clone(), started_machine.clone())) {
                started.push((from, started_machine));
            }
        }
    }
    started
}

struct Drawing<'m> {
    machine: &'m Machine,
    prefix: &'m str,
    /// Each state as written: the first flat state of its name and line.
    written: Vec<&'m State>,
    /// Every flat state's written one, by id.
    node_of: HashMap<StateId, StateId>,
}

impl<'m> Drawing<'m> {
    fn new(machine: &'m Machine, prefix: &'m str) -> Drawing<'m> {
        let mut written: Vec<&State> = Vec::new();
        let mut first: HashMap<(&str, usize), StateId> = HashMap::new();
        let mut node_of = HashMap::new();
        let region = |s: &State| {
            let paths = machine.atomic_paths(s);
            paths.len() > 1
                || machine
                    .composites
                    .iter()
                    .any(|c| c.atomic && c.name == s.name)
        };
        for state in machine.states.iter().filter(|s| !region(s)) {
            let id = *first
                .entry((state.name.as_str(), state.line))
                .or_insert_with(|| {
                    written.push(state);
                    state.id
                });
            node_of.insert(state.id, id);
        }
        Drawing {
            machine,
            prefix,
            written,
            node_of,
        }
    }

    fn node(&self, flat: StateId) -> String {
        match self.machine.state(flat) {
            Some(s) => self.nodes(s).swap_remove(0),
            None => format!("{}s{}", self.prefix, node(flat)),
        }
    }

    /// The nodes a flat state is drawn as: its atomic states', each region's as written.
    fn nodes(&self, state: &State) -> Vec<String> {
        let paths = self.machine.atomic_paths(state);
        paths
            .into_iter()
            .map(|path| match self.atomic(path) {
                Some(c) => format!("{}a{c}", self.prefix),
                None => {
                    let id = self.node_of.get(&state.id).copied().unwrap_or(state.id);
                    format!("{}s{}", self.prefix, node(id))
                }
            })
            .collect()
    }

    /// The node of flat state `state` in composite `c`: a region's state itself, else the
    /// first of the state's nodes inside it.
    fn node_inside(&self, state: &State, c: usize) -> String {
        let composite = &self.machine.composites[c];
        if composite.atomic {
            return format!("{}a{c}", self.prefix);
        }
        let inside = |path: &str| {
            (path.strip_prefix(composite.name.as_str())).is_some_and(|rest| rest.starts_with('.'))
        };
        let paths = self.machine.atomic_paths(state);
        match paths.iter().position(|p| inside(p)) {
            Some(i) => self.nodes(state).swap_remove(i),
            None => self.node(state.id),
        }
    }

    /// The atomic state of a region `path` names (an index into the composites).
    fn atomic(&self, path: &str) -> Option<usize> {
        (self.machine.composites.iter()).position(|c| c.atomic && c.name == path)
    }

    /// The node a transition is drawn to: the state it enters that its source was not in (a
    /// region's move), else its target's.
    fn target_node(&self, t: &Transition) -> String {
        let (Some(from), Some(to)) = (self.machine.state(t.source), self.machine.state(t.target))
        else {
            return self.node(t.target);
        };
        let before = self.machine.atomic_paths(from);
        let entered = self.machine.atomic_paths(to);
        let own = t.composite.filter(|&c| self.machine.composites[c].atomic);
        match (entered.iter().find(|p| !before.contains(p)), own) {
            (Some(path), _) if entered.len() > 1 => match self.atomic(path) {
                Some(c) => format!("{}a{c}", self.prefix),
                None => self.node(t.target),
            },
            // A region's move back into its own state: drawn back to it.
            (None, Some(c)) if entered.len() > 1 => format!("{}a{c}", self.prefix),
            _ => self.node(t.target),
        }
    }

    /// A transition with several targets: out of `from` (a cluster's edge, or the node
    /// `source`) to a fork, and from it into each (a state in each region).
    fn forked(
        &self,
        t: &Transition,
        (from, cluster): (&str, bool),
        source: &str,
        label: &str,
        indent: &str,
    ) -> String {
        let fork = format!("{from}_fork{}", t.line);
        let tail = if cluster {
            format!(", ltail={}", quote(from))
        } else {
            String::new()
        };
        let mut out = format!(
            "{indent}{fork} [shape=point, width=0.05];\n\
             {indent}{source} -> {fork} [label=\"{label}\"{tail}, arrowhead=none];\n"
        );
        for node in self.target_nodes(t) {
            let _ = writeln!(out, "{indent}{fork} -> {node};");
        }
        out
    }

    /// The node of each of the targets a transition names: the region's state the flat
    /// target holds at or inside the written one.
    fn target_nodes(&self, t: &Transition) -> Vec<String> {
        let entered =
            (self.machine.state(t.target)).map_or_else(Vec::new, |s| self.machine.atomic_paths(s));
        let node = |written: &String| {
            let inside = entered.iter().find(|p| {
                *p == written
                    || p.strip_prefix(written.as_str())
                        .is_some_and(|rest| rest.starts_with('.'))
            });
            match inside.and_then(|p| self.atomic(p)) {
                Some(c) => format!("{}a{c}", self.prefix),
                None => self.node(t.target),
            }
        };
        t.targets.iter().map(node).collect()
    }

    /// The nodes the initial state is drawn as.
    fn nodes_of_initial(&self) -> Vec<String> {
        self.machine
            .state(self.machine.initial)
            .map_or_else(Vec::new, |s| self.nodes(s))
    }

    fn cluster_name(&self, composite: usize) -> String {
        format!("cluster_{}c{composite}", self.prefix)
    }

    /// The composites around `state`, innermost first.
    fn around(&self, state: &State) -> Vec<usize> {
        let composites = &self.machine.composites;
        let inner = self.machine.composite_of(state);
        std::iter::successors(inner, |&c| composites[c].parent).collect()
    }

    /// The states and clusters directly in `within` (`None`: the machine), clusters nested.
    fn cluster(&self, out: &mut String, within: Option<usize>, indent: &str) {
        for state in &self.written {
            if self.machine.composite_of(state) == within {
                self.state(out, state, indent);
            }
        }
        for (c, composite) in self.machine.composites.iter().enumerate() {
            if composite.parent != within {
                continue;
            }
            let short = composite.name.rsplit('.').next().unwrap_or(&composite.name);
            if composite.atomic {
                let mut label = format!("{}\\n", escape(short));
                activities(
                    &mut label,
                    &composite.on_entry,
                    &composite.on_exit,
                    &composite.internal,
                );
                let initial = self
                    .nodes_of_initial()
                    .contains(&format!("{}a{c}", self.prefix));
                let peripheries = if initial { ", peripheries=2" } else { "" };
                let _ = writeln!(
                    out,
                    "{indent}{}a{c} [label=\"{label}\"{peripheries}];",
                    self.prefix
                );
                continue;
            }
            // A region of a parallel state is drawn dashed, as UML separates regions.
            let region = within.is_some_and(|p| self.machine.composites[p].parallel);
            let style = if region {
                "\"rounded,dashed\""
            } else {
                "rounded"
            };
            let mut label = format!("{}\\l", escape(short));
            activities(
                &mut label,
                &composite.on_entry,
                &composite.on_exit,
                &composite.internal,
            );
            let _ = writeln!(out, "{indent}subgraph {} {{", quote(&self.cluster_name(c)));
            let inner = format!("{indent}  ");
            let _ = writeln!(
                out,
                "{inner}label=\"{label}\"; labeljust=l; style={style}; fontname=\"Helvetica\"; fontsize=10;"
            );
            self.cluster(out, Some(c), &inner);
            let _ = writeln!(out, "{indent}}}");
        }
    }

    /// A state with its own activities (a flat state's hold its composites' too).
    fn state(&self, out: &mut String, state: &State, indent: &str) {
        let composites = &self.machine.composites;
        let around = self.around(state);
        let entered: usize = around[..state.arrives_through.min(around.len())]
            .iter()
            .map(|&c| composites[c].on_entry.len())
            .sum();
        let staying: usize = around.iter().map(|&c| composites[c].internal.len()).sum();
        // The manifest's parameters, set first of the initial state's arrival (`link.rs`),
        // come before its composites' part and are drawn as its own.
        let params: Vec<String> = (self.machine.interface.params.iter())
            .map(|p| global_of(&self.machine.name, &p.name))
            .collect();
        let lead = (state.on_entry.iter())
            .take_while(|a| matches!(a, Action::Statement(Statement::Assign { name, .. }) if params.contains(name)))
            .count();
        let own: Vec<Action> = (state.on_entry[..lead].iter())
            .chain(state.on_entry.get(lead + entered..).unwrap_or_default())
            .cloned()
            .collect();
        let short = state.name.rsplit('.').next().unwrap_or(&state.name);
        let mut label = format!("{} ({})\\n", escape(short), state.id);
        activities(
            &mut label,
            &own,
            &state.on_exit,
            state.internal.get(staying..).unwrap_or_default(),
        );
        let peripheries = if self.node_of.get(&self.machine.initial) == Some(&state.id) {
            ", peripheries=2"
        } else {
            ""
        };
        let _ = writeln!(
            out,
            "{indent}{} [label=\"{label}\"{peripheries}];",
            self.node(state.id)
        );
    }

    /// Each transition once as written: a state's own from its node, numbered among them; a
    /// composite's from its cluster's edge, numbered among the composite's.
    fn edges(&self, out: &mut String, indent: &str) {
        // One written transition lowers to several (a copy a state, an arm a place a history
        // resumes): each is drawn once, as its last, which for a history is the one that
        // carries the label as written.
        let written = |t: &Transition| {
            let from = match t.composite {
                Some(c) if self.machine.composites[c].atomic => format!("{}a{c}", self.prefix),
                Some(c) => self.cluster_name(c),
                None => self.node(t.source),
            };
            (from, t.line)
        };
        let mut last: HashMap<(String, usize), &Transition> = HashMap::new();
        let mut order: Vec<(String, usize)> = Vec::new();
        for t in &self.machine.transitions {
            let key = written(t);
            if last.insert(key.clone(), t).is_none() {
                order.push(key);
            }
        }
        let mut numbers: HashMap<&str, usize> = HashMap::new();
        for key in &order {
            let t = last[key];
            let from = key.0.as_str();
            let number = numbers.entry(from).or_default();
            *number += 1;
            let (said, style) = crate::dot_text::stays_marks(t);
            let label = format!("{number}: {}{said}", escape(&t.shown().to_string()));
            let target = self.target_node(t);
            let cluster_of = t.composite.filter(|&c| !self.machine.composites[c].atomic);
            // A composite's transition leaves from a node inside its cluster (Graphviz clips
            // the edge there), never from another region's state.
            let source = match (t.composite, self.machine.state(t.source)) {
                (Some(c), Some(state)) => self.node_inside(state, c),
                _ => self.node(t.source),
            };
            if !t.targets.is_empty() {
                let from_cluster = cluster_of.is_some();
                out.push_str(&self.forked(t, (from, from_cluster), &source, &label, indent));
                continue;
            }
            // One that stays loops on the state it fires in, wherever it was written.
            let Some(c) = cluster_of.filter(|_| !t.stays) else {
                let _ = writeln!(
                    out,
                    "{indent}{source} -> {target} [label=\"{label}\"{style}];"
                );
                continue;
            };
            let cluster = quote(from);
            let within = self.machine.state(t.target).is_some_and(|s| {
                let path = &self.machine.composites[c].name;
                self.machine.state_is_in(s, path) && s.name != *path
            });
            if !within {
                let _ = writeln!(
                    out,
                    "{indent}{source} -> {target} [label=\"{label}\", ltail={cluster}];"
                );
                continue;
            }
            // Leaving the composite and entering it again (SCXML's external transition):
            // out of its edge to a point outside it and back in, since an edge from a
            // cluster to a state inside it is drawn by Graphviz as if between the states.
            let point = format!("{from}_back{}", t.line);
            let _ = writeln!(
                out,
                "{indent}{point} [shape=point, width=0.05];\n\
                 {indent}{source} -> {point} [label=\"{label}\", ltail={cluster}, arrowhead=none];\n\
                 {indent}{point} -> {target};"
            );
        }
    }
}

fn activities(label: &mut String, entry: &[Action], exit: &[Action], internal: &[Action]) {
    for (section, actions) in [("entry", entry), ("exit", exit), ("internal", internal)] {
        for action in actions {
            let _ = write!(label, "{section}: {}\\l", escape(&show(action)));
        }
    }
}
