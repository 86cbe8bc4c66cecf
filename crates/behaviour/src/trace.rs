//! The trace of a run for people: one line per state change, posting, control command and
//! changed answer (with who answered), time first. The JSON-lines trace keeps every event; this
//! view leaves out answers that repeat the previous one (same value, same answerer), which would
//! drown the rest.

use crate::error::BehaviourError;
use proclaim_runner::{Answerer, Event};
use rustc_hash::FxHashMap;
use std::fmt::Write;

#[derive(Default)]
pub struct TraceView {
    last_answer: FxHashMap<(String, String), (bool, Answerer)>,
    width: usize,
}

impl TraceView {
    /// `width`: the machine-name column's width (the longest name of the behaviour), at most
    /// [`TraceView::WIDEST`]: a longer name runs past the column.
    pub fn new(width: usize) -> TraceView {
        TraceView {
            last_answer: FxHashMap::default(),
            width: width.min(Self::WIDEST),
        }
    }

    /// The widest the name column grows (`format!` panics on widths past u16::MAX).
    pub const WIDEST: usize = 40;

    /// The event as a line, or `None` when it says nothing new.
    pub fn line(&mut self, event: &Event) -> Option<String> {
        let what = self.what(event)?;
        let mut line = String::new();
        match event.at() {
            Some(at) => {
                // In whole microseconds, as the JSON trace keeps it, so a replay prints the
                // same digits.
                let at = std::time::Duration::from_micros(at.as_micros() as u64);
                let _ = write!(line, "{:>8.3}s ", at.as_secs_f64());
            }
            None => line.push_str("          "),
        }
        let _ = write!(
            line,
            "{:<width$}  {what}",
            event.machine(),
            width = self.width
        );
        Some(line)
    }

    /// What the event says, after the time and the machine's name.
    fn what(&mut self, event: &Event) -> Option<String> {
        let what = match event {
            Event::Entered { state, .. } => format!("→ {state}"),
            Event::Fired { label, .. } => format!("fires on {label}"),
            Event::Posted {
                ty,
                content,
                priority: 0,
                ..
            } => format!("posts {ty}: {content}"),
            Event::Posted {
                ty,
                content,
                priority,
                ..
            } => format!("posts {ty}: {content} @{priority}"),
            Event::Suppressed {
                ty,
                content,
                priority,
                by,
                by_priority,
                until,
                ..
            } => format!(
                "suppressed {ty}: {content} @{priority} (held by {by} @{by_priority} until {:.3}s)",
                until.as_secs_f64()
            ),
            Event::TookOver {
                ty,
                content,
                priority,
                ..
            } => format!("takes over {ty}: {content} @{priority} (the hold above ran out)"),
            // A variable's every change would drown the trace; the JSON trace keeps them.
            Event::Assigned { .. } => return None,
            Event::Control { command, .. } => format!("told {command}"),
            Event::Answered {
                machine,
                atom,
                value,
                by,
                ..
            } => self.answer(machine, atom, *value, by)?,
            Event::UnknownFunction { function, .. } => {
                format!("host function {function} is not registered; skipped")
            }
            Event::Reloaded { state, .. } => format!("reloaded, in {state}"),
            Event::ReloadFailed { error, .. } => {
                format!("reload failed, runs on unchanged: {error}")
            }
            Event::Halted { reason, .. } => format!("halted: {reason}"),
            Event::Finished { state, .. } => format!("finished in {state}"),
            Event::Printed { text, .. } => format!("prints {text}"),
            Event::Warned { message, .. } => format!("warning: {message}"),
        };
        Some(what)
    }

    /// An answer, shown when its value or who gave it changes.
    fn answer(&mut self, machine: &str, atom: &str, value: bool, by: &Answerer) -> Option<String> {
        let key = (machine.to_string(), atom.to_string());
        let now = (value, by.clone());
        if self.last_answer.get(&key) == Some(&now) {
            return None;
        }
        self.last_answer.insert(key, now);
        Some(match by {
            Answerer::Expert(who) => format!("{atom} = {value}  ({who})"),
            Answerer::Posted(who) => format!("{atom} = {value}  (as posted by {who})"),
            Answerer::TimedOut => format!("{atom}: no answer in time, counted false"),
            Answerer::NoExpert => format!("{atom}: no expert answers it, counted false"),
        })
    }
}

/// Reads a JSON-lines trace; a bad line is reported with its number.
pub fn read_trace(text: &str) -> Result<Vec<Event>, BehaviourError> {
    text.lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty())
        .map(|(i, l)| {
            serde_json::from_str(l).map_err(|e| BehaviourError::TraceLine {
                line: i + 1,
                error: e.to_string(),
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn entered(machine: &str) -> Event {
        Event::Entered {
            machine: machine.into(),
            state: "A".into(),
            id: 1,
            round: 0,
            at: std::time::Duration::from_millis(1500),
        }
    }

    #[test]
    fn names_line_up_and_a_name_longer_than_the_column_runs_past_it() {
        let mut view = TraceView::new(6);
        assert_eq!(
            view.line(&entered("Door")).unwrap(),
            "   1.500s Door    → A"
        );
        let long = "M".repeat(70_000);
        let mut view = TraceView::new(long.len());
        let line = view.line(&entered(&long)).unwrap();
        assert!(line.ends_with(&format!("{long}  → A")), "{}", &line[..40]);
    }
}
