//! Why a theory did not load, as a struct C reads and frees with [`proclaim_error_free`].

use crate::string::owned;
use std::ffi::{c_char, CString};

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

impl ProclaimError {
    /// A new error on the heap, as C receives it.
    pub(crate) fn boxed(file: &str, place: Option<(usize, usize)>, message: &str) -> *mut Self {
        let (line, column) = place.unwrap_or((0, 0));
        let saturate = |n: usize| u32::try_from(n).unwrap_or(u32::MAX);
        Box::into_raw(Box::new(ProclaimError {
            file: owned(file),
            line: saturate(line),
            column: saturate(column),
            message: owned(message),
        }))
    }
}

impl Drop for ProclaimError {
    fn drop(&mut self) {
        for text in [self.file, self.message] {
            if !text.is_null() {
                // SAFETY: both were made by `owned` (CString::into_raw) and are freed only here.
                drop(unsafe { CString::from_raw(text) });
            }
        }
    }
}

/// Frees an error and its strings. Null is ignored.
///
/// # Safety
/// `error` is null or an error returned by this library and not freed yet.
#[no_mangle]
pub unsafe extern "C" fn proclaim_error_free(error: *mut ProclaimError) {
    if !error.is_null() {
        drop(Box::from_raw(error));
    }
}
