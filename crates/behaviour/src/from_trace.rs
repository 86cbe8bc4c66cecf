//! A run's JSON trace (`proclaim run --trace`) read as a recording, so that `explain` can say why
//! a theory answered as it did in a run that was traced rather than recorded. The trace keeps
//! what was posted, in the order it happened, and every answer a machine read with who gave
//! it; from those this rebuilds the board's messages: each posting, and for each answer of an
//! expert the query and the expert's posting of it. What a trace loses: a posting's value is
//! kept as text (read back by `Value::parse`: a truth, a whole number, a fraction or text), and
//! a ringlet that neither posted nor read anything leaves no line.

use crate::recorded::{Recorded, Recording};
use proclaim_board::{Value, QUERY_TYPE};
use proclaim_runner::{Answerer, Event, Ringlet};

impl Recording {
    /// The recording a trace's events stand for: `machines` are the behaviour's machines in
    /// schedule order (a ringlet is numbered by its machine's place).
    pub fn from_trace(events: Vec<Event>, machines: &[&str]) -> Recording {
        let mut recording = Recording::default();
        // Messages are numbered from 1 in the order the trace has them.
        let push = |recording: &mut Recording, module: &str, ty: &str, value: Value| {
            recording.messages.push(Recorded {
                seq: recording.messages.len() as u64 + 1,
                module: module.to_string(),
                ty: ty.to_string(),
                value,
            });
        };
        for event in &events {
            if let Some(place) = machines.iter().position(|m| *m == event.machine()) {
                let rang = |r: &Ringlet| r.round == event.round() && r.machine == place;
                if !recording
                    .ringlets
                    .iter()
                    .rev()
                    .take(machines.len())
                    .any(rang)
                {
                    recording.ringlets.push(Ringlet {
                        round: event.round(),
                        machine: place,
                        seq: recording.messages.len() as u64,
                        at: event.at().unwrap_or_default(),
                        snapshot: None,
                    });
                }
            }
            match event {
                Event::Posted {
                    machine,
                    ty,
                    content,
                    ..
                } => {
                    push(&mut recording, machine, ty, Value::parse(content));
                }
                Event::Answered {
                    machine,
                    atom,
                    value,
                    by: Answerer::Expert(expert),
                    ..
                } => {
                    push(
                        &mut recording,
                        machine,
                        QUERY_TYPE,
                        Value::Str(atom.clone()),
                    );
                    push(&mut recording, expert, atom, Value::Bool(*value));
                }
                _ => {}
            }
        }
        recording.events = events;
        recording
    }
}
