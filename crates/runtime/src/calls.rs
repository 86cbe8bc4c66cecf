//! What a compiled behaviour's machine code calls, as the runner does it: asking a label's
//! atom, reading the whiteboard through the ringlet's snapshot, posting (under subsumption),
//! assigning, control commands. Generic over the behaviour's [`Tables`]; the printed code calls
//! `ask::<Behaviour>(w, m, k)`, and the functions that read no table without one ([`GENERIC`]
//! names those that do).

use crate::tables::Tables;
use crate::world::{
    board_value, convert, min_due, truthy, v_bool, v_int, v_none, v_some, value_text, By,
    Elsewhere, Scalar, World, COMMAND_OFF, COMMAND_ON, COMMAND_RESTART, COMMAND_RESUME,
    COMMAND_SUSPEND, DORMANT, RUNNING, SUSPENDED,
};
use crate::QUERY_TYPE;

/// The calls the printed code makes with the behaviour's tables (`name::<Behaviour>(w, …)`).
pub const GENERIC: &[&str] = &[
    "ask",
    "ask_posted",
    "assign",
    "begin_ringlet",
    "command",
    "obey",
    "post",
    "post_extern",
    "post_text",
    "print_text",
    "proved",
    "read_extern",
    "report_finished",
    "ringlet_due",
    "take_snapshot",
];

/// A theory input from a posting's content, as the reasoner expert reads it: true, false, a
/// whole number (true unless 0), or unknown for anything else.
#[inline]
pub fn set_input(w: &mut World, v: usize, content: &str) {
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

/// Whether a posting's type is `b` (C compares the texts; here they are `&str`s).
#[inline]
pub fn same(a: &str, b: &str) -> bool {
    a == b
}

/// Machine `m` asks output `k`: the answer its label reads, reported once the label is proved.
pub fn ask<B: Tables>(w: &mut World, m: usize, k: usize) -> bool {
    let value = B::answer(w, k);
    w.asked[m][k] = true;
    // No expert answers it: the runner reads its newest posting instead, from the snapshot.
    if !w.supplied[k] {
        w.ext_read[m] = true;
    } else if let Some(e) = B::OUTPUT_BOARD[k] {
        // An expert answers by posting its answer, which the machines read as a value.
        w.ext[e] = Some(v_bool(value));
        w.ext_by[e] = B::OUTPUT_EXPERT[k];
    }
    let expert = w.supplied[k].then_some(B::OUTPUT_EXPERT[k]);
    if let Some(expert) = expert {
        let atom = B::OUTPUT_NAME[k];
        w.message(B::MACHINE_NAME[m], QUERY_TYPE, || serde_json::json!(atom));
        w.message(expert, atom, || serde_json::Value::Bool(value));
        // The expert posts its answer: a theory reading the atom as an input sees it.
        B::apply_input(w, atom, if value { "true" } else { "false" });
        w.queried(atom, value);
    }
    let by = expert.map_or(By::Nobody, By::Expert);
    w.pending.push((B::OUTPUT_NAME[k], value, by));
    value
}

/// Proves a transition's label; the answers it read are reported once it is proved, as the
/// runner reports them.
pub fn proved<B: Tables>(w: &mut World, m: usize, label: impl FnOnce(&mut World) -> bool) -> bool {
    let holds = label(w);
    // By index, so that the list keeps its room for the next label.
    for i in 0..w.pending.len() {
        let (atom, value, by) = w.pending[i];
        w.answered(B::MACHINE_NAME[m], atom, value, by);
    }
    w.pending.clear();
    holds
}

/// Whether machine `m`'s last ringlet asked an expert the atom whiteboard value `e` is: then a
/// posting of it is news only when the answer changed, which the answers' own test sees.
pub(crate) fn asked_of_expert<B: Tables>(w: &World, m: usize, e: usize) -> bool {
    (0..B::OUTPUT_NAME.len()).any(|k| B::OUTPUT_BOARD[k] == Some(e) && w.asked[m][k])
}

/// What a whiteboard value never posted reads as.
fn unposted<B: Tables>(e: usize) -> Scalar {
    if B::EXTERN_BOUND[e] {
        v_int(0)
    } else {
        v_none()
    }
}

/// The output whose atom whiteboard value `e` is, when an expert answered the ringlet's
/// question of it: the ringlet reads that answer, as the runner holds an expert's answer.
fn answered_here<B: Tables>(w: &World, e: usize) -> Option<usize> {
    (0..B::OUTPUT_NAME.len())
        .find(|k| B::OUTPUT_BOARD[*k] == Some(e) && w.supplied[*k] && w.asked[w.ringing][*k])
}

/// A whiteboard value as the ringlet reads it: live before the snapshot (in OnEntry), then
/// what the ringlet posted itself, else an expert's answer it asked, else the snapshot; and
/// who posted it (none: nobody).
fn read_board<B: Tables>(w: &mut World, e: usize) -> (Scalar, Option<&'static str>) {
    let m = w.ringing;
    let by = |v: Option<Scalar>, by: &'static str| match v {
        Some(v) => (v, Some(by)),
        None => (unposted::<B>(e), None),
    };
    if !w.past_snapshot {
        return by(w.ext[e], w.ext_by[e]);
    }
    if let Some(own) = w.ext_own[m][e] {
        return (own, Some(B::MACHINE_NAME[m]));
    }
    if let Some(k) = answered_here::<B>(w, e) {
        return (v_bool(B::answer(w, k)), Some(B::OUTPUT_EXPERT[k]));
    }
    w.ext_read[m] = true;
    by(w.ext_seen[m][e], w.ext_seen_by[m][e])
}

