//! A behaviour's plan printed as a Cargo project: `src/behaviour.rs` (a ringlet a machine, the
//! round schedule), `src/theories.rs` (a decision diagram a theory), `src/charts.rs` (the
//! machines drawn), `src/main.rs` (a host taking `proclaim run`'s options for one behaviour) and
//! `src/board.rs` (the whiteboard, or its absence). The values, the world and the trace's events
//! are `proclaim-runtime`'s, copied into `runtime/`, so a trace is the interpreter's by
//! construction and the project builds with crates from crates.io alone; only a project asked
//! for a whiteboard depends on this repository's crates, by path.

use crate::machine_code;
use crate::plan::Plan;
use crate::print_c::{board_of_outputs, board_of_statuses, fill};
use crate::rust_template::BODY;
use crate::spell_rust::Rust;
use crate::tabulate::Compiled;
use proclaim_lower::LOOP_LIMIT;
use std::fmt::Write;
use std::path::Path;

/// This repository's cargo configuration, for a project built with its Zenoh crates: their TCP
/// links must close at once there as here (docs/spec/behaviour.md §1.1, "Partitions").
const CARGO_CONFIG: &str = include_str!("../../../.cargo/config.toml");

/// The host: reads an impersonator script, runs the behaviour and writes the trace.
const MAIN: &str = include_str!("rust_main.rs.txt");
/// The whiteboard the host shows the run on (`--monitor`, `--listen`, `--connect`).
const BOARD: &str = include_str!("rust_board.rs.txt");
/// The whiteboard's absence, in a project compiled without one.
const NO_BOARD: &str = include_str!("rust_no_board.rs.txt");
/// The versions this repository builds with, so a generated project builds with the same.
const LOCK: &str = include_str!("../../../Cargo.lock");

/// The manifest of `runtime/`, the copy of `proclaim-runtime` a project carries: its
/// dependencies as `crates/runtime/Cargo.toml` has them, with the workspace's versions.
const RUNTIME_MANIFEST: &str = "# proclaim's runtime, copied from its repository (do not edit).\n[package]\nname = \"proclaim-runtime\"\nversion = \"0.1.0\"\nedition = \"2021\"\npublish = false\n\n[dependencies]\nrustc-hash = \"2\"\nserde = { version = \"1\", features = [\"derive\"] }\nserde_json = \"1\"\n";

/// Every file of the Cargo project: path and text. `whiteboard` is this repository's root when
/// the program is to run on a whiteboard (`--monitor`, `--listen`, `--connect`):
/// `proclaim-host-board` (and through it the board, the monitor, the runner and, with the
/// `network` feature, Zenoh) and the runtime are then dependencies by path. Without it the
/// project carries its own copy of the runtime and needs nothing from this repository.
pub(crate) fn project_files(plan: &Plan, whiteboard: Option<&Path>) -> Vec<(String, String)> {
    let mut files = vec![
        ("Cargo.toml".into(), manifest(plan, whiteboard)),
        ("Cargo.lock".into(), LOCK.into()),
        ("src/main.rs".into(), MAIN.into()),
        ("src/behaviour.rs".into(), behaviour(plan)),
        ("src/theories.rs".into(), theories(plan)),
        ("src/charts.rs".into(), charts(plan)),
        (
            "src/board.rs".into(),
            (if whiteboard.is_some() {
                BOARD
            } else {
                NO_BOARD
            })
            .into(),
        ),
    ];
    if whiteboard.is_some() {
        files.push((".cargo/config.toml".into(), CARGO_CONFIG.into()));
    } else {
        files.push(("runtime/Cargo.toml".into(), RUNTIME_MANIFEST.into()));
        for (path, text) in proclaim_runtime::SOURCES {
            files.push((format!("runtime/{path}"), text.to_string()));
        }
    }
    files
}

/// A Cargo package name from the behaviour's name.
fn package_name(name: &str) -> String {
    let tail: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '-'
            }
        })
        .collect();
    format!("behaviour-{}", tail.trim_matches('-'))
}

