//! A behaviour's machines as freestanding C99 rounds of ringlets over compiled theories, for the
//! slice this crate supports yet: machines that post constant values and whose labels are
//! theory outputs, `!`, `&&`, `||`, `TRUE` and `timeout`; anything else is refused with its
//! file and line.

use crate::c::c_identifier;
use crate::tabulate::{compile, Compiled, Domain};
use proclaim_behaviour::{Behaviour, Schedule, MANIFEST};
use proclaim_fsm::{Action, BinOp, Expr, UnOp};
use std::fmt::Write;

/// Why a behaviour was not compiled: where, and what.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Refusal {
    pub file: String,
    pub line: usize,
    pub what: String,
}

impl std::fmt::Display for Refusal {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{}:{}: cannot be compiled: {}",
            self.file, self.line, self.what
        )
    }
}

impl std::error::Error for Refusal {}

/// The files of a compiled behaviour: name and text.
pub struct CBehaviour {
    pub files: Vec<(String, String)>,
}

/// The host harness: reads an impersonator script on standard input, runs the behaviour on a
/// virtual clock and writes the trace as `proclaim run --trace` does.
const HARNESS: &str = include_str!("harness.c");

struct Output {
    name: String,
    theory: usize,
    index: usize,
    expert: String,
}

/// Compiles `behaviour` (its theories over true/false/unknown inputs, its machines as code).
pub fn compile_behaviour(behaviour: &Behaviour) -> Result<CBehaviour, Refusal> {
    let refuse = |file: &str, line: usize, what: String| Refusal {
        file: file.to_string(),
        line,
        what,
    };
    let manifest = behaviour.files.show(MANIFEST);
    let manifest_text = behaviour.files.read(MANIFEST).unwrap_or_default();
    // The manifest line that starts with one of `starts`, for a refusal to point at.
    let line_of = |starts: &[&str]| {
        manifest_text
            .lines()
            .position(|l| starts.iter().any(|s| l.trim_start().starts_with(s)))
            .map_or(1, |i| i + 1)
    };
    if behaviour.manifest.schedule != Schedule::Rounds {
        return Err(refuse(
            &manifest,
            line_of(&["schedule"]),
            "schedule = \"concurrent\"".into(),
        ));
    }
    if !behaviour.programs.is_empty() {
        return Err(refuse(
            &manifest,
            line_of(&["[[prolog]]", "[[expert]]"]),
            "a Prolog or program expert (a target without processes cannot run it)".into(),
        ));
    }
    if !behaviour.sensors.is_empty() {
        return Err(refuse(
            &manifest,
            line_of(&["[[sensor]]"]),
            "a sensor (sensor wrappers are not compiled yet)".into(),
        ));
    }
    if !behaviour.suppress.is_empty() {
        return Err(refuse(
            &manifest,
            line_of(&["[suppress]"]),
            "suppression ([suppress] is not compiled yet)".into(),
        ));
    }
    let mut theories: Vec<(Compiled, String, Vec<String>)> = Vec::new();
    let mut outputs: Vec<Output> = Vec::new();
    // Input message type → (theory, input index).
    let mut inputs: Vec<(String, usize, usize)> = Vec::new();
    for (t, loaded) in behaviour.theories.iter().enumerate() {
        let compiled = compile(&loaded.theory, loaded.limits, Domain::Ternary)
            .map_err(|e| refuse(&behaviour.files.show(&loaded.file), 1, e.to_string()))?;
        for (i, atom) in compiled.inputs.iter().enumerate() {
            let ty = loaded
                .mapping
                .get(atom)
                .cloned()
                .unwrap_or_else(|| atom.clone());
            inputs.push((ty, t, i));
        }
        for (o, name) in compiled.outputs.iter().enumerate() {
            if outputs.iter().any(|x| &x.name == name) {
                return Err(refuse(
                    &behaviour.files.show(&loaded.file),
                    1,
                    format!("output `{name}` answered by two theories"),
                ));
            }
            outputs.push(Output {
                name: name.clone(),
                theory: t,
                index: o,
                expert: loaded.name.clone(),
            });
        }
        let prefix = format!("theory_{}", c_identifier(&loaded.name));
        let types = compiled
            .inputs
            .iter()
            .map(|a| loaded.mapping.get(a).cloned().unwrap_or_else(|| a.clone()))
            .collect();
        theories.push((compiled, prefix, types));
    }
    let names: Vec<String> = behaviour
        .machines
        .iter()
        .map(|m| m.machine.name.clone())
        .collect();
    let mut code = String::new();
    let mut rings = String::new();
    let mut reads = String::new();
    let mut dues = String::new();
    let mut inits = String::new();
    for (m, loaded) in behaviour.machines.iter().enumerate() {
        let machine = &loaded.machine;
        let file = &behaviour.files.show(&loaded.file);
        if !loaded.start {
            return Err(refuse(
                file,
                1,
                "a sub-machine that does not start (start = false)".into(),
            ));
        }
        if let Some(u) = machine.unread.first() {
            return Err(refuse(
                file,
                u.line,
                format!("the label `{}` that did not read", u.label),
            ));
        }
        let mut cases = String::new();
        let mut entries = String::new();
        let mut read_cases = String::new();
        let mut due_cases = String::new();
        for state in &machine.states {
            let id = state.id;
            // Entry actions, and whether the state is final.
            let mut entry = String::new();
            for action in &state.on_entry {
                entry.push_str(&action_c(action, file, state.line, &names, &inputs, m)?);
            }
            let outgoing: Vec<_> = machine.outgoing(id).collect();
            if outgoing.is_empty() {
                writeln!(
                    entry,
                    "            w->cb.finished(w, \"{}\", \"{}\");\n            w->done[{m}] = 1;",
                    esc(&machine.name),
                    esc(&state.name)
                )
                .unwrap();
            }
            writeln!(entries, "        case {id}:\n            w->cb.entered(w, \"{}\", \"{}\", {id});\n{entry}            break;", esc(&machine.name), esc(&state.name)).unwrap();
            let mut body = String::new();
            let mut read = Vec::new();
            let mut due = Vec::new();
            for t in &outgoing {
                let label = label_c(&t.label, file, t.line, &outputs, &mut read, &mut due, m)?;
                let mut exit = String::new();
                for action in &state.on_exit {
                    exit.push_str(&action_c(action, file, state.line, &names, &inputs, m)?);
                }
                writeln!(
                    body,
                    "        if ({label}) {{\n            w->cb.fired(w, \"{}\", {id}, {}, \"{}\");\n{exit}            w->state[{m}] = {};\n            w->just_entered[{m}] = 1;\n            return 1;\n        }}",
                    esc(&machine.name),
                    t.target,
                    esc(&t.label.to_string()),
                    t.target
                )
                .unwrap();
            }
            let mut internal = String::new();
            for action in &state.internal {
                internal.push_str(&action_c(action, file, state.line, &names, &inputs, m)?);
            }
            writeln!(cases, "    case {id}:\n{body}{internal}        return 0;").unwrap();
            read.sort_unstable();
            read.dedup();
            let read_expr: Vec<String> = read.iter().map(|k| format!("k == {k}u")).collect();
            writeln!(
                read_cases,
                "    case {id}:\n        return {};",
                if read_expr.is_empty() {
                    "0".into()
                } else {
                    read_expr.join(" || ")
                }
            )
            .unwrap();
            let due_expr: String = due
                .iter()
                .map(|ms| {
                    format!("        due = min_due(due, w->entered_ms[{m}] + {ms}u, w->now_ms);\n")
                })
                .collect();
            writeln!(due_cases, "    case {id}:\n{due_expr}        break;").unwrap();
        }
        writeln!(
            code,
            "static int ring_{m}(struct world *w)
{{
    if (w->just_entered[{m}]) {{
        w->just_entered[{m}] = 0;
        w->entered_ms[{m}] = w->now_ms;
        switch (w->state[{m}]) {{
{entries}        default:
            break;
        }}
    }}
    snapshot(w, {m});
    switch (w->state[{m}]) {{
{cases}    default:
        return 0;
    }}
}}

static int reads_{m}(const struct world *w, unsigned k)
{{
    (void)k;
    switch (w->state[{m}]) {{
{read_cases}    default:
        return 0;
    }}
}}

static uint64_t due_{m}(const struct world *w, uint64_t due)
{{
    switch (w->state[{m}]) {{
{due_cases}    default:
        break;
    }}
    return due;
}}
"
        )
        .unwrap();
        writeln!(rings, "    if (!w->done[{m}] || w->just_entered[{m}]) {{\n        fired |= ring_{m}(w);\n    }}").unwrap();
        writeln!(reads, "    if (!w->done[{m}]) {{\n        for (k = 0; k < BEHAVIOUR_OUTPUTS; k++) {{\n            if (reads_{m}(w, k) && answer(w, k) != w->seen[{m}][k]) {{\n                return 1;\n            }}\n        }}\n    }}").unwrap();
        writeln!(
            dues,
            "    if (!w->done[{m}]) {{\n        due = due_{m}(w, due);\n    }}"
        )
        .unwrap();
        writeln!(
            inits,
            "    w->state[{m}] = {};\n    w->just_entered[{m}] = 1;",
            machine.initial
        )
        .unwrap();
    }
    let period_ms = behaviour.ring_period.as_millis() as u64;
    if behaviour.ring_period.as_micros() % 1000 != 0 {
        return Err(refuse(
            &manifest,
            line_of(&["ring_period"]),
            "a ring period that is not whole milliseconds".into(),
        ));
    }
    let variables: usize = theories
        .iter()
        .map(|(c, _, _)| c.variables())
        .sum::<usize>()
        .max(1);
    let machines = names.len().max(1);
    let outputs_n = outputs.len().max(1);
    let mut h = String::new();
    writeln!(h, "/* The behaviour `{}` compiled by proclaim (generated: do not edit). */\n#ifndef BEHAVIOUR_H\n#define BEHAVIOUR_H\n#include <stdint.h>\n", comment(&behaviour.name)).unwrap();
    writeln!(h, "#define BEHAVIOUR_MACHINES {machines}\n#define BEHAVIOUR_OUTPUTS {outputs_n}\n#define BEHAVIOUR_VARIABLES {variables}\n#define BEHAVIOUR_PERIOD_MS {period_ms}u\n").unwrap();
    h.push_str(
        "struct world;

/* What the behaviour tells its host: postings, and the events of `proclaim run --trace`. */
struct world_callbacks {
    void (*post)(struct world *w, const char *machine, const char *type, const char *content);
    void (*entered)(struct world *w, const char *machine, const char *state, long id);
    void (*finished)(struct world *w, const char *machine, const char *state);
    void (*answered)(struct world *w, const char *machine, const char *atom, int value, const char *expert);
    void (*fired)(struct world *w, const char *machine, long from, long to, const char *label);
    /* At the start of each round, before its ringlets: post what came from outside by now. */
    void (*round_started)(struct world *w);
};

/* The whiteboard's values the behaviour reads and its machines' states. */
struct world {
    struct world_callbacks cb;
    void *user;
    /* The user's millisecond counter: set before each behaviour_round. */
    uint64_t now_ms;
    uint64_t round;
    long state[BEHAVIOUR_MACHINES];
    unsigned char just_entered[BEHAVIOUR_MACHINES];
    unsigned char done[BEHAVIOUR_MACHINES];
    uint64_t entered_ms[BEHAVIOUR_MACHINES];
    /* Each theory input: known, then true. */
    unsigned char in[BEHAVIOUR_VARIABLES];
    /* The answers each machine's last ringlet saw. */
    unsigned char seen[BEHAVIOUR_MACHINES][BEHAVIOUR_OUTPUTS];
};

void behaviour_init(struct world *w);
/* One round: a ringlet of every machine in manifest order; 1 when one fired (the next round follows at once). */
int behaviour_round(struct world *w);
/* A posting from outside the machines (an impersonator, a sensor); 1 when it is news to a machine's labels. */
int behaviour_outside(struct world *w, const char *type, const char *content);
/* 1 when an answer a machine's current labels read differs from what its last ringlet saw. */
int behaviour_news(const struct world *w);
/* 1 when `atom` is an answer of the behaviour's theories. */
int behaviour_answers(const char *atom);
/* Milliseconds from now_ms until the next round is due without news (a timeout or the ring period). */
uint64_t behaviour_next_due_ms(const struct world *w);
/* 1 when every machine is in a final state. */
int behaviour_finished(const struct world *w);

#endif
",
    );
    let mut c = String::new();
    writeln!(c, "/* The behaviour `{}` compiled by proclaim (generated: do not edit). */\n#include <stdint.h>\n#include \"behaviour.h\"", comment(&behaviour.name)).unwrap();
    for (_, prefix, _) in &theories {
        writeln!(c, "#include \"{prefix}.h\"").unwrap();
    }
    let mut answer_cases = String::new();
    let mut offset = 0;
    let mut offsets = Vec::new();
    for (compiled, _, _) in &theories {
        offsets.push(offset);
        offset += compiled.variables();
    }
    for (k, o) in outputs.iter().enumerate() {
        writeln!(
            answer_cases,
            "    case {k}:\n        return {}_answer({}u, w->in + {});",
            theories[o.theory].1, o.index, offsets[o.theory]
        )
        .unwrap();
    }
    let output_names: Vec<String> = outputs
        .iter()
        .map(|o| format!("\"{}\"", esc(&o.name)))
        .collect();
    let experts: Vec<String> = outputs
        .iter()
        .map(|o| format!("\"{}\"", esc(&o.expert)))
        .collect();
    let machine_names: Vec<String> = names.iter().map(|n| format!("\"{}\"", esc(n))).collect();
    let mut input_cases = String::new();
    for (ty, t, i) in &inputs {
        let v = offsets[*t] + 2 * i;
        writeln!(input_cases, "    if (same(type, \"{}\")) {{\n        set_input(w, {v}, content);\n        return 1;\n    }}", esc(ty)).unwrap();
    }
    write!(
        c,
        "
static const char *const output_name[{outputs_n}] = {{{}}};
static const char *const output_expert[{outputs_n}] = {{{}}};
static const char *const machine_name[{machines}] = {{{}}};

static int same(const char *a, const char *b)
{{
    while (*a != '\\0' && *a == *b) {{
        a++;
        b++;
    }}
    return *a == *b;
}}

/* A theory input from a posting's content: true, false, or unknown for anything else. */
static void set_input(struct world *w, unsigned v, const char *content)
{{
    if (same(content, \"true\")) {{
        w->in[v] = 1;
        w->in[v + 1] = 1;
    }} else if (same(content, \"false\")) {{
        w->in[v] = 1;
        w->in[v + 1] = 0;
    }} else {{
        w->in[v] = 0;
        w->in[v + 1] = 0;
    }}
}}

/* Whether the posting's type is a theory input (then applied). */
static int apply_input(struct world *w, const char *type, const char *content)
{{
{input_cases}    (void)w;
    (void)type;
    (void)content;
    return 0;
}}

static int answer(const struct world *w, unsigned k)
{{
    switch (k) {{
{answer_cases}    default:
        (void)w;
        return 0;
    }}
}}

static int ask(struct world *w, unsigned m, unsigned k)
{{
    int value = answer(w, k);
    w->cb.answered(w, machine_name[m], output_name[k], value, output_expert[k]);
    return value;
}}

static void post(struct world *w, unsigned m, const char *type, const char *content)
{{
    w->cb.post(w, machine_name[m], type, content);
    (void)apply_input(w, type, content);
}}

static void snapshot(struct world *w, unsigned m)
{{
    unsigned k;
    for (k = 0; k < BEHAVIOUR_OUTPUTS; k++) {{
        w->seen[m][k] = (unsigned char)answer(w, k);
    }}
}}

static int elapsed_at_least(const struct world *w, unsigned m, uint64_t ms)
{{
    return w->now_ms - w->entered_ms[m] >= ms;
}}

static uint64_t min_due(uint64_t due, uint64_t at, uint64_t now)
{{
    uint64_t left = at > now ? at - now : 0;
    return left < due ? left : due;
}}

{code}
void behaviour_init(struct world *w)
{{
    unsigned v, m, k;
    /* Helpers a behaviour without theories, or whose labels ask none, leaves unused. */
    (void)ask;
    (void)set_input;
    w->round = 0;
    for (v = 0; v < BEHAVIOUR_VARIABLES; v++) {{
        w->in[v] = 0;
    }}
    for (m = 0; m < BEHAVIOUR_MACHINES; m++) {{
        w->done[m] = 0;
        w->entered_ms[m] = 0;
        for (k = 0; k < BEHAVIOUR_OUTPUTS; k++) {{
            w->seen[m][k] = 0;
        }}
    }}
{inits}}}

int behaviour_round(struct world *w)
{{
    int fired = 0;
    w->round++;
    if (w->cb.round_started) {{
        w->cb.round_started(w);
    }}
{rings}    return fired;
}}

int behaviour_outside(struct world *w, const char *type, const char *content)
{{
    return apply_input(w, type, content) && behaviour_news(w);
}}

int behaviour_news(const struct world *w)
{{
    unsigned k;
    (void)k;
{reads}    return 0;
}}

int behaviour_answers(const char *atom)
{{
{answers_body}}}

uint64_t behaviour_next_due_ms(const struct world *w)
{{
    uint64_t due = BEHAVIOUR_PERIOD_MS;
{dues}    return due;
}}

int behaviour_finished(const struct world *w)
{{
    unsigned m;
    for (m = 0; m < BEHAVIOUR_MACHINES; m++) {{
        if (!w->done[m]) {{
            return 0;
        }}
    }}
    return 1;
}}
",
        if output_names.is_empty() { "0".to_string() } else { output_names.join(", ") },
        if experts.is_empty() { "0".to_string() } else { experts.join(", ") },
        machine_names.join(", "),
        answers_body = if outputs.is_empty() {
            "    (void)atom;\n    return 0;\n".to_string()
        } else {
            format!("    unsigned k;\n    for (k = 0; k < {}u; k++) {{\n        if (same(atom, output_name[k])) {{\n            return 1;\n        }}\n    }}\n    return 0;\n", outputs.len())
        },
    )
    .unwrap();
    let mut files = vec![
        ("behaviour.h".to_string(), h),
        ("behaviour.c".to_string(), c),
        ("main.c".to_string(), HARNESS.to_string()),
    ];
    for (compiled, prefix, _) in &theories {
        let source = compiled.to_c(prefix);
        files.push((format!("{prefix}.h"), source.header));
        files.push((format!("{prefix}.c"), source.source));
    }
    Ok(CBehaviour { files })
}

