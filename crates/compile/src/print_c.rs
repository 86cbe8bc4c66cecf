//! A behaviour's plan printed as freestanding C99: `behaviour.h` (the world's values in a
//! struct, its callbacks), `behaviour.c` (a `ring_M` a machine, the round schedule), a decision
//! function a theory, and the host harness `main.c`.

use crate::c_template::{BODY, HEADER, HELD_TYPES, SUPPRESSION};
use crate::machine_code;
use crate::plan::Plan;
use crate::spell_c::C;
use proclaim_runner::LOOP_LIMIT;
use std::fmt::Write;

/// The host harness: reads an impersonator script on standard input, runs the behaviour on a
/// virtual clock and writes the trace as `proclaim run --trace` does.
const HARNESS: &str = include_str!("harness.c");

/// Every file of the compiled behaviour: name and text.
pub(crate) fn behaviour_files(plan: &Plan) -> Vec<(String, String)> {
    let mut files = vec![
        ("behaviour.h".to_string(), header(plan)),
        ("behaviour.c".to_string(), source(plan)),
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

fn header(plan: &Plan) -> String {
    let mut h = String::new();
    let _ = writeln!(h, "/* The behaviour `{}` compiled by proclaim (generated: do not edit). */\n#ifndef BEHAVIOUR_H\n#define BEHAVIOUR_H\n#include <stdint.h>\n", comment(&plan.name));
    let _ = writeln!(
        h,
        "#define BEHAVIOUR_MACHINES {}\n#define BEHAVIOUR_OUTPUTS {}\n#define BEHAVIOUR_VARIABLES {}\n#define BEHAVIOUR_VALUES {}\n#define BEHAVIOUR_EXTERNS {}\n#define BEHAVIOUR_TEXT {}\n#define BEHAVIOUR_COMMANDS {}\n#define BEHAVIOUR_ASKS {}\n#define BEHAVIOUR_PERIOD_MS {}u\n",
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
    let held = !plan.suppressed.is_empty();
    if held {
        let _ = writeln!(
            h,
            "#define BEHAVIOUR_SUPPRESSED {}\n#define BEHAVIOUR_LAYERS {}\n#define BEHAVIOUR_HELD_TEXT {}\n",
            plan.suppressed.len(),
            plan.layers().len(),
            plan.longest_posting()
        );
    }
    h.push_str(&fill(
        HEADER,
        &[
            ("held_types", if held { HELD_TYPES } else { "" }),
            (
                "held_field",
                if held {
                    "    /* Each type under subsumption, in name order. */\n    struct held_line held[BEHAVIOUR_SUPPRESSED];\n"
                } else {
                    ""
                },
            ),
        ],
    ));
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

fn source(plan: &Plan) -> String {
    let mut c = String::new();
    let _ = writeln!(c, "/* The behaviour `{}` compiled by proclaim (generated: do not edit). */\n#include <stdint.h>\n#include \"behaviour.h\"", comment(&plan.name));
    for theory in &plan.theories {
        let _ = writeln!(c, "#include \"{}.h\"", theory.prefix);
    }
    // Only a theory's answers: the impersonator's atoms are the script's to set.
    let answers_body = if plan.theory_outputs() == 0 {
        "    (void)atom;\n    return 0;\n".to_string()
    } else {
        format!("    unsigned k;\n    for (k = 0; k < {}u; k++) {{\n        if (same(atom, output_name[k])) {{\n            return 1;\n        }}\n    }}\n    return 0;\n", plan.theory_outputs())
    };
    let var_inits = var_inits(plan);
    let held = Held::of(plan);
    let (sensor_atoms, sensor_starts) = sensor_tables(plan);
    let outputs_n = plan.outputs.len().max(1).to_string();
    let extern_names = strings(plan.externs.iter().map(|b| b.name.as_str()));
    let machines = plan.machines.len().max(1).to_string();
    let loop_limit = LOOP_LIMIT.to_string();
    c.push_str(&fill(
        BODY,
        &[
            ("outputs_n", &outputs_n),
            (
                "output_names",
                &strings(plan.outputs.iter().map(|o| o.name.as_str())),
            ),
            (
                "experts",
                &strings(plan.outputs.iter().map(|o| o.expert.as_str())),
            ),
            ("machines", &machines),
            (
                "machine_names",
                &strings(plan.machines.iter().map(|m| m.name.as_str())),
            ),
            ("priorities", &held.priorities),
            ("externs_n", &plan.externs.len().max(1).to_string()),
            ("extern_names", &extern_names),
            ("externs", &plan.externs.len().to_string()),
            (
                "extern_bound",
                &numbers(plan.externs.iter().map(|b| i64::from(b.bound))),
            ),
            ("output_board", &numbers(board_of_outputs(plan))),
            ("status_board", &numbers(board_of_statuses(plan))),
            ("theory_outputs", &plan.theory_outputs().to_string()),
            ("outputs", &plan.outputs.len().to_string()),
            ("sensors", &plan.sensors.len().to_string()),
            ("sensors_n", &plan.sensors.len().max(1).to_string()),
            (
                "sensor_names",
                &strings(plan.sensors.iter().map(|(n, _)| n.as_str())),
            ),
            ("sensor_atoms_n", &sensor_atoms.len().max(1).to_string()),
            ("sensor_atoms", &strings(sensor_atoms.iter().copied())),
            ("sensor_starts", &sensor_starts.join(", ")),
            ("suppression", &held.suppression),
            ("held_back", &held.held_back),
            ("held_init", &held.init),
            ("take_over", &held.take_over),
            ("release_due", &held.release_due),
            ("answers", &machine_code::answers(plan, &C)),
            ("runtime", RUNTIME),
            ("loop_limit", &loop_limit),
            ("code", &machine_code::printed(plan, &C)),
            (
                "initials",
                &numbers(plan.machines.iter().map(|m| m.initial)),
            ),
            (
                "starts",
                &numbers(plan.machines.iter().map(|m| i64::from(m.start))),
            ),
            ("var_inits", &var_inits),
            ("answers_body", &answers_body),
        ],
    ));
    c
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

/// Each value slot's start: a whole 0, or false.
fn var_inits(plan: &Plan) -> String {
    plan.slots
        .iter()
        .enumerate()
        .map(|(slot, is_bool)| {
            let value = if *is_bool { "v_bool(0)" } else { "v_int(0)" };
            format!("    w->var[{slot}] = {value};\n")
        })
        .collect()
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

/// The parts of `behaviour.c` for subsumption: empty but the priorities for a behaviour
/// without `[suppress]`.
struct Held {
    priorities: String,
    suppression: String,
    held_back: String,
    init: String,
    take_over: String,
    release_due: String,
}

impl Held {
    fn of(plan: &Plan) -> Held {
        let priorities: Vec<String> = plan
            .machines
            .iter()
            .map(|m| format!("{}ul", m.priority))
            .collect();
        let priorities = if priorities.is_empty() {
            "0".into()
        } else {
            priorities.join(", ")
        };
        if plan.suppressed.is_empty() {
            return Held {
                priorities,
                suppression: String::new(),
                held_back: String::new(),
                init: String::new(),
                take_over: String::new(),
                release_due: String::new(),
            };
        }
        let layers = plan.layers();
        let machine_layers: Vec<String> = plan
            .machines
            .iter()
            .map(|m| {
                let layer = layers.iter().position(|p| *p == m.priority).unwrap_or(0);
                format!("{layer}u")
            })
            .collect();
        let held_ms: Vec<String> = plan
            .suppressed
            .iter()
            .map(|s| format!("{}u", s.hold_ms))
            .collect();
        let suppression = fill(
            SUPPRESSION,
            &[
                (
                    "held_types",
                    &strings(plan.suppressed.iter().map(|s| s.ty.as_str())),
                ),
                ("held_ms", &held_ms.join(", ")),
                ("machine_layers", &machine_layers.join(", ")),
            ],
        );
        Held {
            priorities,
            suppression,
            held_back: "    if (held_back(w, m, type, content)) {\n        return;\n    }\n".into(),
            init: "    for (v = 0; v < BEHAVIOUR_SUPPRESSED; v++) {\n        w->held[v].shown.known = 0;\n        w->held[v].subsuming = 0;\n        for (k = 0; k < BEHAVIOUR_LAYERS; k++) {\n            w->held[v].newest[k].known = 0;\n        }\n    }\n".into(),
            take_over: "    take_over(w);\n".into(),
            release_due: "    due = release_due(w, due);\n".into(),
        }
    }
}

/// Text as a C string literal's inside.
pub(crate) fn esc(text: &str) -> String {
    let mut out = String::new();
    for c in text.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '?' => out.push_str("\\?"),
            c if (c as u32) < 0x20 || (c as u32) > 0x7e => {
                let mut buf = [0u8; 4];
                for b in c.encode_utf8(&mut buf).bytes() {
                    let _ = write!(out, "\\{b:03o}");
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

/// The C helpers compiled activities call: the runner's values and `arith`'s operators on them.
const RUNTIME: &str = r#"
/* A value as the runner holds it: a whole number, or a truth value (0 or 1); `none` for a
 * whiteboard value never posted, which arithmetic keeps and a comparison finds false. */
#define CONVERT_WHOLE 0
#define CONVERT_TRUTH 1
#define CONVERT_KEPT 2

static struct value v_int(int64_t i)
{
    struct value v;
    v.i = i;
    v.is_bool = 0;
    v.none = 0;
    return v;
}

static struct value v_none(void)
{
    struct value v = v_int(0);
    v.none = 1;
    return v;
}

/* What an activity makes of a value: no value is a whole 0, as the runner's activities have it. */
static struct value v_some(struct value v)
{
    return v.none ? v_int(0) : v;
}

static struct value v_bool(int b)
{
    struct value v;
    v.i = b ? 1 : 0;
    v.is_bool = 1;
    v.none = 0;
    return v;
}

static int truthy(struct value v)
{
    return v.i != 0;
}

/* Wrapping arithmetic, as the runner's `wrapping_add` and kin. */
static int64_t wrap(uint64_t u)
{
    return u <= (uint64_t)INT64_MAX ? (int64_t)u : -(int64_t)(~u) - 1;
}

static struct value v_add(struct value a, struct value b)
{
    if (a.none || b.none) {
        return v_none();
    }
    return v_int(wrap((uint64_t)a.i + (uint64_t)b.i));
}

static struct value v_sub(struct value a, struct value b)
{
    if (a.none || b.none) {
        return v_none();
    }
    return v_int(wrap((uint64_t)a.i - (uint64_t)b.i));
}

static struct value v_mul(struct value a, struct value b)
{
    if (a.none || b.none) {
        return v_none();
    }
    return v_int(wrap((uint64_t)a.i * (uint64_t)b.i));
}

/* Dividing by zero gives the largest whole number, as gufsm's INT_MAX. */
static struct value v_div(struct value a, struct value b)
{
    if (a.none || b.none) {
        return v_none();
    }
    if (b.i == 0) {
        return v_int(INT64_MAX);
    }
    if (b.i == -1) {
        return v_int(wrap(0u - (uint64_t)a.i));
    }
    return v_int(a.i / b.i);
}

static struct value v_rem(struct value a, struct value b)
{
    if (a.none || b.none) {
        return v_none();
    }
    if (b.i == 0) {
        return v_int(INT64_MAX);
    }
    if (b.i == -1) {
        return v_int(0);
    }
    return v_int(a.i % b.i);
}

static struct value v_neg(struct value a)
{
    if (a.none) {
        return a;
    }
    return v_int(wrap(0u - (uint64_t)a.i));
}

static struct value v_abs(struct value a)
{
    return a.i < 0 ? v_neg(a) : a;
}

static struct value v_eq(struct value a, struct value b)
{
    return v_bool(!a.none && !b.none && a.i == b.i);
}

static struct value v_ne(struct value a, struct value b)
{
    return v_bool(!a.none && !b.none && a.i != b.i);
}

static struct value v_lt(struct value a, struct value b)
{
    return v_bool(!a.none && !b.none && a.i < b.i);
}

static struct value v_le(struct value a, struct value b)
{
    return v_bool(!a.none && !b.none && a.i <= b.i);
}

static struct value v_gt(struct value a, struct value b)
{
    return v_bool(!a.none && !b.none && a.i > b.i);
}

static struct value v_ge(struct value a, struct value b)
{
    return v_bool(!a.none && !b.none && a.i >= b.i);
}

/* The first when it is not greater (min) or not less (max), as the runner picks. */
static struct value v_min(struct value a, struct value b)
{
    if (a.none || b.none) {
        return v_none();
    }
    return a.i <= b.i ? a : b;
}

static struct value v_max(struct value a, struct value b)
{
    if (a.none || b.none) {
        return v_none();
    }
    return a.i >= b.i ? a : b;
}

static struct value convert(int conversion, struct value v)
{
    if (conversion == CONVERT_WHOLE) {
        return v_int(v.i);
    }
    if (conversion == CONVERT_TRUTH) {
        return v_bool(truthy(v));
    }
    return v;
}

/* A value's text, as the trace shows it, into `out` (at least 21 bytes); its length. */
static unsigned value_text(char *out, struct value v)
{
    char digits[20];
    unsigned n = 0, len = 0;
    uint64_t u;
    const char *word;
    if (v.is_bool) {
        word = v.i ? "true" : "false";
        while (word[len] != '\0') {
            out[len] = word[len];
            len++;
        }
        out[len] = '\0';
        return len;
    }
    u = v.i < 0 ? 0u - (uint64_t)v.i : (uint64_t)v.i;
    do {
        digits[n++] = (char)('0' + (int)(u % 10u));
        u /= 10u;
    } while (u != 0u);
    if (v.i < 0) {
        out[len++] = '-';
    }
    while (n > 0) {
        out[len++] = digits[--n];
    }
    out[len] = '\0';
    return len;
}

static void text_clear(struct world *w)
{
    w->text_length = 0;
    w->text[0] = '\0';
}

static void text_literal(struct world *w, const char *s)
{
    while (*s != '\0') {
        w->text[w->text_length++] = *s++;
    }
    w->text[w->text_length] = '\0';
}

static void text_value(struct world *w, struct value v)
{
    w->text_length += value_text(w->text + w->text_length, v);
}

static void text_whole(struct world *w, struct value v)
{
    text_value(w, v_int(v.i));
}

/* An assignment as the runner makes it: converted to the variable's type, reported when the
 * value changed; a global's change is news to the labels that read globals. */
static void assign(struct world *w, unsigned m, unsigned slot, int conversion, int global,
                   const char *name, struct value v)
{
    char shown[24];
    v = convert(conversion, v_some(v));
    if (w->var[slot].i == v.i && w->var[slot].is_bool == v.is_bool) {
        return;
    }
    w->var[slot] = v;
    if (global) {
        w->globals_changes++;
    }
    (void)value_text(shown, v);
    w->cb.assigned(w, machine_name[m], name, shown);
}
"#;
