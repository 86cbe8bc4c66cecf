//! A behaviour's plan printed as a Cargo project: `src/behaviour.rs` (a ringlet a machine, the
//! round schedule), `src/theories.rs` (a decision diagram a theory), `src/charts.rs` (the
//! machines drawn), `src/main.rs` (a host taking `proclaim run`'s options for one behaviour) and
//! `src/board.rs` (the whiteboard, or its absence). The values, the world and the trace's events
//! are `proclaim-runtime`'s, copied into `runtime/`, so a trace is the interpreter's by
//! construction and the project builds with crates from crates.io alone; only a project asked
//! for a whiteboard depends on this repository's crates, by path.

use crate::plan::{
    Answer, Condition, Conversion, MachinePlan, Piece, Plan, StatePlan, Step, Value,
};
use crate::print_c::{board_of_outputs, board_of_statuses, fill, input_updates};
use crate::rust_template::{BODY, RING};
use crate::tabulate::Compiled;
use proclaim_fsm::control::Command;
use proclaim_runner::LOOP_LIMIT;
use std::fmt::Write;
use std::path::Path;

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
/// the program is to run on a whiteboard (`--monitor`, `--listen`, `--connect`): its crates
/// (board, monitor, runner, Zenoh) and its runtime are then dependencies by path. Without it the
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
    if whiteboard.is_none() {
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
                "proclaim-runtime = {{ path = {} }}\nproclaim-board = {{ path = {} }}\nproclaim-monitor = {{ path = {} }}\nproclaim-runner = {{ path = {} }}\ntokio = {{ version = \"1.40\", features = [\"rt-multi-thread\", \"signal\", \"time\", \"sync\"] }}\nproclaim-zenoh = {{ path = {}, optional = true }}\n\n[features]\n# The whiteboard shared with other processes and robots (`--listen`, `--connect`): Zenoh's\n# stack is large, so it is built only when asked for.\nnetwork = [\"dep:proclaim-zenoh\"]\n",
                path("runtime"),
                path("board"),
                path("monitor"),
                path("runner"),
                path("zenoh"),
            );
        }
    }
    out.push_str("\n# Its own workspace, wherever it is written.\n[workspace]\n");
    out
}

