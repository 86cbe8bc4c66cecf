//! The one integration-test binary of the reasoner: the worked cases of cdl.md §6 and a theory's diagnostics.

mod diagnostics;
mod reasoner;
