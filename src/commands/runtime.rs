//! The async runtime of every command that needs one: one builder, one failure.

use crate::failure::Failure;
use tokio::runtime::{Builder, Runtime};

/// How a command's tasks are driven.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shape {
    /// One thread: a sensor wrapper or a simulator alone.
    OneThread,
    /// Two worker threads: a behaviour, a board across processes (the machines here have two
    /// cores).
    TwoThreads,
    /// One thread and tokio's paused clock: when every task waits, time jumps to the next timer,
    /// so a minute of behaviour passes at once and in the same order every time.
    VirtualClock,
}

pub fn runtime(shape: Shape) -> Result<Runtime, Failure> {
    match shape {
        Shape::OneThread => Builder::new_current_thread().enable_all().build(),
        Shape::TwoThreads => Builder::new_multi_thread()
            .worker_threads(2)
            .enable_all()
            .build(),
        Shape::VirtualClock => Builder::new_current_thread()
            .enable_all()
            .start_paused(true)
            .build(),
    }
    .map_err(Failure::Runtime)
}
