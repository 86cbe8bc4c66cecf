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

/// The cut-down player, as a user meets it: `verify` fails it with a counterexample
/// whose script posts a negative sighting, `run --script` replays it to RIGHT without a
/// warning, and a sum of free values is undecided with its reason, in words and in JSON.
#[test]
fn a_copied_sighting_fails_with_a_numeric_counterexample_that_replays() {
    let controllers =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("crates/verify/tests/controllers");
    let cutdown = controllers.join("cutdown");
    let script = std::env::temp_dir().join(format!("cutdown-{}.script", std::process::id()));
    let o = proclaim(&[
        "verify",
        cutdown.to_str().unwrap(),
        "--never",
        "A.RIGHT",
        "--counterexample",
        script.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}{}", stdout(&o), stderr(&o));
    assert!(stdout(&o).contains("--never: FAILS"), "{}", stdout(&o));
    let text = std::fs::read_to_string(&script).expect("the script is written");
    assert!(text.contains("\nballRR = -"), "{text}");
    // The command printed replays it from anywhere, and ends.
    let said = stderr(&o);
    let command = said
        .split("replay it with `proclaim ")
        .nth(1)
        .and_then(|rest| rest.split('`').next())
        .unwrap_or_else(|| panic!("no replay command in: {said}"));
    let replayed = std::process::Command::new(env!("CARGO_BIN_EXE_proclaim"))
        .args(command.split(' '))
        .current_dir(std::env::temp_dir())
        .output()
        .unwrap();
    assert_eq!(
        replayed.status.code(),
        Some(0),
        "{command}: {}",
        stderr(&replayed)
    );
    assert!(
        stdout(&replayed).contains("→ RIGHT"),
        "{}",
        stdout(&replayed)
    );
    let o = proclaim(&[
        "run",
        cutdown.to_str().unwrap(),
        "--script",
        script.to_str().unwrap(),
        "--virtual-clock",
        "--for",
        "2s",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(
        stdout(&o).contains("A             → RIGHT"),
        "{}",
        stdout(&o)
    );
    assert!(!stderr(&o).contains("warning"), "{}", stderr(&o));

    let sum = controllers.join("accumulator");
    let mut args = vec![
        "verify",
        sum.to_str().unwrap(),
        "--never",
        "Sum.FULL && total < 0",
    ];
    args.extend(["--max-states", "2000"]);
    let o = proclaim(&args);
    assert_eq!(o.status.code(), Some(3), "{}", stdout(&o));
    assert!(
        stdout(&o)
            .contains("step: `total + step` combines it with another free value, at Sum.machine:"),
        "{}",
        stdout(&o)
    );
    args.push("--json");
    let o = proclaim(&args);
    let json: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
    assert_eq!(json["report"]["inexact"][0]["value"], "step", "{json}");
    let _ = std::fs::remove_file(&script);
    let _ = std::fs::remove_file(script.with_extension("jsonl"));
}

/// `--json` prints a document on stdout whatever happens: bad input is `{"error": …}` with exit
/// 2 (it printed nothing, so a program reading it found no JSON at all).
#[test]
fn json_output_says_what_was_wrong_on_bad_input() {
    for (behaviour, why) in [
        (
            "microwave",
            "machine Microwave has no state or variable `ZZZ`",
        ),
        ("/nonexistent", "no behaviour `/nonexistent`"),
    ] {
        let o = proclaim(&["verify", behaviour, "--never", "Microwave.ZZZ", "--json"]);
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        let json: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON on stdout");
        assert!(json["error"].as_str().unwrap().contains(why), "{json}");
        assert_eq!(json["exit"], 2);
    }
}

/// A label atom the counterexample read before anything posted it (false to the model, as to
/// the runner) is posted false from the script's start: its replay asks no absent expert, so
/// it floods no warning, and still fires as the counterexample did.
#[test]
fn a_counterexamples_script_sets_what_its_ringlets_read_unposted() {
    let dir = crate::behaviour_folder(
        "verify-unposted",
        &[
            (
                "A.machine",
                "machine A\ninitial S\nstate S {\n    when b -> U\n    when a -> T\n}\nstate T { }\nstate U { }\n",
            ),
            ("behaviour.toml", "[[machine]]\nfile = \"A.machine\"\n"),
        ],
    );
    let script = dir.join("cx.script");
    let o = proclaim(&[
        "verify",
        dir.to_str().unwrap(),
        "--never",
        "A.T",
        "--counterexample",
        script.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}{}", stdout(&o), stderr(&o));
    let text = std::fs::read_to_string(&script).expect("the script is written");
    assert!(text.contains("b = false  # read, never posted"), "{text}");
    assert!(!stderr(&o).contains("no module answers"), "{}", stderr(&o));
    let trace = std::fs::read_to_string(script.with_extension("jsonl")).unwrap();
    assert!(trace.contains("\"state\":\"T\""), "{trace}");
}

/// A behaviour whose machines race (`schedule = "concurrent"`) is verified as it runs in
/// rounds, and `verify` says so on its error stream (its report, and `--json`, stay as they
/// are); one in rounds gets no such warning.
#[test]
fn a_concurrent_behaviour_is_verified_as_rounds_and_told_so() {
    let machine = "machine M\nstate A { when after(1s) -> B }\nstate B { }\n";
    let manifest = |schedule: &str| format!("{schedule}[[machine]]\nfile = \"M.machine\"\n");
    for (schedule, warned) in [("schedule = \"concurrent\"\n", true), ("", false)] {
        let dir = crate::behaviour_folder(
            &format!("verify-schedule-{warned}"),
            &[
                ("M.machine", machine),
                ("behaviour.toml", &manifest(schedule)),
            ],
        );
        let o = proclaim(&["verify", dir.to_str().unwrap(), "--reachable", "M.B"]);
        assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
        assert!(stdout(&o).contains("--reachable: holds"), "{}", stdout(&o));
        assert_eq!(
            stderr(&o).contains("verify models the round schedule"),
            warned,
            "{}",
            stderr(&o)
        );
    }
}

/// A counterexample says which clock a due time test counts from: the search's 3 s are LOOK's
/// (`machines/search`), not the head's current turn's. LOOK is no younger than its turns, so
/// the head has turned once before the search can give up (the first turn's 400 ms, tried
/// first, are up by then).
#[test]
fn a_composites_due_time_test_is_shown_with_its_composite() {
    let o = proclaim(&["verify", "machines/search", "--never", "Search.GIVE_UP"]);
    assert_eq!(o.status.code(), Some(1), "{}{}", stdout(&o), stderr(&o));
    let out = stdout(&o);
    assert!(
        out.contains("Search: LOOK.LEFT -> LOOK.RIGHT (when after_ms(400)); due: after_ms(400)")
            && out.contains(
                "Search: LOOK.RIGHT -> GIVE_UP (when after(3s)); due: after(3s) since LOOK"
            ),
        "{out}"
    );
}

/// A head and legs side by side (`machines/tracker`, §3.2): its properties over both regions
/// hold, every kick ends (each region's time its own), no transition as written is reported
/// never to fire for the combinations that cannot happen, and a counterexample names a move of
/// both regions in one ringlet with each region's clock.
#[test]
fn regions_verify_over_both_and_a_joined_move_shows_each_clock() {
    let o = proclaim(&["verify", "machines/tracker"]);
    assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
    assert_eq!(stdout(&o).matches(": holds").count(), 3, "{}", stdout(&o));
    assert!(!stdout(&o).contains("never fires"), "{}", stdout(&o));
    let o = proclaim(&[
        "verify",
        "machines/tracker",
        "--leads-to",
        "Striker.PLAY.LEGS.KICK ~> !Striker.PLAY.LEGS.KICK",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
    let o = proclaim(&[
        "verify",
        "machines/tracker",
        "--never",
        "Striker.PLAY.HEAD.SCAN_RIGHT && Striker.PLAY.LEGS.KICKED",
    ]);
    assert_eq!(o.status.code(), Some(1), "{}{}", stdout(&o), stderr(&o));
    assert!(
        stdout(&o).contains("(when after_ms(400) && after(1s)); due: after_ms(400) since PLAY.HEAD.SCAN_LEFT, after(1s) since PLAY.LEGS.KICK"),
        "{}",
        stdout(&o)
    );
}

/// The whole goalkeeper (`machines/goalkeeper`): a dive nested in the body's region beside the
/// head's, its fall a sub-machine given its side. Its four properties hold on both engines
/// (one over both regions, one over the sub-machine's state); a counterexample to "the keeper
/// never lies with its dive landed" replays in the runner to the head braced beside it.
#[test]
fn the_whole_goalkeeper_verifies_on_both_engines_and_its_counterexample_replays() {
    for engine in ["explicit", "symbolic"] {
        let o = proclaim(&["verify", "machines/goalkeeper", "--engine", engine]);
        assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
        assert_eq!(stdout(&o).matches(": holds").count(), 4, "{}", stdout(&o));
        for finding in ["never fires", "never entered"] {
            assert!(!stdout(&o).contains(finding), "{}", stdout(&o));
        }
    }
    let script = std::env::temp_dir().join(format!("goalkeeper-{}.script", std::process::id()));
    let o = proclaim(&[
        "verify",
        "machines/goalkeeper",
        "--never",
        "Goalkeeper.PLAY.BODY.DIVE.LIE && Dive.LANDED",
        "--counterexample",
        script.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}{}", stdout(&o), stderr(&o));
    let o = proclaim(&[
        "run",
        "machines/goalkeeper",
        "--script",
        script.to_str().unwrap(),
        "--virtual-clock",
        "--for",
        "3s",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(
        stdout(&o).contains("→ PLAY.HEAD.BRACE, PLAY.BODY.DIVE.LIE"),
        "{}",
        stdout(&o)
    );
    let _ = std::fs::remove_file(&script);
    let _ = std::fs::remove_file(script.with_extension("jsonl"));
}

/// A region's move back into its own state is one transition however the other regions stand:
/// it fires beside `a1`, so its combination with `a2`, which is never entered, does not make
/// it "never fires" (the differential test's seed 167 found it reported so).
#[test]
fn a_regions_move_back_into_its_own_state_is_one_finding_whatever_the_others_stand_in() {
    let machine = "machine M\nparallel P {\n    state A {\n        state a1 { }\n        state a2 { }\n    }\n    state B {\n        state b1 { when tick -> b1 }\n    }\n}\n";
    let dir = crate::behaviour_folder(
        "region-loop-findings",
        &[
            ("M.machine", machine),
            ("behaviour.toml", "[[machine]]\nfile = \"M.machine\"\n"),
        ],
    );
    let o = proclaim(&["verify", dir.to_str().unwrap()]);
    let said = format!("{}{}", stdout(&o), stderr(&o));
    assert!(said.contains("M.P.A.a2 is never entered"), "{said}");
    assert!(!said.contains("never fires"), "{said}");
    // A composite's move back into itself, which `in` keeps from firing beside `b2` (a review's
    // case): one finding or none, never one a combination.
    let machine = "machine M\nparallel P {\n    state A {\n        state D {\n            when again && in(B.b1) -> D\n            state d1 { when go -> d2 }\n            state d2 { }\n        }\n    }\n    state B {\n        state b1 { when flip && !again -> b2 }\n        state b2 { }\n    }\n}\n";
    let dir = crate::behaviour_folder(
        "composite-loop-findings",
        &[
            ("M.machine", machine),
            ("behaviour.toml", "[[machine]]\nfile = \"M.machine\"\n"),
        ],
    );
    let o = proclaim(&["verify", dir.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
    let said = format!("{}{}", stdout(&o), stderr(&o));
    assert!(!said.contains("never fires"), "{said}");
}

/// A composite's transition that stays is one finding, whichever state inside it fires from
/// (each copy stays where it fired): one that fires from one of them is never said not to fire,
/// and one that fires from none is said once (a review found a finding a copy).
#[test]
fn a_composites_transition_that_stays_is_one_finding_wherever_it_fires() {
    let machine = |label: &str| {
        format!("machine M\nstate P {{\n    when {label} {{\n        n = 1;\n    }}\n    state A {{ when go -> B }}\n    state B {{ when back -> A }}\n}}\n")
    };
    let said = |tag: &str, label: &str| {
        let dir = crate::behaviour_folder(
            tag,
            &[
                ("M.machine", machine(label).as_str()),
                ("behaviour.toml", "[[machine]]\nfile = \"M.machine\"\n"),
            ],
        );
        let o = proclaim(&["verify", dir.to_str().unwrap()]);
        assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
        format!("{}{}", stdout(&o), stderr(&o))
    };
    let once = said("stays-findings", "tick && in(A)");
    assert!(!once.contains("never fires"), "{once}");
    let never = said("stays-never-findings", "tick && in(A) && in(B)");
    assert_eq!(never.matches("never fires").count(), 1, "{never}");
    assert!(
        never.contains("the transition P -> P (when tick && in(A) && in(B), line 3) never fires"),
        "{never}"
    );
}

/// Two regions that move on one label together only ever fire their joined arm: neither
/// transition is reported never to fire (a review found the first one was).
#[test]
fn a_transition_that_only_fires_joined_with_another_regions_is_not_reported_never_firing() {
    let machine = "machine M\nparallel P {\n    state A {\n        state a1 { when go -> a2 }\n        state a2 { }\n    }\n    state B {\n        state b1 { when go -> b2 }\n        state b2 { }\n    }\n}\n";
    let dir = crate::behaviour_folder(
        "joined-findings",
        &[
            ("M.machine", machine),
            ("behaviour.toml", "[[machine]]\nfile = \"M.machine\"\n"),
        ],
    );
    // No property: the whole graph is searched, so never-fires findings are said.
    let o = proclaim(&["verify", dir.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
    assert!(!stdout(&o).contains("never fires"), "{}", stdout(&o));
}

/// A deadlock found with the clocks of different machines unordered is said unconfirmed only
/// where its run does not follow through the model with them ordered.
#[test]
fn a_deadlocks_run_is_followed_with_the_clocks_of_different_machines_ordered() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let said = |o: &std::process::Output| stdout(o) + &stderr(o);
    // The waiter waits for ever once Quick and Slow are done: a run with the clocks ordered.
    let real = root.join("tests/clocks-deadlock");
    let o = proclaim(&["verify", real.to_str().expect("UTF-8")]);
    let out = said(&o);
    assert_eq!(o.status.code(), Some(0), "{out}");
    assert!(
        out.contains("deadlock: nothing can fire any more while Waiter.W wait"),
        "{out}"
    );
    assert!(!out.contains("unordered against each other"), "{out}");
    // Quick is stuck only if Slow's three seconds are up before its half second: no run is.
    let stuck = root.join("tests/clocks-stuck");
    let stuck = stuck.to_str().expect("UTF-8");
    let out = said(&proclaim(&["verify", stuck]));
    assert!(
        out.contains("deadlock: nothing can fire any more while Quick.STUCK wait"),
        "{out}"
    );
    assert!(
        out.contains("the clocks of Quick, Slow unordered against each other"),
        "{out}"
    );
    let out = said(&proclaim(&["verify", stuck, "--clock-order"]));
    assert!(!out.contains("deadlock"), "{out}");
}

/// Quick's half second and Slow's three start in one round. The search takes the clocks of
/// different machines unordered, so it finds Slow leaving S with Quick still in A; checked
/// again with them ordered, the property holds. `--clock-order` orders every property from
/// the start, and `--emit` writes the ordered model. Where the ordered check runs out of
/// budget (four more machines with timeouts, a small budget), the run found is followed
/// through the ordered model: one that needs a timeout out of order is not, and the property
/// is undecided, the report naming the machines; one that does not (a button pressed three
/// times) is, and decides.
#[test]
fn clocks_of_different_machines_are_ordered_where_a_run_decides_a_verdict() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = root.join("crates/verify/tests/agree/machine-clocks");
    let dir = dir.to_str().expect("a path in UTF-8");
    let never = ["verify", dir, "--never", "Slow.LATE && Quick.A"];
    let o = proclaim(&never);
    assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
    let out = stdout(&o);
    assert!(out.contains("--never: holds"), "{out}");
    assert!(
        out.contains("checked again with the clocks of different machines ordered"),
        "{out}"
    );
    assert!(!out.contains("unordered"), "{out}");
    let mut ordered = never.to_vec();
    ordered.push("--clock-order");
    let o = proclaim(&ordered);
    assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
    let out = stdout(&o);
    assert!(out.contains("--never: holds"), "{out}");
    assert!(!out.contains("checked again"), "{out}");
    // SPIN's model is the ordered one.
    let mut emit = never.to_vec();
    emit.extend(["--emit", "promela"]);
    let o = proclaim(&emit);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(stdout(&o).contains("byte ord["), "{}", stdout(&o));

    let crowded = root.join("tests/clocks-crowded");
    let crowded = crowded.to_str().expect("a path in UTF-8");
    // The symbolic engine finds the first run; the ordered search runs out, and the run,
    // which needs Slow's three seconds up before Quick's half second, is not followed.
    let crowded_check = |property: &str| {
        proclaim(&[
            "verify",
            crowded,
            "--never",
            property,
            "--max-states",
            "5000",
            "--engine",
            "symbolic",
        ])
    };
    let o = crowded_check("late == 1 && Quick.A");
    assert_eq!(o.status.code(), Some(3), "{}{}", stdout(&o), stderr(&o));
    let out = stdout(&o);
    assert!(
        out.contains("--never: undecided (its run not confirmed with the clocks"),
        "{out}"
    );
    assert!(
        out.contains("the clocks of Quick, Slow, M1, M2, M3, M4 unordered"),
        "{out}"
    );
    assert!(!out.contains("shortest counterexample"), "{out}");
    // Three presses need no clock out of order: their run is followed through the ordered
    // model, whatever the clocks did, and decides.
    let o = crowded_check("Button.HELD");
    assert_eq!(o.status.code(), Some(1), "{}{}", stdout(&o), stderr(&o));
    let out = stdout(&o);
    assert!(
        out.contains("--never: FAILS (its run, found with the clocks of different machines unordered, followed with them ordered)"),
        "{out}"
    );
    assert!(out.contains("a counterexample, by rounds:"), "{out}");
    assert!(
        out.contains("Button: THRICE -> HELD (when pressed)"),
        "{out}"
    );
    assert!(!out.contains("unordered against each other"), "{out}");
    // A lasso is followed exactly, round its loop until the ordered worlds at its start
    // come back: the button held, the toggles go on for ever.
    let o = proclaim(&[
        "verify",
        crowded,
        "--always-eventually",
        "Button.UP",
        "--max-states",
        "1000",
        "--engine",
        "symbolic",
        "--json",
    ]);
    assert_eq!(o.status.code(), Some(1), "{}{}", stdout(&o), stderr(&o));
    let report: serde_json::Value = serde_json::from_str(&stdout(&o)).expect("JSON");
    let p = &report["report"]["properties"][0];
    assert_eq!(p["verdict"], "fails", "{p}");
    assert_eq!(p["followed"], true, "{p}");
    let looped = p["cycle"]["steps"].as_array().expect("a loop");
    assert!(!looped.is_empty(), "{p}");
    // Each machine ends the loop in the state it started it in.
    let (mut first, mut last) = (serde_json::Map::new(), serde_json::Map::new());
    for s in looped {
        let machine = s["machine"].as_str().expect("a machine").to_string();
        first.entry(machine.clone()).or_insert(s["from"].clone());
        let to = if s["to"].is_null() {
            &s["from"]
        } else {
            &s["to"]
        };
        last.insert(machine, to.clone());
    }
    assert_eq!(first, last, "{p}");
    assert!(
        (looped.iter()).all(|s| s["machine"] != "Button" || s["from"] == "HELD"),
        "{p}"
    );
}
