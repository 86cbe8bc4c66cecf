//! A machine's diagram for the page: `proclaim draw`'s DOT rendered to SVG by Graphviz when it
//! is installed, else a plain layered layout drawn here; either way a state's group is titled
//! with its DOT node name (`s3`) and a transition's with `s3->s5`, which is what the page lights.

use proclaim_fsm::Machine;
use serde::Serialize;
use std::fmt::Write as _;
use std::io::Write as _;
use std::process::{Command, Stdio};

/// What the page knows of one machine besides where it is.
#[derive(Clone, Debug, Serialize)]
pub struct Chart {
    pub name: String,
    /// Started with the behaviour (a sub-machine waits to be started).
    pub start: bool,
    pub initial: i64,
    pub states: Vec<ChartState>,
    pub transitions: Vec<ChartTransition>,
    /// The diagram.
    pub svg: String,
    /// Who drew it: `graphviz`, or `built-in` when Graphviz is not installed.
    pub drawn_by: &'static str,
}

#[derive(Clone, Debug, Serialize)]
pub struct ChartState {
    pub id: i64,
    pub name: String,
    /// Its group's title in the SVG.
    pub node: String,
    /// The other nodes lit with it: a state of a parallel state's regions is drawn as one
    /// state a region (`docs/spec/behaviour.md` §3.2).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub also: Vec<String>,
}

#[derive(Clone, Debug, Serialize)]
pub struct ChartTransition {
    pub from: i64,
    pub to: i64,
    pub label: String,
    /// It acts and stays (`when p { … }`, §3.2): drawn as a dashed loop, as `proclaim draw`
    /// draws it, not as a move out and in again.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub stays: bool,
}

impl Chart {
    /// A machine as `proclaim draw` draws it.
    pub fn of_machine(machine: &Machine, start: bool) -> Chart {
        let drawn = proclaim_fsm::drawn_nodes(machine);
        let states = machine
            .states
            .iter()
            .zip(drawn)
            .map(|(s, (_, mut nodes))| {
                let regions = nodes.len() > 1 || nodes.first().is_some_and(|n| n.starts_with('a'));
                ChartState {
                    id: s.id,
                    name: s.name.clone(),
                    node: if regions { nodes.remove(0) } else { node(s.id) },
                    also: if regions { nodes } else { Vec::new() },
                }
            })
            .collect();
        let transitions = machine
            .transitions
            .iter()
            .map(|t| ChartTransition {
                from: t.source,
                to: t.target,
                label: t.shown().to_string(),
                stays: t.stays,
            })
            .collect();
        Chart::drawn(
            machine.name.clone(),
            start,
            machine.initial,
            states,
            transitions,
            &proclaim_fsm::to_dot(machine),
        )
    }

    /// A machine from its parts and `proclaim draw`'s DOT of it, as a behaviour compiled by
    /// `proclaim compile --target rust` keeps them: the same chart as [`Chart::of_machine`].
    pub fn of_parts(
        name: String,
        start: bool,
        initial: i64,
        states: &[(i64, &str)],
        transitions: &[(i64, i64, &str, bool)],
        dot: &str,
    ) -> Chart {
        let states = states
            .iter()
            .map(|(id, name)| ChartState {
                id: *id,
                name: name.to_string(),
                node: node(*id),
                also: Vec::new(),
            })
            .collect();
        let transitions = transitions
            .iter()
            .map(|&(from, to, label, stays)| ChartTransition {
                from,
                to,
                label: label.to_string(),
                stays,
            })
            .collect();
        Chart::drawn(name, start, initial, states, transitions, dot)
    }

