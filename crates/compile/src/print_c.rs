//! A behaviour's plan printed as freestanding C99: `behaviour.h` (its sizes), `behaviour.c` (its
//! tables, then the runtime, then its own functions: a ringlet a machine, its answers), a
//! decision function a theory, and the host harness `main.c`. The runtime and the harness are
//! real C files in `crates/compile/c/`, copied beside them.

use crate::machine_code;
use crate::plan::Plan;
use crate::spell_c::{esc, C};
use proclaim_lower::LOOP_LIMIT;
use std::fmt::Write;

/// The world, its callbacks and the host's API, for any behaviour's sizes.
const PROCLAIM_H: &str = include_str!("../c/proclaim.h");
/// The runtime a behaviour's functions call, included by `behaviour.c` after its tables.
const RUNTIME_H: &str = include_str!("../c/proclaim_runtime.h");
/// The host harness: reads an impersonator script on standard input, runs the behaviour on a
/// virtual clock and writes the trace as `proclaim run --trace` does.
const HARNESS: &str = include_str!("../c/harness.c");

/// Every file of the compiled behaviour: name and text.
pub(crate) fn behaviour_files(plan: &Plan) -> Vec<(String, String)> {
    let mut files = vec![
        ("behaviour.h".to_string(), header(plan)),
        ("behaviour.c".to_string(), source(plan)),
        ("proclaim.h".to_string(), PROCLAIM_H.to_string()),
        ("proclaim_runtime.h".to_string(), RUNTIME_H.to_string()),
        ("main.c".to_string(), HARNESS.to_string()),
    ];
    for theory in &plan.theories {
        let c = theory.compiled.to_c(&theory.prefix);
        files.push((format!("{}.h", theory.prefix), c.header));
        files.push((format!("{}.c", theory.prefix), c.source));
    }
    files
}

/// `template` with each `@NAME@` replaced by its value, in one pass (values are not searched).
pub(crate) fn fill(template: &str, values: &[(&str, &str)]) -> String {
    let mut out = String::with_capacity(template.len());
    let mut rest = template;
    while let Some(at) = rest.find('@') {
        out.push_str(&rest[..at]);
        let after = &rest[at + 1..];
        let named = after.find('@').and_then(|end| {
            let name = &after[..end];
            values
                .iter()
                .find(|(key, _)| *key == name)
                .map(|(_, value)| (end, *value))
        });
        match named {
            Some((end, value)) => {
                out.push_str(value);
                rest = &after[end + 1..];
            }
            None => {
                out.push('@');
                rest = after;
            }
        }
    }
    out.push_str(rest);
    out
}

/// `behaviour.h`: the behaviour's sizes, then `proclaim.h`.
fn header(plan: &Plan) -> String {
    let mut h = String::new();
    let _ = writeln!(h, "/* The behaviour `{}` compiled by proclaim (generated: do not edit). */\n#ifndef BEHAVIOUR_H\n#define BEHAVIOUR_H\n#include <stdint.h>\n", comment(&plan.name));
    let _ = writeln!(
        h,
        "#define BEHAVIOUR_MACHINES {}\n#define BEHAVIOUR_OUTPUTS {}\n#define BEHAVIOUR_VARIABLES {}\n#define BEHAVIOUR_VALUES {}\n#define BEHAVIOUR_EXTERNS {}\n#define BEHAVIOUR_TEXT {}\n#define BEHAVIOUR_COMMANDS {}\n#define BEHAVIOUR_ASKS {}\n#define BEHAVIOUR_PERIOD_MS {}u\n#define BEHAVIOUR_LOOP_LIMIT {LOOP_LIMIT}u",
        plan.machines.len().max(1),
        plan.outputs.len().max(1),
        plan.variables().max(1),
        plan.slots.len().max(1),
        plan.externs.len().max(1),
        plan.longest_text,
        plan.commands.max(1),
        plan.most_asks().max(1),
        plan.period_ms
    );
    let _ = writeln!(
        h,
        "/* The composite states of the machines' charts, across the behaviour. */\n#define BEHAVIOUR_COMPOSITES {}",
        plan.composites.len().max(1)
    );
    let _ = writeln!(
        h,
        "/* The types under subsumption (the manifest's `[suppress]`), the distinct priorities of\n * the machines, and the longest text a held posting keeps. */\n#define BEHAVIOUR_SUPPRESSED {}\n#define BEHAVIOUR_LAYERS {}\n#define BEHAVIOUR_HELD_TEXT {}\n",
        plan.suppressed.len(),
        plan.layers().len().max(1),
        plan.longest_posting().max(1)
    );
    let _ = writeln!(
        h,
        "/* The types with a declared range (the manifest's `[ranges]`), and how many values outside\n * it a type's warnings remember. */\n#define BEHAVIOUR_RANGES {}\n#define BEHAVIOUR_RANGE_MEMORY {RANGE_MEMORY}\n",
        plan.ranges.len()
    );
    h.push_str("#include \"proclaim.h\"\n\n#endif\n");
    h
}

