//! What a call returns: whether it answered, and if not, why.

use std::ffi::{c_char, c_int};

/// The outcome of a call. Only `PROCLAIM_STATUS_OK` means its out-parameters were written with an
/// answer.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ProclaimStatus {
    /// The call did what it was asked.
    Ok = 0,
    /// The search ran out of its step budget inside an attack cycle before deciding the goal:
    /// neither proved nor refuted (the answer written is `false`, "not proved").
    Undecided = 1,
    /// The theory has no such atom.
    UnknownAtom = 2,
    /// The theory declares its inputs and this atom is not one of them: it is concluded, not set.
    NotAnInput = 3,
    /// The value, together with the other inputs, contradicts the theory's axioms; the session was
    /// left as it was.
    InputConflict = 4,
    /// A null pointer, text that is not UTF-8, or a number that is no algorithm or value.
    BadArgument = 5,
    /// The reasoner panicked (a bug); the panic was stopped at the boundary. A session that
    /// panicked answers `PROCLAIM_STATUS_PANIC` to every later call: free it.
    Panic = 6,
    /// The theory's inputs have more combinations than a truth table may hold (2^20): group
    /// mutually exclusive inputs as `input{a, b, c}`, or ask rows one at a time.
    TooManyRows = 7,
    /// The handle was freed: its `_free` already ran (a second `_free` says this too). A freed
    /// handle keeps a few bytes so that this is an answer, not undefined behaviour.
    DeadHandle = 8,
    /// A call on another thread is running on this session (a session is for one thread at a
    /// time); nothing was done. A `_free` that says this freed nothing.
    Busy = 9,
}

impl ProclaimStatus {
    const ALL: [ProclaimStatus; 10] = [
        ProclaimStatus::Ok,
        ProclaimStatus::Undecided,
        ProclaimStatus::UnknownAtom,
        ProclaimStatus::NotAnInput,
        ProclaimStatus::InputConflict,
        ProclaimStatus::BadArgument,
        ProclaimStatus::Panic,
        ProclaimStatus::TooManyRows,
        ProclaimStatus::DeadHandle,
        ProclaimStatus::Busy,
    ];

    /// The status a number from C stands for, if any.
    pub fn from_code(code: c_int) -> Option<ProclaimStatus> {
        ProclaimStatus::ALL
            .into_iter()
            .find(|s| *s as c_int == code)
    }

    /// What the status means, for a failure whose call gave no detail of its own.
    pub(crate) fn description(self) -> &'static str {
        match self {
            ProclaimStatus::Ok => "ok",
            ProclaimStatus::Undecided => "the search ran out of its budget before deciding",
            ProclaimStatus::UnknownAtom => "the theory has no such atom",
            ProclaimStatus::NotAnInput => "the atom is not an input of the theory",
            ProclaimStatus::InputConflict => "the value contradicts the theory's axioms",
            ProclaimStatus::BadArgument => "a bad argument",
            ProclaimStatus::Panic => {
                "the reasoner panicked (a bug; the panic was stopped here); free the session"
            }
            ProclaimStatus::TooManyRows => "the truth table would have too many rows",
            ProclaimStatus::DeadHandle => "the handle was freed already",
            ProclaimStatus::Busy => "a call on another thread is running on this session",
        }
    }

    /// The name C programs print, NUL-terminated so it can be handed out as is.
    fn name_with_nul(self) -> &'static str {
        match self {
            ProclaimStatus::Ok => "ok\0",
            ProclaimStatus::Undecided => "undecided\0",
            ProclaimStatus::UnknownAtom => "unknown atom\0",
            ProclaimStatus::NotAnInput => "not an input\0",
            ProclaimStatus::InputConflict => "input conflict\0",
            ProclaimStatus::BadArgument => "bad argument\0",
            ProclaimStatus::Panic => "panic\0",
            ProclaimStatus::TooManyRows => "too many rows\0",
            ProclaimStatus::DeadHandle => "dead handle\0",
            ProclaimStatus::Busy => "busy\0",
        }
    }
}

/// The name of a status ("ok", "undecided", "unknown atom", …), a static string the caller must
/// not free; "not a status" for a number that is none.
#[no_mangle]
pub extern "C" fn proclaim_status_name(status: c_int) -> *const c_char {
    ProclaimStatus::from_code(status)
        .map_or("not a status\0", ProclaimStatus::name_with_nul)
        .as_ptr()
        .cast()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::ffi::CStr;

    #[test]
    fn every_status_has_a_name_and_other_numbers_say_so() {
        let name = |code| {
            unsafe { CStr::from_ptr(proclaim_status_name(code)) }
                .to_str()
                .unwrap()
        };
        assert_eq!(name(ProclaimStatus::Undecided as c_int), "undecided");
        assert_eq!(name(ProclaimStatus::Panic as c_int), "panic");
        assert_eq!(name(ProclaimStatus::TooManyRows as c_int), "too many rows");
        assert_eq!(name(ProclaimStatus::DeadHandle as c_int), "dead handle");
        assert_eq!(name(ProclaimStatus::Busy as c_int), "busy");
        assert_eq!(name(10), "not a status");
        assert_eq!(name(-1), "not a status");
    }
}
