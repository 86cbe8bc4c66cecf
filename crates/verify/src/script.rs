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
//! between a machine's OnEntry and its snapshot, falls after that round, and two ringlets of
//! one round that read a value differently get one of them; and time tests come due when the
//! clock says, not when the counterexample needed them. Each of these, where a counterexample
//! needs it, is a note.
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
    let mut lines: Vec<Line> = Vec::new();
    for a in &trace.initially {
        set(&mut lines, &mut notes, None, a);
    }
    for name in &trace.unposted {
        let value = "false  # read, never posted: false, as the model read it";
        lines.push((None, name.clone(), value.to_string()));
    }
    let period = ring_period.as_secs_f64();
    let mut timers = Vec::new();
    for (i, s) in trace.steps.iter().enumerate() {
        let at = ((f64::from(s.round) - 0.5) * period * 1e4).round() / 1e4;
        // A value a ringlet of round r read was set before that round: in the middle of
        // round r - 1's period (from the start, for round 1).
        let before = ((f64::from(s.round) - 1.5) * period * 1e4).round() / 1e4;
        for a in &s.read {
            set(&mut lines, &mut notes, (s.round > 1).then_some(before), a);
        }
        for a in &s.between {
            notes.push(format!(
                "`{}` = {} read by {} otherwise than by an earlier ringlet of round {}: set before that round",
                a.name, a.value, s.machine, s.round
            ));
            set(&mut lines, &mut notes, (s.round > 1).then_some(before), a);
        }
        // Every ringlet of a round runs at the round's moment: a change inside one, or
        // between two, has no moment of its own, and falls after the round.
        for a in &s.at_snapshot {
            notes.push(format!(
                "`{}` = {} between {}'s OnEntry and its snapshot in round {}: set after that round",
                a.name, a.value, s.machine, s.round
            ));
        }
        let later = trace.steps.get(i + 1).is_some_and(|n| n.round == s.round);
        for a in s.environment.iter().filter(|_| later) {
            notes.push(format!(
                "`{}` = {} after {}'s ringlet, before the next machine's in round {}: set after that round",
                a.name, a.value, s.machine, s.round
            ));
        }
        for a in s.at_snapshot.iter().chain(&s.environment) {
            set(&mut lines, &mut notes, Some(at), a);
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
    for (when, name, value) in lines {
        let _ = match when {
            None => writeln!(out, "{name} = {value}"),
            Some(at) => writeln!(out, "at {at}s {name} = {value}"),
        };
    }
    (out, notes)
}

/// A script line: when (from the start, or at a time in seconds), the name, the value.
type Line = (Option<f64>, String, String);

/// The line setting `a` at `when`, and a note where a script cannot set it, or where another
/// line already sets it to something else at that moment.
fn set(lines: &mut Vec<Line>, notes: &mut Vec<String>, when: Option<f64>, a: &Assignment) {
    let Some(v) = &a.script else {
        notes.push(format!(
            "`{}` must be {}, which a script cannot set (truths, numbers and one-line text only)",
            a.name, a.value
        ));
        return;
    };
    let clash = lines.iter().find(|(w, n, _)| *w == when && *n == a.name);
    if let Some((_, _, other)) = clash.filter(|(_, _, other)| other != v) {
        notes.push(format!(
            "`{}` must be {other} and then {v} at one moment of the script (two ringlets of a round read it differently), which sets one value at a time",
            a.name
        ));
    }
    lines.push((when, a.name.clone(), v.clone()));
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::outcome::TraceStep;

    fn set_to(name: &str, value: i64) -> Assignment {
        Assignment {
            name: name.into(),
            value: value.to_string(),
            truth: None,
            script: Some(value.to_string()),
        }
    }

    fn ringlet(round: u32, machine: &str) -> TraceStep {
        TraceStep {
            round,
            machine: machine.into(),
            from: "S".into(),
            to: None,
            label: None,
            timers: Vec::new(),
            read: Vec::new(),
            at_snapshot: Vec::new(),
            between: Vec::new(),
            environment: Vec::new(),
        }
    }

    fn check(steps: Vec<TraceStep>, script: &str, notes: &[&str]) {
        let trace = Trace {
            initially: vec![set_to("level", 0)],
            steps,
            unposted: vec!["door".into()],
            run: Default::default(),
        };
        let (written, said) = to_script(&trace, Duration::from_millis(100), "t");
        let lines: Vec<&str> = (written.lines()).filter(|l| !l.starts_with('#')).collect();
        assert_eq!(lines.join("\n"), script);
        assert_eq!(said, notes);
    }

    #[test]
    fn a_change_no_moment_of_the_clock_can_carry_is_a_note() {
        // Round 2: A reads level 3, then B reads it as 4; the world sets `knob` after A's
        // ringlet (before B's), and `dial` inside B's, between its OnEntry and its snapshot.
        let mut a = ringlet(2, "A");
        a.read.push(set_to("level", 3));
        a.environment.push(set_to("knob", 1));
        let mut b = ringlet(2, "B");
        b.read.push(set_to("level", 4));
        b.at_snapshot.push(set_to("dial", 7));
        let mut c = ringlet(3, "A");
        c.environment.push(set_to("knob", 2));
        check(
            vec![ringlet(1, "A"), a, b, c],
            "level = 0\ndoor = false  # read, never posted: false, as the model read it\n\
             at 0.05s level = 3\nat 0.15s knob = 1\nat 0.05s level = 4\nat 0.15s dial = 7\n\
             at 0.25s knob = 2",
            &[
                "`knob` = 1 after A's ringlet, before the next machine's in round 2: set after that round",
                "`level` must be 3 and then 4 at one moment of the script (two ringlets of a round read it differently), which sets one value at a time",
                "`dial` = 7 between B's OnEntry and its snapshot in round 2: set after that round",
            ],
        );
        // One machine a round, reading and changing in turn: nothing to note.
        let mut a = ringlet(2, "A");
        a.read.push(set_to("level", 3));
        a.environment.push(set_to("knob", 1));
        check(
            vec![ringlet(1, "A"), a],
            "level = 0\ndoor = false  # read, never posted: false, as the model read it\n\
             at 0.05s level = 3\nat 0.15s knob = 1",
            &[],
        );
    }
}
