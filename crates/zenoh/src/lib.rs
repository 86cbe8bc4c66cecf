//! The whiteboard across processes and robots, over Zenoh 1.9 (TCP, peer to peer, no broker):
//! the only crate that depends on Zenoh, built into `proclaim` by its `zenoh` feature.
//!
//! One process holds the board and listens on an explicit endpoint (loopback unless told
//! otherwise); others connect to it and keep a replica in step. Every semantic of the
//! in-process board holds across them: sequence numbers and states are the holder's, a signal is
//! consumed once (in the process that declared its type a signal), data histories and the
//! module registry are replicated, and queries and their timeouts run on the replica. Multicast
//! scouting is off; TLS and access control come from Zenoh's own configuration file.

mod board;
mod error;
mod probe;
mod session;
mod threads;
mod wire;

pub use board::whiteboard;
pub use error::NetworkError;
pub use probe::ping;
pub use session::{Role, Settings};
pub use threads::{prefer_few_threads, FEW_THREADS};
