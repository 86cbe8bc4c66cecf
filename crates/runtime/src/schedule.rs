//! A compiled behaviour's round schedule and what its host asks of it (`docs/spec/behaviour.md`
//! §3.1): every behaviour's [`Tables`] is a [`CompiledBehaviour`] the host runs, by this one
//! implementation.

use crate::calls::{asked_of_expert, finished, post_status};
use crate::event::Event;
use crate::host::CompiledBehaviour;
use crate::tables::Tables;
use crate::world::{outside_value, World, DORMANT, RUNNING};

impl<B: Tables> CompiledBehaviour for B {
    const SCRIPT: Option<(&'static str, &'static str)> = B::SCRIPT;
    const MACHINE_NAMES: &'static [&'static str] = B::MACHINE_NAME;

    /// The behaviour at its start, reporting its events to `sink` (none made without one).
    fn init(sink: Option<Box<dyn FnMut(Event)>>) -> World {
        let machines = B::MACHINE_NAME.len();
        let (outputs, externs) = (B::OUTPUT_NAME.len(), B::EXTERN_NAME.len());
        let mut w = World::new(machines, outputs, B::INPUTS, externs, sink);
        w.supplied[..B::THEORY_OUTPUTS].fill(true);
        if !B::SUPPRESSED.is_empty() {
            let holds = B::SUPPRESSED
                .iter()
                .map(|(ty, ms)| (*ty, std::time::Duration::from_millis(*ms)));
            w.suppressor = Some(crate::Suppressor::new(holds));
        }
        w.var = B::var_inits();
        w.composite_ms = vec![0; B::COMPOSITE_MACHINE.len()];
        w.composite_entering = vec![true; B::COMPOSITE_MACHINE.len()];
        for m in 0..machines {
            w.state[m] = B::INITIAL[m];
            w.initial[m] = B::INITIAL[m];
            w.just_entered[m] = true;
            w.status[m] = if B::STARTS[m] { RUNNING } else { DORMANT };
        }
        for m in 0..machines {
            post_status::<B>(&mut w, m);
        }
        w
    }

    /// Tells the recording and the whiteboard, when there are any, what the run's start
    /// posted: each machine's running state.
    fn announce(w: &mut World) {
        if w.telling() {
            for m in 0..B::MACHINE_NAME.len() {
                post_status::<B>(w, m);
            }
        }
    }

    /// The run's own modules: its machines, its experts and the impersonator.
    fn modules() -> Vec<&'static str> {
        let machines = B::MACHINE_NAME.iter().chain(B::OUTPUT_EXPERT.iter());
        let mut modules: Vec<&'static str> = machines.copied().collect();
        modules.push("impersonator");
        modules
    }

    /// One round: `started` (what came from outside by now is posted), then a ringlet of
    /// every machine in manifest order; whether one fired (the next round follows at once).
    fn round(w: &mut World, started: impl FnOnce(&mut World)) -> bool {
        w.round += 1;
        started(w);
        take_over::<B>(w);
        w.fresh.fill(false);
        let fired = B::ring_machines(w);
        fired || w.fresh.iter().any(|f| *f)
    }

    /// A posting from outside the machines (an impersonator, a sensor, another process);
    /// whether it is news to a machine's labels.
    fn outside(w: &mut World, module: &str, ty: &str, content: &str) -> bool {
        hold_to_range::<B>(w, module, ty, content);
        let applied = B::apply_input(w, ty, content);
        (apply_extern::<B>(w, module, ty, content) || applied) && Self::news(w)
    }

    /// Whether an answer a machine's current labels read differs from what its last ringlet
    /// saw.
    fn news(w: &World) -> bool {
        (0..B::MACHINE_NAME.len()).any(|m| {
            w.status[m] == RUNNING
                && (answer_news::<B>(w, m)
                    || (w.globals_seen[m] != w.globals_changes && B::reads_globals(w, m))
                    || (0..B::EXTERN_NAME.len()).any(|e| {
                        B::reads_extern(w, m, e)
                            && !asked_of_expert::<B>(w, m, e)
                            && w.extern_news(m, e)
                    }))
        })
    }

    /// Whether `atom` is an answer of the behaviour's theories (the script may not set it).
    fn answers(atom: &str) -> bool {
        B::OUTPUT_NAME[..B::THEORY_OUTPUTS].contains(&atom)
    }

    /// The host answers `atom` from outside (its script sets it): whether it is an atom from
    /// outside the behaviour's labels ask, or a whiteboard value its machines read (a label
    /// asking it is then answered by the impersonator, as the interpreter's script answers it).
    fn supply(w: &mut World, atom: &str) -> bool {
        let outside = &B::OUTPUT_NAME[B::THEORY_OUTPUTS..];
        if let Some(k) = outside.iter().position(|o| *o == atom) {
            w.supplied[B::THEORY_OUTPUTS + k] = true;
            return true;
        }
        match B::EXTERN_NAME.iter().position(|name| *name == atom) {
            Some(e) => {
                w.scripted[e] = Some(false);
                true
            }
            None => false,
        }
    }

    /// A sensor none of whose atoms are in `scripted`, and its atoms: the interpreter would
    /// run that sensor, which a compiled behaviour does not have.
    fn unscripted_sensor(scripted: &[&str]) -> Option<(&'static str, &'static [&'static str])> {
        B::SENSORS
            .iter()
            .find(|(_, atoms)| !atoms.iter().any(|a| scripted.contains(a)))
            .copied()
    }

    /// Whether `name` is a machine's (a posting to it is a control command).
    fn is_machine(name: &str) -> bool {
        B::MACHINE_NAME.contains(&name)
    }

    /// Milliseconds from now until the next round is due without news (a timeout or the
    /// period); none while no machine runs (then only news starts a round, as the runner
    /// waits).
    fn next_due_ms(w: &World) -> Option<u64> {
        let period = w.status.contains(&RUNNING).then_some(B::PERIOD_MS);
        match (period, Self::next_test_ms(w)) {
            (Some(period), Some(test)) => Some(period.min(test)),
            (period, test) => period.or(test),
        }
    }

    /// Milliseconds from now until the soonest time test of a running machine, or hold with
    /// a lower posting behind it, comes due; none when nothing waits on the clock.
    fn next_test_ms(w: &World) -> Option<u64> {
        let mut due = u64::MAX;
        for m in 0..B::MACHINE_NAME.len() {
            if w.status[m] == RUNNING {
                due = B::due_of(w, m, due);
            }
        }
        // A hold running out with a lower posting behind it changes what readers see.
        if let Some(release) = w.suppressor.as_ref().and_then(|s| s.next_release()) {
            due = due.min((release.as_millis() as u64).saturating_sub(w.now_ms));
        }
        (due != u64::MAX).then_some(due)
    }

    fn finished(w: &World) -> bool {
        finished::<B>(w)
    }
}

