//! Strings handed to C: allocated here, freed only by [`proclaim_string_free`].

use std::ffi::{c_char, CString};

/// `text` as a NUL-terminated string the caller owns. A NUL inside (a theory text may hold one,
/// and messages quote the text) becomes U+FFFD, since C would take it for the end.
pub(crate) fn owned(text: &str) -> *mut c_char {
    let bytes = if text.contains('\0') {
        text.replace('\0', "\u{FFFD}").into_bytes()
    } else {
        text.as_bytes().to_vec()
    };
    CString::new(bytes).expect("NULs were replaced").into_raw()
}

/// Frees a string this library returned (an explanation). Null is ignored. A string is plain
/// memory C reads directly, not a handle: freeing it twice is undefined, as with `free()`.
///
/// # Safety
/// `text` is null or a string returned by this library and not freed yet.
#[no_mangle]
pub unsafe extern "C" fn proclaim_string_free(text: *mut c_char) {
    if !text.is_null() {
        drop(CString::from_raw(text));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::ffi::CStr;

    #[test]
    fn a_nul_inside_does_not_cut_the_string() {
        let text = owned("a\0b");
        assert_eq!(
            unsafe { CStr::from_ptr(text) }.to_str().unwrap(),
            "a\u{FFFD}b"
        );
        unsafe { proclaim_string_free(text) };
        unsafe { proclaim_string_free(std::ptr::null_mut()) };
    }
}