/// A list of C string literals, or `0` for an empty array's one element.
fn strings<'a>(texts: impl Iterator<Item = &'a str>) -> String {
    let quoted: Vec<String> = texts.map(|t| format!("\"{}\"", esc(t))).collect();
    if quoted.is_empty() {
        "0".into()
    } else {
        quoted.join(", ")
    }
}

/// `behaviour.c`: the tables, the runtime, then the behaviour's own functions.
fn source(plan: &Plan) -> String {
    let mut c = String::new();
    let _ = writeln!(c, "/* The behaviour `{}` compiled by proclaim (generated: do not edit). */\n#include <stdint.h>\n#include \"behaviour.h\"", comment(&plan.name));
    for theory in &plan.theories {
        let _ = writeln!(c, "#include \"{}.h\"", theory.prefix);
    }
    c.push('\n');
    tables(plan, &mut c);
    c.push_str("\n#include \"proclaim_runtime.h\"\n\n");
    c.push_str(&machine_code::answers(plan, &C));
    c.push_str(&machine_code::printed(plan, &C));
    c
}

/// A `static const` array of the behaviour: its element type, name, values (at least one: C
/// has no empty arrays) and what it says.
type Table = (&'static str, &'static str, String, &'static str);

/// The tables the runtime reads (`proclaim_runtime.h` names them).
fn tables(plan: &Plan, c: &mut String) {
    let _ = writeln!(c, "/* The answers a theory gives come first; the atoms from outside follow. Counts as variables,\n * not literals, so that an empty range is no comparison a compiler warns of. */\nstatic const unsigned theory_outputs = {}u;\nstatic const unsigned outputs = {}u;\nstatic const unsigned sensors = {}u;\nstatic const unsigned externs = {}u;\nstatic const unsigned composites = {}u;",
        plan.theory_outputs(), plan.outputs.len(), plan.sensors.len(), plan.externs.len(), plan.composites.len());
    let mut all = machine_tables(plan);
    all.extend(board_tables(plan));
    if !plan.suppressed.is_empty() {
        all.extend(held_tables(plan));
    }
    if !plan.ranges.is_empty() {
        all.extend(range_tables(plan));
    }
    for (ty, name, values, why) in all {
        if !why.is_empty() {
            let _ = writeln!(c, "/* {why} */");
        }
        let _ = writeln!(c, "static const {ty} {name}[] = {{{values}}};");
    }
}

fn machine_tables(plan: &Plan) -> Vec<Table> {
    let machines = &plan.machines;
    vec![
        ("char *const", "machine_name", strings(machines.iter().map(|m| m.name.as_str())), ""),
        ("long", "machine_initial", numbers(machines.iter().map(|m| m.initial)), ""),
        (
            "unsigned char",
            "machine_starts",
            numbers(machines.iter().map(|m| i64::from(m.start))),
            "Whether each machine runs from the start (else it is dormant until started).",
        ),
        (
            "unsigned long",
            "machine_priority",
            numbers(machines.iter().map(|m| i64::from(m.priority))),
            "Each machine's subsumption layer, which its postings carry.",
        ),
        (
            "int",
            "status_board",
            numbers(board_of_statuses(plan)),
            "The whiteboard value each machine's running state is posted to (`NameIsRunning`), or -1.",
        ),
        (
            "unsigned char",
            "value_is_bool",
            numbers(plan.slots.iter().map(|b| i64::from(*b))),
            "Whether each value slot starts as a truth value (false) rather than a whole 0.",
        ),
        (
            "unsigned",
            "composite_machine",
            numbers(plan.composites.iter().map(|&m| m as i64)),
            "The machine each composite state is in: its transitions' time tests count from its entry.",
        ),
    ]
}

/// The outputs, the whiteboard values read and the sensors' atoms.
fn board_tables(plan: &Plan) -> Vec<Table> {
    let (outputs, externs) = (&plan.outputs, &plan.externs);
    let (atoms, starts) = sensor_tables(plan);
    vec![
        ("char *const", "output_name", strings(outputs.iter().map(|o| o.name.as_str())), ""),
        ("char *const", "output_expert", strings(outputs.iter().map(|o| o.expert.as_str())), ""),
        (
            "int",
            "output_board",
            numbers(board_of_outputs(plan)),
            "The whiteboard value of each output's atom (-1 for none): an expert's answer is posted there.",
        ),
        ("char *const", "extern_name", strings(externs.iter().map(|b| b.name.as_str())), ""),
        (
            "unsigned char",
            "extern_bound",
            numbers(externs.iter().map(|b| i64::from(b.bound))),
            "Whether each whiteboard value is bound with `extern` (read as a whole 0 while unposted).",
        ),
        ("char *const", "sensor_name", strings(plan.sensors.iter().map(|(n, _)| n.as_str())), ""),
        (
            "char *const",
            "sensor_atom",
            strings(atoms.into_iter()),
            "Each sensor's atoms, one after another; `sensor_start[s]` is where sensor `s`'s begin.",
        ),
        ("unsigned", "sensor_start", starts.join(", "), ""),
    ]
}

/// How many values outside a declared range a compiled C behaviour remembers a type, to say
/// each once (it has no heap).
const RANGE_MEMORY: usize = 16;

/// The declared ranges: each type, its ends, and the end of its warning as the runner words it.
fn range_tables(plan: &Plan) -> Vec<Table> {
    let shown = plan.ranges.iter().map(|(_, low, high)| {
        format!(", outside its declared range {low}..{high} (the manifest's [ranges]): what `verify` proved assumed it")
    });
    let shown: Vec<String> = shown.collect();
    vec![
        (
            "char *const",
            "range_type",
            strings(plan.ranges.iter().map(|(ty, _, _)| ty.as_str())),
            "The types with a declared range, their lowest and highest whole numbers, and the end of the warning when a posting from outside leaves one.",
        ),
        ("int64_t", "range_low", list(plan.ranges.iter().map(|r| int64(r.1))), ""),
        ("int64_t", "range_high", list(plan.ranges.iter().map(|r| int64(r.2))), ""),
        ("char *const", "range_shown", strings(shown.iter().map(String::as_str)), ""),
    ]
}

/// A 64-bit whole number as a C constant (the lowest has no literal of its own).
fn int64(i: i64) -> String {
    match i {
        i64::MIN => "(-INT64_MAX - 1)".into(),
        _ => format!("INT64_C({i})"),
    }
}

fn list(items: impl Iterator<Item = String>) -> String {
    items.collect::<Vec<_>>().join(", ")
}

/// Subsumption's: the types held, for how long, and each machine's layer.
fn held_tables(plan: &Plan) -> Vec<Table> {
    let layers = plan.layers();
    let layer = |p: u32| layers.iter().position(|l| *l == p).unwrap_or(0) as i64;
    let held_ms: Vec<String> = plan
        .suppressed
        .iter()
        .map(|s| format!("{}u", s.hold_ms))
        .collect();
    vec![
        (
            "char *const",
            "held_type",
            strings(plan.suppressed.iter().map(|s| s.ty.as_str())),
            "The types under subsumption, in name order, and how long a higher layer's posting holds each.",
        ),
        ("uint64_t", "held_ms", held_ms.join(", "), ""),
        (
            "unsigned",
            "machine_layer",
            numbers(plan.machines.iter().map(|m| layer(m.priority))),
            "Each machine's rank among the distinct priorities, lowest 0.",
        ),
    ]
}

/// A list of C numbers, or `0` for an empty array's one element.
fn numbers(values: impl Iterator<Item = i64>) -> String {
    let shown: Vec<String> = values.map(|v| v.to_string()).collect();
    if shown.is_empty() {
        "0".into()
    } else {
        shown.join(", ")
    }
}

/// The whiteboard value of each output's atom, or -1.
pub(crate) fn board_of_outputs(plan: &Plan) -> impl Iterator<Item = i64> + '_ {
    plan.outputs.iter().map(|o| {
        plan.externs
            .iter()
            .position(|b| b.name == o.name)
            .map_or(-1, |e| e as i64)
    })
}

/// The whiteboard value each machine's running state is posted to, or -1.
pub(crate) fn board_of_statuses(plan: &Plan) -> impl Iterator<Item = i64> + '_ {
    (0..plan.machines.len()).map(|m| {
        plan.externs
            .iter()
            .position(|b| b.status_of == Some(m))
            .map_or(-1, |e| e as i64)
    })
}

/// Every sensor's atoms one after another, and where each sensor's begin (and the last ends).
fn sensor_tables(plan: &Plan) -> (Vec<&str>, Vec<String>) {
    let sensor_atoms: Vec<&str> = plan
        .sensors
        .iter()
        .flat_map(|(_, atoms)| atoms.iter().map(String::as_str))
        .collect();
    let mut sensor_starts = vec!["0u".to_string()];
    let mut start = 0;
    for (_, atoms) in &plan.sensors {
        start += atoms.len();
        sensor_starts.push(format!("{start}u"));
    }
    (sensor_atoms, sensor_starts)
}

fn comment(text: &str) -> String {
    text.replace("*/", "* /")
}
