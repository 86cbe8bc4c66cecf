//! A proving session behind an opaque handle: input values and cached answers, behind a small
//! header that outlives `proclaim_session_free` so that a freed session is detected, not used.

use crate::detail::{fail, reported};
use crate::guard::guarded;
use crate::names;
use crate::status::ProclaimStatus;
use crate::theory::{live_theory, ProclaimTheory};
use crate::value::ValueArgument;
use proclaim_cdl::{SearchLimits, Session};
use std::cell::UnsafeCell;
use std::ffi::c_char;
use std::sync::atomic::{AtomicU8, Ordering};

/// No call is running; the session may be taken.
const IDLE: u8 = 0;
/// A call is running on it (on some thread): another call or a free is refused with `BUSY`.
const BUSY: u8 = 1;
/// Freed: the session is gone and only this header is left.
const DEAD: u8 = 2;
/// A call panicked: the session may be half-updated, so it answers nothing more.
const POISONED: u8 = 3;

/// A session: every input unknown until set; for one thread at a time. The pointer C holds is a
/// small header that is never deallocated (`proclaim_session_free` drops the session and marks
/// the header dead), so that a freed session answers `DEAD_HANDLE` rather than being undefined
/// behaviour. Each call marks the header busy with one compare-and-swap and idle again with one
/// store: a call from a second thread meanwhile answers `BUSY` instead of racing.
pub struct ProclaimSession {
    state: AtomicU8,
    /// Its theory's identity, which the handles it accepts carry.
    tag: u32,
    /// The session; `None` once freed. Touched only by the call that moved `state` to `BUSY`, or
    /// by the free that moved it to `DEAD`.
    session: UnsafeCell<Option<Box<Session>>>,
}

/// Runs `body` on the session behind `session`, with the checks every session call makes: null
/// is a bad argument, a freed session is a dead handle, a session another call is running on is
/// busy, a poisoned session answers `Panic`, and a panic poisons it.
///
/// # Safety
/// `session` is null or from [`proclaim_session_new`] (freed or not).
pub(crate) unsafe fn with_session(
    session: *mut ProclaimSession,
    body: impl FnOnce(&mut Session) -> ProclaimStatus,
) -> ProclaimStatus {
    with_session_of(session, |session, _tag| body(session))
}

/// [`with_session`], telling `body` the identity of the session's theory too.
///
/// # Safety
/// `session` is null or from [`proclaim_session_new`] (freed or not).
#[inline]
pub(crate) unsafe fn with_session_of(
    session: *mut ProclaimSession,
    body: impl FnOnce(&mut Session, u32) -> ProclaimStatus,
) -> ProclaimStatus {
    let Some(handle) = session.as_ref() else {
        return reported(fail(ProclaimStatus::BadArgument, "the session is null"));
    };
    if let Err(state) =
        handle
            .state
            .compare_exchange(IDLE, BUSY, Ordering::Acquire, Ordering::Relaxed)
    {
        return reported(refusal(state));
    }
    // SAFETY: this call moved the state from IDLE to BUSY, so nothing else touches the session
    // until the store below; IDLE means it was not freed.
    let Some(inner) = (*handle.session.get()).as_deref_mut() else {
        handle.state.store(DEAD, Ordering::Release);
        return reported(ProclaimStatus::DeadHandle);
    };
    let tag = handle.tag;
    let status = guarded(ProclaimStatus::Panic, || body(inner, tag));
    let after = if status == ProclaimStatus::Panic {
        POISONED
    } else {
        IDLE
    };
    handle.state.store(after, Ordering::Release);
    reported(status)
}

/// What a call on a session in `state` (not `IDLE`) answers.
fn refusal(state: u8) -> ProclaimStatus {
    match state {
        BUSY => ProclaimStatus::Busy,
        DEAD => ProclaimStatus::DeadHandle,
        _ => ProclaimStatus::Panic,
    }
}

