//! The fixed text of a behaviour compiled to a Cargo project, with `@NAME@` where
//! `print_rust.rs` fills in the behaviour's own parts.

/// `src/behaviour.rs` around its machines' code.
pub(crate) const BODY: &str = r#"//! The behaviour `@name@` compiled by proclaim (generated: do not edit): a ringlet a machine,
//! the round schedule, and what its host asks of it.

use crate::runtime::*;
use proclaim_runtime::{Event, QUERY_TYPE};

pub const MACHINES: usize = @machines@;
pub const OUTPUTS: usize = @outputs@;
pub const VARIABLES: usize = @variables@;
/// The period of rounds without news, in milliseconds.
pub const PERIOD_MS: u64 = @period_ms@;
const COMMANDS: usize = @commands@;
const LOOP_LIMIT: u32 = @loop_limit@;
/// How long a query to an expert in another process waits, in milliseconds.
const ANSWER_TIMEOUT_MS: u64 = @answer_timeout_ms@;
const OUTPUT_NAME: [&str; OUTPUTS] = [@output_names@];
/// The outputs a theory answers come first; the impersonator's atoms follow.
const THEORY_OUTPUTS: usize = @theory_outputs@;
/// The behaviour's own script (`[impersonator]`): its file and text, played without `--script`.
pub const SCRIPT: Option<(&str, &str)> = @script@;
/// Each sensor wrapper and the atoms it answers: the host's script must set one of them.
const SENSORS: [(&str, &[&str]); @sensors_n@] = [@sensors@];
const OUTPUT_EXPERT: [&str; OUTPUTS] = [@experts@];
const MACHINE_NAME: [&str; MACHINES] = [@machine_names@];
const INITIAL: [i64; MACHINES] = [@initials@];
/// Whether each machine runs from the start (else it is dormant until started).
const STARTS: [bool; MACHINES] = [@starts@];
/// The machines' names, in schedule order.
pub const MACHINE_NAMES: &[&str] = &MACHINE_NAME;
pub const EXTERNS: usize = @externs@;
const EXTERN_NAME: [&str; EXTERNS] = [@extern_names@];
/// Whether each whiteboard value is bound with `extern` (read as a whole 0 while unposted).
const EXTERN_BOUND: [bool; EXTERNS] = [@extern_bound@];
/// The whiteboard value of each output's atom: an expert's answer is posted there.
const OUTPUT_BOARD: [Option<usize>; OUTPUTS] = [@output_board@];
/// The whiteboard value each machine's running state is posted to (`NameIsRunning`).
const STATUS_BOARD: [Option<usize>; MACHINES] = [@status_board@];
/// Each machine's subsumption layer, which its postings carry.
const PRIORITY: [u32; MACHINES] = [@priorities@];
/// The types under subsumption and how long a higher layer's posting holds each, in ms.
const SUPPRESSED: [(&str, u64); @suppressed_n@] = [@suppressed@];

/// A theory input from a posting's content, as the reasoner expert reads it: true, false, a
/// whole number (true unless 0), or unknown for anything else.
fn set_input(w: &mut World, v: usize, content: &str) {
    let whole = content.strip_prefix('-').unwrap_or(content);
    let (known, value) = match content {
        "true" => (true, true),
        "false" => (true, false),
        _ if !whole.is_empty() && whole.bytes().all(|b| b.is_ascii_digit()) => {
            (true, whole.bytes().any(|b| b != b'0'))
        }
        _ => (false, false),
    };
    w.input[v] = known;
    w.input[v + 1] = value;
}

// `answer`: each output's answer; `apply_input`: whether a posting's type is a theory input
// (then applied).
@answers@
fn same(a: &str, b: &str) -> bool {
    a == b
}

