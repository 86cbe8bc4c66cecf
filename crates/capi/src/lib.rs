//! The reasoner behind a C ABI, for C and C++ programs (`include/proclaim.h`, generated from
//! these files by cbindgen; `tests/header.rs` fails when the checked-in header is stale).
//!
//! Everything is an opaque handle freed by its own function: a theory loaded from text
//! ([`proclaim_theory_load`]), a session over it ([`proclaim_session_new`]) whose inputs are set
//! ([`proclaim_session_set`]) and whose literals are proved ([`proclaim_session_prove`]) or
//! explained ([`proclaim_session_explain`]); in a loop, atoms and literals are looked up once
//! ([`proclaim_theory_input`], [`proclaim_theory_literal`]) and named by handle
//! ([`proclaim_session_set_input`], [`proclaim_session_prove_literal`]); a theory's truth table is one struct of arrays
//! ([`proclaim_theory_table`]). Loads ([`proclaim_theory_load`], `_load_named`,
//! [`proclaim_theory_load_file`]) and [`proclaim_session_new`] return a handle or null; every
//! other call returns a [`ProclaimStatus`], and [`proclaim_last_error_message`] says why the last
//! failing call on the thread failed (which atom, and the nearest the theory has). A null
//! pointer, text that is not UTF-8 or an out-of-range enum value is
//! `PROCLAIM_STATUS_BAD_ARGUMENT`, never undefined behaviour (the header declares algorithms and
//! values as enums; the library receives them as `int`s and checks them), and a panic inside the
//! reasoner is caught at the boundary and returned as `PROCLAIM_STATUS_PANIC` (the session it
//! happened in answers nothing afterwards).
//!
//! A theory is immutable and may be shared between threads; a session is used by one thread at a
//! time (a call while another thread's call runs on it answers `PROCLAIM_STATUS_BUSY`). A session
//! keeps its theory alive, so the theory may be freed first.
//!
//! A freed handle (theory, session, table, load error) is detectably dead: the pointer C holds is
//! a small header that is never deallocated nor reused, so every later call with it, and a second
//! free, answers `PROCLAIM_STATUS_DEAD_HANDLE` (a freed theory makes no session: null). The
//! library lists those headers (`kept.rs`), so a leak checker counts them still reachable, and
//! anything it counts lost is a leak. A free
//! racing a call on another thread is safe: the call runs with its own reference to the theory,
//! or the session's free answers `BUSY` and frees nothing. Strings (explanations) are plain
//! memory, freed once, as with `free()`.

mod algorithm;
mod detail;
mod error;
mod explain;
mod guard;
mod handles;
mod kept;
mod names;
mod prove;
mod session;
mod status;
mod table;
mod text_from_c;
mod text_to_c;
mod theory;
mod value;

pub use algorithm::{AlgorithmArgument, ProclaimAlgorithm};
pub use detail::proclaim_last_error_message;
pub use error::{proclaim_error_free, ProclaimError};
pub use explain::proclaim_session_explain;
pub use handles::{
    proclaim_session_prove_literal, proclaim_session_set_input, proclaim_theory_input,
    proclaim_theory_literal, ProclaimInput, ProclaimLiteral,
};
pub use prove::proclaim_session_prove;
pub use session::{
    proclaim_session_free, proclaim_session_new, proclaim_session_set, proclaim_session_set_budget,
    ProclaimSession,
};
pub use status::{proclaim_status_name, ProclaimStatus};
pub use table::{proclaim_table_free, proclaim_theory_table, ProclaimTable};
pub use text_to_c::proclaim_string_free;
pub use theory::{
    proclaim_theory_free, proclaim_theory_load, proclaim_theory_load_file,
    proclaim_theory_load_named, ProclaimTheory,
};
pub use value::{ProclaimValue, ValueArgument};
