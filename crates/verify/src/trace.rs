//! Counterexamples for people: a path of the graph replayed step by step with the
//! environment's choices spelled out (what it set, which time tests came due), in rounds.

use crate::explore::Graph;
use crate::kind::ValueKind;
use crate::model::SlotId;
use crate::model::Storage;
use crate::outcome::{Assignment, Trace, TraceStep};
use crate::ringlet::{initial_worlds, Choice, Detail, StepGenerator, Successor};
use crate::search::Search;
use crate::seen::{Names, Run, Seen, Shown};
use crate::values::{key, ValueId, NEVER};
use crate::world::SystemState;
use crate::world::POSTED;
use proclaim_board::Value;
use proclaim_experts::ScriptValue;
use rustc_hash::FxHashMap;

fn assignment(model: &Search, slot: SlotId, value: ValueId) -> Assignment {
    let values = model.values.borrow();
    let v = values.get(value);
    Assignment {
        name: model.slots[slot].name.clone(),
        value: model.show(v),
        truth: match v {
            Some(Value::Bool(b)) => Some(*b),
            _ => None,
        },
        script: v.and_then(script_value).map(|s| s.to_string()),
    }
}

/// A value as an impersonator script sets it, where a script can.
fn script_value(v: &Value) -> Option<ScriptValue> {
    Some(match v {
        Value::Bool(b) => ScriptValue::Truth(*b),
        Value::Int(i) => ScriptValue::Whole(*i),
        Value::Float(x) if x.is_finite() => ScriptValue::Fraction(*x),
        Value::Str(s) if !s.contains(['#', '\n']) => ScriptValue::Text(s.clone()),
        _ => return None,
    })
}

/// The path from an initial state to state `id`.
pub fn trace(model: &Search, graph: &Graph, id: u32) -> Trace {
    let (initial, path) = graph.path(model, id);
    let steps = path
        .into_iter()
        .map(|(parent, choice)| (graph.world(parent), choice));
    trace_of(model, initial, steps)
}

/// The path from initial world `initial` taking, from each state, the step of its choice.
pub fn replay(model: &Search, graph: &Graph, initial: usize, path: &[(u32, Choice)]) -> Trace {
    trace_of(
        model,
        initial,
        path.iter()
            .map(|&(parent, choice)| (graph.world(parent), choice)),
    )
}

/// The path from initial world number `initial` through `path`: each world a step starts from
/// and the choice it took there.
pub fn trace_of(
    model: &Search,
    initial: usize,
    path: impl IntoIterator<Item = (SystemState, Choice)>,
) -> Trace {
    let Some(first) = initial_worlds(model).nth(initial) else {
        return Trace {
            initially: Vec::new(),
            steps: Vec::new(),
            unposted: Vec::new(),
            run: Run::default(),
        };
    };
    let initially = model
        .stored_free_slots()
        .filter(|(slot, _)| first.values[*slot] != NEVER)
        .map(|(slot, _)| assignment(model, slot, first.values[slot]))
        .collect();
    // What a free type chosen when read was last seen to hold: a read is told only where it
    // differs, as the world's moves are.
    let mut last_read: FxHashMap<SlotId, ValueId> = FxHashMap::default();
    // What the ringlets of this round read so far, by type.
    let mut this_round: FxHashMap<SlotId, ValueId> = FxHashMap::default();
    let mut unposted: Vec<String> = Vec::new();
    let stepper = StepGenerator::new(model);
    let mut round = 1;
    let mut steps = Vec::new();
    let mut successors = Vec::new();
    let mut run = Run::new(names(model));
    run.start(seen(model, &first));
    for (world, choice) in path {
        successors.clear();
        stepper.successors(&world, true, &mut successors);
        let Some(s) = successors.iter().find(|s| s.choice == choice) else {
            // Replaying is deterministic; a step not found again would be a bug in the model,
            // and the trace ends where it could be followed.
            break;
        };
        if s.wrapped {
            round += 1;
            this_round.clear();
        }
        run.push(s.machine, seen(model, &s.world));
        let detail = s.detail.clone().unwrap_or_default();
        for &(slot, v) in &detail.read {
            let name = &model.slots[slot].name;
            if v == NEVER
                && model.slots[slot].value_kind == ValueKind::Truth
                && !unposted.contains(name)
            {
                unposted.push(name.clone());
            }
        }
        let reads = (&mut last_read, &mut this_round);
        steps.push(step(model, s, round, &detail, reads));
    }
    Trace {
        initially,
        steps,
        unposted,
        run,
    }
}

