//! Embedding the reasoner: load a theory, hold a session, change inputs as sensors report, ask
//! the outputs, and explain an answer. Run with `cargo run --example embed`.

use proclaim_cdl::{load, Algorithm, Engine, Language, Session};

const MICROWAVE: &str = include_str!("../theories/microwave.dl");

fn main() {
    let theory = match load(MICROWAVE, Language::Dl) {
        Ok(theory) => theory,
        Err(errors) => {
            eprint!(
                "{}",
                proclaim_syntax::render(&errors, "microwave.dl", MICROWAVE, false)
            );
            std::process::exit(2);
        }
    };
    let door = theory.atom("doorOpen").expect("declared input");
    let time = theory.atom("timeLeft").expect("declared input");
    let cook = theory.lit("cook").expect("an output");
    let light = theory.lit("light").expect("an output");

    let mut session = Session::new(Engine::new(theory));
    // Sensor postings arrive one at a time; unknown inputs stay unknown until posted.
    for (door_open, time_left) in [(false, false), (false, true), (true, true), (false, true)] {
        session
            .set_input(door, Some(door_open))
            .expect("consistent");
        session
            .set_input(time, Some(time_left))
            .expect("consistent");
        println!(
            "door open {door_open:<5}  time left {time_left:<5}  ->  cook {:<5}  light {}",
            session.prove(Algorithm::Beta, cook),
            session.prove(Algorithm::Beta, light)
        );
    }
    print!("{}", session.explain(Algorithm::Beta, cook, 1));
}
