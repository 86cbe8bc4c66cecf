//! The one integration-test binary of theories compiled to C: reduced diagrams, random and shipped theories against the reasoner, and refusals.

mod canonical;
mod common;
mod random;
mod refusals;
mod shipped;