/// Step `s` of round `round` for people, with what the environment did (`detail`); a read is
/// told where it differs from `last_read`, which it updates.
fn step(
    model: &Search,
    s: &Successor,
    round: u32,
    detail: &Detail,
    (last_read, this_round): (
        &mut FxHashMap<SlotId, ValueId>,
        &mut FxHashMap<SlotId, ValueId>,
    ),
) -> TraceStep {
    let m = &model.machines[s.machine];
    let state = &m.states[s.from];
    let shown = |list: &[(SlotId, ValueId)]| -> Vec<Assignment> {
        (list.iter())
            .map(|&(slot, v)| assignment(model, slot, v))
            .collect()
    };
    let Told {
        read,
        inside,
        between,
    } = reads_told(detail, last_read, this_round);
    let mut at_snapshot = detail.at_snapshot.clone();
    at_snapshot.extend(inside);
    TraceStep {
        round,
        machine: m.name.clone(),
        from: state.name.clone(),
        to: s.fired.and_then(|t| moved_to(m, &state.transitions[t])),
        label: s.fired.map(|t| m.shown(&state.transitions[t]).to_string()),
        timers: (detail.timers.iter())
            .map(|&i| m.time_test_shown(&state.time_tests[i]))
            .collect(),
        at_snapshot: shown(&at_snapshot),
        between: shown(&between),
        read: shown(&read),
        environment: shown(&detail.environment),
    }
}

/// A free type and the value a ringlet read of it.
type Read = (SlotId, ValueId);

/// A ringlet's reads as a trace tells them.
struct Told {
    /// Changes the world made since the last read or posting: a script sets them before the
    /// round.
    read: Vec<Read>,
    /// Changes inside the ringlet (after what it read or posted before): no moment of the
    /// clock is there.
    inside: Vec<Read>,
    /// Read otherwise than by an earlier ringlet of this round: changed between two.
    between: Vec<Read>,
}

/// The reads of a ringlet to tell, in the order made, with what the machine posted between
/// them (`detail.posted`) taken as what the type holds next: a read that differs from what was
/// last read or posted is the world's change. One that differs from what this very ringlet
/// read or posted before (its OnEntry read one value, its snapshot another) changed inside
/// the ringlet; one that differs from what an earlier ringlet of its round read, between the
/// two (`this_round`). A script can say neither.
fn reads_told(
    detail: &Detail,
    last_read: &mut FxHashMap<SlotId, ValueId>,
    this_round: &mut FxHashMap<SlotId, ValueId>,
) -> Told {
    let mut told = Told {
        read: Vec::new(),
        inside: Vec::new(),
        between: Vec::new(),
    };
    // What this ringlet has read or posted so far, by type.
    let mut here: FxHashMap<SlotId, ValueId> = FxHashMap::default();
    let mut posts = detail.posted.iter().peekable();
    for (i, &(slot, v)) in detail.read.iter().enumerate() {
        while let Some(&(_, posted, value)) = posts.next_if(|p| p.0 <= i) {
            last_read.insert(posted, value);
            here.insert(posted, value);
        }
        let before = last_read.insert(slot, v).unwrap_or(NEVER);
        let earlier = this_round.get(&slot).copied();
        match here.insert(slot, v) {
            Some(mine) if mine != v => told.inside.push((slot, v)),
            None if earlier.is_some_and(|e| e != v) => told.between.push((slot, v)),
            _ if before != v => told.read.push((slot, v)),
            _ => {}
        }
    }
    for &(_, posted, value) in posts {
        last_read.insert(posted, value);
        here.insert(posted, value);
    }
    // What this ringlet leaves a type at is what the next ringlet of the round meets.
    this_round.extend(here);
    told
}

