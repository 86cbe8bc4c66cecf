//! The handle modules hold, and the query protocol of behaviour.md §2: post a query for an atom,
//! wait for its expert's answer, time out as false.

use crate::image::BoardImage;
use crate::local::LocalBoard;
use crate::message::{Kind, Message};
use crate::pattern::Pattern;
use crate::registry::{ModuleDecl, Registry};
use crate::snapshot::Snapshot;
use crate::stats::Stats;
use crate::transport::{Restored, Subscription, Transport};
use crate::value::Value;
use std::sync::Arc;
use std::time::Duration;

pub use proclaim_runtime::QUERY_TYPE;

/// The type an expert posts `true` on when it could not decide `atom` within its limits (and
/// answered it false), and `false` on once it decides it again: how a page, a log or a machine
/// tells a false answer from an undecided one without a third truth value on the wire.
pub fn undecided_type(atom: &str) -> String {
    format!("{atom}Undecided")
}

/// How a query ended.
#[derive(Clone, Debug, PartialEq)]
pub enum QueryOutcome {
    /// An expert proclaimed the atom.
    Answered {
        value: bool,
        by: Arc<str>,
        after: Duration,
    },
    /// No answer in time: the label counts as false.
    TimedOut,
    /// No registered module answers the atom: false at once, never a hang.
    NoExpert,
}

impl QueryOutcome {
    /// The label's truth: the answer, or false when there was none.
    pub fn truth(&self) -> bool {
        matches!(self, QueryOutcome::Answered { value: true, .. })
    }
}

/// A clonable handle on a whiteboard.
#[derive(Clone)]
pub struct Whiteboard {
    transport: Arc<dyn Transport>,
    /// The (module, atom) pairs already warned of asking what nobody answers: a machine asks
    /// at every ring, and one warning says it.
    unanswered: Arc<parking_lot::Mutex<rustc_hash::FxHashSet<(String, String)>>>,
}

impl Whiteboard {
    /// A new in-process whiteboard.
    pub fn local() -> Whiteboard {
        Whiteboard::new(Arc::new(LocalBoard::new()))
    }

    pub fn new(transport: Arc<dyn Transport>) -> Whiteboard {
        let board = Whiteboard {
            transport,
            unanswered: Arc::default(),
        };
        board.declare(QUERY_TYPE, Kind::Data);
        board
    }

    pub fn declare(&self, ty: &str, kind: Kind) {
        self.transport.declare(ty, kind);
    }

    /// How a type's messages are kept.
    pub fn kind(&self, ty: &str) -> Kind {
        self.transport.kind(ty)
    }

    pub fn post(&self, module: &str, ty: &str, value: impl Into<Value>) -> Message {
        self.transport.post(module, ty, value.into())
    }

    /// Posts with a priority: what a machine of a subsumption layer posts (`Suppressor`
    /// decides beforehand whether it may be seen at all).
    pub fn post_ranked(
        &self,
        module: &str,
        ty: &str,
        value: impl Into<Value>,
        priority: u32,
    ) -> Message {
        self.transport
            .post_ranked(module, ty, value.into(), priority)
    }

    pub fn latest(&self, ty: &str) -> Option<Message> {
        self.transport.latest(ty)
    }

    /// The current value of a state used as a proposition (truthiness rule), if ever posted.
    pub fn truth(&self, ty: &str) -> Option<bool> {
        self.transport.latest(ty).map(|m| m.value.truthy())
    }

    pub async fn wait_for(&self, ty: &str, after: u64, timeout: Duration) -> Option<Message> {
        self.transport.wait_for(ty, after, timeout).await
    }

    /// The data message nearest `time` on either side.
    pub fn nearest(&self, ty: &str, time: Duration) -> Option<Message> {
        self.transport.nearest(ty, time, std::cmp::Ordering::Equal)
    }

    /// The nearest data message at or after `time`.
    pub fn nearest_not_older(&self, ty: &str, time: Duration) -> Option<Message> {
        self.transport
            .nearest(ty, time, std::cmp::Ordering::Greater)
    }

    /// The nearest data message at or before `time`.
    pub fn nearest_not_newer(&self, ty: &str, time: Duration) -> Option<Message> {
        self.transport.nearest(ty, time, std::cmp::Ordering::Less)
    }

    /// Messages whose type matches `pattern` (`LEDS`, `*Received`, `*`).
    pub fn subscribe(&self, pattern: &str) -> Subscription {
        self.transport.subscribe(Pattern::parse(pattern))
    }

    pub fn subscribe_pattern(&self, pattern: Pattern) -> Subscription {
        self.transport.subscribe(pattern)
    }

    pub fn register(&self, decl: ModuleDecl) {
        self.transport.register(decl);
    }

    pub fn registry(&self) -> Registry {
        self.transport.registry()
    }

    pub fn stats(&self) -> Stats {
        self.transport.stats()
    }

    /// The whole board as it is now, in O(1); reading it never holds the board up.
    pub fn snapshot(&self) -> Snapshot {
        self.transport.snapshot()
    }

    pub fn now(&self) -> Duration {
        self.transport.now()
    }

    /// Takes `image` up (a run resumed from a checkpoint) before anything is posted: whole in
    /// process; a shared board keeps what the others hold ([`Transport::restore`]).
    pub fn restore(&self, image: &BoardImage) -> Result<Restored, String> {
        self.transport.restore(image)
    }

    /// Asks for a proclamation of `atom` and waits at most `timeout` for it. A query for an atom
    /// no registered module answers ends at once with [`QueryOutcome::NoExpert`]; a timeout is
    /// a warning, and the label counts as false.
    pub async fn query(&self, module: &str, atom: &str, timeout: Duration) -> QueryOutcome {
        if !self.transport.is_answered(atom) {
            self.transport.count_query(false, true);
            let first = self
                .unanswered
                .lock()
                .insert((module.to_string(), atom.to_string()));
            if first {
                tracing::warn!(module, atom, "query for an atom no module answers");
            } else {
                tracing::debug!(module, atom, "query for an atom no module answers");
            }
            return QueryOutcome::NoExpert;
        }
        let asked = self.post(module, QUERY_TYPE, atom);
        let answer = self.wait_for(atom, asked.seq, timeout).await;
        self.transport.count_query(answer.is_none(), false);
        match answer {
            Some(m) => {
                let value = m.value.truthy();
                tracing::debug!(module, atom, value, by = %m.module, "query answered");
                QueryOutcome::Answered {
                    value,
                    after: m.time.saturating_sub(asked.time),
                    by: m.module,
                }
            }
            None => {
                tracing::warn!(
                    module,
                    atom,
                    ?timeout,
                    "query timed out; the label counts as false"
                );
                QueryOutcome::TimedOut
            }
        }
    }
}
