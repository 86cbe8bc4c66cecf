//! The meaning of a machine's ringlet and of an activity's statements, written once
//! (`docs/spec/behaviour.md` §3.1, §4): [`ringlet`] says what a ringlet runs and in which order,
//! [`walk`] how an activity's statements are walked. The runner and the checker run them; the
//! Promela writer and the code generators print what they say. No I/O, no async.

pub mod ringlet;
pub mod walk;

pub use ringlet::{Arm, Next, RingletPlan, RingletRun};
pub use walk::{walk_to_end, Effects, Walk, LOOP_LIMIT};
