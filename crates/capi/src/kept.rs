//! The headers of freed handles, held by the library for good: a freed handle answers
//! `DEAD_HANDLE` because its header is never deallocated nor reused, and listing every such
//! header here keeps it reachable, so a leak checker tells memory kept on purpose ("still
//! reachable") from memory lost ("definitely lost"), which the C tests require to be none.

use std::sync::{Mutex, PoisonError};

/// Addresses of freed handles' headers, in the order freed.
static KEPT: Mutex<Vec<usize>> = Mutex::new(Vec::new());

/// Keeps the header at `header` reachable for the rest of the process; called once per handle,
/// by the free that marked it dead.
pub(crate) fn keep<T>(header: *const T) {
    KEPT.lock()
        .unwrap_or_else(PoisonError::into_inner)
        .push(header as usize);
}
