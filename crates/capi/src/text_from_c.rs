//! Text from C: pointers that may be null and bytes that may not be UTF-8, both errors.

use std::ffi::{c_char, CStr};
use std::fmt;

/// Why text from C could not be read.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum BadText {
    Null,
    /// Not UTF-8; the bytes before this offset are.
    NotUtf8 {
        valid_up_to: usize,
    },
}

impl fmt::Display for BadText {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            BadText::Null => write!(f, "the text is a null pointer"),
            BadText::NotUtf8 { valid_up_to } => {
                write!(f, "the text is not UTF-8 (byte {valid_up_to} is not)")
            }
        }
    }
}

/// A NUL-terminated string.
///
/// # Safety
/// `text` is null or points to a NUL-terminated string that lives as long as `'a`.
pub(crate) unsafe fn nul_terminated<'a>(text: *const c_char) -> Result<&'a str, BadText> {
    if text.is_null() {
        return Err(BadText::Null);
    }
    utf8(CStr::from_ptr(text).to_bytes())
}

/// `len` bytes at `text` (no terminator needed; NUL bytes are part of the text).
///
/// # Safety
/// `text` is null or points to `len` readable bytes that live as long as `'a`.
pub(crate) unsafe fn sized<'a>(text: *const c_char, len: usize) -> Result<&'a str, BadText> {
    if text.is_null() {
        return Err(BadText::Null);
    }
    utf8(std::slice::from_raw_parts(text.cast::<u8>(), len))
}

fn utf8(bytes: &[u8]) -> Result<&str, BadText> {
    std::str::from_utf8(bytes).map_err(|e| BadText::NotUtf8 {
        valid_up_to: e.valid_up_to(),
    })
}
