//! The C API called as C calls it (raw pointers, NUL-terminated strings, numbers for enums):
//! answers equal the Rust session's, errors carry their place, and bad arguments are statuses.

use proclaim_capi::*;
use std::ffi::{c_char, c_int, CStr, CString};
use std::ptr::{null, null_mut};

const MICROWAVE: &str = include_str!("../../../theories/microwave.dl");
const ALGORITHMS: [ProclaimAlgorithm; 5] = [
    ProclaimAlgorithm::Mu,
    ProclaimAlgorithm::Pi,
    ProclaimAlgorithm::Beta,
    ProclaimAlgorithm::Alpha,
    ProclaimAlgorithm::Delta,
];

fn c(text: &str) -> CString {
    CString::new(text).unwrap()
}

fn load(text: &str) -> Result<*mut ProclaimTheory, (String, u32, u32, String)> {
    let mut error = null_mut();
    let theory = unsafe { proclaim_theory_load(text.as_ptr().cast(), text.len(), &mut error) };
    if theory.is_null() {
        Err(unsafe { taken(error) })
    } else {
        assert!(error.is_null());
        Ok(theory)
    }
}

/// The error's fields, and the error freed.
unsafe fn taken(error: *mut ProclaimError) -> (String, u32, u32, String) {
    assert!(!error.is_null(), "a failed load sets the error");
    let read = |text: *mut c_char| CStr::from_ptr(text).to_str().unwrap().to_string();
    let fields = (
        read((*error).file),
        (*error).line,
        (*error).column,
        read((*error).message),
    );
    proclaim_error_free(error);
    fields
}

fn prove(session: *mut ProclaimSession, literal: &str, algorithm: c_int) -> (ProclaimStatus, bool) {
    let mut answer = false;
    let status = unsafe {
        proclaim_session_prove(
            session,
            c(literal).as_ptr(),
            AlgorithmArgument(algorithm),
            &mut answer,
        )
    };
    (status, answer)
}

fn set(session: *mut ProclaimSession, atom: &str, value: c_int) -> ProclaimStatus {
    unsafe { proclaim_session_set(session, c(atom).as_ptr(), ValueArgument(value)) }
}

#[test]
fn every_algorithm_answers_as_the_rust_session_does_on_every_input() {
    let theory = load(MICROWAVE).unwrap();
    let session = unsafe { proclaim_session_new(theory) };
    // Freed before the session is used: the session holds the theory.
    unsafe { proclaim_theory_free(theory) };
    let rust_theory = proclaim_cdl::load(MICROWAVE, proclaim_cdl::Language::Dl).unwrap();
    let (door, time) = (
        rust_theory.atom("doorOpen").unwrap(),
        rust_theory.atom("timeLeft").unwrap(),
    );
    let mut rust = proclaim_cdl::Session::new(proclaim_cdl::Engine::new(rust_theory.clone()));
    let values = [
        (ProclaimValue::False, Some(false)),
        (ProclaimValue::True, Some(true)),
        (ProclaimValue::Unknown, None),
    ];
    for (door_value, door_open) in values {
        for (time_value, time_left) in values {
            assert_eq!(
                set(session, "doorOpen", door_value as c_int),
                ProclaimStatus::Ok
            );
            assert_eq!(
                set(session, "timeLeft", time_value as c_int),
                ProclaimStatus::Ok
            );
            rust.set_input(door, door_open).unwrap();
            rust.set_input(time, time_left).unwrap();
            for (algorithm, rust_algorithm) in
                ALGORITHMS.into_iter().zip(proclaim_cdl::Algorithm::ALL)
            {
                for literal in ["cook", "~cook", "light", "~light"] {
                    let expected = rust.prove(rust_algorithm, rust_theory.lit(literal).unwrap());
                    assert_eq!(
                        prove(session, literal, algorithm as c_int),
                        (ProclaimStatus::Ok, expected),
                        "{literal} under {rust_algorithm:?}, door {door_open:?}, time {time_left:?}"
                    );
                }
            }
        }
    }
    unsafe { proclaim_session_free(session) };
}

