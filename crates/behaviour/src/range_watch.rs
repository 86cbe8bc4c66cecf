//! Holds a run to the manifest's `[ranges]`: a posting from outside the machines (a script, a
//! sensor, another process) that leaves its type's declared range is a warning in the trace,
//! once per type and value (the ones given are shared, so a checkpoint keeps them), since what `verify` proved of the behaviour assumed the range.

use crate::checkpoint::RangeWarning;
use crate::ranges::DeclaredRange;
use parking_lot::Mutex;
use proclaim_board::Subscription;
use proclaim_runner::{Event, RoundCounter};
use rustc_hash::FxHashSet;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use tokio::sync::mpsc;

/// Watches `postings` (of the declared types) until the run ends; `machines` are the
/// behaviour's own, whose postings are computed, not assumed.
pub(crate) async fn watch(
    mut postings: Subscription,
    ranges: Vec<DeclaredRange>,
    machines: Vec<String>,
    (said, handled): (Arc<Mutex<FxHashSet<RangeWarning>>>, Arc<AtomicU64>),
    (trace, epoch, round): (
        mpsc::UnboundedSender<Event>,
        tokio::time::Instant,
        RoundCounter,
    ),
) {
    while let Some(m) = postings.next().await {
        handled.store(m.seq, Ordering::Relaxed);
        if machines.iter().any(|name| **name == *m.module) {
            continue;
        }
        let Some(range) = ranges.iter().find(|r| *r.ty == *m.ty) else {
            continue;
        };
        let warning = RangeWarning {
            ty: m.ty.to_string(),
            value: m.value.to_string(),
        };
        if range.contains(&m.value) || !said.lock().insert(warning) {
            continue;
        }
        let event = Event::Warned {
            machine: m.module.to_string(),
            message: format!(
                "posted {} = {}, outside its declared range {range} (the manifest's [ranges]): what `verify` proved assumed it",
                m.ty, m.value
            ),
            at: epoch.elapsed(),
            round: round.get(),
        };
        if trace.send(event).is_err() {
            return;
        }
    }
}