/// Whether an answer machine `m`'s current labels read, and its last ringlet asked (or, for a
/// theory's, read the board for), differs from what that ringlet saw.
fn answer_news<B: Tables>(w: &World, m: usize) -> bool {
    (0..B::OUTPUT_NAME.len()).any(|k| {
        B::reads(w, m, k)
            && (w.asked[m][k] || (k < B::THEORY_OUTPUTS && w.ext_read[m]))
            && B::answer(w, k) != w.seen[m][k]
    })
}

/// A posting from outside to a whiteboard variable's type: whether it was one. A value the
/// compiled behaviour cannot hold is a warning, and the variable keeps its value.
fn apply_extern<B: Tables>(w: &mut World, module: &str, ty: &str, content: &str) -> bool {
    let Some(e) = B::EXTERN_NAME.iter().position(|name| *name == ty) else {
        return false;
    };
    let Some(value) = outside_value(content) else {
        w.warned(
            module,
            &format!(
                "posted {ty} = {content}, which a compiled behaviour cannot hold (it holds whole numbers and truth values): {ty} keeps its value"
            ),
        );
        return false;
    };
    w.ext[e] = Some(value);
    w.ext_by[e] = "impersonator";
    if w.scripted[e].is_some() {
        w.scripted[e] = Some(content == "true");
    }
    true
}

/// Holds a posting from outside to its type's declared range (the manifest's `[ranges]`): one
/// that leaves it is a warning, once per type and value, as the runner's (`verify` proved what
/// it proved assuming the range).
fn hold_to_range<B: Tables>(w: &mut World, module: &str, ty: &str, content: &str) {
    let Some(&(_, low, high)) = B::RANGES.iter().find(|(t, _, _)| *t == ty) else {
        return;
    };
    let inside = outside_value(content).is_some_and(|v| (low..=high).contains(&v.i));
    if inside || !w.range_said.insert((ty.to_string(), content.to_string())) {
        return;
    }
    w.warned(
        module,
        &format!(
            "posted {ty} = {content}, outside its declared range {low}..{high} (the manifest's [ranges]): what `verify` proved assumed it"
        ),
    );
}

/// At a round's start: every held type whose hold ran out with a lower posting behind it gets
/// that posting, as the runner's schedule has it.
fn take_over<B: Tables>(w: &mut World) {
    let Some(suppressor) = w.suppressor.as_mut() else {
        return;
    };
    let released = suppressor.release(std::time::Duration::from_millis(w.now_ms));
    for posting in released {
        w.took_over(
            &posting.module,
            &posting.ty,
            &posting.value,
            posting.priority,
            posting.at,
        );
        B::apply_input(w, &posting.ty, &posting.value);
    }
}