#[test]
fn a_theory_that_does_not_load_says_where_and_why() {
    let (file, line, column, message) = load("input{a}.\nR: a => b.\nS: a => .\n").unwrap_err();
    assert_eq!((file.as_str(), line, column), ("theory", 3, 9));
    assert!(
        message.starts_with("theory does not load (1 error)"),
        "{message}"
    );
    assert!(
        message.contains("3 │ S: a => ."),
        "the line is quoted: {message}"
    );

    let name = c("kitchen.dl");
    let text = "R: a => b\nS: => c.";
    let mut error = null_mut();
    let theory = unsafe {
        proclaim_theory_load_named(name.as_ptr(), text.as_ptr().cast(), text.len(), &mut error)
    };
    assert!(theory.is_null());
    let (file, line, _, message) = unsafe { taken(error) };
    assert_eq!((file.as_str(), line), ("kitchen.dl", 2));
    assert!(message.starts_with("kitchen.dl does not load"), "{message}");
}

#[test]
fn null_text_and_bad_utf8_are_errors_with_a_place_when_there_is_one() {
    let mut error = null_mut();
    assert!(unsafe { proclaim_theory_load(null(), 3, &mut error) }.is_null());
    let (_, line, column, message) = unsafe { taken(error) };
    assert_eq!((line, column), (0, 0));
    assert_eq!(message, "the text is a null pointer");

    let bytes = b"a.\nb\xff.";
    let mut error = null_mut();
    assert!(
        unsafe { proclaim_theory_load(bytes.as_ptr().cast(), bytes.len(), &mut error) }.is_null()
    );
    let (_, line, column, message) = unsafe { taken(error) };
    assert_eq!(
        (line, column, message.as_str()),
        (2, 2, "the text is not UTF-8 (byte 4 is not)")
    );

    // No error wanted: null error_out is allowed and nothing leaks into it.
    assert!(
        unsafe { proclaim_theory_load(bytes.as_ptr().cast(), bytes.len(), null_mut()) }.is_null()
    );
    let mut error = null_mut();
    assert!(
        unsafe { proclaim_theory_load_named(null(), b"a.".as_ptr().cast(), 2, &mut error) }
            .is_null()
    );
    assert!(unsafe { taken(error) }
        .3
        .contains("name: the text is a null pointer"));
}

#[test]
fn wrong_arguments_are_statuses_not_crashes() {
    let theory = load(MICROWAVE).unwrap();
    let session = unsafe { proclaim_session_new(theory) };
    let mut answer = false;
    let beta = ProclaimAlgorithm::Beta as c_int;
    let cook = c("cook");
    unsafe {
        assert!(proclaim_session_new(null()).is_null());
        assert_eq!(
            proclaim_session_prove(
                null_mut(),
                cook.as_ptr(),
                AlgorithmArgument(beta),
                &mut answer
            ),
            ProclaimStatus::BadArgument
        );
        assert_eq!(
            proclaim_session_prove(session, null(), AlgorithmArgument(beta), &mut answer),
            ProclaimStatus::BadArgument
        );
        assert_eq!(
            proclaim_session_prove(session, cook.as_ptr(), AlgorithmArgument(beta), null_mut()),
            ProclaimStatus::BadArgument
        );
        assert_eq!(
            proclaim_session_prove(session, cook.as_ptr(), AlgorithmArgument(5), &mut answer),
            ProclaimStatus::BadArgument
        );
        let not_utf8 = b"c\xffok\0";
        assert_eq!(
            proclaim_session_prove(
                session,
                not_utf8.as_ptr().cast(),
                AlgorithmArgument(beta),
                &mut answer
            ),
            ProclaimStatus::BadArgument
        );
        assert_eq!(
            proclaim_session_set(session, null(), ValueArgument(1)),
            ProclaimStatus::BadArgument
        );
        assert_eq!(
            proclaim_session_set_budget(session, 0),
            ProclaimStatus::BadArgument
        );
        assert_eq!(
            proclaim_session_set_budget(null_mut(), 10),
            ProclaimStatus::BadArgument
        );
        let mut text = null_mut();
        assert_eq!(
            proclaim_session_explain(session, cook.as_ptr(), AlgorithmArgument(9), 1, &mut text),
            ProclaimStatus::BadArgument
        );
        assert_eq!(
            proclaim_session_explain(
                session,
                cook.as_ptr(),
                AlgorithmArgument(beta),
                1,
                null_mut()
            ),
            ProclaimStatus::BadArgument
        );
        assert!(text.is_null());
    }
    assert_eq!(set(session, "doorOpen", 3), ProclaimStatus::BadArgument);
    assert_eq!(set(session, "doorOpen", -1), ProclaimStatus::BadArgument);
    assert_eq!(set(session, "dorOpen", 1), ProclaimStatus::UnknownAtom);
    assert_eq!(set(session, "cook", 1), ProclaimStatus::NotAnInput);
    assert_eq!(
        prove(session, "coook", beta),
        (ProclaimStatus::UnknownAtom, false)
    );
    unsafe {
        proclaim_session_free(session);
        proclaim_theory_free(theory);
        // Freeing null is allowed, as with free().
        proclaim_session_free(null_mut());
        proclaim_theory_free(null_mut());
        proclaim_error_free(null_mut());
    }
}

