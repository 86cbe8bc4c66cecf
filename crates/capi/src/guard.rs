//! Stops panics at the boundary: unwinding into C is undefined behaviour, so every exported
//! function runs its body through [`guarded`].

use std::panic::{catch_unwind, AssertUnwindSafe};

/// Runs `body`, or returns `on_panic` when it panics. The panic message still goes to the panic
/// hook (stderr by default), which is where a bug report starts.
pub(crate) fn guarded<T>(on_panic: T, body: impl FnOnce() -> T) -> T {
    guarded_else(|| on_panic, body)
}

/// [`guarded`] whose answer to a panic is made only when there is one: an answer that owns
/// memory (an error for C to free) made up front would be lost whenever `body` returns.
pub(crate) fn guarded_else<T>(on_panic: impl FnOnce() -> T, body: impl FnOnce() -> T) -> T {
    // Unwind safety: a session that panicked is marked and refuses later calls
    // (`session::with_session`); theories are immutable once built.
    catch_unwind(AssertUnwindSafe(body)).unwrap_or_else(|_| on_panic())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ProclaimStatus;

    #[test]
    fn a_panic_becomes_the_fallback_and_an_answer_passes_through() {
        assert_eq!(
            guarded(ProclaimStatus::Panic, || panic!("a bug in the reasoner")),
            ProclaimStatus::Panic
        );
        assert_eq!(
            guarded(ProclaimStatus::Panic, || ProclaimStatus::Ok),
            ProclaimStatus::Ok
        );
    }
}