fn ask(w: &mut World, m: usize, k: usize) -> bool {
    let value = answer(w, k);
    w.asked[m][k] = true;
    // No expert answers it: the runner reads its newest posting instead, from the snapshot.
    if !w.supplied[k] {
        w.ext_read[m] = true;
    } else if let Some(e) = OUTPUT_BOARD[k] {
        // An expert answers by posting its answer, which the machines read as a value.
        w.ext[e] = Some(v_bool(value));
        w.ext_by[e] = OUTPUT_EXPERT[k];
    }
    let expert = w.supplied[k].then_some(OUTPUT_EXPERT[k]);
    if let Some(expert) = expert {
        w.message(MACHINE_NAME[m], QUERY_TYPE, || serde_json::json!(OUTPUT_NAME[k]));
        w.message(expert, OUTPUT_NAME[k], || serde_json::Value::Bool(value));
        // The expert posts its answer: a theory reading the atom as an input sees it.
        apply_input(w, OUTPUT_NAME[k], if value { "true" } else { "false" });
        w.queried(OUTPUT_NAME[k], value);
    }
    let by = expert.map_or(By::Nobody, By::Expert);
    w.pending.push((OUTPUT_NAME[k], value, by));
    value
}

/// Proves a transition's label; the answers it read are reported once it is proved, as the
/// runner reports them.
fn proved(w: &mut World, m: usize, label: impl FnOnce(&mut World) -> bool) -> bool {
    let holds = label(w);
    // By index, so that the list keeps its room for the next label.
    for i in 0..w.pending.len() {
        let (atom, value, by) = w.pending[i];
        w.answered(MACHINE_NAME[m], atom, value, by);
    }
    w.pending.clear();
    holds
}

/// Whether machine `m`'s last ringlet asked an expert the atom whiteboard value `e` is: then a
/// posting of it is news only when the answer changed, which the answers' own test sees.
fn asked_of_expert(w: &World, m: usize, e: usize) -> bool {
    (0..OUTPUTS).any(|k| OUTPUT_BOARD[k] == Some(e) && w.asked[m][k])
}

/// What a whiteboard value never posted reads as.
fn unposted(e: usize) -> Scalar {
    if EXTERN_BOUND[e] {
        v_int(0)
    } else {
        v_none()
    }
}

/// The output whose atom whiteboard value `e` is, when an expert answered the ringlet's
/// question of it: the ringlet reads that answer, as the runner holds an expert's answer.
fn answered_here(w: &World, e: usize) -> Option<usize> {
    (0..OUTPUTS).find(|k| OUTPUT_BOARD[*k] == Some(e) && w.supplied[*k] && w.asked[w.ringing][*k])
}

/// A whiteboard value as the ringlet reads it: live before the snapshot (in OnEntry), then
/// what the ringlet posted itself, else an expert's answer it asked, else the snapshot; and
/// who posted it (none: nobody).
fn read_board(w: &mut World, e: usize) -> (Scalar, Option<&'static str>) {
    let m = w.ringing;
    let by = |v: Option<Scalar>, by: &'static str| match v {
        Some(v) => (v, Some(by)),
        None => (unposted(e), None),
    };
    if !w.past_snapshot {
        return by(w.ext[e], w.ext_by[e]);
    }
    if let Some(own) = w.ext_own[m][e] {
        return (own, Some(MACHINE_NAME[m]));
    }
    if let Some(k) = answered_here(w, e) {
        return (v_bool(answer(w, k)), Some(OUTPUT_EXPERT[k]));
    }
    w.ext_read[m] = true;
    by(w.ext_seen[m][e], w.ext_seen_by[m][e])
}

fn read_extern(w: &mut World, e: usize) -> Scalar {
    read_board(w, e).0
}