fn manifest(plan: &Plan, whiteboard: Option<&Path>) -> String {
    let mut out = format!(
        "# The behaviour `{}` compiled by proclaim (generated: do not edit).\n[package]\nname = \"{}\"\nversion = \"0.1.0\"\nedition = \"2021\"\npublish = false\n\n[dependencies]\nserde_json = \"1\"\n",
        plan.name.replace('\n', " "),
        package_name(&plan.name),
    );
    match whiteboard {
        None => out.push_str("proclaim-runtime = { path = \"runtime\" }\n"),
        Some(repository) => {
            let path = |krate: &str| {
                format!(
                    "{:?}",
                    repository.join("crates").join(krate).to_string_lossy()
                )
            };
            let _ = write!(
                out,
                "proclaim-runtime = {{ path = {} }}\nproclaim-host-board = {{ path = {} }}\n\n[features]\n# The whiteboard shared with other processes and robots (`--listen`, `--connect`): Zenoh's\n# stack is large, so it is built only when asked for.\nnetwork = [\"proclaim-host-board/network\"]\n",
                path("runtime"),
                path("host-board"),
            );
        }
    }
    out.push_str("\n# Its own workspace, wherever it is written.\n[workspace]\n");
    out
}

/// `src/charts.rs`: each machine as `proclaim draw` draws it, for the monitor's page.
fn charts(plan: &Plan) -> String {
    let mut out = format!(
        "//! Each machine as `proclaim draw` draws it (generated by proclaim: do not edit): what the\n//! monitor's page shows.\n\n/// The behaviour's name.\npub const NAME: &str = {:?};\n\npub struct Drawn {{\n    pub name: &'static str,\n    pub start: bool,\n    pub initial: i64,\n    pub states: &'static [(i64, &'static str)],\n    pub transitions: &'static [(i64, i64, &'static str, bool)],\n    pub dot: &'static str,\n}}\n\npub const CHARTS: &[Drawn] = &[\n",
        plan.name
    );
    for m in &plan.machines {
        let states = list(m.states.iter().map(|s| format!("({}, {:?})", s.id, s.name)));
        let transitions = list(
            m.drawing
                .transitions
                .iter()
                .map(|(from, to, label, stays)| format!("({from}, {to}, {label:?}, {stays})")),
        );
        let _ = writeln!(
            out,
            "    Drawn {{\n        name: {:?},\n        start: {},\n        initial: {},\n        states: &[{states}],\n        transitions: &[{transitions}],\n        dot: {:?},\n    }},",
            m.name, m.start, m.initial, m.drawing.dot
        );
    }
    out.push_str("];\n");
    out
}

/// `src/theories.rs`: each theory's decision diagram and its evaluation.
fn theories(plan: &Plan) -> String {
    let mut out = String::from("//! The behaviour's theories as decision diagrams (generated by proclaim: do not edit):\n//! nodes 0 and 1 are false and true; `input[v]` is decision variable `v`.\n");
    for theory in &plan.theories {
        out.push_str(&diagram(&theory.prefix, &theory.compiled));
    }
    out
}

fn diagram(prefix: &str, compiled: &Compiled) -> String {
    let d = &compiled.diagram;
    let list = |values: Vec<u32>| -> String {
        let texts: Vec<String> = values.iter().map(u32::to_string).collect();
        texts.join(", ")
    };
    let n = d.nodes.len();
    format!(
        "\n/// Theory `{}`: output `output`'s answer; false for an output out of range.\npub fn {prefix}(output: usize, input: &[bool]) -> bool {{\n    const VAR: [u32; {n}] = [{}];\n    const LOW: [u32; {n}] = [{}];\n    const HIGH: [u32; {n}] = [{}];\n    const ROOT: [u32; {}] = [{}];\n    let Some(root) = ROOT.get(output) else {{\n        return false;\n    }};\n    let mut node = *root as usize;\n    while node > 1 {{\n        node = if input[VAR[node] as usize] {{ HIGH[node] }} else {{ LOW[node] }} as usize;\n    }}\n    node == 1\n}}\n",
        compiled.name.replace('\n', " "),
        list(d.nodes.iter().map(|x| x.var).collect()),
        list(d.nodes.iter().map(|x| x.low).collect()),
        list(d.nodes.iter().map(|x| x.high).collect()),
        d.roots.len(),
        list(d.roots.clone()),
    )
}

/// Items of a Rust array, separated by commas.
fn list(items: impl Iterator<Item = String>) -> String {
    items.collect::<Vec<_>>().join(", ")
}

/// An index the C tables write as -1 for none, as a Rust `Option`.
fn optional_index(index: i64) -> String {
    usize::try_from(index).map_or("None".to_string(), |i| format!("Some({i})"))
}

/// A list of Rust string literals.
fn strings<'a>(texts: impl Iterator<Item = &'a str>) -> String {
    let quoted: Vec<String> = texts.map(|t| format!("{t:?}")).collect();
    quoted.join(", ")
}