/// `src/charts.rs`: each machine as `proclaim draw` draws it, for the monitor's page.
fn charts(plan: &Plan) -> String {
    let mut out = format!(
        "//! Each machine as `proclaim draw` draws it (generated by proclaim: do not edit): what the\n//! monitor's page shows.\n\n/// The behaviour's name.\npub const NAME: &str = {:?};\n\npub struct Drawn {{\n    pub name: &'static str,\n    pub start: bool,\n    pub initial: i64,\n    pub states: &'static [(i64, &'static str)],\n    pub transitions: &'static [(i64, i64, &'static str)],\n    pub dot: &'static str,\n}}\n\npub const CHARTS: &[Drawn] = &[\n",
        plan.name
    );
    for m in &plan.machines {
        let states = list(m.states.iter().map(|s| format!("({}, {:?})", s.id, s.name)));
        let transitions = list(
            m.drawing
                .transitions
                .iter()
                .map(|(from, to, label)| format!("({from}, {to}, {label:?})")),
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

/// The arms of `answer` (a theory's decision diagram, or an atom from outside's variable) and
/// of `apply_input` (each type once, setting every variable pair it sets).
fn answers_and_inputs(plan: &Plan) -> (String, String) {
    let mut answer_cases = String::new();
    for (k, o) in plan.outputs.iter().enumerate() {
        let _ = match o.answer {
            Answer::Theory {
                theory,
                index,
                offset,
            } => writeln!(
                answer_cases,
                "        {k} => crate::theories::{}({index}, &w.input[{offset}..]),",
                plan.theories[theory].prefix
            ),
            Answer::Outside { variable } => {
                writeln!(answer_cases, "        {k} => w.input[{}],", variable + 1)
            }
        };
    }
    let mut input_cases = String::new();
    for (ty, inputs) in plan.input_types() {
        let sets = input_updates(
            &inputs,
            [
                "            set_input(w, @v@, content);",
                "            if w.input[@v@ + 1] {",
                "                w.input[@o@] = true;\n                w.input[@o@ + 1] = false;",
                "            }",
            ],
        );
        let _ = writeln!(
            input_cases,
            "        {ty:?} => {{\n{sets}            true\n        }}"
        );
    }
    (answer_cases, input_cases)
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
    let (answer_cases, input_cases) = answers_and_inputs(plan);
    let schedule = Schedule::of(plan);
    let (priorities, suppressed, sensors, script) = outside_tables(plan);
    let numbers = [
        plan.machines.len().to_string(),
        plan.outputs.len().to_string(),
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
            ("machines", &numbers[0]),
            ("outputs", &numbers[1]),
            ("variables", &numbers[2]),
            ("period_ms", &numbers[3]),
            ("commands", &numbers[5]),
            ("loop_limit", &numbers[6]),
            ("answer_timeout_ms", &numbers[4]),
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
            ("externs", &plan.externs.len().to_string()),
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
            ("sensors_n", &plan.sensors.len().to_string()),
            ("sensors", &sensors),
            ("suppressed_n", &plan.suppressed.len().to_string()),
            ("suppressed", &suppressed),
            ("input_cases", &input_cases),
            ("answer_cases", &answer_cases),
            ("code", &schedule.code),
            ("finals", &schedule.finals),
            ("var_inits", &var_inits(plan)),
            ("inits", &schedule.inits),
            ("rings", &schedule.rings),
            ("reads", &schedule.reads),
            ("dues", &schedule.dues),
            ("tops", &schedule.tops),
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

/// The parts of `behaviour.rs` written once a machine.
#[derive(Default)]
struct Schedule {
    code: String,
    rings: String,
    reads: String,
    dues: String,
    inits: String,
    finals: String,
    tops: String,
}

impl Schedule {
    fn of(plan: &Plan) -> Schedule {
        let mut s = Schedule::default();
        for (m, machine) in plan.machines.iter().enumerate() {
            s.code.push_str(&machine_code(m, machine));
            let _ = writeln!(s.rings, "    if w.status[{m}] == RUNNING && !w.fresh[{m}] && !done(w, {m}) {{\n        fired |= ring_{m}(w);\n        obey(w);\n    }}");
            let _ = writeln!(s.reads, "    if w.status[{m}] == RUNNING {{\n        for k in 0..OUTPUTS {{\n            if reads_{m}(w, k) && (w.asked[{m}][k] || (k < THEORY_OUTPUTS && w.ext_read[{m}])) && answer(w, k) != w.seen[{m}][k] {{\n                return true;\n            }}\n        }}\n        if w.globals_seen[{m}] != w.globals_changes && reads_globals_{m}(w) {{\n            return true;\n        }}\n        if (0..EXTERNS).any(|e| reads_extern_{m}(w, e) && !asked_of_expert(w, {m}, e) && w.extern_news({m}, e)) {{\n            return true;\n        }}\n    }}");
            let _ = writeln!(
                s.dues,
                "    if w.status[{m}] == RUNNING {{\n        due = due_{m}(w, due);\n    }}"
            );
            let _ = writeln!(
                s.inits,
                "    w.state[{m}] = {};\n    w.initial[{m}] = {};\n    w.just_entered[{m}] = true;\n    w.status[{m}] = {};",
                machine.initial,
                machine.initial,
                if machine.start { "RUNNING" } else { "DORMANT" }
            );
            let _ = writeln!(s.finals, "        {m} => final_{m}(w),");
            if machine.start {
                let _ = writeln!(
                    s.tops,
                    "    if !done(w, {m}) {{\n        return false;\n    }}"
                );
            }
        }
        s
    }
}

/// Whether machine `m` is in one of `ids`.
fn state_test(m: usize, ids: &[i64]) -> String {
    if ids.is_empty() {
        "let _ = w;\n    false".into()
    } else {
        let ids: Vec<String> = ids.iter().map(i64::to_string).collect();
        format!("matches!(w.state[{m}], {})", ids.join(" | "))
    }
}

/// Machine `m`'s functions: its ringlet, what its labels read, its final states, its dues.
fn machine_code(m: usize, machine: &MachinePlan) -> String {
    let mut entries = String::new();
    let mut cases = String::new();
    let mut read_cases = String::new();
    let mut due_cases = String::new();
    let mut extern_cases = String::new();
    for state in &machine.states {
        let id = state.id;
        if !state.reads_externs.is_empty() {
            let read: Vec<String> = state
                .reads_externs
                .iter()
                .map(|e| format!("e == {e}"))
                .collect();
            let _ = writeln!(extern_cases, "        {id} => {},", read.join(" || "));
        }
        entries.push_str(&entry_case(m, machine, state));
        cases.push_str(&ring_case(m, machine, state));
        let read: Vec<String> = state.reads.iter().map(|k| format!("k == {k}")).collect();
        let read = if read.is_empty() {
            "false".into()
        } else {
            read.join(" || ")
        };
        let _ = writeln!(read_cases, "        {id} => {read},");
        let due: String = state
            .due_ms
            .iter()
            .map(|ms| {
                format!("            let due = min_due(due, w.entered_ms[{m}].wrapping_add({ms}), w.now_ms);\n")
            })
            .collect();
        let _ = writeln!(
            due_cases,
            "        {id} => {{\n{due}            due\n        }}"
        );
    }
    let ids = |keep: fn(&StatePlan) -> bool| -> Vec<i64> {
        machine
            .states
            .iter()
            .filter(|s| keep(s))
            .map(|s| s.id)
            .collect()
    };
    let m_text = m.to_string();
    fill(
        RING,
        &[
            ("m", &m_text),
            ("entries", &entries),
            ("cases", &cases),
            ("read_cases", &read_cases),
            ("extern_cases", &extern_cases),
            ("global_test", &state_test(m, &ids(|s| s.reads_globals))),
            ("final_test", &state_test(m, &ids(|s| s.is_final))),
            ("due_cases", &due_cases),
        ],
    )
}

/// What entering `state` does: the event, its OnEntry, and a final state's end.
fn entry_case(m: usize, machine: &MachinePlan, state: &StatePlan) -> String {
    let mut entry = steps(m, &state.entry, 4);
    if state.is_final {
        let _ = writeln!(
            entry,
            "                report_finished(w, {m}, {:?});",
            state.name
        );
    }
    format!(
        "            {id} => {{\n                w.entered({:?}, {:?}, {id});\n{entry}            }}\n",
        machine.name,
        state.name,
        id = state.id
    )
}

/// A ringlet in `state`: its transitions tried in order, else its internal activity.
fn ring_case(m: usize, machine: &MachinePlan, state: &StatePlan) -> String {
    let id = state.id;
    let exit = steps(m, &state.exit, 4);
    let mut body = String::new();
    for t in &state.transitions {
        let _ = writeln!(
            body,
            "            if proved(w, {m}, |w| {}) {{\n                w.fired({:?}, {id}, {}, {:?});\n{exit}                w.state[{m}] = {};\n                w.just_entered[{m}] = true;\n                return true;\n            }}",
            condition(m, &t.condition),
            machine.name,
            t.target,
            t.label,
            t.target
        );
    }
    let internal = steps(m, &state.internal, 3);
    format!("        {id} => {{\n{body}{internal}            false\n        }}\n")
}

/// A label's Rust.
fn condition(m: usize, c: &Condition) -> String {
    match c {
        Condition::Constant(b) => b.to_string(),
        Condition::Ask(k) => format!("ask(w, {m}, {k})"),
        Condition::AskPosted { number, atom } => format!("ask_posted(w, {m}, {number}, {atom:?})"),
        Condition::Not(c) => format!("!{}", condition(m, c)),
        Condition::Both { and, left, right } => format!(
            "({} {} {})",
            condition(m, left),
            if *and { "&&" } else { "||" },
            condition(m, right)
        ),
        Condition::Elapsed(ms) => format!("elapsed_at_least(w, {m}, {ms})"),
        Condition::Truth(v) => truth(v),
    }
}

fn truth(v: &Value) -> String {
    format!("truthy({})", value(v))
}

/// A value's Rust (a `Scalar`).
fn value(v: &Value) -> String {
    match v {
        Value::Bool(b) => format!("v_bool({b})"),
        Value::Int(i) if *i == i64::MIN => "v_int(i64::MIN)".into(),
        Value::Int(i) => format!("v_int({i})"),
        Value::Slot(slot) => format!("w.var[{slot}]"),
        Value::Extern(number) => format!("read_extern(w, {number})"),
        Value::Not(operand) => format!("v_bool(!{})", truth(operand)),
        Value::Logic { and, left, right } => format!(
            "v_bool({} {} {})",
            truth(left),
            if *and { "&&" } else { "||" },
            truth(right)
        ),
        Value::Apply(function, arguments) => {
            let arguments: Vec<String> = arguments.iter().map(value).collect();
            format!("{}({})", function.helper(), arguments.join(", "))
        }
    }
}

fn steps(m: usize, steps: &[Step], depth: usize) -> String {
    steps.iter().map(|s| step(m, s, depth)).collect()
}

/// One step's Rust, indented `depth` levels.
fn step(m: usize, s: &Step, depth: usize) -> String {
    let pad = " ".repeat(4 * depth);
    match s {
        Step::Post { ty, content } => format!("{pad}post(w, {m}, {ty:?}, {content:?});\n"),
        Step::PostBuilt { ty, pieces } => {
            format!(
                "{}{pad}post_text(w, {m}, {ty:?});\n",
                build_text(pieces, &pad)
            )
        }
        Step::Command {
            ty,
            word,
            command,
            target,
        } => format!(
            "{pad}post(w, {m}, {ty:?}, {word:?});\n{pad}command(w, {target}, {}, {word:?});\n",
            command_code(*command)
        ),
        Step::Print(pieces) => format!("{}{pad}print_text(w, {m});\n", build_text(pieces, &pad)),
        Step::PostExtern { number, value: v } => format!(
            "{pad}let value = {};\n{pad}post_extern(w, {m}, {number}, value);\n",
            value(v)
        ),
        Step::Assign {
            slot,
            conversion,
            global,
            name,
            value: v,
        } => format!(
            "{pad}let value = {};\n{pad}assign(w, {m}, {slot}, {}, {global}, {name:?}, value);\n",
            value(v),
            conversion_code(*conversion)
        ),
        Step::Block(body) => format!("{pad}{{\n{}{pad}}}\n", steps(m, body, depth + 1)),
        Step::Loop { .. } => for_loop(m, s, depth),
        Step::Nothing => String::new(),
    }
}

/// A `for` loop as a `while`, stopped at the runner's loop limit with its warning.
fn for_loop(m: usize, s: &Step, depth: usize) -> String {
    let Step::Loop {
        number: n,
        state,
        init,
        condition,
        body,
        step: next,
    } = s
    else {
        return String::new();
    };
    let pad = " ".repeat(4 * depth);
    let inner = " ".repeat(4 * (depth + 1));
    let deeper = " ".repeat(4 * (depth + 2));
    let mut out = format!("{pad}{{\n{inner}let mut rounds_{n}: u32 = 0;\n");
    if let Some(init) = init {
        out.push_str(&step(m, init, depth + 1));
    }
    let condition = condition.as_ref().map_or("true".into(), truth);
    let warning = format!("a `for` loop in state {state} stopped after {LOOP_LIMIT} rounds");
    let _ = writeln!(
        out,
        "{inner}while {condition} {{\n{deeper}if rounds_{n} == LOOP_LIMIT {{\n{deeper}    w.warned(MACHINE_NAME[{m}], {warning:?});\n{deeper}    break;\n{deeper}}}\n{deeper}rounds_{n} += 1;"
    );
    out.push_str(&step(m, body, depth + 2));
    if let Some(next) = next {
        out.push_str(&step(m, next, depth + 2));
    }
    let _ = writeln!(out, "{inner}}}\n{pad}}}");
    out
}

/// The Rust that builds `pieces` into `w.text`.
fn build_text(pieces: &[Piece], pad: &str) -> String {
    let mut out = format!("{pad}w.text_clear();\n");
    for piece in pieces {
        match piece {
            Piece::Literal(s) if s.is_empty() => {}
            Piece::Literal(s) => {
                let _ = writeln!(out, "{pad}w.text_literal({s:?});");
            }
            Piece::Value(v) => {
                let _ = writeln!(
                    out,
                    "{pad}let value = {};\n{pad}w.text_value(value);",
                    value(v)
                );
            }
            Piece::Whole(v) => {
                let _ = writeln!(
                    out,
                    "{pad}let value = {};\n{pad}w.text_whole(value);",
                    value(v)
                );
            }
        }
    }
    out
}

fn conversion_code(conversion: Conversion) -> &'static str {
    match conversion {
        Conversion::Whole => "CONVERT_WHOLE",
        Conversion::Truth => "CONVERT_TRUTH",
        Conversion::Kept => "CONVERT_KEPT",
    }
}

fn command_code(command: Option<Command>) -> &'static str {
    match command {
        Some(Command::On) => "COMMAND_ON",
        Some(Command::Off) => "COMMAND_OFF",
        Some(Command::Suspend) => "COMMAND_SUSPEND",
        Some(Command::Resume) => "COMMAND_RESUME",
        Some(Command::Restart) => "COMMAND_RESTART",
        Some(Command::Reload) | Some(Command::Reread) | None => "COMMAND_UNKNOWN",
    }
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