/// Whiteboard value `e` as the ringlet reads it.
pub fn read_extern<B: Tables>(w: &mut World, e: usize) -> Scalar {
    read_board::<B>(w, e).0
}

/// A label atom nobody answers: the runner reads the atom's newest posting as the ringlet sees
/// it and reports who posted it (a never posted atom is false, answered by nobody).
pub fn ask_posted<B: Tables>(w: &mut World, m: usize, e: usize, atom: &'static str) -> bool {
    if let Some(value) = w.scripted[e] {
        return scripted::<B>(w, (m, e), atom, value);
    }
    // On a shared whiteboard an expert in another process may answer it, as it answers the
    // runner's query.
    let asked = w
        .elsewhere
        .as_mut()
        .map(|ask| ask(B::MACHINE_NAME[m], atom, B::ANSWER_TIMEOUT_MS));
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
    let (v, by) = read_board::<B>(w, e);
    let value = !v.none && truthy(v);
    w.asked_posted[m][e] = Some(value);
    let by = match by.filter(|_| !v.none) {
        Some(poster) => By::Posted(poster),
        None => By::Nobody,
    };
    w.pending.push((atom, value, by));
    value
}

/// The host's script answers a label's atom that no module of the behaviour declares, as the
/// interpreter's impersonator does: asked, it posts its answer.
fn scripted<B: Tables>(
    w: &mut World,
    (m, e): (usize, usize),
    atom: &'static str,
    value: bool,
) -> bool {
    w.message(B::MACHINE_NAME[m], QUERY_TYPE, || serde_json::json!(atom));
    w.message("impersonator", atom, || serde_json::Value::Bool(value));
    w.ext[e] = Some(v_bool(value));
    w.ext_by[e] = "impersonator";
    B::apply_input(w, atom, if value { "true" } else { "false" });
    w.queried(atom, value);
    w.asked_posted[m][e] = Some(value);
    w.pending.push((atom, value, By::Expert("impersonator")));
    value
}

/// A machine's posting: shown (then a theory input takes it), or held back by a higher
/// layer's posting of a type under subsumption (then no reader sees it).
pub fn post<B: Tables>(w: &mut World, m: usize, ty: &str, content: &str) {
    let (machine, priority) = (B::MACHINE_NAME[m], B::PRIORITY[m]);
    if let Some(suppressor) = w.suppressor.as_mut() {
        let now = std::time::Duration::from_millis(w.now_ms);
        let verdict = suppressor.offer(machine, ty, &content.to_string(), priority, now);
        if let crate::Visibility::Suppressed {
            by,
            priority: p,
            until,
        } = verdict
        {
            w.suppressed(machine, ty, content, priority, &by, p, until);
            return;
        }
    }
    w.posted(machine, ty, content, priority);
    w.message(machine, ty, || board_value(content));
    B::apply_input(w, ty, content);
}

