//! The one integration-test binary of the runner: machines on the whiteboard, the activity language, and what one ringlet reads.

mod activities;
mod ringlet_reads;
mod runner;