/// A new session over `theory`, every input unknown; null when `theory` is null or freed. The
/// session holds its own reference to the theory. Freed by [`proclaim_session_free`].
///
/// # Safety
/// `theory` is null or from `proclaim_theory_load` (freed or not).
#[no_mangle]
pub unsafe extern "C" fn proclaim_session_new(
    theory: *const ProclaimTheory,
) -> *mut ProclaimSession {
    let (engine, tag) = match live_theory(theory) {
        Ok(live) => live,
        Err(status) => {
            reported(status);
            return std::ptr::null_mut();
        }
    };
    guarded(std::ptr::null_mut(), || {
        Box::into_raw(Box::new(ProclaimSession {
            state: AtomicU8::new(IDLE),
            tag,
            session: UnsafeCell::new(Some(Box::new(Session::new(engine)))),
        }))
    })
}

/// Sets the input `atom` to `value`, a `ProclaimValue` (`PROCLAIM_VALUE_TRUE`, `_FALSE`,
/// `_UNKNOWN`); only what depends on it is re-proved, when next asked. Setting one atom of an
/// input group (`input{a, b, c}`) true sets the others false. Returns `UNKNOWN_ATOM`, `NOT_AN_INPUT` (the
/// theory declares its inputs and this is not one), `INPUT_CONFLICT` (the session is left as it
/// was), or `BAD_ARGUMENT`.
///
/// # Safety
/// `session` is null or from [`proclaim_session_new`] (freed or not);
/// `atom` is null or a NUL-terminated string.
#[no_mangle]
pub unsafe extern "C" fn proclaim_session_set(
    session: *mut ProclaimSession,
    atom: *const c_char,
    value: ValueArgument,
) -> ProclaimStatus {
    with_session(session, |session| {
        let value = match value.value() {
            Ok(value) => value,
            Err(status) => return status,
        };
        let atom = match names::input(session, atom) {
            Ok(atom) => atom,
            Err(status) => return status,
        };
        match session.set_input(atom, value) {
            Ok(()) => ProclaimStatus::Ok,
            Err(conflict) => fail(ProclaimStatus::InputConflict, conflict.to_string()),
        }
    })
}

/// Sets `steps`, how many goals the search may expand inside one attack cycle before it gives
/// up and answers `PROCLAIM_STATUS_UNDECIDED` (10,000,000 unless set; 0 is a bad argument).
///
/// # Safety
/// `session` is null or from [`proclaim_session_new`] (freed or not).
#[no_mangle]
pub unsafe extern "C" fn proclaim_session_set_budget(
    session: *mut ProclaimSession,
    steps: u64,
) -> ProclaimStatus {
    with_session(session, |session| {
        if steps == 0 {
            return fail(
                ProclaimStatus::BadArgument,
                "the budget is 0 steps; give one or more",
            );
        }
        session.set_limits(SearchLimits {
            steps,
            ..session.limits()
        });
        ProclaimStatus::Ok
    })
}

/// Frees a session: `OK`, or `DEAD_HANDLE` when it was freed already, or `BUSY` when a call on
/// another thread is running on it (nothing is freed; free it once that call has returned). Null
/// is ignored (`OK`), as with `free()`. A poisoned session is freed like any other.
///
/// What stays allocated is the handle's header (a few bytes: a state byte, the theory's
/// identity and a null pointer), so that later calls with the pointer say `DEAD_HANDLE`; it is
/// never reused, so no later session can be mistaken for this one.
///
/// # Safety
/// `session` is null or from [`proclaim_session_new`] (freed or not).
#[no_mangle]
pub unsafe extern "C" fn proclaim_session_free(session: *mut ProclaimSession) -> ProclaimStatus {
    let Some(handle) = session.as_ref() else {
        return ProclaimStatus::Ok;
    };
    let mut state = handle.state.load(Ordering::Acquire);
    loop {
        if state == BUSY || state == DEAD {
            return reported(refusal(state));
        }
        match handle
            .state
            .compare_exchange(state, DEAD, Ordering::AcqRel, Ordering::Acquire)
        {
            Ok(_) => break,
            Err(now) => state = now,
        }
    }
    // SAFETY: this free moved the state to DEAD, so no call touches the session again.
    let inner = (*handle.session.get()).take();
    crate::kept::keep(handle);
    guarded(ProclaimStatus::Panic, || {
        drop(inner);
        ProclaimStatus::Ok
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What a freed handle keeps for ever is its header: the session itself is behind a pointer.
    #[test]
    fn a_freed_handle_keeps_a_header_of_a_few_bytes() {
        assert!(std::mem::size_of::<ProclaimSession>() <= 16);
        assert!(std::mem::size_of::<ProclaimTheory>() <= 32);
    }
}