/// Machine `m` posts `v` to whiteboard variable `e` (an assignment to it, or a posting).
pub fn post_extern<B: Tables>(w: &mut World, m: usize, e: usize, v: Scalar) {
    let v = v_some(v);
    let shown = value_text(v);
    let (machine, ty) = (B::MACHINE_NAME[m], B::EXTERN_NAME[e]);
    w.posted(machine, ty, &shown, B::PRIORITY[m]);
    w.message(machine, ty, || board_value(&shown));
    B::apply_input(w, ty, &shown);
    w.ext[e] = Some(v);
    w.ext_by[e] = machine;
    if w.past_snapshot {
        w.ext_own[m][e] = Some(v);
    }
}

/// Posts the text built.
pub fn post_text<B: Tables>(w: &mut World, m: usize, ty: &str) {
    let text = std::mem::take(&mut w.text);
    post::<B>(w, m, ty, &text);
    w.text = text;
}

/// Prints the text built.
pub fn print_text<B: Tables>(w: &mut World, m: usize) {
    let text = std::mem::take(&mut w.text);
    w.printed(B::MACHINE_NAME[m], &text);
    w.text = text;
}

// The three below are called from every machine's own code with its number: inlined there, a
// ringlet costs what it cost written out (not inlined, a behaviour of hundreds of machines was
// measurably slower).

/// Whether machine `m` rings in this round: running, not started in it, and not over.
#[inline(always)]
pub fn ringlet_due<B: Tables>(w: &World, m: usize) -> bool {
    w.status[m] == RUNNING && !w.fresh[m] && !done::<B>(w, m)
}

/// A ringlet of machine `m` begins: whether it has just entered its state (then its OnEntry
/// runs first).
#[inline(always)]
pub fn begin_ringlet<B: Tables>(w: &mut World, m: usize) -> bool {
    w.ringing = m;
    w.ringlet_begins(m);
    w.past_snapshot = false;
    if !w.just_entered[m] {
        return false;
    }
    w.just_entered[m] = false;
    w.entered_ms[m] = w.now_ms;
    for c in composites_of::<B>(m) {
        if std::mem::take(&mut w.composite_entering[c]) {
            w.composite_ms[c] = w.now_ms;
        }
    }
    true
}

/// The composite states of machine `m`'s chart ([`Tables::COMPOSITE_MACHINE`]).
fn composites_of<B: Tables>(m: usize) -> impl Iterator<Item = usize> {
    (0..B::COMPOSITE_MACHINE.len()).filter(move |&c| B::COMPOSITE_MACHINE[c] == m)
}

/// A move enters composite state `c`: its time starts when the move arrives.
#[inline(always)]
pub fn enter_composite(w: &mut World, c: usize) {
    w.composite_entering[c] = true;
}

/// The ringlet's snapshot (`docs/spec/behaviour.md` 3.1), after OnEntry.
#[inline(always)]
pub fn take_snapshot<B: Tables>(w: &mut World, m: usize) {
    for k in 0..B::OUTPUT_NAME.len() {
        w.seen[m][k] = B::answer(w, k);
        w.asked[m][k] = false;
    }
    w.extern_snapshot(m);
    w.globals_seen[m] = w.globals_changes;
}

/// The soonest of `due` and `ms` after machine `m` entered its state.
#[inline]
pub fn due_after(w: &World, m: usize, ms: u64, due: u64) -> u64 {
    min_due(due, w.entered_ms[m].wrapping_add(ms), w.now_ms)
}

/// Whether machine `m` has been in its state at least `ms`.
#[inline]
pub fn elapsed_at_least(w: &World, m: usize, ms: u64) -> bool {
    w.now_ms.wrapping_sub(w.entered_ms[m]) >= ms
}

