//! Handles used after their `_free`: every kind (theory, session, table, load error) answers
//! `DEAD_HANDLE` to every later call and to a second free, from one thread or from several racing
//! a free; a session used by two threads at once answers `BUSY` rather than corrupting itself.

use proclaim_capi::*;
use std::ffi::{c_int, CString};
use std::ptr::null_mut;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Barrier;

const MICROWAVE: &str = include_str!("../../../theories/microwave.dl");
const BETA: c_int = ProclaimAlgorithm::Beta as c_int;
const TRUE: c_int = ProclaimValue::True as c_int;

fn c(text: &str) -> CString {
    CString::new(text).unwrap()
}

fn theory() -> *mut ProclaimTheory {
    let theory =
        unsafe { proclaim_theory_load(MICROWAVE.as_ptr().cast(), MICROWAVE.len(), null_mut()) };
    assert!(!theory.is_null());
    theory
}

/// The raw pointer, sendable to another thread: the handles are made for it (theories may be
/// shared, sessions refuse a second user with `BUSY`).
struct Shared<T>(*mut T);
impl<T> Clone for Shared<T> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<T> Copy for Shared<T> {}
impl<T> Shared<T> {
    /// The pointer, through a method so that a closure captures the `Shared` (which is `Sync`),
    /// not the raw pointer field (which is not).
    fn get(self) -> *mut T {
        self.0
    }
}
unsafe impl<T> Send for Shared<T> {}
unsafe impl<T> Sync for Shared<T> {}

/// Every call a theory takes, with what it returns on a dead theory.
fn theory_calls(theory: *mut ProclaimTheory) -> Vec<(&'static str, ProclaimStatus)> {
    let mut input = 0;
    let mut literal = 0;
    let mut table = null_mut();
    let session = unsafe { proclaim_session_new(theory) };
    let dead_session = if session.is_null() {
        ProclaimStatus::DeadHandle
    } else {
        unsafe { proclaim_session_free(session) }
    };
    unsafe {
        vec![
            (
                "input",
                proclaim_theory_input(theory, c("doorOpen").as_ptr(), &mut input),
            ),
            (
                "literal",
                proclaim_theory_literal(theory, c("cook").as_ptr(), &mut literal),
            ),
            ("table", proclaim_theory_table(theory, &mut table)),
            ("session_new (null when dead)", dead_session),
        ]
    }
}

/// Every call a session takes.
fn session_calls(
    session: *mut ProclaimSession,
    input: u64,
    literal: u64,
) -> Vec<(&'static str, ProclaimStatus)> {
    let mut answer = false;
    let mut text = null_mut();
    let cook = c("cook");
    unsafe {
        vec![
            (
                "set",
                proclaim_session_set(session, c("doorOpen").as_ptr(), ValueArgument(TRUE)),
            ),
            (
                "set_input",
                proclaim_session_set_input(session, input, ValueArgument(TRUE)),
            ),
            ("set_budget", proclaim_session_set_budget(session, 100)),
            (
                "prove",
                proclaim_session_prove(
                    session,
                    cook.as_ptr(),
                    AlgorithmArgument(BETA),
                    &mut answer,
                ),
            ),
            (
                "prove_literal",
                proclaim_session_prove_literal(
                    session,
                    literal,
                    AlgorithmArgument(BETA),
                    &mut answer,
                ),
            ),
            (
                "explain",
                proclaim_session_explain(
                    session,
                    cook.as_ptr(),
                    AlgorithmArgument(BETA),
                    1,
                    &mut text,
                ),
            ),
        ]
    }
}

fn handles(theory: *mut ProclaimTheory) -> (u64, u64) {
    let (mut input, mut literal) = (0, 0);
    unsafe {
        assert_eq!(
            proclaim_theory_input(theory, c("timeLeft").as_ptr(), &mut input),
            ProclaimStatus::Ok
        );
        assert_eq!(
            proclaim_theory_literal(theory, c("cook").as_ptr(), &mut literal),
            ProclaimStatus::Ok
        );
    }
    (input, literal)
}

