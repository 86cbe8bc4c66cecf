//! Why the last call on a thread failed, in words (`proclaim_last_error_message`): a status says
//! "unknown atom", the detail says which atom and the nearest one the theory has.

use crate::status::ProclaimStatus;
use std::cell::RefCell;
use std::ffi::{c_char, CString};

thread_local! {
    /// The detail a call under way gave for its failure, until the call returns.
    static PENDING: RefCell<Option<String>> = const { RefCell::new(None) };
    /// The detail of this thread's last failed call, NUL-terminated for C.
    static LAST: RefCell<CString> = RefCell::new(CString::default());
}

/// Fails with `status`, saying why; the call's answer passes through [`reported`] on its way out.
pub(crate) fn fail(status: ProclaimStatus, why: impl Into<String>) -> ProclaimStatus {
    PENDING.with(|pending| *pending.borrow_mut() = Some(why.into()));
    status
}

/// A call's answer on its way to C: a failure's detail (or, when the call gave none, the
/// status's own description) becomes this thread's last error message; success leaves the
/// message of the last failure as it was.
pub(crate) fn reported(status: ProclaimStatus) -> ProclaimStatus {
    // Only a failing call gives a detail, so a success has none to clear: it touches nothing,
    // which keeps the thread-local off every answered call's path.
    if status != ProclaimStatus::Ok {
        let why = PENDING.with(|pending| pending.borrow_mut().take());
        set(&why.unwrap_or_else(|| status.description().to_string()));
    }
    status
}

/// Sets this thread's last error message (a load's rendered errors, a refused session).
pub(crate) fn set(message: &str) {
    let message = CString::new(message.replace('\0', "\u{FFFD}")).unwrap_or_default();
    LAST.with(|last| *last.borrow_mut() = message);
}

/// Why the last call on this thread that failed (returned a status other than `OK`, or null
/// for a handle) did: "`cok` is no atom of the theory; did you mean `cook`?", "the algorithm is
/// 42, which is none of PROCLAIM_ALGORITHM_MU (0) to _DELTA (4)". Empty before any call failed.
/// Calls that succeed leave it as it was. The string belongs to the library and holds until the
/// next failing call on the same thread: copy it to keep it; do not free it.
#[no_mangle]
pub extern "C" fn proclaim_last_error_message() -> *const c_char {
    // The string's buffer moves only when the message is replaced, by a later failure.
    LAST.with(|last| last.borrow().as_ptr())
}
