//! Why a theory did not load, as a struct C reads and frees with [`proclaim_error_free`].

use crate::guard::guarded;
use crate::status::ProclaimStatus;
use crate::text_to_c::owned;
use std::ffi::{c_char, CString};
use std::sync::atomic::{AtomicBool, Ordering};

/// A theory that did not load: where its first error is, and every error rendered as
/// `proclaim check` prints it (file, line, the line itself with a caret, a hint).
#[repr(C)]
#[derive(Debug)]
pub struct ProclaimError {
    /// The name the text was loaded under ("theory" unless given).
    pub file: *mut c_char,
    /// 1-based line of the first error; 0 when the error has no place (a null pointer).
    pub line: u32,
    /// 1-based column (in characters) of the first error; 0 when it has no place.
    pub column: u32,
    /// Every error, rendered; several lines.
    pub message: *mut c_char,
}

/// An error with its mark. `error` comes first (and the struct is `repr(C)`) so a pointer to the
/// whole is a pointer to the error C sees. Never deallocated: [`proclaim_error_free`] frees the
/// strings, empties `error` and clears `live`, so that a second free says `DEAD_HANDLE`.
#[repr(C)]
struct Marked {
    error: ProclaimError,
    live: AtomicBool,
}

impl ProclaimError {
    /// Deallocates an error that never reached C (the caller did not ask for it): with no
    /// pointer to it outside, nothing can use it after, so no header need stay.
    ///
    /// # Safety
    /// `error` is from [`ProclaimError::boxed`] and no copy of the pointer is left anywhere.
    pub(crate) unsafe fn discard(error: *mut ProclaimError) {
        if !error.is_null() {
            let marked = Box::from_raw(error.cast::<Marked>());
            for text in [marked.error.file, marked.error.message] {
                if !text.is_null() {
                    drop(CString::from_raw(text));
                }
            }
        }
    }

    /// A new error on the heap, as C receives it.
    pub(crate) fn boxed(file: &str, place: Option<(usize, usize)>, message: &str) -> *mut Self {
        let (line, column) = place.unwrap_or((0, 0));
        let saturate = |n: usize| u32::try_from(n).unwrap_or(u32::MAX);
        Box::into_raw(Box::new(Marked {
            error: ProclaimError {
                file: owned(file),
                line: saturate(line),
                column: saturate(column),
                message: owned(message),
            },
            live: AtomicBool::new(true),
        }))
        .cast()
    }
}

/// Frees an error's strings: `OK`, or `DEAD_HANDLE` when it was freed already. Null is ignored
/// (`OK`), as with `free()`. The struct itself stays readable, emptied (null strings, line and
/// column 0), and is never reused.
///
/// # Safety
/// `error` is null or a pointer this library returned (freed or not), not read by another thread
/// during the free.
#[no_mangle]
pub unsafe extern "C" fn proclaim_error_free(error: *mut ProclaimError) -> ProclaimStatus {
    if error.is_null() {
        return ProclaimStatus::Ok;
    }
    let marked = error.cast::<Marked>();
    // Only `live` is borrowed before the swap: a second free racing this one touches nothing else.
    let live = &*std::ptr::addr_of!((*marked).live);
    if !live.swap(false, Ordering::AcqRel) {
        return crate::detail::reported(ProclaimStatus::DeadHandle);
    }
    crate::kept::keep(marked);
    let texts = [(*error).file, (*error).message];
    *error = ProclaimError {
        file: std::ptr::null_mut(),
        line: 0,
        column: 0,
        message: std::ptr::null_mut(),
    };
    guarded(ProclaimStatus::Panic, || {
        for text in texts.into_iter().filter(|t| !t.is_null()) {
            // SAFETY: both were made by `owned` (CString::into_raw); the swap above lets only
            // this free reach them.
            drop(unsafe { CString::from_raw(text) });
        }
        ProclaimStatus::Ok
    })
}
