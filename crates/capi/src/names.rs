//! Atoms and literals named by C strings, looked up in the session's theory.

use crate::detail::fail;
use crate::status::ProclaimStatus;
use crate::text_from_c::nul_terminated;
use proclaim_cdl::{Atom, Lit, Session, Theory};
use std::ffi::c_char;

/// Text from C that should name something, or `BAD_ARGUMENT` saying which argument it is.
///
/// # Safety
/// `text` is null or a NUL-terminated string.
pub(crate) unsafe fn text<'a>(text: *const c_char, what: &str) -> Result<&'a str, ProclaimStatus> {
    nul_terminated(text).map_err(|bad| fail(ProclaimStatus::BadArgument, format!("{what}: {bad}")))
}

/// `UNKNOWN_ATOM` for `literal` (`cok`, `~cok`), saying which atom, and the theory's nearest
/// literal when one is close.
pub(crate) fn unknown_atom(theory: &Theory, literal: &str) -> ProclaimStatus {
    let (sign, name) = match literal.strip_prefix('~') {
        Some(atom) => ("~", atom.trim()),
        None => ("", literal),
    };
    let names = (0..theory.atom_count()).map(|i| theory.atom_name(Atom(i as u32)));
    let why = match proclaim_syntax::nearest(names, name) {
        Some(close) => {
            format!("`{name}` is no atom of the theory; did you mean `{sign}{close}`?")
        }
        None => format!("`{name}` is no atom of the theory"),
    };
    fail(ProclaimStatus::UnknownAtom, why)
}

/// The literal `text` names (`cook`, `~cook`).
///
/// # Safety
/// `text` is null or a NUL-terminated string.
pub(crate) unsafe fn literal(
    session: &Session,
    text: *const c_char,
) -> Result<Lit, ProclaimStatus> {
    let text = self::text(text, "the literal")?.trim();
    let theory = session.engine().theory();
    theory.lit(text).ok_or_else(|| unknown_atom(theory, text))
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
    let text = self::text(text, "the atom")?.trim();
    let atom = theory
        .atom(text)
        .ok_or_else(|| unknown_atom(theory, text))?;
    let mut declared = theory.input_atoms().peekable();
    if declared.peek().is_some() && !declared.any(|a| a == atom) {
        let inputs: Vec<&str> = theory.input_atoms().map(|a| theory.atom_name(a)).collect();
        return Err(fail(
            ProclaimStatus::NotAnInput,
            format!(
                "`{text}` is not an input: the theory concludes it; its inputs are {}",
                inputs.join(", ")
            ),
        ));
    }
    Ok(atom)
}