/// A label atom nobody answers: the runner reads the atom's newest posting as the ringlet sees
/// it and reports who posted it (a never posted atom is false, answered by nobody).
fn ask_posted(w: &mut World, m: usize, e: usize, atom: &'static str) -> bool {
    // On a shared whiteboard an expert in another process may answer it, as it answers the
    // runner's query.
    let asked = w.elsewhere.as_mut().map(|ask| ask(MACHINE_NAME[m], atom, ANSWER_TIMEOUT_MS));
    let answered = match asked {
        Some(Elsewhere::Answered(value, expert)) => Some((value, By::Expert(expert))),
        Some(Elsewhere::TimedOut) => Some((false, By::TimedOut)),
        Some(Elsewhere::NoExpert) | None => None,
    };
    if let Some((value, by)) = answered {
        if let By::Expert(expert) = by {
            // The expert posted its answer: the board's value is that answer now.
            w.ext[e] = Some(v_bool(value));
            w.ext_by[e] = expert;
        }
        w.asked_posted[m][e] = Some(value);
        w.pending.push((atom, value, by));
        return value;
    }
    let (v, by) = read_board(w, e);
    let value = !v.none && truthy(v);
    w.asked_posted[m][e] = Some(value);
    let by = match by.filter(|_| !v.none) {
        Some(poster) => By::Posted(poster),
        None => By::Nobody,
    };
    w.pending.push((atom, value, by));
    value
}

/// A machine's posting: shown (then a theory input takes it), or held back by a higher
/// layer's posting of a type under subsumption (then no reader sees it).
fn post(w: &mut World, m: usize, ty: &str, content: &str) {
    if let Some(suppressor) = w.suppressor.as_mut() {
        let now = std::time::Duration::from_millis(w.now_ms);
        let value = content.to_string();
        let verdict = suppressor.offer(MACHINE_NAME[m], ty, &value, PRIORITY[m], now);
        if let proclaim_runtime::Visibility::Suppressed { by, priority, until } = verdict {
            w.suppressed(MACHINE_NAME[m], ty, content, PRIORITY[m], &by, priority, until);
            return;
        }
    }
    w.posted(MACHINE_NAME[m], ty, content, PRIORITY[m]);
    w.message(MACHINE_NAME[m], ty, || board_value(content));
    apply_input(w, ty, content);
}

/// Machine `m` posts `v` to whiteboard variable `e` (an assignment to it, or a posting).
fn post_extern(w: &mut World, m: usize, e: usize, v: Scalar) {
    let v = v_some(v);
    let shown = value_text(v);
    w.posted(MACHINE_NAME[m], EXTERN_NAME[e], &shown, PRIORITY[m]);
    w.message(MACHINE_NAME[m], EXTERN_NAME[e], || board_value(&shown));
    apply_input(w, EXTERN_NAME[e], &shown);
    w.ext[e] = Some(v);
    w.ext_by[e] = MACHINE_NAME[m];
    if w.past_snapshot {
        w.ext_own[m][e] = Some(v);
    }
}

/// A posting from outside to a whiteboard variable's type (a script's truth word): whether it
/// was one.
fn apply_extern(w: &mut World, ty: &str, content: &str) -> bool {
    match EXTERN_NAME.iter().position(|name| *name == ty) {
        Some(e) => {
            w.ext[e] = Some(v_bool(content == "true"));
            w.ext_by[e] = "impersonator";
            true
        }
        None => false,
    }
}

/// At a round's start: every held type whose hold ran out with a lower posting behind it gets
/// that posting, as the runner's schedule has it.
fn take_over(w: &mut World) {
    let Some(suppressor) = w.suppressor.as_mut() else {
        return;
    };
    let released = suppressor.release(std::time::Duration::from_millis(w.now_ms));
    for posting in released {
        w.took_over(&posting.module, &posting.ty, &posting.value, posting.priority, posting.at);
        apply_input(w, &posting.ty, &posting.value);
    }
}

/// Posts the text built.
fn post_text(w: &mut World, m: usize, ty: &str) {
    let text = std::mem::take(&mut w.text);
    post(w, m, ty, &text);
    w.text = text;
}

fn print_text(w: &mut World, m: usize) {
    let text = std::mem::take(&mut w.text);
    w.printed(MACHINE_NAME[m], &text);
    w.text = text;
}

// The three below are called from every machine's own code with its number: inlined there, a
// ringlet costs what it cost written out (not inlined, a behaviour of hundreds of machines was
// measurably slower).

/// Whether machine `m` rings in this round: running, not started in it, and not over.
#[inline(always)]
fn ringlet_due(w: &World, m: usize) -> bool {
    w.status[m] == RUNNING && !w.fresh[m] && !done(w, m)
}

