//! The meaning of a machine's ringlet, of an activity's statements and of an expression, written
//! once (`docs/spec/behaviour.md` §3.1, §4): [`ringlet`] says what a ringlet runs and in which
//! order, [`walk`] how an activity's statements are walked, [`read`] how a back end that does
//! not run them meets each kind, [`evaluate`] how an expression is, with [`arith`]'s C
//! arithmetic and [`builtin`]'s calls. The runner and the checker run them; the Promela writer
//! and the code generators print what they say. No I/O, no async.

pub mod arith;
pub mod builtin;
pub mod evaluate;
pub mod read;
pub mod ringlet;
pub mod walk;

pub use evaluate::Evaluate;
pub use read::{read_statement, StatementReader};
pub use ringlet::{Arm, Arms, Next, RingletPlan, RingletRun};
pub use walk::{walk_to_end, Effects, Walk, LOOP_LIMIT};
