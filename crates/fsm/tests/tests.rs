//! The one integration-test binary of machine files: labels, the T/A and Qfsm importers, the corpus, and edits in place.

mod chart;
mod edit;
mod interface;
mod machines;
mod scxml;
