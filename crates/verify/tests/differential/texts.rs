//! Text among the random behaviours' free inputs (issue 44): a third input `in2` that a sensor
//! posts as text, copied into the global `t0` and compared, as itself and as the copy, with
//! text constants in labels. Drawn from a sequence of its own, over the numbers' behaviour once
//! it is written, so that a seed without text makes the behaviour and the scripts it always
//! made.

use crate::common::random_behaviour::Rng;
use std::fmt::Write;

/// The text constants the behaviours compare with.
const WORDS: [&str; 3] = ["go", "stop", ""];

/// `machine` (a `.machine` file's text) with text read, copied and tested, or as it was: every
/// activity reads `in2` and sets `t0`, and one label in four also tests `in2` or `t0`.
pub(super) fn with_text(machine: &str, rng: &mut Rng) -> String {
    if !rng.chance(35) {
        return machine.to_string();
    }
    let mut out = String::new();
    // The copy is tested only where something sets it: an unset `t0` is the number 0.
    let copies = machine.contains("extern in1; ");
    for line in machine.lines() {
        let mut line = line.to_string();
        if line.contains("extern in1; ") {
            let set = if rng.chance(60) {
                "t0 = in2;".to_string()
            } else {
                format!("t0 = \"{}\";", rng.pick(&WORDS))
            };
            line = line.replacen(
                "extern in1; ",
                &format!("extern in1; extern in2; {set} "),
                1,
            );
        }
        let indent = line.len() - line.trim_start().len();
        let label_at = indent + "when ".len();
        let written = line[indent..].starts_with("when ") && !line[label_at..].starts_with("done");
        if written && rng.chance(25) {
            let rest = &line[label_at..];
            let end = rest
                .find(" -> ")
                .or_else(|| rest.find(" { "))
                .unwrap_or(rest.len());
            let joint = rng.pick(&["&&", "||"]);
            let test = term(rng, copies);
            line = format!(
                "{}when ({}) {joint} {test}{}",
                &line[..indent],
                &rest[..end],
                &rest[end..]
            );
        }
        let _ = writeln!(out, "{line}");
    }
    out
}

/// A test of the text input or of its copy.
fn term(rng: &mut Rng, copies: bool) -> String {
    let name = if copies && rng.chance(50) {
        "t0"
    } else {
        "in2"
    };
    let op = rng.pick(&["==", "!="]);
    if copies && rng.chance(15) {
        // Copies compared with each other: every order of them must be in the domain.
        return format!("in2 {op} t0");
    }
    format!("{name} {op} \"{}\"", rng.pick(&WORDS))
}

/// The script lines that post `in2`: at the start, and now and again after, as the numbers'
/// script does.
pub(super) fn script(rng: &mut Rng) -> String {
    let word = |rng: &mut Rng| *rng.pick(&["go", "stop", "", "kick"]);
    let mut out = format!("in2 = \"{}\"\n", word(rng));
    for step in 1..=20 {
        if rng.chance(30) {
            let _ = writeln!(out, "at {}ms in2 = \"{}\"", step * 50, word(rng));
        }
    }
    out
}