/// A ringlet of machine `m` begins: whether it has just entered its state (then its OnEntry
/// runs first).
#[inline(always)]
fn begin_ringlet(w: &mut World, m: usize) -> bool {
    w.ringing = m;
    w.ringlet_begins(m);
    w.past_snapshot = false;
    if !w.just_entered[m] {
        return false;
    }
    w.just_entered[m] = false;
    w.entered_ms[m] = w.now_ms;
    true
}

/// The ringlet's snapshot (`docs/spec/behaviour.md` 3.1), after OnEntry.
#[inline(always)]
fn take_snapshot(w: &mut World, m: usize) {
    snapshot(w, m);
    w.extern_snapshot(m);
    w.globals_seen[m] = w.globals_changes;
}

/// The soonest of `due` and `ms` after machine `m` entered its state.
fn due_after(w: &World, m: usize, ms: u64, due: u64) -> u64 {
    min_due(due, w.entered_ms[m].wrapping_add(ms), w.now_ms)
}

fn snapshot(w: &mut World, m: usize) {
    for k in 0..OUTPUTS {
        let value = answer(w, k);
        w.seen[m][k] = value;
        w.asked[m][k] = false;
    }
}

fn elapsed_at_least(w: &World, m: usize, ms: u64) -> bool {
    w.now_ms.wrapping_sub(w.entered_ms[m]) >= ms
}

/// An assignment as the runner makes it: converted to the variable's type, reported when the
/// value changed; a global's change is news to the labels that read globals.
fn assign(w: &mut World, m: usize, slot: usize, conversion: u8, global: bool, name: &str, v: Scalar) {
    let v = convert(conversion, v_some(v));
    if w.var[slot] == v {
        return;
    }
    w.var[slot] = v;
    if global {
        w.globals_changes += 1;
    }
    w.assigned(MACHINE_NAME[m], name, || value_text(v));
}

/// The machine's run is over: reported, and the trace ends once every machine's is.
fn report_finished(w: &mut World, m: usize, state: &str) {
    if w.over {
        return;
    }
    w.finished(MACHINE_NAME[m], state);
    w.over = finished(w);
}

/// Whether a machine's run is over for now: in a state with no way out, its OnEntry run.
fn done(w: &World, m: usize) -> bool {
    !w.just_entered[m] && final_state(w, m)
}

/// A control command posted to machine `m`, obeyed when the ringlet ends.
fn command(w: &mut World, m: usize, code: u8, word: &'static str) {
    w.message(MACHINE_NAME[w.ringing], MACHINE_NAME[m], || serde_json::json!(word));
    if w.commands[m].len() < COMMANDS {
        w.commands[m].push((code, word));
        w.commands_waiting = true;
    }
}

/// The runner posts a machine's running state to `NameIsRunning` when it starts and whenever
/// that changes.
fn post_status(w: &mut World, m: usize) {
    if w.telling() {
        let ty = format!("{}IsRunning", MACHINE_NAME[m]);
        let running = w.status[m] == RUNNING;
        w.message(MACHINE_NAME[m], &ty, || serde_json::Value::Bool(running));
    }
    if let Some(e) = STATUS_BOARD[m] {
        w.ext[e] = Some(v_bool(w.status[m] == RUNNING));
        w.ext_by[e] = MACHINE_NAME[m];
    }
}

/// gufsm's SuspensibleMachine, as the runner's `control`: whether it started the machine.
fn control(w: &mut World, m: usize, code: u8, word: &str) -> bool {
    let was_running = w.status[m] == RUNNING;
    w.control(MACHINE_NAME[m], word);
    let started = obey_command(w, m, code);
    if was_running != (w.status[m] == RUNNING) {
        post_status(w, m);
    }
    started
}

