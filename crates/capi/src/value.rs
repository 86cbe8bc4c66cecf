//! An input's value as a number C can pass: true, false or unknown.

use crate::detail::fail;
use crate::status::ProclaimStatus;
use std::ffi::c_int;

/// An input value. The header declares the functions' parameter as this enum; the library
/// receives it as an `int` ([`ValueArgument`]), so a number outside this list is an error the
/// call reports rather than undefined behaviour.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ProclaimValue {
    False = 0,
    True = 1,
    /// Not known (yet): as if the sensor had never reported.
    Unknown = 2,
}

/// A [`ProclaimValue`] as C passes it: any `int`, checked by [`ValueArgument::value`]. cbindgen
/// writes it as `ProclaimValue` (`[export.rename]` in cbindgen.toml).
///
/// cbindgen:ignore
#[repr(transparent)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ValueArgument(pub c_int);

impl ValueArgument {
    /// The value (`None` inside for unknown), or `BAD_ARGUMENT` saying what number came instead.
    pub(crate) fn value(self) -> Result<Option<bool>, ProclaimStatus> {
        ProclaimValue::from_code(self.0).ok_or_else(|| {
            fail(
                ProclaimStatus::BadArgument,
                format!(
                    "the value is {}, which is none of PROCLAIM_VALUE_FALSE (0), _TRUE (1), \
                     _UNKNOWN (2)",
                    self.0
                ),
            )
        })
    }
}

impl From<ProclaimValue> for ValueArgument {
    fn from(value: ProclaimValue) -> ValueArgument {
        ValueArgument(value as c_int)
    }
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