/// A trace as text, one ringlet a line, grouped by round.
pub fn render(trace: &Trace) -> String {
    let mut out = String::new();
    let show = |a: &[Assignment]| {
        a.iter()
            .map(|a| format!("{} = {}", a.name, a.value))
            .collect::<Vec<_>>()
            .join(", ")
    };
    if !trace.initially.is_empty() {
        out.push_str(&format!("  initially: {}\n", show(&trace.initially)));
    }
    let mut round = 0;
    for s in &trace.steps {
        if s.round != round {
            round = s.round;
            out.push_str(&format!("  round {round}\n"));
        }
        let mut line = format!("    {}: {}", s.machine, s.from);
        match (&s.to, &s.label) {
            (Some(to), Some(label)) => line.push_str(&format!(" -> {to} (when {label})")),
            (None, Some(label)) => line.push_str(&format!(" acts and stays (when {label})")),
            _ => line.push_str(" stays"),
        }
        if !s.timers.is_empty() {
            line.push_str(&format!("; due: {}", s.timers.join(", ")));
        }
        if !s.read.is_empty() {
            line.push_str(&format!("; reads {}", show(&s.read)));
        }
        if !s.between.is_empty() {
            line.push_str(&format!("; since the last ringlet: {}", show(&s.between)));
        }
        if !s.at_snapshot.is_empty() {
            line.push_str(&format!("; before its snapshot: {}", show(&s.at_snapshot)));
        }
        if !s.environment.is_empty() {
            line.push_str(&format!("; then the world sets {}", show(&s.environment)));
        }
        out.push_str(&line);
        out.push('\n');
    }
    out
}

/// The state a fired transition moved to; `None` for one that stays (§3.2).
fn moved_to(m: &crate::model::MachineModel, t: &crate::model::TransitionModel) -> Option<String> {
    (!m.machine.transitions[t.index].stays).then(|| m.states[t.target].name.clone())
}

/// What `world` shows of the behaviour, by value ([`Seen`]).
pub(crate) fn seen(model: &Search, world: &SystemState) -> Seen {
    let values = model.values.borrow();
    let shown = |id: ValueId| match (id, values.get(id)) {
        (POSTED, _) => Shown::Posted,
        (_, None) => Shown::Never,
        (_, Some(v)) => Shown::Is(key(v)),
    };
    Seen {
        turn: world.turn,
        machines: (world.machines.iter())
            .map(|c| (c.state, c.status as u8, c.just_entered, c.fresh, c.time))
            .collect(),
        values: (world.values.iter().enumerate())
            .map(|(slot, &id)| match model.storage[slot] {
                Storage::Stored => shown(id),
                // Only whether it was posted yet: what it holds is chosen where it is read.
                Storage::ChosenWhenRead if id == NEVER => Shown::Never,
                Storage::ChosenWhenRead => Shown::Posted,
                Storage::Unread => Shown::Unstored,
            })
            .collect(),
        saw: world.saw.iter().map(|&id| shown(id)).collect(),
    }
}

/// The names of `model`'s slots and `saw()`s, which a [`Run`] of it keeps.
pub(crate) fn names(model: &Search) -> Names {
    Names {
        slots: model.slots.iter().map(|s| s.name.clone()).collect(),
        saw: (model.saw.iter())
            .map(|(k, name)| format!("{}: {name}", model.machines[*k].name))
            .collect(),
    }
}