/// The constants of what comes from outside the machines' code: each machine's priority, the
/// types under subsumption, the sensors' atoms and the behaviour's own script.
fn outside_tables(plan: &Plan) -> (String, String, String, String) {
    let priorities: Vec<String> = plan
        .machines
        .iter()
        .map(|m| m.priority.to_string())
        .collect();
    let priorities = priorities.join(", ");
    let suppressed: Vec<String> = plan
        .suppressed
        .iter()
        .map(|s| format!("({:?}, {})", s.ty, s.hold_ms))
        .collect();
    let suppressed = suppressed.join(", ");
    let sensors: Vec<String> = plan
        .sensors
        .iter()
        .map(|(name, atoms)| format!("({name:?}, &{atoms:?})"))
        .collect();
    let sensors = sensors.join(", ");
    let script = match &plan.script {
        Some((file, text)) => format!("Some(({file:?}, {text:?}))"),
        None => "None".into(),
    };
    (priorities, suppressed, sensors, script)
}

/// `src/behaviour.rs`.
fn behaviour(plan: &Plan) -> String {
    let (priorities, suppressed, sensors, script) = outside_tables(plan);
    let numbers = [
        plan.variables().to_string(),
        plan.period_ms.to_string(),
        plan.answer_timeout_ms.to_string(),
        plan.commands.max(1).to_string(),
        LOOP_LIMIT.to_string(),
    ];
    fill(
        BODY,
        &[
            ("name", &plan.name.replace('\n', " ")),
            ("inputs", &numbers[0]),
            ("period_ms", &numbers[1]),
            ("commands", &numbers[3]),
            ("loop_limit", &numbers[4]),
            ("answer_timeout_ms", &numbers[2]),
            (
                "output_names",
                &strings(plan.outputs.iter().map(|o| o.name.as_str())),
            ),
            (
                "experts",
                &strings(plan.outputs.iter().map(|o| o.expert.as_str())),
            ),
            (
                "machine_names",
                &strings(plan.machines.iter().map(|m| m.name.as_str())),
            ),
            ("priorities", &priorities),
            (
                "extern_names",
                &strings(plan.externs.iter().map(|b| b.name.as_str())),
            ),
            (
                "extern_bound",
                &list(plan.externs.iter().map(|b| b.bound.to_string())),
            ),
            (
                "output_board",
                &list(board_of_outputs(plan).map(optional_index)),
            ),
            (
                "status_board",
                &list(board_of_statuses(plan).map(optional_index)),
            ),
            ("theory_outputs", &plan.theory_outputs().to_string()),
            ("script", &script),
            ("sensors", &sensors),
            ("suppressed", &suppressed),
            ("answers", &machine_code::answers(plan, &Rust)),
            ("code", &machine_code::printed(plan, &Rust)),
            (
                "initials",
                &list(plan.machines.iter().map(|m| m.initial.to_string())),
            ),
            (
                "starts",
                &list(plan.machines.iter().map(|m| m.start.to_string())),
            ),
            ("var_inits", &var_inits(plan)),
            (
                "composite_machine",
                &list(plan.composites.iter().map(ToString::to_string)),
            ),
            (
                "ranges",
                &list(
                    plan.ranges
                        .iter()
                        .map(|(ty, low, high)| format!("({ty:?}, {low}, {high})")),
                ),
            ),
        ],
    )
}

/// Each value slot's start: a whole 0, or false for one that starts as a truth value.
fn var_inits(plan: &Plan) -> String {
    let starts: Vec<&str> = plan
        .slots
        .iter()
        .map(|is_bool| {
            if *is_bool {
                "v_bool(false)"
            } else {
                "v_int(0)"
            }
        })
        .collect();
    starts.join(", ")
}

#[cfg(test)]
mod tests {
    use super::RUNTIME_MANIFEST;

    /// The names under `[dependencies]` in a manifest.
    fn dependencies(manifest: &str) -> Vec<String> {
        let mut names: Vec<String> = manifest
            .split("[dependencies]")
            .nth(1)
            .unwrap_or_default()
            .lines()
            .take_while(|l| !l.starts_with('['))
            .filter_map(|l| l.split(['.', ' ', '=']).next())
            .filter(|name| !name.is_empty() && !name.starts_with('#'))
            .map(str::to_string)
            .collect();
        names.sort();
        names
    }

    #[test]
    fn the_runtimes_copy_depends_on_what_the_runtime_does() {
        let manifest = concat!(env!("CARGO_MANIFEST_DIR"), "/../runtime/Cargo.toml");
        let workspace = std::fs::read_to_string(manifest).unwrap();
        assert_eq!(dependencies(RUNTIME_MANIFEST), dependencies(&workspace));
        assert_eq!(
            dependencies(RUNTIME_MANIFEST),
            ["rustc-hash", "serde", "serde_json"]
        );
    }
}
