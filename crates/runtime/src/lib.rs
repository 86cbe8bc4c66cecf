//! What a behaviour compiled to Rust runs on, and what it shares with the interpreter: the
//! trace's events and the recording's ringlets (`event.rs`), subsumption (`suppress.rs`), the
//! impersonator's script and durations (`script.rs`, `lines.rs`), the world a compiled
//! behaviour's machines run in (`world.rs`), what their printed code calls (`calls.rs`) over the
//! behaviour's tables (`tables.rs`), the round schedule (`schedule.rs`) and the program around it
//! (`host.rs`).
//!
//! `proclaim compile --target rust` copies this crate's files into the project it writes, so a
//! compiled behaviour builds with crates from crates.io alone; the interpreter's crates use the
//! same files, so both report one trace and read one script by construction. Only `host.rs`, a
//! program's `main`, does I/O (the command line, files, the clock), and `source.rs`, which
//! reads a file whole within a bound for every reader above.

pub mod calls;
pub mod event;
pub mod host;
mod lines;
mod schedule;
mod script;
mod source;
pub mod suppress;
pub mod tables;
pub mod world;

pub use event::{Answerer, Event, Ringlet};
pub use lines::{code_lines, parse_duration, LineError, LineErrors, LONGEST_DURATION};
pub use script::{parse_script, Script, ScriptStep, ScriptValue, When};
pub use source::{read_source, read_within, too_large, Unread, MAX_SOURCE_BYTES};
pub use suppress::{Holding, Ranked, Suppressor, Visibility};
pub use tables::Tables;

/// The message type of a query; its content is the atom (the original's name).
pub const QUERY_TYPE: &str = "updateProofsForOutput";

/// Every source file of this crate, as a generated project carries it: path and text.
pub const SOURCES: &[(&str, &str)] = &[
    ("src/lib.rs", include_str!("lib.rs")),
    ("src/calls.rs", include_str!("calls.rs")),
    ("src/event.rs", include_str!("event.rs")),
    ("src/host.rs", include_str!("host.rs")),
    ("src/lines.rs", include_str!("lines.rs")),
    ("src/schedule.rs", include_str!("schedule.rs")),
    ("src/script.rs", include_str!("script.rs")),
    ("src/source.rs", include_str!("source.rs")),
    ("src/suppress.rs", include_str!("suppress.rs")),
    ("src/tables.rs", include_str!("tables.rs")),
    ("src/world.rs", include_str!("world.rs")),
];
