//! `proclaim verify`'s liveness options as users run them: `--eventually`, `--leads-to`,
//! `--always-eventually` and `--fair`, their lassos, scripts, exit codes and errors.

use crate::proclaim;
use std::process::Output;

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn the_microwave_stops_cooking_and_a_liveness_that_fails_prints_its_lasso() {
    let o = proclaim(&["verify", "microwave"]);
    assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
    assert!(
        stdout(&o)
            .contains("cooking stops: holds (leads_to Microwave.COOKING ~> !Microwave.COOKING)"),
        "{}",
        stdout(&o)
    );

    // Nothing makes the oven start: the button may never be pressed.
    let never_pressed = [
        "verify",
        "microwave",
        "--leads-to",
        "Microwave.IDLE ~> Microwave.COOKING",
    ];
    let o = proclaim(&never_pressed);
    assert_eq!(o.status.code(), Some(1), "{}", stdout(&o));
    let out = stdout(&o);
    assert!(out.contains("--leads-to: FAILS"), "{out}");
    assert!(out.contains("the way in, by rounds:\n  round 1\n"), "{out}");
    assert!(
        out.contains("then this loop, for ever:\n  round 2\n    Microwave: IDLE stays"),
        "{out}"
    );

    // Unless the environment presses it, the door shut, again and again.
    let mut fair = never_pressed.to_vec();
    fair.extend(["--fair", "timeLeft && !doorOpen"]);
    let o = proclaim(&fair);
    assert_eq!(o.status.code(), Some(0), "{}", stdout(&o));
    assert!(
        stdout(&o).contains("assuming fair timeLeft && !doorOpen"),
        "{}",
        stdout(&o)
    );

    // A run that ends: after DONE nothing rings, and IDLE never comes again.
    let o = proclaim(&[
        "verify",
        "microwave",
        "--always-eventually",
        "Microwave.IDLE",
        "--eventually",
        "Microwave.IDLE",
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stdout(&o));
    let out = stdout(&o);
    assert!(out.contains("--always-eventually: FAILS"), "{out}");
    assert!(
        out.contains("then no machine can ring any more, for ever"),
        "{out}"
    );
    assert!(out.contains("--eventually: holds"), "{out}");
}

#[test]
fn a_lasso_is_written_as_a_script_that_plays_its_loop_several_times() {
    let dir = crate::behaviour_folder("verify-lasso", &[]);
    let script = dir.join("lasso.script");
    let o = proclaim(&[
        "verify",
        "microwave",
        "--leads-to",
        "Microwave.IDLE ~> Microwave.COOKING",
        "--counterexample",
        script.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}{}", stdout(&o), stderr(&o));
    let text = std::fs::read_to_string(&script).expect("the script is written");
    assert!(text.contains("# A lasso: the way in to round 1"), "{text}");
    assert!(text.contains("so it is played 5 times"), "{text}");
    assert!(script.with_extension("jsonl").exists());
}

#[test]
fn liveness_options_refuse_bad_input_with_its_place() {
    let o = proclaim(&["verify", "microwave", "--leads-to", "Microwave.IDLE"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("`P ~> Q`"), "{}", stderr(&o));
    let o = proclaim(&[
        "verify",
        "microwave",
        "--leads-to",
        "Microwave.IDLE ~> Microwave.BAKING",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("column 19"), "{}", stderr(&o));
    let o = proclaim(&[
        "verify",
        "microwave",
        "--never",
        "Microwave.DONE",
        "--fair",
        "doorOpen",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("--fair is an assumption of liveness"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn liveness_is_emitted_as_ltl_for_spin() {
    let o = proclaim(&[
        "verify",
        "microwave",
        "--eventually",
        "Microwave.DONE",
        "--fair",
        "timeLeft",
        "--emit",
        "promela",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(
        stdout(&o).contains("ltl p0 { ([]<> acc[0] && []<> fair0_0) -> (<> lp0) }"),
        "{}",
        stdout(&o)
    );
}
