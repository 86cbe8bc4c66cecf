//! Asking whether an algorithm proves a literal.

use crate::algorithm::ProclaimAlgorithm;
use crate::names;
use crate::session::{with_session, ProclaimSession};
use crate::status::ProclaimStatus;
use std::ffi::{c_char, c_int};

/// Whether `algorithm` (a `ProclaimAlgorithm`) proves `literal` (`cook`, `~cook`) given the
/// inputs set so far: writes the answer to `*answer_out` and returns `OK`. When the search could
/// not decide within its budget it writes `false` (not proved) and returns `UNDECIDED`. Otherwise
/// `UNKNOWN_ATOM` or `BAD_ARGUMENT`, and `*answer_out` is left alone.
///
/// # Safety
/// `session` is null or from `proclaim_session_new` (freed or not);
/// `literal` is null or a NUL-terminated string;
/// `answer_out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn proclaim_session_prove(
    session: *mut ProclaimSession,
    literal: *const c_char,
    algorithm: c_int,
    answer_out: *mut bool,
) -> ProclaimStatus {
    with_session(session, |session| {
        let Some(algorithm) = ProclaimAlgorithm::from_code(algorithm) else {
            return ProclaimStatus::BadArgument;
        };
        if answer_out.is_null() {
            return ProclaimStatus::BadArgument;
        }
        let literal = match names::literal(session, literal) {
            Ok(literal) => literal,
            Err(status) => return status,
        };
        let (answer, status) = match session.decide(algorithm, literal) {
            Ok(answer) => (answer, ProclaimStatus::Ok),
            Err(_undecided) => (false, ProclaimStatus::Undecided),
        };
        *answer_out = answer;
        status
    })
}
