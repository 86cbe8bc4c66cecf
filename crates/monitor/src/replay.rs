//! A recorded run at any of its moments: the whiteboard after each event kept as a persistent
//! snapshot (each shares all but one type with the one before), and the picture of the machines
//! rebuilt from the nearest checkpoint.

use crate::diagram::Chart;
use crate::picture::Picture;
use proclaim_board::{LocalBoard, Message, Snapshot, Transport, Value};
use proclaim_runner::{Answerer, Event};
use std::sync::Arc;
use std::time::Duration;

/// A picture is kept every this many events; a moment between is folded from the one before.
const CHECKPOINT: usize = 256;

pub struct Timeline {
    events: Vec<Event>,
    /// `boards[i]`: the board after the first `i` events.
    boards: Vec<Snapshot>,
    /// `checkpoints[k]`: the picture after the first `k * CHECKPOINT` events.
    checkpoints: Vec<Picture>,
}

impl Timeline {
    /// The trace's events.
    pub fn events(&self) -> &[Event] {
        &self.events
    }

    /// The machines' postings and their experts' answers are what the board held.
    pub fn new(charts: &[Chart], events: Vec<Event>) -> Timeline {
        let board = LocalBoard::new();
        let mut boards = Vec::with_capacity(events.len() + 1);
        boards.push(board.snapshot());
        let mut picture = Picture::new(charts);
        let mut checkpoints = vec![picture.clone()];
        for (i, event) in events.iter().enumerate() {
            let seq = i as u64 + 1;
            let posted = match event {
                Event::Posted {
                    machine,
                    ty,
                    content,
                    priority,
                    at,
                    ..
                }
                | Event::TookOver {
                    machine,
                    ty,
                    content,
                    priority,
                    at,
                    ..
                } => Some((
                    machine.as_str(),
                    ty.as_str(),
                    Value::parse(content),
                    *priority,
                    *at,
                )),
                Event::Answered {
                    atom,
                    value,
                    by: Answerer::Expert(expert),
                    at,
                    ..
                } => Some((expert.as_str(), atom.as_str(), Value::Bool(*value), 0, *at)),
                _ => None,
            };
            if let Some((module, ty, value, priority, time)) = posted {
                board.apply(
                    Message {
                        ty: Arc::from(ty),
                        value,
                        module: Arc::from(module),
                        seq,
                        time,
                        priority,
                    },
                    false,
                );
            }
            let mut snapshot = board.snapshot();
            snapshot.time = event
                .at()
                .unwrap_or_else(|| boards.last().map_or(Duration::ZERO, |b: &Snapshot| b.time));
            boards.push(snapshot);
            picture.observe(event);
            if (i + 1) % CHECKPOINT == 0 {
                checkpoints.push(picture.clone());
            }
        }
        Timeline {
            events,
            boards,
            checkpoints,
        }
    }

    /// How many events.
    pub fn len(&self) -> usize {
        self.events.len()
    }

    pub fn is_empty(&self) -> bool {
        self.events.is_empty()
    }

    /// The time of each moment: 0 before the first event, then each event's.
    pub fn times(&self) -> Vec<u64> {
        self.boards
            .iter()
            .map(|b| u64::try_from(b.time.as_micros()).unwrap_or(u64::MAX))
            .collect()
    }

    /// The round of each event.
    pub fn rounds(&self) -> Vec<u64> {
        self.events.iter().map(Event::round).collect()
    }

    /// The machines and the board after the first `at` events.
    pub fn at(&self, at: usize) -> (Picture, Snapshot) {
        let at = at.min(self.events.len());
        let k = at / CHECKPOINT;
        let mut picture = self.checkpoints[k].clone();
        for event in &self.events[k * CHECKPOINT..at] {
            picture.observe(event);
        }
        (picture, self.boards[at].clone())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn posted(ty: &str, content: &str, ms: u64) -> Event {
        Event::Posted {
            round: 0,
            machine: "M".into(),
            ty: ty.into(),
            content: content.into(),
            priority: 0,
            at: Duration::from_millis(ms),
        }
    }

    #[test]
    fn each_moment_shows_the_board_as_it_was_then() {
        let events: Vec<Event> = (0..1000)
            .map(|i| posted(if i % 2 == 0 { "a" } else { "b" }, &i.to_string(), i))
            .collect();
        let timeline = Timeline::new(&[], events);
        assert_eq!(timeline.len(), 1000);
        let (_, board) = timeline.at(0);
        assert!(board.is_empty());
        let (picture, board) = timeline.at(301);
        assert_eq!(
            board.newest("a").map(|m| m.value.to_string()),
            Some("300".into())
        );
        assert_eq!(
            board.newest("b").map(|m| m.value.to_string()),
            Some("299".into())
        );
        assert_eq!(picture.count, 301);
        let (_, end) = timeline.at(usize::MAX);
        assert_eq!(
            end.newest("b").map(|m| m.value.to_string()),
            Some("999".into())
        );
        assert_eq!(timeline.times()[301], 300_000);
    }
}
