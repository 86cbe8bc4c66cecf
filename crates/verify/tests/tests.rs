//! The one integration-test binary of the verifier: its verdicts, liveness, reductions, conformance with the runner and agreement with SPIN.

mod common {
    pub mod allocated;
    pub mod families;
    pub mod odometer;
    pub mod random_behaviour;
}
/// Every allocation of this test process is counted (`common::allocated`), so a test can hold
/// `--max-memory` to what the heap really grew by. nextest runs each test in its own process.
#[global_allocator]
static ALLOCATED: common::allocated::Counting = common::allocated::Counting;

mod checkpoints;
mod conformance;
mod differential;
mod followed;
mod free_values;
mod liveness;
mod race;
mod reductions;
mod spin;
mod verify;