#[test]
fn an_input_that_contradicts_the_axioms_is_refused_and_changes_nothing() {
    let theory = load("input{a}. input{b}. \\/{~a, ~b}. R: a => c. output{beta c}.").unwrap();
    let session = unsafe { proclaim_session_new(theory) };
    let beta = ProclaimAlgorithm::Beta as c_int;
    assert_eq!(
        set(session, "a", ProclaimValue::True as c_int),
        ProclaimStatus::Ok
    );
    assert_eq!(
        set(session, "b", ProclaimValue::True as c_int),
        ProclaimStatus::InputConflict
    );
    assert_eq!(prove(session, "c", beta), (ProclaimStatus::Ok, true));
    assert_eq!(
        prove(session, "b", ProclaimAlgorithm::Mu as c_int),
        (ProclaimStatus::Ok, false)
    );
    unsafe {
        proclaim_session_free(session);
        proclaim_theory_free(theory);
    }
}

#[test]
fn a_search_past_its_budget_is_undecided_until_the_budget_is_raised() {
    let mut text = Vec::new();
    proclaim_gen::Family::parse("ladder", &[6])
        .unwrap()
        .write(&mut text, proclaim_gen::Format::Dl)
        .unwrap();
    // The crossed ladder of tests/reasoner.rs: 1,000 steps do not decide `t0` (it is true).
    let text = String::from_utf8(text).unwrap() + "x: t0 => ~t2.\n";
    let theory = load(&text).unwrap();
    let session = unsafe { proclaim_session_new(theory) };
    let beta = ProclaimAlgorithm::Beta as c_int;
    assert_eq!(
        unsafe { proclaim_session_set_budget(session, 1000) },
        ProclaimStatus::Ok
    );
    assert_eq!(
        prove(session, "t0", beta),
        (ProclaimStatus::Undecided, false)
    );
    assert_eq!(prove(session, "~t0", beta), (ProclaimStatus::Ok, false));
    assert_eq!(
        unsafe { proclaim_session_set_budget(session, 10_000_000) },
        ProclaimStatus::Ok
    );
    assert_eq!(prove(session, "t0", beta), (ProclaimStatus::Ok, true));
    unsafe {
        proclaim_session_free(session);
        proclaim_theory_free(theory);
    }
}

