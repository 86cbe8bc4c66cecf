//! A proving session behind an opaque handle: input values and cached answers.

use crate::guard::guarded;
use crate::names;
use crate::status::ProclaimStatus;
use crate::theory::ProclaimTheory;
use crate::value::ProclaimValue;
use proclaim_cdl::{SearchLimits, Session};
use std::ffi::{c_char, c_int};

/// A session: every input unknown until set. Not for two threads at once.
pub struct ProclaimSession {
    session: Session,
    /// Its theory's identity, which the handles it accepts carry.
    tag: u32,
    /// Set when a call panicked: the session may be half-updated, so it answers nothing more.
    poisoned: bool,
}

/// Runs `body` on the session behind `session`, with the checks every session call makes: null
/// is a bad argument, a poisoned session answers `Panic`, and a panic poisons it.
///
/// # Safety
/// `session` is null or a live session from [`proclaim_session_new`].
pub(crate) unsafe fn with_session(
    session: *mut ProclaimSession,
    body: impl FnOnce(&mut Session) -> ProclaimStatus,
) -> ProclaimStatus {
    with_session_of(session, |session, _tag| body(session))
}

/// [`with_session`], telling `body` the identity of the session's theory too.
///
/// # Safety
/// `session` is null or a live session from [`proclaim_session_new`].
pub(crate) unsafe fn with_session_of(
    session: *mut ProclaimSession,
    body: impl FnOnce(&mut Session, u32) -> ProclaimStatus,
) -> ProclaimStatus {
    let Some(handle) = session.as_mut() else {
        return ProclaimStatus::BadArgument;
    };
    if handle.poisoned {
        return ProclaimStatus::Panic;
    }
    let tag = handle.tag;
    let status = guarded(ProclaimStatus::Panic, || body(&mut handle.session, tag));
    if status == ProclaimStatus::Panic {
        handle.poisoned = true;
    }
    status
}

/// A new session over `theory`, every input unknown; null when `theory` is null. The session
/// holds its own reference to the theory. Freed by [`proclaim_session_free`].
///
/// # Safety
/// `theory` is null or a live theory from `proclaim_theory_load`.
#[no_mangle]
pub unsafe extern "C" fn proclaim_session_new(
    theory: *const ProclaimTheory,
) -> *mut ProclaimSession {
    let Some(theory) = theory.as_ref() else {
        return std::ptr::null_mut();
    };
    guarded(std::ptr::null_mut(), || {
        Box::into_raw(Box::new(ProclaimSession {
            session: Session::new(theory.engine.clone()),
            tag: theory.tag,
            poisoned: false,
        }))
    })
}

/// Sets an input atom to a `ProclaimValue` (`PROCLAIM_VALUE_TRUE`, `_FALSE`, `_UNKNOWN`); only
/// what depends on it is re-proved, when next asked. Setting one atom of an input group
/// (`input{a, b, c}`) true sets the others false. Returns `UNKNOWN_ATOM`, `NOT_AN_INPUT` (the
/// theory declares its inputs and this is not one), `INPUT_CONFLICT` (the session is left as it
/// was), or `BAD_ARGUMENT`.
///
/// # Safety
/// `session` is null or a live session; `atom` is null or a NUL-terminated string.
#[no_mangle]
pub unsafe extern "C" fn proclaim_session_set(
    session: *mut ProclaimSession,
    atom: *const c_char,
    value: c_int,
) -> ProclaimStatus {
    with_session(session, |session| {
        let Some(value) = ProclaimValue::from_code(value) else {
            return ProclaimStatus::BadArgument;
        };
        let atom = match names::input(session, atom) {
            Ok(atom) => atom,
            Err(status) => return status,
        };
        match session.set_input(atom, value) {
            Ok(()) => ProclaimStatus::Ok,
            Err(_conflict) => ProclaimStatus::InputConflict,
        }
    })
}

/// Sets how many goals the search may expand inside one attack cycle before it gives up and
/// answers `PROCLAIM_STATUS_UNDECIDED` (10,000,000 unless set; 0 is a bad argument).
///
/// # Safety
/// `session` is null or a live session.
#[no_mangle]
pub unsafe extern "C" fn proclaim_session_set_budget(
    session: *mut ProclaimSession,
    steps: u64,
) -> ProclaimStatus {
    with_session(session, |session| {
        if steps == 0 {
            return ProclaimStatus::BadArgument;
        }
        session.set_limits(SearchLimits {
            steps,
            ..session.limits()
        });
        ProclaimStatus::Ok
    })
}

/// Frees a session. Null is ignored.
///
/// # Safety
/// `session` is null or a session returned by this library and not freed yet.
#[no_mangle]
pub unsafe extern "C" fn proclaim_session_free(session: *mut ProclaimSession) {
    if !session.is_null() {
        drop(Box::from_raw(session));
    }
}
