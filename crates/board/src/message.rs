//! A message on the whiteboard and the three kinds of message type.

use crate::value::Value;
use std::sync::Arc;
use std::time::Duration;

/// How the whiteboard keeps the messages of one type.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Kind {
    /// One current value; a new post replaces it; reading does not consume it.
    State,
    /// Consumed by its first reader (commands such as `Placer: On`, `reload`).
    Signal,
    /// A bounded, time-stamped history.
    Data,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Message {
    /// The message type, such as `LEDS`, `readyReceived` or `Placer`.
    pub ty: Arc<str>,
    pub value: Value,
    /// The module that posted it.
    pub module: Arc<str>,
    /// Board-wide, strictly increasing from 1.
    pub seq: u64,
    /// Since the board was created (on tokio's clock, so tests can pause it).
    pub time: Duration,
    /// The poster's rank for subsumption (`suppress.rs`): 0, the default, for every poster
    /// that gives none; it matters only for a type declared suppressed.
    pub priority: u32,
}