#[test]
fn an_explanation_is_the_rust_one_in_a_string_the_caller_frees() {
    let theory = load(MICROWAVE).unwrap();
    let session = unsafe { proclaim_session_new(theory) };
    assert_eq!(
        set(session, "doorOpen", ProclaimValue::True as c_int),
        ProclaimStatus::Ok
    );
    assert_eq!(
        set(session, "timeLeft", ProclaimValue::True as c_int),
        ProclaimStatus::Ok
    );
    let mut text = null_mut();
    let status = unsafe {
        proclaim_session_explain(
            session,
            c("cook").as_ptr(),
            AlgorithmArgument(ProclaimAlgorithm::Beta as c_int),
            1,
            &mut text,
        )
    };
    assert_eq!(status, ProclaimStatus::Ok);
    let explanation = unsafe { CStr::from_ptr(text) }
        .to_str()
        .unwrap()
        .to_string();
    unsafe { proclaim_string_free(text) };

    let rust_theory = proclaim_cdl::load(MICROWAVE, proclaim_cdl::Language::Dl).unwrap();
    let mut rust = proclaim_cdl::Session::new(proclaim_cdl::Engine::new(rust_theory.clone()));
    for input in ["doorOpen", "timeLeft"] {
        rust.set_input(rust_theory.atom(input).unwrap(), Some(true))
            .unwrap();
    }
    let expected = rust.explain(
        proclaim_cdl::Algorithm::Beta,
        rust_theory.lit("cook").unwrap(),
        1,
    );
    assert_eq!(explanation, expected.to_string());
    assert!(explanation.contains("DoorCut"), "{explanation}");
    unsafe {
        proclaim_session_free(session);
        proclaim_theory_free(theory);
    }
}

/// Every theory of `theories/` (and its classics): the C table's cells are the Rust table's.
#[test]
fn the_truth_table_is_the_rust_tables_cell_for_cell() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../theories");
    let mut paths: Vec<_> = ["", "classics"]
        .iter()
        .flat_map(|dir| std::fs::read_dir(root.join(dir)).unwrap())
        .map(|entry| entry.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "dl"))
        .collect();
    paths.sort();
    assert!(paths.len() >= 9, "{paths:?}");
    for path in paths {
        let text = std::fs::read_to_string(&path).unwrap();
        let expected = proclaim_cdl::truth_table(std::sync::Arc::new(proclaim_cdl::Engine::new(
            proclaim_cdl::load(&text, proclaim_cdl::Language::Dl).unwrap(),
        )))
        .unwrap();
        let theory = load(&text).unwrap();
        let mut table = null_mut();
        assert_eq!(
            unsafe { proclaim_theory_table(theory, &mut table) },
            ProclaimStatus::Ok
        );
        unsafe { proclaim_theory_free(theory) };
        let t = unsafe { &*table };
        let name = |names: *const *const c_char, i: usize| {
            unsafe { CStr::from_ptr(*names.add(i)) }
                .to_str()
                .unwrap()
                .to_string()
        };
        let inputs: Vec<String> = (0..t.input_count).map(|i| name(t.input_names, i)).collect();
        let headings: Vec<String> = (0..t.output_count)
            .map(|c| name(t.output_names, c))
            .collect();
        assert_eq!(inputs, expected.inputs, "{}", path.display());
        let expected_headings: Vec<&str> = expected
            .columns
            .iter()
            .map(|c| c.heading.as_str())
            .collect();
        assert_eq!(headings, expected_headings, "{}", path.display());
        assert_eq!(t.row_count, expected.rows.len(), "{}", path.display());
        for (r, row) in expected.rows.iter().enumerate() {
            let cell =
                |values: *const bool, width: usize, i: usize| unsafe { *values.add(r * width + i) };
            let c_inputs: Vec<bool> = (0..t.input_count)
                .map(|i| cell(t.inputs, t.input_count, i))
                .collect();
            assert_eq!(c_inputs, row.inputs, "{} row {r}", path.display());
            let consistent = unsafe { *t.consistent.add(r) };
            assert_eq!(
                consistent,
                row.outputs.is_some(),
                "{} row {r}",
                path.display()
            );
            let c_outputs: Vec<bool> = (0..t.output_count)
                .map(|c| cell(t.outputs, t.output_count, c))
                .collect();
            let want = row
                .outputs
                .clone()
                .unwrap_or_else(|| vec![false; t.output_count]);
            assert_eq!(c_outputs, want, "{} row {r}", path.display());
        }
        unsafe { proclaim_table_free(table) };
    }
}

