//! The one integration-test binary of the compile crate: reduced diagrams, random and shipped theories against the reasoner, refusals, and the C runtime compiled alone.

mod canonical;
mod common;
mod random;
mod refusals;
mod runtime_c;
mod shipped;