fn action_c(
    action: &Action,
    file: &str,
    line: usize,
    machines: &[String],
    inputs: &[(String, usize, usize)],
    m: usize,
) -> Result<String, Refusal> {
    let refuse = |what: String| Refusal {
        file: file.to_string(),
        line,
        what,
    };
    match action {
        Action::Post { ty, content } => {
            if machines.contains(ty) {
                return Err(refuse(format!("sub-machine control (`{ty}: {content}`)")));
            }
            let Some(text) = posted_text(content) else {
                return Err(refuse(format!(
                    "the number `{}` (floating-point postings are not compiled yet)",
                    content.trim()
                )));
            };
            if inputs.iter().any(|(t, _, _)| t == ty)
                && !["true", "false", "unknown"].contains(&text.as_str())
            {
                return Err(refuse(format!(
                    "a theory input posted as `{content}` (only true, false or unknown)"
                )));
            }
            Ok(format!(
                "            post(w, {m}u, \"{}\", \"{}\");\n",
                esc(ty),
                esc(&text)
            ))
        }
        Action::Call { function, .. } => Err(refuse(format!(
            "the host function `{function}` (host functions are not compiled yet)"
        ))),
        Action::Statement(s) => Err(refuse(format!(
            "the statement `{s}` (variables and statements are not compiled yet)"
        ))),
        Action::Code(text) => Err(refuse(format!("the unread code `{text}`"))),
    }
}

