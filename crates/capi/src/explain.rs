//! Why an algorithm proves or refutes a literal, as text C owns.

use crate::algorithm::AlgorithmArgument;
use crate::detail::fail;
use crate::names;
use crate::session::{with_session, ProclaimSession};
use crate::status::ProclaimStatus;
use crate::text_to_c::owned;
use std::ffi::c_char;

/// Explains `±algorithm literal` as `proclaim explain` prints it: the supporting rule, each
/// attacker and what became of it, following antecedents `depth` levels down. Writes a string the
/// caller frees with `proclaim_string_free` to `*text_out` and returns `OK`; otherwise
/// `UNKNOWN_ATOM` or `BAD_ARGUMENT`, and `*text_out` is left alone.
///
/// # Safety
/// `session` is null or from `proclaim_session_new` (freed or not);
/// `literal` is null or a NUL-terminated string;
/// `text_out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn proclaim_session_explain(
    session: *mut ProclaimSession,
    literal: *const c_char,
    algorithm: AlgorithmArgument,
    depth: u32,
    text_out: *mut *mut c_char,
) -> ProclaimStatus {
    with_session(session, |session| {
        let algorithm = match algorithm.algorithm() {
            Ok(algorithm) => algorithm,
            Err(status) => return status,
        };
        if text_out.is_null() {
            return fail(ProclaimStatus::BadArgument, "text_out is null");
        }
        let literal = match names::literal(session, literal) {
            Ok(literal) => literal,
            Err(status) => return status,
        };
        let explanation = session.explain(algorithm, literal, depth as usize);
        *text_out = owned(&explanation.to_string());
        ProclaimStatus::Ok
    })
}