fn obey_command(w: &mut World, m: usize, code: u8) -> bool {
    match code {
        COMMAND_ON | COMMAND_RESUME => {
            if w.status[m] == DORMANT {
                w.state[m] = w.initial[m];
            } else if w.status[m] == RUNNING {
                return false;
            }
            w.status[m] = RUNNING;
            w.just_entered[m] = true;
            true
        }
        COMMAND_RESTART => {
            w.status[m] = RUNNING;
            w.state[m] = w.initial[m];
            w.just_entered[m] = true;
            true
        }
        COMMAND_SUSPEND => {
            if w.status[m] == RUNNING {
                w.status[m] = SUSPENDED;
            }
            false
        }
        COMMAND_OFF => {
            w.status[m] = DORMANT;
            false
        }
        _ => false,
    }
}

/// The commands waiting for each machine, in schedule order; a machine started rings from the
/// next round.
fn obey(w: &mut World) {
    if !w.commands_waiting {
        return;
    }
    w.commands_waiting = false;
    for m in 0..MACHINES {
        let commands = std::mem::take(&mut w.commands[m]);
        for (code, word) in commands {
            if control(w, m, code, word) {
                w.fresh[m] = true;
            }
        }
    }
}

@code@
/// The behaviour at its start, reporting its events to `sink` (none made without one).
pub fn init(sink: Option<Box<dyn FnMut(Event)>>) -> World {
    let mut w = World::new(MACHINES, OUTPUTS, VARIABLES, EXTERNS, sink);
    w.supplied[..THEORY_OUTPUTS].fill(true);
    if !SUPPRESSED.is_empty() {
        let holds = SUPPRESSED
            .iter()
            .map(|(ty, ms)| (*ty, std::time::Duration::from_millis(*ms)));
        w.suppressor = Some(proclaim_runtime::Suppressor::new(holds));
    }
    w.var = vec![@var_inits@];
    for m in 0..MACHINES {
        w.state[m] = INITIAL[m];
        w.initial[m] = INITIAL[m];
        w.just_entered[m] = true;
        w.status[m] = if STARTS[m] { RUNNING } else { DORMANT };
    }
    for m in 0..MACHINES {
        post_status(&mut w, m);
    }
    w
}

/// Tells the recording and the whiteboard, when there are any, what the run's start posted:
/// each machine's running state.
pub fn announce(w: &mut World) {
    if w.telling() {
        for m in 0..MACHINES {
            post_status(w, m);
        }
    }
}

/// The run's own modules: its machines, its experts and the impersonator.
pub fn modules() -> Vec<&'static str> {
    let mut modules: Vec<&'static str> = MACHINE_NAME.iter().chain(OUTPUT_EXPERT.iter()).copied().collect();
    modules.push("impersonator");
    modules
}

/// One round: `started` (what came from outside by now is posted), then a ringlet of every
/// machine in manifest order; whether one fired (the next round follows at once).
pub fn round(w: &mut World, started: impl FnOnce(&mut World)) -> bool {
    let mut fired = false;
    w.round += 1;
    started(w);
    take_over(w);
    for m in 0..MACHINES {
        w.fresh[m] = false;
    }
    fired |= ring_machines(w);
    fired || w.fresh.iter().any(|f| *f)
}

/// A posting from outside the machines (an impersonator, a sensor); whether it is news to a
/// machine's labels.
pub fn outside(w: &mut World, ty: &str, content: &str) -> bool {
    let applied = apply_input(w, ty, content);
    (apply_extern(w, ty, content) || applied) && news(w)
}

/// Whether an answer a machine's current labels read differs from what its last ringlet saw.
pub fn news(w: &World) -> bool {
    (0..MACHINES).any(|m| {
        w.status[m] == RUNNING
            && ((0..OUTPUTS).any(|k| {
                reads(w, m, k)
                    && (w.asked[m][k] || (k < THEORY_OUTPUTS && w.ext_read[m]))
                    && answer(w, k) != w.seen[m][k]
            }) || (w.globals_seen[m] != w.globals_changes && reads_globals(w, m))
                || (0..EXTERNS).any(|e| {
                    reads_extern(w, m, e) && !asked_of_expert(w, m, e) && w.extern_news(m, e)
                }))
    })
}