#[test]
fn a_freed_theory_answers_dead_handle_to_every_call_and_a_second_free() {
    let theory = theory();
    for (call, status) in theory_calls(theory) {
        assert_eq!(status, ProclaimStatus::Ok, "{call} on a live theory");
    }
    assert_eq!(unsafe { proclaim_theory_free(theory) }, ProclaimStatus::Ok);
    for (call, status) in theory_calls(theory) {
        assert_eq!(
            status,
            ProclaimStatus::DeadHandle,
            "{call} on a freed theory"
        );
    }
    assert_eq!(
        unsafe { proclaim_theory_free(theory) },
        ProclaimStatus::DeadHandle
    );
    assert_eq!(
        unsafe { proclaim_theory_free(null_mut()) },
        ProclaimStatus::Ok
    );
}

#[test]
fn a_freed_session_answers_dead_handle_and_its_theorys_handles_still_work_elsewhere() {
    let theory = theory();
    let (input, literal) = handles(theory);
    let session = unsafe { proclaim_session_new(theory) };
    for (call, status) in session_calls(session, input, literal) {
        assert_eq!(status, ProclaimStatus::Ok, "{call} on a live session");
    }
    assert_eq!(
        unsafe { proclaim_session_free(session) },
        ProclaimStatus::Ok
    );
    for (call, status) in session_calls(session, input, literal) {
        assert_eq!(
            status,
            ProclaimStatus::DeadHandle,
            "{call} on a freed session"
        );
    }
    assert_eq!(
        unsafe { proclaim_session_free(session) },
        ProclaimStatus::DeadHandle
    );
    assert_eq!(
        unsafe { proclaim_session_free(null_mut()) },
        ProclaimStatus::Ok
    );

    // A session outlives its theory's handle; the new session is a new handle, not the old one.
    let other = unsafe { proclaim_session_new(theory) };
    assert_ne!(
        other, session,
        "a freed session's header is never handed out again"
    );
    assert_eq!(unsafe { proclaim_theory_free(theory) }, ProclaimStatus::Ok);
    for (call, status) in session_calls(other, input, literal) {
        assert_eq!(
            status,
            ProclaimStatus::Ok,
            "{call} after its theory's handle was freed"
        );
    }
    assert_eq!(unsafe { proclaim_session_free(other) }, ProclaimStatus::Ok);
}

#[test]
fn a_freed_table_or_load_error_is_emptied_and_a_second_free_says_dead_handle() {
    let theory = theory();
    let mut table = null_mut();
    assert_eq!(
        unsafe { proclaim_theory_table(theory, &mut table) },
        ProclaimStatus::Ok
    );
    assert!(unsafe { (*table).row_count } > 0);
    assert_eq!(unsafe { proclaim_table_free(table) }, ProclaimStatus::Ok);
    // What C reads from a freed table is empty, not freed memory.
    let emptied = unsafe { &*table };
    assert_eq!(
        (emptied.input_count, emptied.output_count, emptied.row_count),
        (0, 0, 0)
    );
    assert!(emptied.inputs.is_null() && emptied.outputs.is_null() && emptied.consistent.is_null());
    assert!(emptied.input_names.is_null() && emptied.output_names.is_null());
    assert_eq!(
        unsafe { proclaim_table_free(table) },
        ProclaimStatus::DeadHandle
    );
    assert_eq!(
        unsafe { proclaim_table_free(null_mut()) },
        ProclaimStatus::Ok
    );
    unsafe { proclaim_theory_free(theory) };

    let broken = "R: a => .";
    let mut error = null_mut();
    let none = unsafe { proclaim_theory_load(broken.as_ptr().cast(), broken.len(), &mut error) };
    assert!(none.is_null() && !error.is_null());
    assert!(unsafe { (*error).line } > 0);
    assert_eq!(unsafe { proclaim_error_free(error) }, ProclaimStatus::Ok);
    let emptied = unsafe { &*error };
    assert!(emptied.file.is_null() && emptied.message.is_null());
    assert_eq!((emptied.line, emptied.column), (0, 0));
    assert_eq!(
        unsafe { proclaim_error_free(error) },
        ProclaimStatus::DeadHandle
    );
    assert_eq!(
        unsafe { proclaim_error_free(null_mut()) },
        ProclaimStatus::Ok
    );
}