#[test]
fn a_table_too_large_is_a_status_and_bad_arguments_write_nothing() {
    let inputs: String = (0..21).map(|i| format!("input{{a{i}}}. ")).collect();
    let theory = load(&format!("{inputs} R: a0 => b.")).unwrap();
    let mut table = null_mut();
    assert_eq!(
        unsafe { proclaim_theory_table(theory, &mut table) },
        ProclaimStatus::TooManyRows
    );
    assert!(table.is_null());
    assert_eq!(
        unsafe { proclaim_theory_table(theory, null_mut()) },
        ProclaimStatus::BadArgument
    );
    assert_eq!(
        unsafe { proclaim_theory_table(null(), &mut table) },
        ProclaimStatus::BadArgument
    );
    assert!(table.is_null());
    unsafe { proclaim_table_free(null_mut()) };
    unsafe { proclaim_theory_free(theory) };
}

/// Handles looked up once answer as names do, on every input and algorithm; a handle of another
/// theory, a forged one and bad lookups are statuses.
#[test]
fn handles_answer_as_names_do_and_a_handle_of_another_theory_is_refused() {
    let theory = load(MICROWAVE).unwrap();
    let lookup_input = |text: &str| {
        let mut handle = 0;
        let status = unsafe { proclaim_theory_input(theory, c(text).as_ptr(), &mut handle) };
        (status, handle)
    };
    let lookup_literal = |text: &str| {
        let mut handle = 0;
        let status = unsafe { proclaim_theory_literal(theory, c(text).as_ptr(), &mut handle) };
        (status, handle)
    };
    let (_, door) = lookup_input("doorOpen");
    let (_, time) = lookup_input(" timeLeft ");
    let by_name = unsafe { proclaim_session_new(theory) };
    let by_handle = unsafe { proclaim_session_new(theory) };
    let values = [
        ProclaimValue::False,
        ProclaimValue::True,
        ProclaimValue::Unknown,
    ];
    for door_value in values {
        for time_value in values {
            for (name, handle, value) in [
                ("doorOpen", door, door_value),
                ("timeLeft", time, time_value),
            ] {
                assert_eq!(set(by_name, name, value as c_int), ProclaimStatus::Ok);
                let status = unsafe {
                    proclaim_session_set_input(by_handle, handle, ValueArgument(value as c_int))
                };
                assert_eq!(status, ProclaimStatus::Ok);
            }
            for algorithm in ALGORITHMS {
                for literal in ["cook", "~cook", "light", "~ light"] {
                    let (status, handle) = lookup_literal(literal);
                    assert_eq!(status, ProclaimStatus::Ok, "{literal}");
                    let mut answer = false;
                    let status = unsafe {
                        proclaim_session_prove_literal(
                            by_handle,
                            handle,
                            AlgorithmArgument(algorithm as c_int),
                            &mut answer,
                        )
                    };
                    assert_eq!(
                        (status, answer),
                        prove(by_name, literal, algorithm as c_int),
                        "{literal} {algorithm:?} {door_value:?} {time_value:?}"
                    );
                }
            }
        }
    }
    // Lookups that fail, each with its status, writing nothing.
    assert_eq!(lookup_input("cook"), (ProclaimStatus::NotAnInput, 0));
    assert_eq!(lookup_input("oven"), (ProclaimStatus::UnknownAtom, 0));
    assert_eq!(lookup_literal("~oven"), (ProclaimStatus::UnknownAtom, 0));
    let mut handle = 0;
    unsafe {
        assert_eq!(
            proclaim_theory_input(theory, null(), &mut handle),
            ProclaimStatus::BadArgument
        );
        assert_eq!(
            proclaim_theory_input(null(), c("doorOpen").as_ptr(), &mut handle),
            ProclaimStatus::BadArgument
        );
        assert_eq!(
            proclaim_theory_literal(theory, c("cook").as_ptr(), null_mut()),
            ProclaimStatus::BadArgument
        );
        assert_eq!(
            proclaim_theory_literal(theory, [0xffu8, 0].as_ptr().cast(), &mut handle),
            ProclaimStatus::BadArgument
        );
    }
    assert_eq!(handle, 0);

    // The same text loaded again is another theory: its handles are refused here.
    let other = load(MICROWAVE).unwrap();
    let mut foreign = 0;
    unsafe {
        assert_eq!(
            proclaim_theory_input(other, c("timeLeft").as_ptr(), &mut foreign),
            ProclaimStatus::Ok
        );
        assert_ne!(foreign, time);
        assert_eq!(
            proclaim_session_set_input(
                by_handle,
                foreign,
                ValueArgument(ProclaimValue::True as c_int)
            ),
            ProclaimStatus::BadArgument
        );
        let mut answer = true;
        assert_eq!(
            proclaim_session_prove_literal(
                by_handle,
                foreign,
                AlgorithmArgument(ProclaimAlgorithm::Beta as c_int),
                &mut answer
            ),
            ProclaimStatus::BadArgument
        );
        assert!(answer, "left alone");
        // A forged number past the theory's atoms, with the right theory in its high bits.
        let forged = (time & !0xffff_ffff) | 0xffff;
        assert_eq!(
            proclaim_session_set_input(
                by_handle,
                forged,
                ValueArgument(ProclaimValue::True as c_int)
            ),
            ProclaimStatus::BadArgument
        );
        assert_eq!(
            proclaim_session_prove_literal(
                by_handle,
                forged,
                AlgorithmArgument(ProclaimAlgorithm::Beta as c_int),
                &mut answer
            ),
            ProclaimStatus::BadArgument
        );
        // Bad values, algorithms and pointers, as by name.
        assert_eq!(
            proclaim_session_set_input(by_handle, time, ValueArgument(3)),
            ProclaimStatus::BadArgument
        );
        let (_, cook) = lookup_literal("cook");
        assert_eq!(
            proclaim_session_prove_literal(by_handle, cook, AlgorithmArgument(5), &mut answer),
            ProclaimStatus::BadArgument
        );
        assert_eq!(
            proclaim_session_prove_literal(by_handle, cook, AlgorithmArgument(2), null_mut()),
            ProclaimStatus::BadArgument
        );
        assert_eq!(
            proclaim_session_set_input(null_mut(), time, ValueArgument(1)),
            ProclaimStatus::BadArgument
        );
        proclaim_theory_free(other);
        proclaim_theory_free(theory);
        proclaim_session_free(by_name);
        proclaim_session_free(by_handle);
    }
}

