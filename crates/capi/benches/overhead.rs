//! What the C boundary costs, side by side in one run: one input change and one question on the
//! microwave (benches/reasoner.rs's "microwave cook": `timeLeft` toggled, then β `cook`) through
//! the Rust session, through the C API by name, and through the C API by atom and literal
//! handles looked up once. The C functions are called through their `extern "C"` symbols from
//! another crate, not inlined, as a C program calls them.
//!
//! `cargo bench -p proclaim-capi --bench overhead`

use criterion::{criterion_group, criterion_main, Criterion};
use proclaim_capi::*;
use proclaim_cdl::{load, Algorithm, Engine, Language, Session};
use std::ffi::{c_int, CString};
use std::hint::black_box;

const MICROWAVE: &str = include_str!("../../../theories/microwave.dl");

/// A session with `doorOpen` false, and the handles of `timeLeft` and `cook`.
fn c_session() -> (*mut ProclaimSession, ProclaimInput, ProclaimLiteral) {
    let mut error = std::ptr::null_mut();
    let theory =
        unsafe { proclaim_theory_load(MICROWAVE.as_ptr().cast(), MICROWAVE.len(), &mut error) };
    assert!(!theory.is_null());
    let session = unsafe { proclaim_session_new(theory) };
    let (mut time_left, mut cook) = (0, 0);
    let name = |text: &str| CString::new(text).unwrap();
    unsafe {
        assert_eq!(
            proclaim_theory_input(theory, name("timeLeft").as_ptr(), &mut time_left),
            ProclaimStatus::Ok
        );
        assert_eq!(
            proclaim_theory_literal(theory, name("cook").as_ptr(), &mut cook),
            ProclaimStatus::Ok
        );
        proclaim_theory_free(theory);
    }
    let door = CString::new("doorOpen").unwrap();
    let status = unsafe {
        proclaim_session_set(
            session,
            door.as_ptr(),
            ValueArgument(ProclaimValue::False as c_int),
        )
    };
    assert_eq!(status, ProclaimStatus::Ok);
    (session, time_left, cook)
}

fn value(on: bool) -> c_int {
    (if on {
        ProclaimValue::True
    } else {
        ProclaimValue::False
    }) as c_int
}

fn overhead(c: &mut Criterion) {
    let mut group = c.benchmark_group("set + prove");

    let theory = load(MICROWAVE, Language::Dl).unwrap();
    let atom = theory.atom("timeLeft").unwrap();
    let lit = theory.lit("cook").unwrap();
    let mut session = Session::new(Engine::new(theory));
    for other in session.engine().clone().theory().input_atoms() {
        session.set_input(other, Some(false)).unwrap();
    }
    let mut on = false;
    group.bench_function("rust", |b| {
        b.iter(|| {
            on = !on;
            session.set_input(atom, Some(on)).unwrap();
            black_box(session.prove(Algorithm::Beta, lit))
        })
    });

    let (session, time_left_handle, cook_handle) = c_session();
    let (time_left, cook) = (
        CString::new("timeLeft").unwrap(),
        CString::new("cook").unwrap(),
    );
    let beta = ProclaimAlgorithm::Beta as c_int;
    group.bench_function("c by name", |b| {
        b.iter(|| {
            on = !on;
            let mut answer = false;
            let set = unsafe {
                proclaim_session_set(session, time_left.as_ptr(), ValueArgument(value(on)))
            };
            let asked = unsafe {
                proclaim_session_prove(session, cook.as_ptr(), AlgorithmArgument(beta), &mut answer)
            };
            black_box((set, asked, answer))
        })
    });
    group.bench_function("c by handle", |b| {
        b.iter(|| {
            on = !on;
            let mut answer = false;
            let set = unsafe {
                proclaim_session_set_input(session, time_left_handle, ValueArgument(value(on)))
            };
            let asked = unsafe {
                proclaim_session_prove_literal(
                    session,
                    cook_handle,
                    AlgorithmArgument(beta),
                    &mut answer,
                )
            };
            black_box((set, asked, answer))
        })
    });
    unsafe { proclaim_session_free(session) };
    group.finish();
}

criterion_group!(benches, overhead);
criterion_main!(benches);