/// Threads looking atoms up and opening sessions while the main thread frees the theory: each
/// call answers as on a live theory or says `DEAD_HANDLE`, and once one has said it, all do.
#[test]
fn a_theory_freed_while_other_threads_use_it_answers_or_is_dead_never_half() {
    let theory = Shared(theory());
    let threads = 4;
    let started = Barrier::new(threads + 1);
    std::thread::scope(|scope| {
        for _ in 0..threads {
            scope.spawn(|| {
                started.wait();
                let mut seen_dead = false;
                for _ in 0..2_000 {
                    let mut input = 0;
                    let status = unsafe {
                        proclaim_theory_input(theory.get(), c("doorOpen").as_ptr(), &mut input)
                    };
                    let session = unsafe { proclaim_session_new(theory.get()) };
                    if !session.is_null() {
                        assert!(
                            !seen_dead,
                            "a session opened after the theory was seen dead"
                        );
                        assert_eq!(
                            unsafe {
                                proclaim_session_set_input(session, input, ValueArgument(TRUE))
                            },
                            status
                        );
                        assert_eq!(
                            unsafe { proclaim_session_free(session) },
                            ProclaimStatus::Ok
                        );
                    }
                    match status {
                        ProclaimStatus::Ok => assert!(!seen_dead, "alive again after dead"),
                        ProclaimStatus::DeadHandle => seen_dead = true,
                        other => panic!("{other:?}"),
                    }
                }
            });
        }
        started.wait();
        std::thread::yield_now();
        assert_eq!(
            unsafe { proclaim_theory_free(theory.get()) },
            ProclaimStatus::Ok
        );
    });
    assert_eq!(
        unsafe { proclaim_theory_free(theory.get()) },
        ProclaimStatus::DeadHandle
    );
}

/// Two threads on one session (against the rules) and a third freeing it: a call either runs
/// alone, or says `BUSY` (another call is running) or `DEAD_HANDLE`; a free during a call says
/// `BUSY` and frees nothing.
#[test]
fn a_session_shared_against_the_rules_says_busy_and_a_free_during_a_call_waits_its_turn() {
    let theory = theory();
    let (input, literal) = handles(theory);
    let session = Shared(unsafe { proclaim_session_new(theory) });
    let freeing = AtomicBool::new(false);
    let answered = AtomicUsize::new(0);
    let started = Barrier::new(3);
    let mut busy_seen = 0;
    std::thread::scope(|scope| {
        let users: Vec<_> = (0..2)
            .map(|_| {
                scope.spawn(|| {
                    started.wait();
                    let mut busy = 0;
                    for i in 0..20_000 {
                        let value = c_int::from(i % 2 == 0);
                        let mut answer = false;
                        let set = unsafe {
                            proclaim_session_set_input(session.get(), input, ValueArgument(value))
                        };
                        let asked = unsafe {
                            proclaim_session_prove_literal(
                                session.get(),
                                literal,
                                AlgorithmArgument(BETA),
                                &mut answer,
                            )
                        };
                        for status in [set, asked] {
                            match status {
                                ProclaimStatus::Ok => {
                                    answered.fetch_add(1, Ordering::SeqCst);
                                }
                                ProclaimStatus::Busy => busy += 1,
                                ProclaimStatus::DeadHandle => {
                                    assert!(freeing.load(Ordering::SeqCst))
                                }
                                other => panic!("{other:?}"),
                            }
                        }
                    }
                    busy
                })
            })
            .collect();
        started.wait();
        // Freed while both are still at it (or once they are done, on a slow machine).
        while answered.load(Ordering::SeqCst) < 5_000 && !users.iter().all(|u| u.is_finished()) {
            std::thread::yield_now();
        }
        freeing.store(true, Ordering::SeqCst);
        loop {
            match unsafe { proclaim_session_free(session.get()) } {
                ProclaimStatus::Ok => break,
                ProclaimStatus::Busy => std::thread::yield_now(),
                other => panic!("{other:?}"),
            }
        }
        busy_seen = users.into_iter().map(|u| u.join().unwrap()).sum::<u32>();
    });
    // Whether the two users ever overlapped depends on the scheduler; what they answered did not.
    eprintln!("{busy_seen} calls answered BUSY");
    assert_eq!(
        unsafe { proclaim_session_free(session.get()) },
        ProclaimStatus::DeadHandle
    );
    unsafe { proclaim_theory_free(theory) };
}
