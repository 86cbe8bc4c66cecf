//! Behaviours whose labels a Prolog knowledge base or another program answers, through the
//! `proclaim` binary as the guide runs them: `run` to the final state, `check`'s located Prolog
//! warnings, `deps` knowing who answers. Each needs SWI-Prolog or python3: skipped without it,
//! failed without it when `CI` is set (`.ci/run` installs Debian's swi-prolog-nox).

use crate::proclaim;
use std::process::{Command, Output};

fn text(o: &Output) -> (String, String) {
    (
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// Whether `program` is on PATH; without it the test is skipped, unless `CI` is set.
fn present(program: &str) -> bool {
    let found = proclaim_experts::find_program(program).is_some();
    if !found {
        assert!(
            std::env::var_os("CI").is_none(),
            "{program} must be installed on CI (.ci/run installs swi-prolog-nox; python3 is in the image)"
        );
        eprintln!("skipped: {program} is not installed");
    }
    found
}

/// The guide's command line: the referee's off-side rule proved by SWI-Prolog, the flag up and
/// down again as the script moves the player and the ball.
#[test]
fn the_referee_runs_to_its_final_state_on_prologs_answers() {
    if !present("swipl") {
        return;
    }
    let o = proclaim(&["run", "machines/referee", "--for", "20s"]);
    let (out, err) = text(&o);
    assert!(o.status.success(), "{out}\n{err}");
    let states: Vec<&str> = out
        .lines()
        .filter_map(|l| l.split_once("Referee       → ").map(|(_, s)| s.trim()))
        .collect();
    assert_eq!(states, ["WATCH", "FLAG", "DOWN"], "{out}");
    assert!(out.contains("offside = true  (offside)"), "{out}");
    assert!(out.contains("finished in DOWN"), "{out}");
    assert!(out.contains("0 timed out"), "{out}");
}

/// The guide's ten-line Python program answers the goalkeeper's `ballNear`.
#[test]
fn the_keeper_dives_on_the_python_programs_answer() {
    if !present("python3") {
        return;
    }
    let o = proclaim(&["run", "machines/ball", "--for", "20s"]);
    let (out, err) = text(&o);
    assert!(o.status.success(), "{out}\n{err}");
    assert!(out.contains("ballNear = true  (ball)"), "{out}");
    assert!(out.contains("Keeper  finished in DIVE"), "{out}");
}

#[test]
fn a_process_expert_is_refused_on_the_virtual_clock() {
    let o = proclaim(&["run", "machines/referee", "--virtual-clock"]);
    let (_, err) = text(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("the expert `offside` is a process on the real clock"),
        "{err}"
    );
}

const REFEREE: &str =
    "machine Referee\nstate WATCH {\n    when offside && handball -> FLAG\n}\nstate FLAG {\n}\n";

/// `check` places each Prolog problem at its line, knows the labels a Prolog expert answers
/// (`offside`) and still says that nobody answers `handball`.
#[test]
fn check_places_prolog_problems_and_knows_its_labels() {
    if !present("swipl") {
        return;
    }
    let dir = crate::behaviour_folder(
        "prolog-check",
        &[
            (
                "behaviour.toml",
                "[[machine]]\nfile = \"Referee.machine\"\n\n[[prolog]]\nfile = \"rules.pl\"\nanswers = [\"offside\", \"onside\"]\ninputs = [\"behindBall\"]\n",
            ),
            ("Referee.machine", REFEREE),
            (
                "rules.pl",
                "% the rules\noffside :- value(behindBall, false).\nbroken :- value(x, .\n",
            ),
        ],
    );
    let folder = dir.to_str().unwrap();
    let o = proclaim(&["check", folder]);
    let (out, err) = text(&o);
    let rules = dir.join("rules.pl").display().to_string();
    assert!(
        err.contains(&format!("{rules}:3:")) && err.contains("Syntax error"),
        "{err}"
    );
    assert!(err.contains("label `onside` is not defined"), "{err}");
    assert!(
        err.contains("label `handball` is answered by no expert"),
        "{err}"
    );
    assert!(
        !err.contains("label `offside` is answered by no expert"),
        "{err}"
    );
    assert_eq!(o.status.code(), Some(1), "{out}\n{err}");
    assert!(out.contains("1 program expert"), "{out}");

    // The diagram: `offside` proclaimed by the Prolog expert in green, `handball` from unknown.
    let o = proclaim(&["deps", folder, "--module", "Referee"]);
    let (dot, err) = text(&o);
    assert!(o.status.success(), "{err}");
    assert!(
        dot.contains("\"rules\" -> \"Referee\" [color=green4, label=\"offside\"]"),
        "{dot}"
    );
    assert!(
        dot.contains("unknown -> \"Referee\" [color=red, fontcolor=red, label=\"handball\"]"),
        "{dot}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// `deps --launch` keeps the Prolog expert the machine needs.
#[test]
fn the_launch_manifest_keeps_the_prolog_expert() {
    let o = proclaim(&["deps", "machines/referee", "--launch", "Referee"]);
    let (out, err) = text(&o);
    assert!(o.status.success(), "{err}");
    assert!(out.contains("[[prolog]]"), "{out}");
    assert!(out.contains("offside.pl"), "{out}");
    assert!(out.contains("answers = [\"offside\"]"), "{out}");
}

/// Without SWI-Prolog, `check` says so at the knowledge base (a warning: the behaviour is
/// sound, the robot lacks a program) and `run` reports the expert that cannot start.
#[test]
fn a_missing_prolog_is_a_warning_at_the_knowledge_base() {
    let o = Command::new(env!("CARGO_BIN_EXE_proclaim"))
        .args(["check", "machines/referee"])
        .env("NO_COLOR", "1")
        .env("PROCLAIM_SWIPL", "/nonexistent/swipl")
        .output()
        .expect("the binary runs");
    let (out, err) = text(&o);
    assert!(o.status.success(), "{out}\n{err}");
    assert!(
        err.contains("offside.pl:1: warning: SWI-Prolog is not installed"),
        "{err}"
    );
}

/// The guide's Python expert is `machines/ball/ball.py` word for word, which the tests run.
#[test]
fn the_guide_shows_the_python_expert_the_tests_run() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let readme = std::fs::read_to_string(root.join("docs/book/src/experts.md")).unwrap();
    let program = std::fs::read_to_string(root.join("machines/ball/ball.py")).unwrap();
    assert_eq!(program.lines().count(), 10);
    assert!(
        readme.contains(&format!("```python\n{program}```")),
        "the guide's example differs from machines/ball/ball.py"
    );
}

/// A launch manifest written elsewhere runs its program expert where it ran: `ball.py` is
/// found from the new manifest.
#[test]
fn a_launch_manifest_written_elsewhere_runs_the_program_where_it_ran() {
    if !present("python3") {
        return;
    }
    let dir = crate::behaviour_folder("program-launch", &[]);
    let manifest = dir.join("keeper.toml");
    let manifest = manifest.to_str().unwrap();
    let o = proclaim(&[
        "deps",
        "machines/ball",
        "--launch",
        "Keeper",
        "-o",
        manifest,
    ]);
    assert!(o.status.success(), "{}", text(&o).1);
    let written = std::fs::read_to_string(manifest).unwrap();
    assert!(
        written.contains("[[expert]]") && written.contains("folder = "),
        "{written}"
    );
    let o = proclaim(&["run", manifest, "--for", "3s"]);
    let (out, err) = text(&o);
    assert!(o.status.success(), "{out}\n{err}");
    assert!(out.contains("ballNear = false  (ball)"), "{out}\n{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// The off-side rule in Prolog beside the theory it mirrors: the expert's default name, the
/// file's stem, is the theory's, and `check` says to rename one.
#[test]
fn an_expert_named_as_another_module_is_an_error() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("theories");
    let manifest = format!(
        "[[machine]]\nfile = \"Referee.machine\"\n\n[[theory]]\nfile = \"{dl}\"\n\n[[prolog]]\nfile = \"{pl}\"\nanswers = [\"offside\"]\n",
        dl = root.join("offside.dl").display(),
        pl = root.join("offside.pl").display(),
    );
    let dir = crate::behaviour_folder(
        "prolog-namesake",
        &[
            ("behaviour.toml", &manifest),
            (
                "Referee.machine",
                "machine Referee\nstate WATCH {\n    when offside -> FLAG\n}\nstate FLAG {\n}\n",
            ),
        ],
    );
    let o = proclaim(&["check", dir.to_str().unwrap()]);
    let (out, err) = text(&o);
    assert_eq!(o.status.code(), Some(1), "{out}\n{err}");
    assert!(err.contains("two modules are named `offside`"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}
