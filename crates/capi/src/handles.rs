//! Atoms and literals looked up by name once, then named by number in every call: the string
//! hashing, UTF-8 checking and input check of a by-name call happen at the lookup, not in the
//! loop. A handle carries its theory's identity, so a session over another theory refuses it
//! (`BAD_ARGUMENT`) instead of answering about whatever atom has that number there.

use crate::algorithm::AlgorithmArgument;
use crate::detail::{fail, reported};
use crate::guard::guarded;
use crate::names;
use crate::session::{with_session_of, ProclaimSession};
use crate::status::ProclaimStatus;
use crate::theory::{live_theory, ProclaimTheory};
use crate::value::ValueArgument;
use proclaim_cdl::{Atom, Lit};
use std::ffi::c_char;

/// An input atom of one theory, from [`proclaim_theory_input`]: its theory's identity in the
/// high 32 bits, the atom's number in the low 32. Valid for every session over that theory.
pub type ProclaimInput = u64;

/// A literal (`cook`, `~cook`) of one theory, from [`proclaim_theory_literal`]; made as
/// [`ProclaimInput`] is.
pub type ProclaimLiteral = u64;

/// Why a handle from another theory's lookup (or no lookup) is refused.
const OTHER_THEORY: &str = "the handle is not one of this session's theory: look it up with \
                            proclaim_theory_input or proclaim_theory_literal on that theory";

fn handle(theory: u32, number: u32) -> u64 {
    (u64::from(theory) << 32) | u64::from(number)
}

/// The number inside `handle` when it belongs to the theory `tag`.
fn number_of(handle: u64, tag: u32) -> Option<u32> {
    ((handle >> 32) as u32 == tag).then_some(handle as u32)
}

/// Looks up the input atom `atom` of `theory` and writes its handle to `*input_out`: `OK`, or
/// `UNKNOWN_ATOM`, `NOT_AN_INPUT` (the theory declares its inputs and this is not one) or
/// `BAD_ARGUMENT`, and `*input_out` is left alone.
///
/// # Safety
/// `theory` is null or from `proclaim_theory_load` (freed or not);
/// `atom` is null or a NUL-terminated string; `input_out` is
/// null or writable.
#[no_mangle]
pub unsafe extern "C" fn proclaim_theory_input(
    theory: *const ProclaimTheory,
    atom: *const c_char,
    input_out: *mut ProclaimInput,
) -> ProclaimStatus {
    if input_out.is_null() {
        return reported(fail(ProclaimStatus::BadArgument, "input_out is null"));
    }
    let (engine, tag) = match live_theory(theory) {
        Ok(live) => live,
        Err(status) => return reported(status),
    };
    reported(guarded(ProclaimStatus::Panic, || {
        match names::input_of(engine.theory(), atom) {
            Ok(atom) => {
                *input_out = handle(tag, atom.0);
                ProclaimStatus::Ok
            }
            Err(status) => status,
        }
    }))
}

/// Looks up `literal` (`cook`, `~cook`) of `theory` and writes its handle to `*literal_out`:
/// `OK`, or `UNKNOWN_ATOM` or `BAD_ARGUMENT`, and `*literal_out` is left alone.
///
/// # Safety
/// `theory` is null or from `proclaim_theory_load` (freed or not);
/// `literal` is null or a NUL-terminated string;
/// `literal_out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn proclaim_theory_literal(
    theory: *const ProclaimTheory,
    literal: *const c_char,
    literal_out: *mut ProclaimLiteral,
) -> ProclaimStatus {
    if literal_out.is_null() {
        return reported(fail(ProclaimStatus::BadArgument, "literal_out is null"));
    }
    let (engine, tag) = match live_theory(theory) {
        Ok(live) => live,
        Err(status) => return reported(status),
    };
    reported(guarded(ProclaimStatus::Panic, || {
        let text = match names::text(literal, "the literal") {
            Ok(text) => text.trim(),
            Err(status) => return status,
        };
        match engine.theory().lit(text) {
            Some(lit) => {
                *literal_out = handle(tag, lit.0);
                ProclaimStatus::Ok
            }
            None => names::unknown_atom(engine.theory(), text),
        }
    }))
}

/// [`proclaim_session_set`](crate::proclaim_session_set) by handle: sets `input` to a
/// `ProclaimValue`. `BAD_ARGUMENT` for a handle of another theory or a value that is none;
/// `INPUT_CONFLICT` as by name.
///
/// # Safety
/// `session` is null or from `proclaim_session_new` (freed or not).
#[no_mangle]
pub unsafe extern "C" fn proclaim_session_set_input(
    session: *mut ProclaimSession,
    input: ProclaimInput,
    value: ValueArgument,
) -> ProclaimStatus {
    with_session_of(session, |session, tag| {
        let value = match value.value() {
            Ok(value) => value,
            Err(status) => return status,
        };
        // Only the lookup makes handles, and it checked the atom is an input; the range is
        // checked again so a forged number is an error, never an index out of bounds.
        let atom = match number_of(input, tag) {
            Some(n) if (n as usize) < session.engine().theory().atom_count() => Atom(n),
            _ => return fail(ProclaimStatus::BadArgument, OTHER_THEORY),
        };
        match session.set_input(atom, value) {
            Ok(()) => ProclaimStatus::Ok,
            Err(conflict) => fail(ProclaimStatus::InputConflict, conflict.to_string()),
        }
    })
}

/// [`proclaim_session_prove`](crate::proclaim_session_prove) by handle: whether `algorithm`
/// proves `literal`, written to `*answer_out`; `OK`, `UNDECIDED` (`false` written), or
/// `BAD_ARGUMENT` for a handle of another theory, and `*answer_out` is left alone.
///
/// # Safety
/// `session` is null or from `proclaim_session_new` (freed or not);
/// `answer_out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn proclaim_session_prove_literal(
    session: *mut ProclaimSession,
    literal: ProclaimLiteral,
    algorithm: AlgorithmArgument,
    answer_out: *mut bool,
) -> ProclaimStatus {
    with_session_of(session, |session, tag| {
        let algorithm = match algorithm.algorithm() {
            Ok(algorithm) => algorithm,
            Err(status) => return status,
        };
        if answer_out.is_null() {
            return fail(ProclaimStatus::BadArgument, "answer_out is null");
        }
        let lit = match number_of(literal, tag) {
            Some(n) if (Lit(n).atom().0 as usize) < session.engine().theory().atom_count() => {
                Lit(n)
            }
            _ => return fail(ProclaimStatus::BadArgument, OTHER_THEORY),
        };
        let (answer, status) = match session.decide(algorithm, lit) {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_handle_names_its_theory_and_number_and_no_other_theorys() {
        let h = handle(7, 42);
        assert_eq!(number_of(h, 7), Some(42));
        assert_eq!(number_of(h, 8), None);
        assert_eq!(
            number_of(handle(u32::MAX, u32::MAX), u32::MAX),
            Some(u32::MAX)
        );
    }
}
