//! The C boundary's cost, side by side in one process: one input change and one question on the
//! microwave (`timeLeft` toggled, then β `cook`) through the Rust session, through the C API by
//! name, and through the C API by handle. The three loops take turns run by run, so a machine
//! that slows down slows all three; each prints its best and median run. The C functions are
//! called through their `extern "C"` symbols in this crate's library, as a C program calls them
//! (`examples/c/bench.c` is the same loop compiled as C).
//!
//! `cargo run --release -p proclaim-capi --example overhead -- 1000000 9` (iterations, runs)

use proclaim_capi::*;
use proclaim_cdl::{load, Algorithm, Engine, Language, Session};
use std::ffi::{c_int, CString};
use std::hint::black_box;
use std::time::Instant;

const MICROWAVE: &str = include_str!("../../../theories/microwave.dl");

fn value(on: bool) -> c_int {
    (if on {
        ProclaimValue::True
    } else {
        ProclaimValue::False
    }) as c_int
}

/// One way of asking, run `iterations` times; how many times `cook` was proved.
trait Way {
    fn name(&self) -> &'static str;
    fn run(&mut self, iterations: u64) -> u64;
}

struct Rust {
    session: Session,
    time_left: proclaim_cdl::Atom,
    cook: proclaim_cdl::Lit,
}

impl Way for Rust {
    fn name(&self) -> &'static str {
        "rust"
    }
    fn run(&mut self, iterations: u64) -> u64 {
        let mut proved = 0;
        for i in 0..iterations {
            let on = i % 2 == 0;
            self.session
                .set_input(self.time_left, Some(on))
                .expect("timeLeft takes a value");
            proved += u64::from(black_box(self.session.prove(Algorithm::Beta, self.cook)));
        }
        proved
    }
}

struct ByName {
    session: *mut ProclaimSession,
    time_left: CString,
    cook: CString,
}

impl Way for ByName {
    fn name(&self) -> &'static str {
        "c by name"
    }
    fn run(&mut self, iterations: u64) -> u64 {
        let mut proved = 0;
        for i in 0..iterations {
            let mut answer = false;
            let (set, asked) = unsafe {
                (
                    proclaim_session_set(
                        self.session,
                        self.time_left.as_ptr(),
                        ValueArgument(value(i % 2 == 0)),
                    ),
                    proclaim_session_prove(
                        self.session,
                        self.cook.as_ptr(),
                        AlgorithmArgument(ProclaimAlgorithm::Beta as c_int),
                        &mut answer,
                    ),
                )
            };
            assert_eq!((set, asked), (ProclaimStatus::Ok, ProclaimStatus::Ok));
            proved += u64::from(black_box(answer));
        }
        proved
    }
}

struct ByHandle {
    session: *mut ProclaimSession,
    time_left: ProclaimInput,
    cook: ProclaimLiteral,
}

impl Way for ByHandle {
    fn name(&self) -> &'static str {
        "c by handle"
    }
    fn run(&mut self, iterations: u64) -> u64 {
        let mut proved = 0;
        for i in 0..iterations {
            let mut answer = false;
            let (set, asked) = unsafe {
                (
                    proclaim_session_set_input(
                        self.session,
                        self.time_left,
                        ValueArgument(value(i % 2 == 0)),
                    ),
                    proclaim_session_prove_literal(
                        self.session,
                        self.cook,
                        AlgorithmArgument(ProclaimAlgorithm::Beta as c_int),
                        &mut answer,
                    ),
                )
            };
            assert_eq!((set, asked), (ProclaimStatus::Ok, ProclaimStatus::Ok));
            proved += u64::from(black_box(answer));
        }
        proved
    }
}

/// Two C sessions over the microwave with `doorOpen` false, and the handles of `timeLeft` and
/// `cook`.
fn c_sessions() -> (ByName, ByHandle) {
    let name = |text: &str| CString::new(text).expect("no NUL");
    let mut error = std::ptr::null_mut();
    let theory =
        unsafe { proclaim_theory_load(MICROWAVE.as_ptr().cast(), MICROWAVE.len(), &mut error) };
    assert!(!theory.is_null(), "the microwave loads");
    let (mut time_left, mut cook) = (0, 0);
    let sessions = unsafe {
        assert_eq!(
            proclaim_theory_input(theory, name("timeLeft").as_ptr(), &mut time_left),
            ProclaimStatus::Ok
        );
        assert_eq!(
            proclaim_theory_literal(theory, name("cook").as_ptr(), &mut cook),
            ProclaimStatus::Ok
        );
        let sessions = [proclaim_session_new(theory), proclaim_session_new(theory)];
        for session in sessions {
            let off = ProclaimValue::False as c_int;
            let set = proclaim_session_set(session, name("doorOpen").as_ptr(), ValueArgument(off));
            assert_eq!(set, ProclaimStatus::Ok);
        }
        proclaim_theory_free(theory);
        sessions
    };
    (
        ByName {
            session: sessions[0],
            time_left: name("timeLeft"),
            cook: name("cook"),
        },
        ByHandle {
            session: sessions[1],
            time_left,
            cook,
        },
    )
}

fn main() {
    let mut args = std::env::args().skip(1);
    let mut number = |default: u64| match args.next() {
        None => Ok(default),
        Some(text) => text
            .parse::<u64>()
            .ok()
            .filter(|n| *n > 0)
            .ok_or_else(|| format!("`{text}` is not a positive whole number")),
    };
    let (iterations, runs) = match (number(1_000_000), number(9)) {
        (Ok(i), Ok(r)) => (i, r as usize),
        (Err(why), _) | (_, Err(why)) => {
            eprintln!("{why}\nusage: overhead [ITERATIONS [RUNS]]");
            std::process::exit(2);
        }
    };
    let theory = load(MICROWAVE, Language::Dl).expect("the microwave loads");
    let (time_left, door, cook) = (
        theory.atom("timeLeft").expect("timeLeft"),
        theory.atom("doorOpen").expect("doorOpen"),
        theory.lit("cook").expect("cook"),
    );
    let mut session = Session::new(Engine::new(theory));
    session.set_input(door, Some(false)).expect("doorOpen");
    let (by_name, by_handle) = c_sessions();
    let mut ways: Vec<Box<dyn Way>> = vec![
        Box::new(Rust {
            session,
            time_left,
            cook,
        }),
        Box::new(by_name),
        Box::new(by_handle),
    ];
    let mut times = vec![Vec::with_capacity(runs); ways.len()];
    for _ in 0..runs {
        for (way, times) in ways.iter_mut().zip(&mut times) {
            let start = Instant::now();
            let proved = way.run(iterations);
            let elapsed = start.elapsed();
            assert_eq!(proved, iterations.div_ceil(2), "{}", way.name());
            times.push(elapsed.as_nanos() as f64 / iterations as f64);
        }
    }
    for (way, times) in ways.iter().zip(&mut times) {
        times.sort_by(f64::total_cmp);
        println!(
            "set + prove {:<11}: best {:.0} ns, median {:.0} ns per iteration ({runs} runs of {iterations} iterations)",
            way.name(),
            times[0],
            times[runs / 2]
        );
    }
}