/// Whether `atom` is an answer of the behaviour's theories (the script may not set it).
pub fn answers(atom: &str) -> bool {
    OUTPUT_NAME[..THEORY_OUTPUTS].contains(&atom)
}

/// The host answers `atom` from outside (its script sets it): whether it is an atom from
/// outside the behaviour's labels ask.
pub fn supply(w: &mut World, atom: &str) -> bool {
    match OUTPUT_NAME[THEORY_OUTPUTS..].iter().position(|o| *o == atom) {
        Some(k) => {
            w.supplied[THEORY_OUTPUTS + k] = true;
            true
        }
        None => false,
    }
}

/// A sensor none of whose atoms are in `scripted`, and its atoms: the interpreter would run
/// that sensor, which a compiled behaviour does not have.
pub fn unscripted_sensor(scripted: &[&str]) -> Option<(&'static str, &'static [&'static str])> {
    SENSORS
        .iter()
        .find(|(_, atoms)| !atoms.iter().any(|a| scripted.contains(a)))
        .copied()
}

/// Whether `name` is a machine's (a posting to it is a control command).
pub fn is_machine(name: &str) -> bool {
    MACHINE_NAME.contains(&name)
}

/// Milliseconds from now until the soonest time test of a running machine, or hold with a
/// lower posting behind it, comes due; none when nothing waits on the clock.
pub fn next_test_ms(w: &World) -> Option<u64> {
    let mut due = u64::MAX;
    for m in 0..MACHINES {
        if w.status[m] == RUNNING {
            due = due_of(w, m, due);
        }
    }
    // A hold running out with a lower posting behind it changes what readers see.
    if let Some(release) = w.suppressor.as_ref().and_then(|s| s.next_release()) {
        due = due.min((release.as_millis() as u64).saturating_sub(w.now_ms));
    }
    (due != u64::MAX).then_some(due)
}

/// Milliseconds from now until the next round is due without news (a timeout or the period);
/// none while no machine runs (then only news starts a round, as the runner waits).
pub fn next_due_ms(w: &World) -> Option<u64> {
    let period = w.status.contains(&RUNNING).then_some(PERIOD_MS);
    match (period, next_test_ms(w)) {
        (Some(period), Some(test)) => Some(period.min(test)),
        (period, test) => period.or(test),
    }
}

/// Whether every machine that starts with the behaviour is in a final state, its OnEntry run.
pub fn finished(w: &World) -> bool {
    (0..MACHINES).all(|m| !STARTS[m] || done(w, m))
}

/// The behaviour as `proclaim_runtime::host` runs it.
pub struct Behaviour;

impl proclaim_runtime::host::CompiledBehaviour for Behaviour {
    const SCRIPT: Option<(&'static str, &'static str)> = SCRIPT;
    const MACHINE_NAMES: &'static [&'static str] = MACHINE_NAMES;
    fn init(sink: Option<Box<dyn FnMut(Event)>>) -> World {
        init(sink)
    }
    fn announce(w: &mut World) {
        announce(w)
    }
    fn modules() -> Vec<&'static str> {
        modules()
    }
    fn round(w: &mut World, started: impl FnOnce(&mut World)) -> bool {
        round(w, started)
    }
    fn outside(w: &mut World, ty: &str, content: &str) -> bool {
        outside(w, ty, content)
    }
    fn news(w: &World) -> bool {
        news(w)
    }
    fn answers(atom: &str) -> bool {
        answers(atom)
    }
    fn supply(w: &mut World, atom: &str) -> bool {
        supply(w, atom)
    }
    fn unscripted_sensor(scripted: &[&str]) -> Option<(&'static str, &'static [&'static str])> {
        unscripted_sensor(scripted)
    }
    fn is_machine(name: &str) -> bool {
        is_machine(name)
    }
    fn next_due_ms(w: &World) -> Option<u64> {
        next_due_ms(w)
    }
    fn next_test_ms(w: &World) -> Option<u64> {
        next_test_ms(w)
    }
    fn finished(w: &World) -> bool {
        finished(w)
    }
}
"#;
