//! Asking whether an algorithm proves a literal.

use crate::algorithm::AlgorithmArgument;
use crate::detail::fail;
use crate::names;
use crate::session::{with_session, ProclaimSession};
use crate::status::ProclaimStatus;
use std::ffi::c_char;

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
    algorithm: AlgorithmArgument,
    answer_out: *mut bool,
) -> ProclaimStatus {
    with_session(session, |session| {
        let algorithm = match algorithm.algorithm() {
            Ok(algorithm) => algorithm,
            Err(status) => return status,
        };
        if answer_out.is_null() {
            return fail(ProclaimStatus::BadArgument, "answer_out is null");
        }
        let literal = match names::literal(session, literal) {
            Ok(literal) => literal,
            Err(status) => return status,
        };
        let (answer, status) = match session.decide(algorithm, literal) {
            Ok(answer) => (answer, ProclaimStatus::Ok),
            Err(undecided) => (
                false,
                fail(ProclaimStatus::Undecided, undecided.to_string()),
            ),
        };
        *answer_out = answer;
        status
    })
}