/// This thread's last error message.
fn last_error() -> String {
    unsafe { CStr::from_ptr(proclaim_last_error_message()) }
        .to_str()
        .unwrap()
        .to_string()
}

#[test]
fn a_failed_call_says_which_atom_or_argument_and_the_nearest_name() {
    let theory = load(MICROWAVE).unwrap();
    let session = unsafe { proclaim_session_new(theory) };
    let beta = ProclaimAlgorithm::Beta as c_int;
    let truth = ProclaimValue::True as c_int;
    let mut input = 0;
    let check = |status: ProclaimStatus, expected: ProclaimStatus, message: &str| {
        assert_eq!(status, expected, "{message}");
        assert_eq!(last_error(), message);
    };
    check(
        prove(session, "cok", beta).0,
        ProclaimStatus::UnknownAtom,
        "`cok` is no atom of the theory; did you mean `cook`?",
    );
    check(
        prove(session, "~cok", beta).0,
        ProclaimStatus::UnknownAtom,
        "`cok` is no atom of the theory; did you mean `~cook`?",
    );
    check(
        prove(session, "kettle", beta).0,
        ProclaimStatus::UnknownAtom,
        "`kettle` is no atom of the theory",
    );
    check(
        set(session, "doorOpn", truth),
        ProclaimStatus::UnknownAtom,
        "`doorOpn` is no atom of the theory; did you mean `doorOpen`?",
    );
    check(
        set(session, "cook", truth),
        ProclaimStatus::NotAnInput,
        "`cook` is not an input: the theory concludes it; its inputs are doorOpen, timeLeft",
    );
    check(
        unsafe { proclaim_theory_input(theory, c("timeleft").as_ptr(), &mut input) },
        ProclaimStatus::UnknownAtom,
        "`timeleft` is no atom of the theory; did you mean `timeLeft`?",
    );
    check(
        prove(session, "cook", 42).0,
        ProclaimStatus::BadArgument,
        "the algorithm is 42, which is none of PROCLAIM_ALGORITHM_MU (0) to \
         PROCLAIM_ALGORITHM_DELTA (4)",
    );
    check(
        set(session, "doorOpen", 7),
        ProclaimStatus::BadArgument,
        "the value is 7, which is none of PROCLAIM_VALUE_FALSE (0), _TRUE (1), _UNKNOWN (2)",
    );
    check(
        unsafe { proclaim_session_prove(session, null(), AlgorithmArgument(beta), null_mut()) },
        ProclaimStatus::BadArgument,
        "answer_out is null",
    );
    check(
        unsafe { proclaim_session_set_budget(session, 0) },
        ProclaimStatus::BadArgument,
        "the budget is 0 steps; give one or more",
    );
    // A call that succeeds leaves the last failure's message.
    assert_eq!(set(session, "doorOpen", truth), ProclaimStatus::Ok);
    assert_eq!(last_error(), "the budget is 0 steps; give one or more");
    unsafe { proclaim_session_free(session) };
    check(
        unsafe { proclaim_session_free(session) },
        ProclaimStatus::DeadHandle,
        "the handle was freed already",
    );
    unsafe { proclaim_theory_free(theory) };
    assert!(unsafe { proclaim_session_new(theory) }.is_null());
    assert_eq!(last_error(), "the handle was freed already");
    assert!(unsafe { proclaim_session_new(null()) }.is_null());
    assert_eq!(last_error(), "the theory is null");
}

