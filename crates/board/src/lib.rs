//! The whiteboard (`docs/spec/behaviour.md` §1–2): every module talks through it and holds
//! no reference to another. Messages have a type, a value, the posting module, a sequence number
//! and a time; a type is a *state* (one current value), a *signal* (consumed by its first reader)
//! or *data* (a bounded time-stamped history). Waiters and subscribers are woken, never polling.
//!
//! [`Whiteboard`] is the handle modules hold; it talks to a [`Transport`]. [`LocalBoard`] is the
//! in-process transport every test runs against; a networked one plugs in behind the same trait.

mod image;
mod json;
mod local;
mod message;
mod pattern;
mod registry;
mod snapshot;
mod stats;
mod subscribers;

pub mod team;
mod transport;
mod value;
mod whiteboard;

pub use image::{nanos, BoardImage, KindName, MessageImage, TypeImage};
pub use local::{LocalBoard, Retention};
pub use message::{Kind, Message};
pub use pattern::Pattern;
pub use proclaim_runtime::{Ranked, Suppressor, Visibility};
pub use registry::{ModuleDecl, Registry};
pub use snapshot::{BoardRow, Snapshot};
pub use stats::Stats;
pub use transport::{BoxFuture, Restored, Subscription, Transport};
pub use value::Value;
pub use whiteboard::{undecided_type, QueryOutcome, Whiteboard, QUERY_TYPE};