    /// A machine known only from what it did (a trace replayed without its behaviour): the
    /// states it entered and the transitions it fired.
    pub fn of_trace(
        name: String,
        initial: i64,
        states: Vec<(i64, String)>,
        transitions: Vec<(i64, i64, String)>,
    ) -> Chart {
        let states: Vec<ChartState> = states
            .into_iter()
            .map(|(id, name)| ChartState {
                id,
                name,
                node: node(id),
                also: Vec::new(),
            })
            .collect();
        let transitions: Vec<ChartTransition> = transitions
            .into_iter()
            .map(|(from, to, label)| ChartTransition {
                from,
                to,
                label,
                stays: false,
            })
            .collect();
        let mut dot = format!("digraph {} {{\n  rankdir=LR;\n", quote(&name));
        dot.push_str("  node [shape=box, style=rounded, fontname=\"Helvetica\", fontsize=10];\n");
        dot.push_str("  edge [fontname=\"Helvetica\", fontsize=9];\n");
        for s in &states {
            let _ = writeln!(dot, "  {} [label={}];", s.node, quote(&s.name));
        }
        for t in &transitions {
            let _ = writeln!(
                dot,
                "  {} -> {} [label={}];",
                node(t.from),
                node(t.to),
                quote(&t.label)
            );
        }
        dot.push_str("}\n");
        Chart::drawn(name, true, initial, states, transitions, &dot)
    }

    fn drawn(
        name: String,
        start: bool,
        initial: i64,
        states: Vec<ChartState>,
        transitions: Vec<ChartTransition>,
        dot: &str,
    ) -> Chart {
        let mut chart = Chart {
            name,
            start,
            initial,
            states,
            transitions,
            svg: String::new(),
            drawn_by: "graphviz",
        };
        match graphviz(dot) {
            Some(svg) => {
                chart.svg = svg;
                chart.drawn_once();
            }
            None => {
                chart.svg = built_in(&chart);
                chart.drawn_by = "built-in";
            }
        }
        chart
    }
}

impl Chart {
    /// A nested state lowers to a flat state for each way into it, and `proclaim draw` draws
    /// it once, as the first (`dot_chart.rs`): the others light that node.
    fn drawn_once(&mut self) {
        let drawn = |node: &str| self.svg.contains(&format!("<title>{node}</title>"));
        let nodes: Vec<String> = self
            .states
            .iter()
            .map(|s| {
                if drawn(&s.node) {
                    return s.node.clone();
                }
                self.states
                    .iter()
                    .find(|other| other.name == s.name && drawn(&other.node))
                    .map_or_else(|| s.node.clone(), |other| other.node.clone())
            })
            .collect();
        for (state, node) in self.states.iter_mut().zip(nodes) {
            state.node = node;
        }
    }
}

/// `proclaim draw`'s node name of a state (ids may be negative; node names may not start `-`).
pub fn node(id: i64) -> String {
    if id < 0 {
        format!("sm{}", -id)
    } else {
        format!("s{id}")
    }
}

fn quote(text: &str) -> String {
    format!("\"{}\"", text.replace('\\', "\\\\").replace('"', "\\\""))
}

/// Graphviz's SVG without its XML prologue (it goes inside the page), or `None` when `dot` is
/// not installed or fails (what it said is logged: the page then draws the machine itself).
fn graphviz(dot: &str) -> Option<String> {
    let mut child = Command::new("dot")
        .arg("-Tsvg")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .ok()?;
    // Graphviz may stop reading early (a label over its 16,384-character limit): a broken pipe
    // here, and its reason on stderr.
    let taken = child.stdin.take()?.write_all(dot.as_bytes());
    let output = child.wait_with_output().ok()?;
    if !output.status.success() || taken.is_err() {
        tracing::warn!(
            "Graphviz could not render a diagram ({}); drawing it here",
            String::from_utf8_lossy(&output.stderr).trim()
        );
        return None;
    }
    let svg = String::from_utf8(output.stdout).ok()?;
    let start = svg.find("<svg")?;
    Some(svg[start..].to_string())
}

const BOX_WIDTH: i64 = 150;
const BOX_HEIGHT: i64 = 36;
const COLUMN: i64 = 230;
const ROW: i64 = 80;

