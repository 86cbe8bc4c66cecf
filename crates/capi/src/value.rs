//! An input's value as a number C can pass: true, false or unknown.

use std::ffi::c_int;

/// An input value. Functions take it as an `int`, so that a number outside this list is an error
/// the call reports rather than undefined behaviour.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ProclaimValue {
    False = 0,
    True = 1,
    /// Not known (yet): as if the sensor had never reported.
    Unknown = 2,
}

impl ProclaimValue {
    /// The value a number from C stands for (`None` inside for unknown), if any.
    pub fn from_code(code: c_int) -> Option<Option<bool>> {
        match code {
            0 => Some(Some(false)),
            1 => Some(Some(true)),
            2 => Some(None),
            _ => None,
        }
    }
}
