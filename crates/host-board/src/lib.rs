//! The whiteboard a behaviour compiled to Rust runs on when asked (`proclaim compile --target
//! rust --whiteboard`): the monitor's page (`--monitor`), or a whiteboard shared over Zenoh with
//! other processes and robots (`--listen`, `--connect`, with the `network` feature). It is what
//! pulls tokio, the monitor and this repository's crates into a compiled program; a program
//! compiled without it runs alone on its script.
//!
//! Every message the interpreter's run would post is posted here as the run goes, the page
//! draws the machines from the trace's events, and what another module posts (the page, another
//! process) comes into the run as a script's posting does. Ctrl-C ends the run as it ends
//! `proclaim run`. The program's host (`proclaim_runtime::host`) drives it through
//! [`HostBoard`].

mod hear;
mod live;
mod place;

pub use live::LiveBoard;
pub use proclaim_monitor::Chart;
use proclaim_runtime::host::{HostBoard, Place};

/// What a program calls before it starts any thread, as Zenoh requires.
pub fn before_threads() {
    #[cfg(feature = "network")]
    proclaim_zenoh::prefer_few_threads();
}

/// Opens the whiteboard `place` says (the host's `OpenBoard`): `name` is the behaviour's,
/// `ours` its own modules (whose postings are not heard back), and `charts` draws its machines
/// when a page is served.
pub fn open(
    place: &Place,
    name: &'static str,
    ours: Vec<&'static str>,
    charts: impl FnOnce() -> Vec<Chart>,
) -> Result<Box<dyn HostBoard>, String> {
    Ok(Box::new(LiveBoard::open(place, name, ours, charts)?))
}
