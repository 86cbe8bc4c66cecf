//! A deliberate change accepted (`proclaim test --update`): a recording's outside replayed on the
//! behaviour as it is now, recorded anew (every whiteboard message, ringlet and event, as `run
//! --record` writes them), with the rounds whose machine events changed, as a snapshot tool
//! shows what it is about to accept.

use crate::load::Behaviour;
use crate::recorded::{message_line, replay, ringlet_line, Recording};
use crate::trace::TraceView;
use proclaim_board::{Message, Pattern, Subscription, Whiteboard};
use proclaim_runner::{Event, Ringlet};
use std::collections::BTreeMap;

/// A recording made again on the behaviour as it is now.
pub struct Rerecorded {
    /// The new recording's lines.
    pub text: String,
    /// Each round whose machines' events changed, in order.
    pub changed: Vec<RoundChange>,
}

/// One round's machine events, as the readable trace shows them, before and after.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RoundChange {
    pub round: u64,
    pub was: Vec<String>,
    pub now: Vec<String>,
}

/// Replays `recording`'s outside on `behaviour` (on a virtual clock of its own: call it from a
/// plain thread) and records the run.
pub fn rerecord(behaviour: &Behaviour, recording: &Recording) -> std::io::Result<Rerecorded> {
    let runtime = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .start_paused(true)
        .build()?;
    let (messages, ringlets, events) = runtime.block_on(async {
        let board = Whiteboard::local();
        let (stop, stopped) = tokio::sync::oneshot::channel();
        let collector = tokio::spawn(collect(board.subscribe_pattern(Pattern::All), stopped));
        let mut ticks = None;
        let events = replay(behaviour, recording, board, |rounds| {
            ticks = Some(rounds.ringlets());
        })
        .await;
        let _ = stop.send(());
        let messages = collector.await.unwrap_or_default();
        let mut ringlets: Vec<Ringlet> = Vec::new();
        if let Some(mut ticks) = ticks {
            while let Ok(r) = ticks.try_recv() {
                ringlets.push(r);
            }
        }
        (messages, ringlets, events)
    });
    // A branch recorded again is still the branch of its parent.
    let mut text = match &recording.branch {
        Some(of) => of.header() + "\n",
        None => String::new(),
    };
    let lines = messages.iter().map(message_line);
    let lines = lines.chain(ringlets.iter().map(ringlet_line));
    let lines = lines.chain(
        events
            .iter()
            .map(|e| serde_json::to_string(e).unwrap_or_default()),
    );
    for line in lines {
        text.push_str(&line);
        text.push('\n');
    }
    let changed = changes(behaviour, &recording.events, &events);
    Ok(Rerecorded { text, changed })
}

/// Every message on the board until told to stop (then what is already queued too).
async fn collect(
    mut all: Subscription,
    mut stop: tokio::sync::oneshot::Receiver<()>,
) -> Vec<Message> {
    let mut got = Vec::new();
    loop {
        tokio::select! {
            biased;
            message = all.next() => match message {
                Some(m) => got.push(m),
                None => break,
            },
            _ = &mut stop => {
                while let Some(m) = all.try_next() {
                    got.push(m);
                }
                break;
            }
        }
    }
    got
}

/// The rounds whose machine events, as the readable trace shows them, differ.
fn changes(behaviour: &Behaviour, was: &[Event], now: &[Event]) -> Vec<RoundChange> {
    let by_round = |events: &[Event]| {
        let width = behaviour
            .machines
            .iter()
            .map(|m| m.machine.name.len())
            .max();
        let mut view = TraceView::new(width.unwrap_or(0));
        let mut rounds: BTreeMap<u64, Vec<String>> = BTreeMap::new();
        let ours = |e: &&Event| {
            behaviour
                .machines
                .iter()
                .any(|m| m.machine.name == e.machine())
        };
        for e in events.iter().filter(ours) {
            if let Some(line) = view.line(e) {
                rounds
                    .entry(e.round())
                    .or_default()
                    .push(line.trim().to_string());
            }
        }
        rounds
    };
    let (was, now) = (by_round(was), by_round(now));
    let mut all: Vec<u64> = was.keys().chain(now.keys()).copied().collect();
    all.sort_unstable();
    all.dedup();
    all.into_iter()
        .filter(|r| was.get(r) != now.get(r))
        .map(|round| RoundChange {
            round,
            was: was.get(&round).cloned().unwrap_or_default(),
            now: now.get(&round).cloned().unwrap_or_default(),
        })
        .collect()
}
