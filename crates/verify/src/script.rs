//! A counterexample as an impersonator script (`proclaim_experts::parse_script`'s format:
//! `doorOpen = false` from the start, `at 1.5s doorOpen = true` later), so that
//! `proclaim run BEHAVIOUR --script FILE --virtual-clock` plays the same environment.
//!
//! What it cannot carry, said in the script's own comments: a script sets truths, numbers
//! and text (a list the counterexample needs is listed, not set); a script speaks in time, not
//! in rounds, so a change the model made in round r is placed in the middle of round r's ring
//! period (`(r - ½) × ring_period`), and a value a ringlet of round r read in the middle of
//! round r - 1's, which is where an idle behaviour's round r runs, but a round that follows a
//! firing at once runs earlier; a change between two machines' ringlets of one round, or
//! between a machine's OnEntry and its snapshot, falls to that round; and time tests come due
//! when the clock says, not when the counterexample needed them.
//!
//! A liveness counterexample is a lasso, a way in and a loop repeated for ever; scripts have
//! no repetition, so [`lasso_script`] plays the way in and then the loop [`LOOP_REPEATS`] times,
//! and says so in a comment.

use crate::outcome::{Assignment, Trace};
use std::fmt::Write;
use std::time::Duration;

/// The script, and the notes of what it does not reproduce (also in the script as comments).
pub fn to_script(trace: &Trace, ring_period: Duration, title: &str) -> (String, Vec<String>) {
    let mut out = String::new();
    let mut notes = Vec::new();
    let _ = writeln!(out, "# {title}");
    let _ = writeln!(
        out,
        "# Written by `proclaim verify`: the environment of the counterexample, one round per {} ms.",
        ring_period.as_millis()
    );
    let mut lines = Vec::new();
    let mut line = |when: Option<f64>, a: &Assignment, lines: &mut Vec<String>| match &a.script {
        Some(v) => lines.push(match when {
            None => format!("{} = {v}", a.name),
            Some(s) => format!("at {s}s {} = {v}", a.name),
        }),
        None => notes.push(format!(
            "`{}` must be {}, which a script cannot set (truths, numbers and one-line text only)",
            a.name, a.value
        )),
    };
    for a in &trace.initially {
        line(None, a, &mut lines);
    }
    for name in &trace.unposted {
        lines.push(format!(
            "{name} = false  # read, never posted: false, as the model read it"
        ));
    }
    let period = ring_period.as_secs_f64();
    let mut timers = Vec::new();
    for s in &trace.steps {
        let at = ((f64::from(s.round) - 0.5) * period * 1e4).round() / 1e4;
        // A value a ringlet of round r read was set before that round: in the middle of
        // round r - 1's period (from the start, for round 1).
        let before = ((f64::from(s.round) - 1.5) * period * 1e4).round() / 1e4;
        for a in &s.read {
            line((s.round > 1).then_some(before), a, &mut lines);
        }
        for a in s.at_snapshot.iter().chain(&s.environment) {
            line(Some(at), a, &mut lines);
        }
        for t in &s.timers {
            timers.push(format!(
                "`{t}` of {}.{} came due in round {}",
                s.machine, s.from, s.round
            ));
        }
    }
    if !timers.is_empty() {
        notes.push(format!(
            "time tests come due by the clock, not as the counterexample needs: {}",
            timers.join("; ")
        ));
    }
    for n in &notes {
        let _ = writeln!(out, "# not reproduced: {n}");
    }
    for l in lines {
        let _ = writeln!(out, "{l}");
    }
    (out, notes)
}

/// How many times a lasso's script plays its loop.
pub const LOOP_REPEATS: u32 = 5;

/// The lasso's way in followed by its loop played `LOOP_REPEATS` times, rounds numbered on.
pub fn unroll(prefix: &Trace, cycle: &Trace) -> Trace {
    let before = prefix.steps.last().map_or(1, |s| s.round);
    let rounds = cycle
        .steps
        .last()
        .map_or(0, |s| s.round.saturating_sub(before));
    let mut steps = prefix.steps.clone();
    for repeat in 0..LOOP_REPEATS {
        steps.extend(cycle.steps.iter().map(|s| {
            let mut s = s.clone();
            s.round += repeat * rounds;
            s
        }));
    }
    Trace {
        initially: prefix.initially.clone(),
        steps,
        unposted: prefix.unposted.clone(),
        run: Default::default(),
    }
}

/// A lasso (a liveness property's counterexample) as a script: [`to_script`] of [`unroll`],
/// with a comment saying where the loop starts and how often it is played.
pub fn lasso_script(
    prefix: &Trace,
    cycle: &Trace,
    ring_period: Duration,
    title: &str,
) -> (String, Vec<String>) {
    let (script, notes) = to_script(&unroll(prefix, cycle), ring_period, title);
    let last = prefix.steps.last().map_or(0, |s| s.round);
    let comment = if cycle.steps.is_empty() {
        format!(
            "# The run ends after round {last}: no machine can ring any more, and it stays so for ever.\n"
        )
    } else {
        format!(
            "# A lasso: the way in to round {last}, then its loop (rounds {} to {}), which repeats for ever; scripts cannot repeat, so it is played {LOOP_REPEATS} times.\n",
            cycle.steps.first().map_or(last, |s| s.round),
            cycle.steps.last().map_or(last, |s| s.round),
        )
    };
    // After the title and the line that says what the script is.
    let mut lines: Vec<&str> = script.split_inclusive('\n').collect();
    let at = lines.len().min(2);
    lines.insert(at, &comment);
    (lines.concat(), notes)
}
