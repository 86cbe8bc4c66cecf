//! A behaviour's machines as freestanding C99 rounds of ringlets over compiled theories: the
//! round schedule of `proclaim_runner::Rounds` (news, time tests, sub-machine control, final
//! states), labels over theory outputs, variables and comparisons, and activities compiled by
//! `activity.rs`; anything else is refused with its file and line.

use crate::activity::{conversion, esc, Activity, Conversion, Variable, Variables, RUNTIME};
use crate::c::c_identifier;
use crate::tabulate::{compile, Compiled, Domain};
use proclaim_behaviour::{Behaviour, Schedule, MANIFEST};
use proclaim_fsm::{Action, BinOp, Expr, Statement, UnOp, TIME_TESTS};
use std::collections::HashMap;
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
    let input_types: Vec<String> = inputs.iter().map(|(ty, _, _)| ty.clone()).collect();
    // Slots: each machine's own variables (declared anywhere in it), then the globals (names a
    // machine assigns without declaring them), as `proclaim_runner::Shared` and `Locals` read.
    let mut slots: Vec<bool> = Vec::new();
    let mut own: Vec<HashMap<String, Variable>> = Vec::new();
    for loaded in &behaviour.machines {
        let file = behaviour.files.show(&loaded.file);
        let mut mine: HashMap<String, Variable> = HashMap::new();
        for state in &loaded.machine.states {
            for s in state_statements(state) {
                if let Statement::Declare { ty, name, .. } = s {
                    let conversion =
                        conversion(ty).map_err(|what| refuse(&file, state.line, what))?;
                    match mine.get_mut(name) {
                        // The type declared last converts; the first gave the starting value.
                        Some(v) => v.conversion = conversion,
                        None => {
                            mine.insert(
                                name.clone(),
                                Variable {
                                    slot: slots.len(),
                                    conversion,
                                },
                            );
                            slots.push(conversion == Conversion::Truth);
                        }
                    }
                }
            }
        }
        own.push(mine);
    }
    let mut globals: HashMap<String, Variable> = HashMap::new();
    for (m, loaded) in behaviour.machines.iter().enumerate() {
        for s in loaded.machine.statements() {
            if let Statement::Assign { name, .. } = s {
                if !own[m].contains_key(name) && !globals.contains_key(name) {
                    globals.insert(
                        name.clone(),
                        Variable {
                            slot: slots.len(),
                            conversion: Conversion::Kept,
                        },
                    );
                    slots.push(false);
                }
            }
        }
    }
    let mut commands = 0;
    let mut longest_text = 1;
    let mut loops = 0;
    let mut code = String::new();
    let mut rings = String::new();
    let mut reads = String::new();
    let mut dues = String::new();
    let mut inits = String::new();
    let mut finals = String::new();
    let mut tops = String::new();
    for (m, loaded) in behaviour.machines.iter().enumerate() {
        let machine = &loaded.machine;
        let file = &behaviour.files.show(&loaded.file);
        if let Some(u) = machine.unread.first() {
            return Err(refuse(
                file,
                u.line,
                format!("the label `{}` that did not read", u.label),
            ));
        }
        let variables = Variables {
            own: own[m].clone(),
            globals: globals.clone(),
        };
        let mut cases = String::new();
        let mut entries = String::new();
        let mut read_cases = String::new();
        let mut due_cases = String::new();
        let mut global_cases = String::new();
        let mut final_ids = Vec::new();
        for state in &machine.states {
            let id = state.id;
            let mut activity = Activity {
                file,
                line: state.line,
                machine: m,
                state: &state.name,
                variables: &variables,
                machines: &names,
                inputs: &input_types,
                longest_text: &mut longest_text,
                loops: &mut loops,
                commands: &mut commands,
            };
            let mut entry = activity.actions(&state.on_entry)?;
            let exit = activity.actions(&state.on_exit)?;
            let internal = activity.actions(&state.internal)?;
            let outgoing: Vec<_> = machine.outgoing(id).collect();
            if outgoing.is_empty() {
                final_ids.push(id);
                let _ = writeln!(
                    entry,
                    "            w->cb.finished(w, \"{}\", \"{}\");",
                    esc(&machine.name),
                    esc(&state.name)
                );
            }
            let _ = writeln!(entries, "        case {id}:\n            w->cb.entered(w, \"{}\", \"{}\", {id});\n{entry}            break;", esc(&machine.name), esc(&state.name));
            let mut body = String::new();
            let mut labels = Labels {
                outputs: &outputs,
                read: Vec::new(),
                due: Vec::new(),
                reads_globals: false,
            };
            for t in &outgoing {
                activity.line = t.line;
                let label = labels.condition(&t.label, &mut activity)?;
                let _ = writeln!(
                    body,
                    "        if ({label}) {{\n            w->cb.fired(w, \"{}\", {id}, {}, \"{}\");\n{exit}            w->state[{m}] = {};\n            w->just_entered[{m}] = 1;\n            return 1;\n        }}",
                    esc(&machine.name),
                    t.target,
                    esc(&t.label.to_string()),
                    t.target
                );
            }
            let _ = writeln!(cases, "    case {id}:\n{body}{internal}        return 0;");
            let Labels {
                mut read,
                due,
                reads_globals,
                ..
            } = labels;
            read.sort_unstable();
            read.dedup();
            let read_expr: Vec<String> = read.iter().map(|k| format!("k == {k}u")).collect();
            let _ = writeln!(
                read_cases,
                "    case {id}:\n        return {};",
                if read_expr.is_empty() {
                    "0".into()
                } else {
                    read_expr.join(" || ")
                }
            );
            let due_expr: String = due
                .iter()
                .map(|ms| {
                    format!("        due = min_due(due, w->entered_ms[{m}] + {ms}u, w->now_ms);\n")
                })
                .collect();
            let _ = writeln!(due_cases, "    case {id}:\n{due_expr}        break;");
            if reads_globals {
                let _ = writeln!(global_cases, "    case {id}:");
            }
        }
        let final_cases: String = final_ids
            .iter()
            .map(|id| format!("    case {id}:\n"))
            .collect();
        let global_return = if global_cases.is_empty() {
            "    (void)w;\n    return 0;\n".to_string()
        } else {
            format!("    switch (w->state[{m}]) {{\n{global_cases}        return 1;\n    default:\n        return 0;\n    }}\n")
        };
        let final_return = if final_cases.is_empty() {
            "    (void)w;\n    return 0;\n".to_string()
        } else {
            format!("    switch (w->state[{m}]) {{\n{final_cases}        return 1;\n    default:\n        return 0;\n    }}\n")
        };
        let _ = writeln!(
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
    w->globals_seen[{m}] = w->globals_changes;
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

/* Whether the current state's labels read a global. */
static int reads_globals_{m}(const struct world *w)
{{
{global_return}}}

static int final_{m}(const struct world *w)
{{
{final_return}}}

static uint64_t due_{m}(const struct world *w, uint64_t due)
{{
    switch (w->state[{m}]) {{
{due_cases}    default:
        break;
    }}
    return due;
}}
"
        );
        let _ = writeln!(rings, "    if (w->status[{m}] == RUNNING && !w->fresh[{m}] && !done(w, {m}u)) {{\n        fired |= ring_{m}(w);\n        obey(w);\n    }}");
        let _ = writeln!(reads, "    if (w->status[{m}] == RUNNING) {{\n        for (k = 0; k < BEHAVIOUR_OUTPUTS; k++) {{\n            if (reads_{m}(w, k) && answer(w, k) != w->seen[{m}][k]) {{\n                return 1;\n            }}\n        }}\n        if (w->globals_seen[{m}] != w->globals_changes && reads_globals_{m}(w)) {{\n            return 1;\n        }}\n    }}");
        let _ = writeln!(
            dues,
            "    if (w->status[{m}] == RUNNING) {{\n        due = due_{m}(w, due);\n    }}"
        );
        let _ = writeln!(
            inits,
            "    w->state[{m}] = {};\n    w->initial[{m}] = {};\n    w->just_entered[{m}] = 1;\n    w->status[{m}] = {};",
            machine.initial,
            machine.initial,
            if loaded.start { "RUNNING" } else { "DORMANT" }
        );
        let _ = writeln!(finals, "    case {m}:\n        return final_{m}(w);");
        if loaded.start {
            let _ = writeln!(
                tops,
                "    if (!done(w, {m}u)) {{\n        return 0;\n    }}"
            );
        }
    }
    let var_inits: String = slots
        .iter()
        .enumerate()
        .map(|(slot, is_bool)| {
            format!(
                "    w->var[{slot}] = {};\n",
                if *is_bool { "v_bool(0)" } else { "v_int(0)" }
            )
        })
        .collect();
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
    let values_n = slots.len().max(1);
    let commands_n = commands.max(1);
    let mut h = String::new();
    let _ = writeln!(h, "/* The behaviour `{}` compiled by proclaim (generated: do not edit). */\n#ifndef BEHAVIOUR_H\n#define BEHAVIOUR_H\n#include <stdint.h>\n", comment(&behaviour.name));
    let _ = writeln!(h, "#define BEHAVIOUR_MACHINES {machines}\n#define BEHAVIOUR_OUTPUTS {outputs_n}\n#define BEHAVIOUR_VARIABLES {variables}\n#define BEHAVIOUR_VALUES {values_n}\n#define BEHAVIOUR_TEXT {longest_text}\n#define BEHAVIOUR_COMMANDS {commands_n}\n#define BEHAVIOUR_PERIOD_MS {period_ms}u\n");
    h.push_str(
        "struct world;

/* What the behaviour tells its host: postings, and the events of `proclaim run --trace`. */
struct world_callbacks {
    void (*post)(struct world *w, const char *machine, const char *type, const char *content);
    void (*entered)(struct world *w, const char *machine, const char *state, long id);
    void (*finished)(struct world *w, const char *machine, const char *state);
    void (*answered)(struct world *w, const char *machine, const char *atom, int value, const char *expert);
    void (*fired)(struct world *w, const char *machine, long from, long to, const char *label);
    /* A variable's value changed (its text as the trace shows it). */
    void (*assigned)(struct world *w, const char *machine, const char *variable, const char *value);
    void (*printed)(struct world *w, const char *machine, const char *text);
    /* A machine obeys a control command (`On`, `Off`, `suspend`, `resume`, `restart`). */
    void (*control)(struct world *w, const char *machine, const char *command);
    void (*warned)(struct world *w, const char *machine, const char *message);
    /* At the start of each round, before its ringlets: post what came from outside by now. */
    void (*round_started)(struct world *w);
};

/* A variable's value as the runner holds it: a whole number, or a truth value (0 or 1). */
struct value {
    int64_t i;
    unsigned char is_bool;
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
    uint64_t entered_ms[BEHAVIOUR_MACHINES];
    /* Each theory input: known, then true. */
    unsigned char in[BEHAVIOUR_VARIABLES];
    /* The answers each machine's last ringlet saw. */
    unsigned char seen[BEHAVIOUR_MACHINES][BEHAVIOUR_OUTPUTS];
    long initial[BEHAVIOUR_MACHINES];
    /* Running, suspended or dormant; started in this round (it rings from the next). */
    unsigned char status[BEHAVIOUR_MACHINES];
    unsigned char fresh[BEHAVIOUR_MACHINES];
    /* Each machine's own variables, then the behaviour's globals. */
    struct value var[BEHAVIOUR_VALUES];
    /* Changes of globals so far, and as each machine's last ringlet saw them. */
    uint64_t globals_changes;
    uint64_t globals_seen[BEHAVIOUR_MACHINES];
    /* Control commands posted to each machine, obeyed when the ringlet that posted them ends. */
    unsigned char command[BEHAVIOUR_MACHINES][BEHAVIOUR_COMMANDS];
    const char *command_word[BEHAVIOUR_MACHINES][BEHAVIOUR_COMMANDS];
    unsigned command_count[BEHAVIOUR_MACHINES];
    /* Whether a command waits (so a ringlet that posted none costs no look at every machine). */
    unsigned char commands_waiting;
    /* The text a posting or a print is built in. */
    char text[BEHAVIOUR_TEXT];
    unsigned text_length;
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
/* 1 when `name` is a machine's (a posting to it is a control command). */
int behaviour_is_machine(const char *name);
/* Milliseconds from now_ms until the next round is due without news (a timeout or the ring period). */
uint64_t behaviour_next_due_ms(const struct world *w);
/* 1 when every machine that starts with the behaviour is in a final state, its OnEntry run. */
int behaviour_finished(const struct world *w);

#endif
",
    );
    let mut c = String::new();
    let _ = writeln!(c, "/* The behaviour `{}` compiled by proclaim (generated: do not edit). */\n#include <stdint.h>\n#include \"behaviour.h\"", comment(&behaviour.name));
    for (_, prefix, _) in &theories {
        let _ = writeln!(c, "#include \"{prefix}.h\"");
    }
    let mut answer_cases = String::new();
    let mut offset = 0;
    let mut offsets = Vec::new();
    for (compiled, _, _) in &theories {
        offsets.push(offset);
        offset += compiled.variables();
    }
    for (k, o) in outputs.iter().enumerate() {
        let _ = writeln!(
            answer_cases,
            "    case {k}:\n        return {}_answer({}u, w->in + {});",
            theories[o.theory].1, o.index, offsets[o.theory]
        );
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
        let _ = writeln!(input_cases, "    if (same(type, \"{}\")) {{\n        set_input(w, {v}, content);\n        return 1;\n    }}", esc(ty));
    }
    let _ = write!(
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

/* A time test still to come due shortens the wait; one already past (its label false for
 * another reason) does not, as the runner's `next_time_test` has it. */
static uint64_t min_due(uint64_t due, uint64_t at, uint64_t now)
{{
    if (at <= now) {{
        return due;
    }}
    return at - now < due ? at - now : due;
}}
{runtime}
#define RUNNING 0
#define SUSPENDED 1
#define DORMANT 2
#define COMMAND_UNKNOWN 0
#define COMMAND_ON 1
#define COMMAND_OFF 2
#define COMMAND_SUSPEND 3
#define COMMAND_RESUME 4
#define COMMAND_RESTART 5
#define LOOP_LIMIT {loop_limit}u

static int final_state(const struct world *w, unsigned m);

/* Whether a machine's run is over for now: in a state with no way out, its OnEntry run. */
static int done(const struct world *w, unsigned m)
{{
    return !w->just_entered[m] && final_state(w, m);
}}

/* A control command posted to machine `m`, obeyed when the ringlet ends. */
static void command(struct world *w, unsigned m, unsigned char code, const char *word)
{{
    if (w->command_count[m] < BEHAVIOUR_COMMANDS) {{
        w->command[m][w->command_count[m]] = code;
        w->command_word[m][w->command_count[m]] = word;
        w->command_count[m]++;
        w->commands_waiting = 1;
    }}
}}

/* gufsm's SuspensibleMachine, as the runner's `control`: whether it started the machine. */
static int control(struct world *w, unsigned m, unsigned char code, const char *word)
{{
    w->cb.control(w, machine_name[m], word);
    switch (code) {{
    case COMMAND_ON:
    case COMMAND_RESUME:
        if (w->status[m] == DORMANT) {{
            w->state[m] = w->initial[m];
        }} else if (w->status[m] == RUNNING) {{
            return 0;
        }}
        w->status[m] = RUNNING;
        w->just_entered[m] = 1;
        return 1;
    case COMMAND_RESTART:
        w->status[m] = RUNNING;
        w->state[m] = w->initial[m];
        w->just_entered[m] = 1;
        return 1;
    case COMMAND_SUSPEND:
        if (w->status[m] == RUNNING) {{
            w->status[m] = SUSPENDED;
        }}
        return 0;
    case COMMAND_OFF:
        w->status[m] = DORMANT;
        return 0;
    default:
        return 0;
    }}
}}

/* The commands waiting for each machine, in schedule order; a machine started rings from the
 * next round. */
static void obey(struct world *w)
{{
    unsigned m, i;
    if (!w->commands_waiting) {{
        return;
    }}
    w->commands_waiting = 0;
    for (m = 0; m < BEHAVIOUR_MACHINES; m++) {{
        for (i = 0; i < w->command_count[m]; i++) {{
            if (control(w, m, w->command[m][i], w->command_word[m][i])) {{
                w->fresh[m] = 1;
            }}
        }}
        w->command_count[m] = 0;
    }}
}}

{code}
static int final_state(const struct world *w, unsigned m)
{{
    switch (m) {{
{finals}    default:
        return 0;
    }}
}}

void behaviour_init(struct world *w)
{{
    unsigned v, m, k;
    /* Helpers a behaviour without theories, or whose labels ask none, leaves unused. */
    (void)ask;
    (void)set_input;
    (void)elapsed_at_least;
    (void)min_due;
    (void)v_int;
    (void)v_bool;
    (void)truthy;
    (void)v_add;
    (void)v_sub;
    (void)v_mul;
    (void)v_div;
    (void)v_rem;
    (void)v_abs;
    (void)v_eq;
    (void)v_ne;
    (void)v_lt;
    (void)v_le;
    (void)v_gt;
    (void)v_ge;
    (void)v_min;
    (void)v_max;
    (void)assign;
    (void)text_clear;
    (void)text_literal;
    (void)text_whole;
    (void)command;
    (void)post;
    (void)text_value;
    (void)v_neg;
    w->round = 0;
    w->globals_changes = 0;
    w->commands_waiting = 0;
    for (v = 0; v < BEHAVIOUR_VARIABLES; v++) {{
        w->in[v] = 0;
    }}
    for (m = 0; m < BEHAVIOUR_MACHINES; m++) {{
        w->entered_ms[m] = 0;
        w->fresh[m] = 0;
        w->globals_seen[m] = 0;
        w->command_count[m] = 0;
        for (k = 0; k < BEHAVIOUR_OUTPUTS; k++) {{
            w->seen[m][k] = 0;
        }}
    }}
{var_inits}{inits}}}

int behaviour_round(struct world *w)
{{
    int fired = 0;
    unsigned m;
    w->round++;
    if (w->cb.round_started) {{
        w->cb.round_started(w);
    }}
    for (m = 0; m < BEHAVIOUR_MACHINES; m++) {{
        w->fresh[m] = 0;
    }}
{rings}    for (m = 0; m < BEHAVIOUR_MACHINES; m++) {{
        fired |= w->fresh[m];
    }}
    return fired;
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

int behaviour_is_machine(const char *name)
{{
    unsigned m;
    for (m = 0; m < BEHAVIOUR_MACHINES; m++) {{
        if (same(name, machine_name[m])) {{
            return 1;
        }}
    }}
    return 0;
}}

uint64_t behaviour_next_due_ms(const struct world *w)
{{
    uint64_t due = BEHAVIOUR_PERIOD_MS;
{dues}    return due;
}}

int behaviour_finished(const struct world *w)
{{
{tops}    (void)w;
    return 1;
}}
",
        if output_names.is_empty() {
            "0".to_string()
        } else {
            output_names.join(", ")
        },
        if experts.is_empty() {
            "0".to_string()
        } else {
            experts.join(", ")
        },
        machine_names.join(", "),
        runtime = RUNTIME,
        loop_limit = proclaim_runner::LOOP_LIMIT,
        answers_body = if outputs.is_empty() {
            "    (void)atom;\n    return 0;\n".to_string()
        } else {
            format!("    unsigned k;\n    for (k = 0; k < {}u; k++) {{\n        if (same(atom, output_name[k])) {{\n            return 1;\n        }}\n    }}\n    return 0;\n", outputs.len())
        },
    );
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

/// What a state's labels read, gathered as they are compiled: the theory outputs they ask, the
/// times their time tests come due, and whether they read a global.
struct Labels<'a> {
    outputs: &'a [Output],
    read: Vec<usize>,
    due: Vec<u64>,
    reads_globals: bool,
}

impl Labels<'_> {
    /// A label as the runner proves it: a name standing as a condition is a variable's truth,
    /// else a theory output asked; `!`, `&&`, `||` over conditions; anything else (comparisons,
    /// arithmetic) a value's truth, computed on the spot.
    fn condition(&mut self, label: &Expr, activity: &mut Activity<'_>) -> Result<String, Refusal> {
        let m = activity.machine;
        let refuse = |activity: &Activity<'_>, what: String| Refusal {
            file: activity.file.to_string(),
            line: activity.line,
            what,
        };
        self.note_globals(label, activity);
        Ok(match label {
            Expr::Bool(b) => {
                if *b {
                    "1".into()
                } else {
                    "0".into()
                }
            }
            Expr::Name(n) if activity.variables.lookup(n).is_some() => activity.truth(label)?,
            Expr::Name(n) => {
                let Some(k) = self.outputs.iter().position(|o| &o.name == n) else {
                    return Err(refuse(activity, format!("the label atom `{n}`, which is no variable and which no theory of the behaviour answers")));
                };
                self.read.push(k);
                format!("ask(w, {m}u, {k}u)")
            }
            Expr::Unary {
                op: UnOp::Not,
                operand,
            } => format!("!{}", self.condition(operand, activity)?),
            Expr::Binary {
                op: op @ (BinOp::And | BinOp::Or),
                left,
                right,
            } => format!(
                "({} {} {})",
                self.condition(left, activity)?,
                if *op == BinOp::And { "&&" } else { "||" },
                self.condition(right, activity)?
            ),
            Expr::Call {
                function,
                arguments,
            } if arguments.len() == 1 && TIME_TESTS.iter().any(|(t, _)| t == function) => {
                // The µs one unit of the argument stands for (1 for timeout, 1000 for after_ms).
                let unit = TIME_TESTS
                    .iter()
                    .find(|(t, _)| t == function)
                    .map_or(1, |(_, us)| *us as u64);
                let micros = match &arguments[0] {
                    Expr::Int(n) if *n >= 0 => (*n as u64).checked_mul(unit),
                    Expr::Duration(d) => Some(*d),
                    _ => None,
                };
                let Some(micros) = micros.filter(|us| us % 1000 == 0) else {
                    return Err(refuse(
                        activity,
                        format!("`{label}` (only a constant time in whole milliseconds: a target's clock counts milliseconds)"),
                    ));
                };
                self.due.push(micros / 1000);
                format!("elapsed_at_least(w, {m}u, {}u)", micros / 1000)
            }
            other => activity.truth(other)?,
        })
    }

    fn note_globals(&mut self, label: &Expr, activity: &Activity<'_>) {
        label.visit_names(&mut |name, _| {
            if matches!(activity.variables.lookup(name), Some((_, true))) {
                self.reads_globals = true;
            }
        });
    }
}

/// The statements of a state's activities, those inside blocks and loops included.
fn state_statements(state: &proclaim_fsm::State) -> Vec<&Statement> {
    let mut out = Vec::new();
    for action in state
        .on_entry
        .iter()
        .chain(&state.on_exit)
        .chain(&state.internal)
    {
        if let Action::Statement(s) = action {
            s.visit(&mut |inner| out.push(inner));
        }
    }
    out
}

fn comment(text: &str) -> String {
    text.replace("*/", "* /")
}