/// States in columns by their distance from the initial state, transitions as curves: plainer
/// than Graphviz, but the same titles, so the page lights it the same way.
fn built_in(chart: &Chart) -> String {
    let index = |id: i64| chart.states.iter().position(|s| s.id == id);
    let (at, width, height) = place(&depths(chart));
    let mut svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}pt\" height=\"{height}pt\" viewBox=\"0 0 {width} {height}\">\n<g class=\"graph\">\n"
    );
    for (k, t) in chart.transitions.iter().enumerate() {
        let (Some(i), Some(j)) = (index(t.from), index(t.to)) else {
            continue;
        };
        let (x1, y1) = (at[i].0 + BOX_WIDTH / 2, at[i].1 + BOX_HEIGHT / 2);
        let (x2, y2) = (at[j].0 + BOX_WIDTH / 2, at[j].1 + BOX_HEIGHT / 2);
        // Bend each edge by its index, so edges between the same states do not overlap.
        let bend = 30 + 12 * (k as i64 % 4);
        let (cx, cy) = if i == j {
            (x1 + BOX_WIDTH / 2 + bend, y1 - bend)
        } else {
            ((x1 + x2) / 2, (y1 + y2) / 2 - bend)
        };
        let (dashes, said) = match t.stays {
            true => (" stroke-dasharray=\"5,3\"", " (stays)"),
            false => ("", ""),
        };
        let _ = writeln!(
            svg,
            "<g class=\"edge\"><title>{}-&gt;{}</title><path fill=\"none\" stroke=\"black\"{dashes} d=\"M{x1},{y1} Q{cx},{cy} {x2},{y2}\"/><text x=\"{cx}\" y=\"{cy}\" font-size=\"9\" font-family=\"Helvetica\" text-anchor=\"middle\">{}{said}</text></g>",
            node(t.from),
            node(t.to),
            escape(&t.label)
        );
    }
    for (s, (x, y)) in chart.states.iter().zip(&at) {
        let _ = writeln!(
            svg,
            "<g class=\"node\"><title>{}</title><rect x=\"{x}\" y=\"{y}\" width=\"{BOX_WIDTH}\" height=\"{BOX_HEIGHT}\" rx=\"8\" fill=\"white\" stroke=\"black\"/><text x=\"{}\" y=\"{}\" font-size=\"11\" font-family=\"Helvetica\" text-anchor=\"middle\">{}</text></g>",
            s.node,
            x + BOX_WIDTH / 2,
            y + BOX_HEIGHT / 2 + 4,
            escape(&s.name)
        );
    }
    svg.push_str("</g>\n</svg>\n");
    svg
}

/// Each state's distance from the initial state (breadth first), `None` where it is never
/// reached.
fn depths(chart: &Chart) -> Vec<Option<usize>> {
    let index = |id: i64| chart.states.iter().position(|s| s.id == id);
    let mut depth: Vec<Option<usize>> = vec![None; chart.states.len()];
    let mut queue = std::collections::VecDeque::new();
    if let Some(i) = index(chart.initial) {
        depth[i] = Some(0);
        queue.push_back(i);
    }
    while let Some(i) = queue.pop_front() {
        let from = chart.states[i].id;
        for t in chart.transitions.iter().filter(|t| t.from == from) {
            if let Some(j) = index(t.to) {
                if depth[j].is_none() {
                    depth[j] = Some(depth[i].unwrap_or(0) + 1);
                    queue.push_back(j);
                }
            }
        }
    }
    depth
}

/// Each state's top-left corner (a column per depth, the states never reached in a last one),
/// and the drawing's width and height.
fn place(depths: &[Option<usize>]) -> (Vec<(i64, i64)>, i64, i64) {
    let last = depths.iter().flatten().max().map_or(0, |d| d + 1);
    let mut rows_used: Vec<i64> = Vec::new();
    let mut at: Vec<(i64, i64)> = Vec::with_capacity(depths.len());
    for d in depths {
        let column = d.unwrap_or(last);
        if rows_used.len() <= column {
            rows_used.resize(column + 1, 0);
        }
        at.push((20 + column as i64 * COLUMN, 20 + rows_used[column] * ROW));
        rows_used[column] += 1;
    }
    let width = 40 + rows_used.len() as i64 * COLUMN;
    let height = 40 + rows_used.iter().max().copied().unwrap_or(1) * ROW;
    (at, width, height)
}

fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// PLAY.KICK is entered from outside PLAY (running PLAY's entry) and from SEARCH: two flat
    /// states, one node, which both light.
    #[test]
    fn every_flat_state_of_a_nested_state_lights_its_one_node() {
        let text = "machine M\ninitial IDLE\nstate IDLE {\n    when go -> PLAY\n}\nstate PLAY {\n    entry {\n        On: x\n    }\n    initial KICK\n    state SEARCH {\n        when seen -> KICK\n    }\n    state KICK {\n        when kicked -> SEARCH\n    }\n}\n";
        let read = proclaim_fsm::parse_machine("M.machine", text);
        assert!(!read.has_errors(), "{:?}", read.diagnostics);
        let machine = &read.machines[0];
        let kicks: Vec<i64> = machine
            .states
            .iter()
            .filter(|s| s.name == "PLAY.KICK")
            .map(|s| s.id)
            .collect();
        assert_eq!(kicks.len(), 2, "{machine:?}");
        let chart = Chart::of_machine(machine, true);
        if chart.drawn_by != "graphviz" {
            eprintln!("skipped: Graphviz is not installed");
            return;
        }
        let nodes: Vec<&str> = chart
            .states
            .iter()
            .filter(|s| s.name == "PLAY.KICK")
            .map(|s| s.node.as_str())
            .collect();
        assert_eq!(nodes, [node(kicks[0]), node(kicks[0])]);
        for state in &chart.states {
            assert!(chart
                .svg
                .contains(&format!("<title>{}</title>", state.node)));
        }
        assert!(chart.svg.contains("<title>cluster_c0</title>"));
    }

    #[test]
    fn the_built_in_layout_titles_states_and_transitions_as_graphviz_does() {
        let chart = Chart {
            name: "M".into(),
            start: true,
            initial: 0,
            states: vec![
                ChartState {
                    id: 0,
                    name: "IDLE".into(),
                    node: node(0),
                    also: Vec::new(),
                },
                ChartState {
                    id: -2,
                    name: "A<B".into(),
                    node: node(-2),
                    also: Vec::new(),
                },
            ],
            transitions: vec![
                ChartTransition {
                    from: 0,
                    to: -2,
                    label: "x && y".into(),
                    stays: false,
                },
                ChartTransition {
                    from: -2,
                    to: -2,
                    label: "z".into(),
                    stays: true,
                },
            ],
            svg: String::new(),
            drawn_by: "built-in",
        };
        let svg = built_in(&chart);
        assert!(svg.contains("<title>s0</title>"), "{svg}");
        assert!(svg.contains("<title>sm2</title>"), "{svg}");
        assert!(svg.contains("<title>s0-&gt;sm2</title>"), "{svg}");
        assert!(
            svg.contains("A&lt;B") && svg.contains("x &amp;&amp; y"),
            "{svg}"
        );
        // A transition that stays is a dashed loop that says so; a move is drawn whole.
        let edge = |title: &str| {
            let at = svg.find(&format!("<title>{title}</title>")).expect(title);
            svg[at..]
                .split("</g>")
                .next()
                .unwrap_or_default()
                .to_string()
        };
        let stays = edge("sm2-&gt;sm2");
        assert!(
            stays.contains("stroke-dasharray") && stays.contains("z (stays)"),
            "{svg}"
        );
        assert!(!edge("s0-&gt;sm2").contains("stroke-dasharray"), "{svg}");
    }

    #[test]
    fn states_stand_in_columns_by_their_distance_from_the_initial_one() {
        // 0 -> 1 -> 2, 0 -> 3; 4 never reached.
        let transitions = [(0, 1), (1, 2), (0, 3)]
            .iter()
            .map(|&(from, to)| ChartTransition {
                from,
                to,
                label: "x".into(),
                stays: false,
            })
            .collect();
        let chart = Chart {
            name: "M".into(),
            start: true,
            initial: 0,
            states: (0..5)
                .map(|id| ChartState {
                    id,
                    name: format!("S{id}"),
                    node: node(id),
                    also: Vec::new(),
                })
                .collect(),
            transitions,
            svg: String::new(),
            drawn_by: "built-in",
        };
        let depths = depths(&chart);
        assert_eq!(depths, [Some(0), Some(1), Some(2), Some(1), None]);
        let (at, width, height) = place(&depths);
        let column = |x: i64| (x - 20) / COLUMN;
        let columns: Vec<i64> = at.iter().map(|&(x, _)| column(x)).collect();
        assert_eq!(columns, [0, 1, 2, 1, 3]);
        assert_eq!(
            at[3].1,
            at[1].1 + ROW,
            "two states of one column one above the other"
        );
        assert_eq!((width, height), (40 + 4 * COLUMN, 40 + 2 * ROW));
    }
}
