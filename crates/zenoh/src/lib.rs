//! The whiteboard across processes and robots, over Zenoh 1.9 (TCP, peer to peer, no broker):
//! the only crate that depends on Zenoh, built into `proclaim` by its `zenoh` feature.
//!
//! No process holds the board: every process keeps its own replica and puts what it posts on the
//! type's own key, `proclaim/<board>/<type>`, the value as plain JSON and the rest in Zenoh's
//! attachment (docs/whiteboard-wire.md), so any Zenoh binding can read or post a type. A late
//! joiner asks the others for the values they own; a process that dies is noticed by its
//! liveliness token and its types turn stale. A signal is consumed once, in the process that
//! declared it a signal first and is alive. One process listens on an explicit endpoint
//! (loopback unless told otherwise), the others connect to it and meet each other through
//! Zenoh's gossip; with `--scout`, they find each other by multicast scouting instead. TLS and
//! access control come from Zenoh's own configuration file. A robot of a team also puts the
//! types its team shares where its teammates hear them (`board/team.rs`).

mod board;
mod error;
mod keys;
mod probe;
mod session;
mod threads;
mod wire;

pub use board::{post_once, stale_type, team_whiteboard, whiteboard, Team};
pub use error::NetworkError;
pub use probe::{bare_receive, ping, BareSender};
pub use session::{Role, Settings, DEFAULT_LEASE, SHORTEST_LEASE};
pub use threads::{prefer_few_threads, FEW_THREADS};
