//! Atoms and literals named by C strings, looked up in the session's theory.

use crate::status::ProclaimStatus;
use crate::text::nul_terminated;
use proclaim_cdl::{Atom, Lit, Session, Theory};
use std::ffi::c_char;

/// The literal `text` names (`cook`, `~cook`).
///
/// # Safety
/// `text` is null or a NUL-terminated string.
pub(crate) unsafe fn literal(
    session: &Session,
    text: *const c_char,
) -> Result<Lit, ProclaimStatus> {
    let text = nul_terminated(text).map_err(|_| ProclaimStatus::BadArgument)?;
    session
        .engine()
        .theory()
        .lit(text.trim())
        .ok_or(ProclaimStatus::UnknownAtom)
}

/// The input atom `text` names. When the theory declares its inputs only those may be set, as
/// `proclaim prove --set` has it: anything else is concluded by rules, not observed.
///
/// # Safety
/// `text` is null or a NUL-terminated string.
pub(crate) unsafe fn input(session: &Session, text: *const c_char) -> Result<Atom, ProclaimStatus> {
    input_of(session.engine().theory(), text)
}

/// [`input`] in a theory rather than a session's.
///
/// # Safety
/// `text` is null or a NUL-terminated string.
pub(crate) unsafe fn input_of(
    theory: &Theory,
    text: *const c_char,
) -> Result<Atom, ProclaimStatus> {
    let text = nul_terminated(text).map_err(|_| ProclaimStatus::BadArgument)?;
    let atom = theory
        .atom(text.trim())
        .ok_or(ProclaimStatus::UnknownAtom)?;
    let mut declared = theory.input_atoms().peekable();
    if declared.peek().is_some() && !declared.any(|a| a == atom) {
        return Err(ProclaimStatus::NotAnInput);
    }
    Ok(atom)
}