#[allow(clippy::too_many_arguments)]
fn label_c(
    label: &Expr,
    file: &str,
    line: usize,
    outputs: &[Output],
    read: &mut Vec<usize>,
    due: &mut Vec<u64>,
    m: usize,
) -> Result<String, Refusal> {
    let refuse = |what: String| Refusal {
        file: file.to_string(),
        line,
        what,
    };
    Ok(match label {
        Expr::Bool(b) => if *b { "1".into() } else { "0".into() },
        Expr::Name(n) if n == "TRUE" || n == "true" => "1".into(),
        Expr::Name(n) if n == "FALSE" || n == "false" => "0".into(),
        Expr::Name(n) => {
            let Some(k) = outputs.iter().position(|o| &o.name == n) else {
                return Err(refuse(format!("the label atom `{n}`, which no theory of the behaviour answers")));
            };
            read.push(k);
            format!("ask(w, {m}u, {k}u)")
        }
        Expr::Unary { op: UnOp::Not, operand } => format!("!{}", label_c(operand, file, line, outputs, read, due, m)?),
        Expr::Binary { op: op @ (BinOp::And | BinOp::Or), left, right } => format!(
            "({} {} {})",
            label_c(left, file, line, outputs, read, due, m)?,
            if *op == BinOp::And { "&&" } else { "||" },
            label_c(right, file, line, outputs, read, due, m)?
        ),
        Expr::Call { function, arguments } if function == "timeout" && arguments.len() == 1 => {
            let micros = match &arguments[0] {
                Expr::Int(n) if *n >= 0 => *n as u64,
                Expr::Duration(d) => *d,
                other => return Err(refuse(format!("timeout({other}) (only a constant time)"))),
            };
            if micros % 1000 != 0 {
                return Err(refuse(format!("timeout({micros}) (a target's clock counts milliseconds)")));
            }
            due.push(micros / 1000);
            format!("elapsed_at_least(w, {m}u, {}u)", micros / 1000)
        }
        other => return Err(refuse(format!("the label `{other}` (only theory outputs, !, &&, ||, TRUE and timeout are compiled yet)"))),
    })
}

/// A posting's content as the runner reads it (`Value::parse`) and shows it in a trace: a truth
/// word, a whole number, or text without its quotes; `None` for a floating-point number, whose
/// printed form is not compiled yet.
fn posted_text(content: &str) -> Option<String> {
    let t = content.trim();
    if t == "true" || t == "false" {
        Some(t.to_string())
    } else if let Ok(i) = t.parse::<i64>() {
        Some(i.to_string())
    } else if t.parse::<f64>().is_ok() {
        None
    } else {
        Some(t.trim_matches('"').to_string())
    }
}

/// Text as a C string literal's inside.
fn esc(text: &str) -> String {
    let mut out = String::new();
    for c in text.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            c if (c as u32) < 0x20 || (c as u32) > 0x7e => {
                let mut buf = [0u8; 4];
                for b in c.encode_utf8(&mut buf).bytes() {
                    write!(out, "\\{b:03o}").unwrap();
                }
            }
            c => out.push(c),
        }
    }
    out
}

fn comment(text: &str) -> String {
    text.replace("*/", "* /")
}
