//! The boundary between modules and where messages travel: in-process here, over a network
//! later, without touching the modules.

use crate::image::BoardImage;
use crate::message::{Kind, Message};
use crate::pattern::Pattern;
use crate::registry::{ModuleDecl, Registry};
use crate::snapshot::Snapshot;
use crate::stats::Stats;
use crate::value::Value;
use std::future::Future;
use std::pin::Pin;
use std::time::Duration;
use tokio::sync::mpsc;

pub type BoxFuture<'a, T> = Pin<Box<dyn Future<Output = T> + Send + 'a>>;

/// A stream of messages matching a pattern. Dropping it unsubscribes.
pub struct Subscription {
    pub(crate) rx: mpsc::Receiver<Message>,
}

impl Subscription {
    pub fn new(rx: mpsc::Receiver<Message>) -> Subscription {
        Subscription { rx }
    }

    /// The next message, or `None` when the board is gone.
    pub async fn next(&mut self) -> Option<Message> {
        self.rx.recv().await
    }

    /// A message already waiting, without blocking.
    pub fn try_next(&mut self) -> Option<Message> {
        self.rx.try_recv().ok()
    }
}

/// What a whiteboard transport does. Every method is cheap and never blocks a thread; the waits
/// are futures.
pub trait Transport: Send + Sync + 'static {
    /// Declares how a type's messages are kept (types are states until declared otherwise).
    fn declare(&self, ty: &str, kind: Kind);
    fn kind(&self, ty: &str) -> Kind;
    /// Posts a message with a priority (`Message::priority`); returns it with its sequence
    /// number and time.
    fn post_ranked(&self, module: &str, ty: &str, value: Value, priority: u32) -> Message;
    /// Posts a message at the default priority, 0.
    fn post(&self, module: &str, ty: &str, value: Value) -> Message {
        self.post_ranked(module, ty, value, 0)
    }
    /// The newest message of a type; for a signal, takes (consumes) the oldest unread one.
    fn latest(&self, ty: &str) -> Option<Message>;
    /// The first message of `ty` with a sequence number above `after` (consuming it if a
    /// signal), waiting up to `timeout` for one to be posted.
    fn wait_for(&self, ty: &str, after: u64, timeout: Duration) -> BoxFuture<'_, Option<Message>>;
    /// Data history reads: the message nearest `time`, with `Ordering::Greater` meaning not older
    /// than it, `Less` not newer, `Equal` either side.
    fn nearest(&self, ty: &str, time: Duration, side: std::cmp::Ordering) -> Option<Message>;
    /// Every message matching `pattern` from now on (monitors: signals are not consumed).
    fn subscribe(&self, pattern: Pattern) -> Subscription;
    fn register(&self, decl: ModuleDecl);
    fn registry(&self) -> Registry;
    /// Whether any registered module answers `atom` (asked on every query: no copying).
    fn is_answered(&self, atom: &str) -> bool;
    fn stats(&self) -> Stats;
    /// Counts a query and its outcome (the protocol lives above the transport).
    fn count_query(&self, timed_out: bool, unanswerable: bool);
    /// The board's clock.
    fn now(&self) -> Duration;
    /// The whole board as it is now, in O(1) (a persistent table shared with the live one).
    fn snapshot(&self) -> Snapshot;
    /// Takes `image` up (a run resumed from a checkpoint), before anything is posted: an
    /// in-process board becomes it whole (messages, sequence numbers, clock and counts); a
    /// board shared with other processes keeps what they hold, and only numbers on after the
    /// image's last message.
    fn restore(&self, image: &BoardImage) -> Result<Restored, String> {
        let _ = image;
        Err("this board cannot take up a checkpoint".into())
    }
}

/// What a board did with a checkpoint's image ([`Transport::restore`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Restored {
    /// The board is the image.
    Whole,
    /// The board is shared: what is current is what the other processes hold; this process's
    /// postings are numbered after the image's.
    Numbering,
}
