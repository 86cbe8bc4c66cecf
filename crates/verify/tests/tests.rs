//! The one integration-test binary of the verifier: its verdicts, liveness, reductions, conformance with the runner and agreement with SPIN.

mod common {
    pub mod families;
    pub mod odometer;
    pub mod random_behaviour;
}
mod conformance;
mod differential;
mod free_values;
mod liveness;
mod reductions;
mod spin;
mod verify;
