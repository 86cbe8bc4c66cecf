//! Embedding the reasoner: load a theory, hold a session, change inputs as sensors report, ask
//! the outputs, and explain an answer. Run with `cargo run --example embed`; the suite runs its
//! test below (`test = true` in Cargo.toml), built with the rest of the suite.

use proclaim_cdl::{load_named, Algorithm, Engine, Language, Session};
use std::error::Error;
use std::io::Write;

const MICROWAVE: &str = include_str!("../theories/microwave.dl");

fn main() -> Result<(), Box<dyn Error>> {
    embed(&mut std::io::stdout().lock())
}

/// The whole example, written to `out`.
fn embed(out: &mut impl Write) -> Result<(), Box<dyn Error>> {
    // A theory that does not load says why, line by line with a caret, through `?`.
    let theory = load_named("microwave.dl", MICROWAVE, Language::Dl)?;
    let door = theory.atom("doorOpen").ok_or("no input doorOpen")?;
    let time = theory.atom("timeLeft").ok_or("no input timeLeft")?;
    let cook = theory.lit("cook").ok_or("no output cook")?;
    let light = theory.lit("light").ok_or("no output light")?;

    let mut session = Session::new(Engine::new(theory));
    // Sensor postings arrive one at a time; unknown inputs stay unknown until posted.
    for (door_open, time_left) in [(false, false), (false, true), (true, true), (false, true)] {
        session.set_input(door, Some(door_open))?;
        session.set_input(time, Some(time_left))?;
        writeln!(
            out,
            "door open {door_open:<5}  time left {time_left:<5}  ->  cook {:<5}  light {}",
            session.prove(Algorithm::Beta, cook),
            session.prove(Algorithm::Beta, light)
        )?;
    }
    write!(out, "{}", session.explain(Algorithm::Beta, cook, 1))?;
    Ok(())
}

#[test]
fn the_embedding_example_runs() {
    let mut out = Vec::new();
    embed(&mut out).expect("the example runs");
    let text = String::from_utf8(out).expect("text");
    assert!(
        text.contains("door open false  time left true   ->  cook true   light true"),
        "{text}"
    );
    assert!(text.contains("+beta cook"), "{text}");
}