/// The soonest of `due` and `ms` after composite state `c` was entered.
#[inline]
pub fn composite_due_after(w: &World, c: usize, ms: u64, due: u64) -> u64 {
    min_due(due, w.composite_ms[c].wrapping_add(ms), w.now_ms)
}

/// Whether its machine has been in composite state `c` at least `ms`.
#[inline]
pub fn composite_elapsed(w: &World, c: usize, ms: u64) -> bool {
    w.now_ms.wrapping_sub(w.composite_ms[c]) >= ms
}

/// An assignment as the runner makes it: converted to the variable's type, reported when the
/// value changed; a global's change is news to the labels that read globals.
pub fn assign<B: Tables>(
    w: &mut World,
    m: usize,
    slot: usize,
    conversion: u8,
    global: bool,
    name: &str,
    v: Scalar,
) {
    let v = convert(conversion, v_some(v));
    if w.var[slot] == v {
        return;
    }
    w.var[slot] = v;
    if global {
        w.globals_changes += 1;
    }
    w.assigned(B::MACHINE_NAME[m], name, || value_text(v));
}

/// The machine's run is over: reported, and the trace ends once every machine's is.
pub fn report_finished<B: Tables>(w: &mut World, m: usize, state: &str) {
    if w.over {
        return;
    }
    w.finished(B::MACHINE_NAME[m], state);
    w.over = finished::<B>(w);
}

/// Whether every machine that starts with the behaviour is in a final state, its OnEntry run.
pub(crate) fn finished<B: Tables>(w: &World) -> bool {
    (0..B::MACHINE_NAME.len()).all(|m| !B::STARTS[m] || done::<B>(w, m))
}

/// Whether a machine's run is over for now: in a state with no way out, its OnEntry run.
fn done<B: Tables>(w: &World, m: usize) -> bool {
    !w.just_entered[m] && B::final_state(w, m)
}

/// A control command posted to machine `m`, obeyed when the ringlet ends.
pub fn command<B: Tables>(w: &mut World, m: usize, code: u8, word: &'static str) {
    w.message(B::MACHINE_NAME[w.ringing], B::MACHINE_NAME[m], || {
        serde_json::json!(word)
    });
    if w.commands[m].len() < B::COMMANDS {
        w.commands[m].push((code, word));
        w.commands_waiting = true;
    }
}

/// The runner posts a machine's running state to `NameIsRunning` when it starts and whenever
/// that changes.
pub(crate) fn post_status<B: Tables>(w: &mut World, m: usize) {
    if w.telling() {
        let ty = format!("{}IsRunning", B::MACHINE_NAME[m]);
        let running = w.status[m] == RUNNING;
        w.message(B::MACHINE_NAME[m], &ty, || serde_json::Value::Bool(running));
    }
    if let Some(e) = B::STATUS_BOARD[m] {
        w.ext[e] = Some(v_bool(w.status[m] == RUNNING));
        w.ext_by[e] = B::MACHINE_NAME[m];
    }
}

/// gufsm's SuspensibleMachine, as the runner's `control`: whether it started the machine.
fn control<B: Tables>(w: &mut World, m: usize, code: u8, word: &str) -> bool {
    let was_running = w.status[m] == RUNNING;
    w.control(B::MACHINE_NAME[m], word);
    let started = obey_command(w, m, code);
    if started {
        // Into its state as from outside: every composite around it is entered again.
        for c in composites_of::<B>(m) {
            w.composite_entering[c] = true;
        }
    }
    if was_running != (w.status[m] == RUNNING) {
        post_status::<B>(w, m);
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
pub fn obey<B: Tables>(w: &mut World) {
    if !w.commands_waiting {
        return;
    }
    w.commands_waiting = false;
    for m in 0..B::MACHINE_NAME.len() {
        let commands = std::mem::take(&mut w.commands[m]);
        for (code, word) in commands {
            if control::<B>(w, m, code, word) {
                w.fresh[m] = true;
            }
        }
    }
}