#[test]
fn a_theory_file_loads_by_its_path_and_a_missing_one_is_an_error_naming_it() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../theories/microwave.dl");
    let mut error = null_mut();
    let theory = unsafe { proclaim_theory_load_file(c(path).as_ptr(), &mut error) };
    assert!(!theory.is_null() && error.is_null());
    let session = unsafe { proclaim_session_new(theory) };
    assert_eq!(
        set(session, "timeLeft", ProclaimValue::True as c_int),
        ProclaimStatus::Ok
    );
    assert_eq!(
        prove(session, "cook", ProclaimAlgorithm::Beta as c_int),
        (ProclaimStatus::Ok, true)
    );
    unsafe { proclaim_session_free(session) };
    unsafe { proclaim_theory_free(theory) };

    let missing = concat!(env!("CARGO_TARGET_TMPDIR"), "/no-such-theory.dl");
    let theory = unsafe { proclaim_theory_load_file(c(missing).as_ptr(), &mut error) };
    assert!(theory.is_null());
    let (file, line, column, message) = unsafe { taken(error) };
    assert_eq!((file.as_str(), line, column), (missing, 0, 0));
    assert!(
        message.starts_with(&format!("{missing} cannot be read: No such file")),
        "{message}"
    );
    assert_eq!(last_error(), message);

    // A file that does not load says where, under its path, as a text loaded by name does.
    let broken = concat!(env!("CARGO_TARGET_TMPDIR"), "/broken.dl");
    std::fs::write(broken, "input{doorOpen}.\nTimer: timeLeft => .\n").unwrap();
    let theory = unsafe { proclaim_theory_load_file(c(broken).as_ptr(), &mut error) };
    assert!(theory.is_null());
    let (file, line, _, message) = unsafe { taken(error) };
    assert_eq!((file.as_str(), line), (broken, 2));
    assert!(
        message.contains("broken.dl does not load (1 error)"),
        "{message}"
    );
    assert!(unsafe { proclaim_theory_load_file(null(), null_mut()) }.is_null());
}
