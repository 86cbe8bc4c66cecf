//! Whole behaviours from `machines/`, loaded from their manifests and run on a paused clock with
//! the impersonator standing in for the GameController and the kitchen, so every trace is
//! exact. Also what loading says about a broken behaviour.

use proclaim_behaviour::{launch, load, Folder, LaunchOptions, TraceView};
use proclaim_board::Whiteboard;
use proclaim_experts::parse_script;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Duration;

fn behaviour_dir(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("machines")
        .join(name)
}

/// Runs a behaviour until every started machine is in a final state, or `limit`; returns the
/// readable trace with answers that repeat left out (as `proclaim run` prints it).
async fn run(name: &str, script: Option<&str>, limit: Duration) -> (Vec<String>, Whiteboard) {
    run_with(name, script, limit, &[]).await
}

/// The same, with raw sensor postings `(when, type, value)` made while it runs, as a robot's
/// drivers would.
async fn run_with(
    name: &str,
    script: Option<&str>,
    limit: Duration,
    sensors: &[(Duration, &str, bool)],
) -> (Vec<String>, Whiteboard) {
    run_folder(name, &behaviour_dir(name), script, limit, sensors).await
}

async fn run_folder(
    name: &str,
    dir: &Path,
    script: Option<&str>,
    limit: Duration,
    sensors: &[(Duration, &str, bool)],
) -> (Vec<String>, Whiteboard) {
    let behaviour =
        load(name, Arc::new(Folder::new(dir))).unwrap_or_else(|e| panic!("{name} loads: {e:#?}"));
    let board = Whiteboard::local();
    let options = LaunchOptions {
        script: script.map(|s| parse_script(s).expect("script parses")),
        ..Default::default()
    };
    let mut running = launch(&behaviour, &board, options).await.expect("starts");
    let drivers = board.clone();
    let postings: Vec<(Duration, String, bool)> = sensors
        .iter()
        .map(|(t, ty, v)| (*t, ty.to_string(), *v))
        .collect();
    let start = tokio::time::Instant::now();
    tokio::spawn(async move {
        for (at, ty, value) in postings {
            tokio::time::sleep_until(start + at).await;
            drivers.post("sensors", &ty, value);
        }
    });
    let mut view = TraceView::new(0);
    let mut lines = running.notes.clone();
    let deadline = tokio::time::Instant::now() + limit;
    while let Ok(Some(event)) = tokio::time::timeout_at(deadline, running.events.recv()).await {
        if let Some(line) = view.line(&event) {
            lines.push(line.split_whitespace().collect::<Vec<_>>().join(" "));
        }
        if running.observe(&event) {
            break;
        }
    }
    running.stop().await;
    (lines, board)
}

/// The trace's lines that say a machine entered a state.
fn transitions(trace: &[String]) -> Vec<&str> {
    trace
        .iter()
        .filter(|l| l.contains('→'))
        .map(String::as_str)
        .collect()
}

#[tokio::test(start_paused = true)]
async fn the_game_controller_plays_a_scripted_game_to_finished() {
    let script = "\
        at 1s readyReceived = true
        at 2s readyReceived = false
        at 2s setReceived = true
        at 3s setReceived = false
        at 3s playingReceived = true
        at 4s penaltyReceived = true
        at 6s penaltyReceived = false
        at 9s playingReceived = false
        at 9s finishedReceived = true
    ";
    let (trace, board) = run("game_controller", Some(script), Duration::from_secs(30)).await;
    let states = transitions(&trace);
    assert_eq!(
        states,
        [
            "0.000s GameController → INITIAL",
            "1.000s GameController → READY",
            "1.000s Placer → LOOK",
            "1.300s Placer → WALK",
            "1.800s Placer → IN_POSITION",
            "2.000s GameController → SET",
            "3.000s GameController → PLAYING",
            "4.000s GameController → PENALIZED",
            "6.000s GameController → PLAYING",
            "9.000s GameController → FINISHED",
        ],
        "{trace:#?}"
    );
    // The receiver and its simulator stand down for the script; the chest button still answers.
    assert_eq!(
        trace[0],
        "left out gamecontroller: the script impersonates readyReceived, setReceived, playingReceived, finishedReceived, penaltyReceived"
    );
    assert!(
        trace.contains(
            &"0.000s GameController shortChestButtonPressed = false (chestButton)".to_string()
        ),
        "{trace:#?}"
    );
    assert!(
        trace.contains(&"4.000s GameController penaltyReceived = true (impersonator)".to_string())
    );
    assert!(trace.contains(&"2.000s Placer told Off".to_string()));
    assert!(trace.contains(
        &"6.000s GameController fires on ~penaltyReceived && playingReceived".to_string()
    ));
    assert_eq!(
        board.latest("Say").unwrap().value.to_string(),
        "\"game over\""
    );
    assert_eq!(board.truth("PlacerIsRunning"), Some(false));
}

#[tokio::test(start_paused = true)]
async fn the_chest_button_penalises_by_hand_before_kick_off() {
    // The raw contact, as the robot's button driver posts it: a 200 ms press at 1 s.
    let (trace, board) = run_with(
        "game_controller",
        Some("at 5s finishedReceived = true\npenaltyReceived = false\n"),
        Duration::from_secs(10),
        &[
            (Duration::from_secs(1), "ChestButton", true),
            (Duration::from_millis(1200), "ChestButton", false),
        ],
    )
    .await;
    let states = transitions(&trace);
    assert_eq!(
        states,
        [
            "0.000s GameController → INITIAL",
            "1.230s GameController → PENALIZED",
            "5.000s GameController → FINISHED",
        ],
        "{trace:#?}"
    );
    assert_eq!(
        board.latest("LEDS").unwrap().value.to_string(),
        "\"ChestBoard Off\""
    );
}

#[tokio::test(start_paused = true)]
async fn the_microwave_cooks_for_a_minute_as_its_theory_decides() {
    // The kitchen script of the behaviour itself: door open at 1 s, shut at 3 s, button at 4 s.
    let (trace, board) = run("microwave", None, Duration::from_secs(120)).await;
    let interesting: Vec<&str> = trace
        .iter()
        .filter(|l| l.contains('→') || l.contains("(microwave)"))
        .map(String::as_str)
        .collect();
    assert_eq!(
        interesting,
        [
            "0.000s Microwave → IDLE",
            "0.000s Microwave cook = false (microwave)",
            "0.000s Microwave light = false (microwave)",
            "1.000s Microwave light = true (microwave)",
            "1.000s Microwave → OPEN",
            "3.000s Microwave light = false (microwave)",
            "3.000s Microwave → IDLE",
            "4.000s Microwave cook = true (microwave)",
            "4.000s Microwave → COOKING",
            "64.000s Microwave → DONE",
        ],
        "{trace:#?}"
    );
    assert_eq!(
        board.latest("Magnetron").unwrap().value.to_string(),
        "\"off\""
    );
    assert_eq!(board.truth("timeLeft"), Some(false));
}

#[tokio::test(start_paused = true)]
async fn opening_the_door_stops_the_magnetron_at_once() {
    let script =
        "doorOpen = false\ntimeLeft = false\nat 1s timeLeft = true\nat 10s doorOpen = true\n";
    let (trace, board) = run("microwave", Some(script), Duration::from_secs(12)).await;
    let states = transitions(&trace);
    assert_eq!(
        states,
        [
            "0.000s Microwave → IDLE",
            "1.000s Microwave → COOKING",
            "10.000s Microwave → OPEN",
        ],
        "{trace:#?}"
    );
    assert!(
        trace.contains(&"10.000s Microwave posts Magnetron: off".to_string()),
        "{trace:#?}"
    );
    assert_eq!(board.latest("Light").unwrap().value.to_string(), "\"on\"");
}

fn temp_behaviour(files: &[(&str, &str)]) -> PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!(
        "proclaim-behaviour-{}-{}",
        std::process::id(),
        files.len() * 31 + files[0].1.len()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, text) in files {
        std::fs::write(dir.join(name), text).unwrap();
    }
    dir
}

#[test]
fn a_broken_behaviour_reports_every_problem_with_file_and_line() {
    let dir = temp_behaviour(&[
        (
            "behaviour.toml",
            "[[machine]]\nfile = \"A.machine\"\n\n[[machine]]\nfile = \"B.machine\"\nstart = false\n\n[[theory]]\nfile = \"t.dl\"\n",
        ),
        ("A.machine", "machine A\nstate S {\n  when x -> Nowhere\n}\n"),
        ("B.machine", "machine B\nstate S {\n  entry {\n"),
        ("t.dl", "a => b\n"),
    ]);
    let problems = match load("broken", Arc::new(Folder::new(&dir))) {
        Ok(_) => panic!("a broken behaviour must not load"),
        Err(e) => e,
    };
    // A theory's problem has its line and column too, as its own reader gives them.
    let theory = &problems[2];
    assert!(
        theory.file.ends_with("t.dl") && theory.is_error(),
        "{problems:#?}"
    );
    assert_eq!(
        (theory.line, theory.column),
        (Some(1), Some(7)),
        "{problems:#?}"
    );
    let errors: Vec<String> = problems.iter().map(ToString::to_string).collect();
    let shown = |f: &str| dir.join(f).display().to_string();
    assert_eq!(
        errors[0],
        format!(
            "{}:3: error: there is no state named `Nowhere`",
            shown("A.machine")
        )
    );
    assert_eq!(
        errors[1],
        format!("{}:4: error: the file ends too early; expected one of `call`, `code`, a name, a quoted string, `}}`, a statement", shown("B.machine"))
    );
    assert!(
        errors[2].contains("t.dl") && errors[2].contains("error"),
        "{errors:#?}"
    );

    let dir = temp_behaviour(&[(
        "behaviour.toml",
        "[[machine]]\nfile = \"A.machine\"\nstrat = false\n",
    )]);
    let errors = load("typo", Arc::new(Folder::new(&dir))).err().unwrap();
    assert!(
        errors[0].to_string().ends_with("behaviour.toml:3: error: unknown field `strat`, expected one of `file`, `start`, `name`, `priority`, `params`"),
        "{errors:#?}"
    );
}

#[test]
fn check_finds_what_only_the_whole_behaviour_shows() {
    let dir = temp_behaviour(&[
        (
            "behaviour.toml",
            "[[machine]]\nfile = \"Main.machine\"\n\n[[machine]]\nfile = \"Helper.machine\"\nstart = false\n\n[[theory]]\nfile = \"t.dl\"\n\n[[module]]\nname = \"leds\"\nreads = [\"LEDS\"]\n",
        ),
        (
            "Main.machine",
            "machine Main\nstate A {\n  entry {\n    Helper: On\n    Helpr: On\n    Ghost: restart\n    LEDS: red\n    Beep: twice\n    sensors_postJoints: On\n  }\n  when TRUE -> B\n  when cook -> B\n  when mystery -> B\n}\nstate B {\n  when ~HelperIsRunning -> A\n  when ~HelperIsRunning -> B\n}\nstate Lost {\n}\n",
        ),
        ("Helper.machine", "machine Helper\nstate H {\n}\n"),
        (
            "t.dl",
            "input{door}.\ninput{timer}.\nR1: timer => cook.\nR2: door => ~cook.\nR2 > R1.\nR3: door => light.\noutput{beta cook}.\noutput{beta light}.\n",
        ),
    ]);
    let behaviour = load("whole", Arc::new(Folder::new(&dir))).unwrap();
    let findings: Vec<String> = proclaim_behaviour::check_behaviour(&behaviour)
        .iter()
        .map(|d| d.to_string().replace(&format!("{}/", dir.display()), ""))
        .collect();
    assert_eq!(
        findings,
        [
            "Main.machine:12: warning: `cook` is never tried: `TRUE` above it (line 11) always fires first",
            "Main.machine:13: warning: `mystery` is never tried: `TRUE` above it (line 11) always fires first",
            "Main.machine:17: warning: `~HelperIsRunning` never fires: the same label above it (line 16) is tried first",
            "Main.machine:19: warning: state Lost is never reached from the initial state A",
            "Main.machine:13: error: label `mystery` is answered by no expert and posted by no module",
            "Main.machine:2: error: `Helpr: On` controls a machine `Helpr` the behaviour does not have (did you mean `Helper`?)",
            "Main.machine:2: error: `Ghost: restart` controls a machine `Ghost` the behaviour does not have (and no module reads `Ghost`)",
            "Main.machine:2: warning: nobody listens to `Beep` postings (name the module that does in the manifest's [[module]] or dictionary)",
            "Main.machine:2: warning: nobody listens to `sensors_postJoints` postings (name the module that does in the manifest's [[module]] or dictionary; `sensors_postJoints: On` is a plain posting, no machine is named `sensors_postJoints`)",
            "t.dl:8: warning: output `light` of theory t is queried by no machine",
            "t.dl:1: warning: input `door` of theory t is posted by no module",
            "t.dl:2: warning: input `timer` of theory t is posted by no module",
        ]
    );
}

/// A composite's OnEntry runs in each flat state inside it: a posting in it that nobody hears
/// is said once, at the composite that wrote it.
#[test]
fn a_composites_posting_nobody_hears_is_said_once_where_it_is_written() {
    let dir = temp_behaviour(&[
        ("behaviour.toml", "[[machine]]\nfile = \"Main.machine\"\n"),
        (
            "Main.machine",
            "machine Main\ninitial PLAY\nstate PLAY {\n  entry {\n    Ghost: suspend\n  }\n  state A { when TRUE -> B }\n  state B { when TRUE -> A }\n}\n",
        ),
    ]);
    let behaviour = load("chart", Arc::new(Folder::new(&dir))).unwrap();
    let findings: Vec<String> = proclaim_behaviour::check_behaviour(&behaviour)
        .iter()
        .map(|d| d.to_string().replace(&format!("{}/", dir.display()), ""))
        .filter(|d| d.contains("Ghost"))
        .collect();
    assert_eq!(
        findings,
        ["Main.machine:3: error: `Ghost: suspend` controls a machine `Ghost` the behaviour does not have (and no module reads `Ghost`)"]
    );
}

/// The Griffith team's head tracker posts `sensors_postJoints: On` and `SpeechOutput: On` to
/// the robot's own modules, not to machines: `check` says nobody in the behaviour listens
/// (a warning), not that a machine is missing (it once refused the file).
#[test]
fn a_control_word_to_a_sensor_wrapper_is_a_plain_posting() {
    let Some(corpus) = crate::corpus_dir() else {
        eprintln!("skipped: ../shared/corpus is absent");
        return;
    };
    let file = "SMHeadBallTrackerFair.fsm";
    let text = std::fs::read_to_string(corpus.join("mipal/machines").join(file)).unwrap();
    let manifest = format!("[[machine]]\nfile = \"{file}\"\n");
    let dir = temp_behaviour(&[("behaviour.toml", &manifest), (file, &text)]);
    let behaviour = load("tracker", Arc::new(Folder::new(&dir))).unwrap();
    let findings: Vec<String> = proclaim_behaviour::check_behaviour(&behaviour)
        .iter()
        .map(|d| d.to_string())
        .filter(|d| d.contains("`sensors_postJoints`") || d.contains("`SpeechOutput`"))
        .collect();
    assert_eq!(findings.len(), 2, "{findings:#?}");
    assert!(
        findings
            .iter()
            .all(|d| d.contains("warning: nobody listens") && d.contains("a plain posting")),
        "{findings:#?}"
    );
}

/// A posting written as a statement, `post("Ghost", "suspend")` or `suspend("Ghost")`, alone
/// or inside a loop, is held to the behaviour as `Ghost: suspend` is (`check` once did not see
/// a statement's posting at all).
#[test]
fn a_posting_written_as_a_statement_is_checked_as_one() {
    let main = "machine Main\ninitial A\nstate A {\n  entry { post(\"sensors_postJoints\", \"On\"); post(\"Helpr\", \"On\"); }\n  when TRUE -> B\n}\nstate B {\n  entry { int i; for (i = 0; i < 2; i = i + 1) { suspend(\"Ghost\"); post(\"Beep\", i); } }\n}\n";
    let dir = temp_behaviour(&[
        (
            "behaviour.toml",
            "[[machine]]\nfile = \"Main.machine\"\n\n[[machine]]\nfile = \"Helper.machine\"\nstart = false\n",
        ),
        ("Main.machine", main),
        ("Helper.machine", "machine Helper\nstate H {\n}\n"),
    ]);
    let behaviour = load("statements", Arc::new(Folder::new(&dir))).unwrap();
    let findings: Vec<String> = proclaim_behaviour::check_behaviour(&behaviour)
        .iter()
        .map(|d| d.to_string().replace(&format!("{}/", dir.display()), ""))
        .collect();
    assert_eq!(
        findings,
        [
            "Main.machine:3: warning: nobody listens to `sensors_postJoints` postings (name the module that does in the manifest's [[module]] or dictionary; `sensors_postJoints: On` is a plain posting, no machine is named `sensors_postJoints`)",
            "Main.machine:3: error: `Helpr: On` controls a machine `Helpr` the behaviour does not have (did you mean `Helper`?)",
            "Main.machine:7: error: `Ghost: suspend` controls a machine `Ghost` the behaviour does not have (and no module reads `Ghost`)",
            "Helper.machine:1: warning: sub-machine `Helper` has `start = false` and no module posts `Helper: On`, so it never runs",
        ]
    );
    // Started by a statement in a loop, the helper runs.
    let started = main.replace("post(\"Beep\", i);", "restart(\"Helper\");");
    std::fs::write(dir.join("Main.machine"), started).unwrap();
    let behaviour = load("statements", Arc::new(Folder::new(&dir))).unwrap();
    let findings = proclaim_behaviour::check_behaviour(&behaviour);
    assert!(
        findings
            .iter()
            .all(|d| !d.to_string().contains("never runs")),
        "{findings:#?}"
    );
}

/// A first team's goalkeeper: the keeper sets a global the dive reads. Checked whole, nothing
/// is wrong; `deps --launch Dive` leaves the keeper out, and there `check` says the dive's
/// labels read a value nothing gives (the launch ran and chose a side at once, silently).
#[test]
fn a_value_a_label_reads_that_nothing_gives_is_a_warning() {
    let dive = "machine Dive\ninitial START\nstate START {\n    when side == 0 -> LEFT\n    when side == 1 -> RIGHT\n}\nstate LEFT { }\nstate RIGHT { }\n";
    let keeper = "machine Keeper\ninitial WAIT\nstate WAIT {\n    entry { side = 1; }\n    when TRUE -> DIVE\n}\nstate DIVE {\n    entry {\n        Dive: On\n    }\n}\n";
    let findings = |dir: &std::path::Path| -> Vec<String> {
        let behaviour = load("keeper", Arc::new(Folder::new(dir))).unwrap();
        proclaim_behaviour::check_behaviour(&behaviour)
            .iter()
            .map(|d| d.to_string().replace(&format!("{}/", dir.display()), ""))
            .collect()
    };
    let whole = temp_behaviour(&[
        (
            "behaviour.toml",
            "[[machine]]\nfile = \"Keeper.machine\"\n\n[[machine]]\nfile = \"Dive.machine\"\nstart = false\n",
        ),
        ("Keeper.machine", keeper),
        ("Dive.machine", dive),
    ]);
    assert_eq!(findings(&whole), Vec::<String>::new());
    let b = load("keeper", Arc::new(Folder::new(&whole))).unwrap();
    let modules = proclaim_behaviour::modules(&b);
    let launch =
        proclaim_behaviour::launch_manifest(&b, &modules, "Dive", &str::to_string).unwrap();
    let alone = temp_behaviour(&[("Dive.machine", dive), ("behaviour.toml", &launch)]);
    assert_eq!(
        findings(&alone),
        ["Dive.machine:4: warning: a label reads `side`, which nothing in this behaviour posts, assigns or answers, so a comparison with it never holds (was the machine that sets it left out? a script, or a module the manifest's [[module]] names, may post it)"]
    );
}

/// The same goalkeeper with the side a parameter of the dive: a start that leaves it out, and
/// a manifest that starts the dive without it, are refused, saying where; `deps --launch Dive`
/// writes the parameter into the manifest, saying who gives it in the whole behaviour.
#[test]
fn a_parameter_nothing_gives_is_refused_and_deps_launch_carries_it() {
    let dive = "machine Dive\nparam side: int\noutcome fell\ninitial START\nstate START {\n    when side == 0 -> LEFT\n    when side == 1 -> RIGHT\n}\nstate LEFT {\n    outcome fell\n}\nstate RIGHT {\n    outcome fell\n}\n";
    let keeper = |start: &str| {
        format!("machine Keeper\ninitial WAIT\nstate WAIT {{\n    when TRUE -> DIVE\n}}\nstate DIVE {{\n    entry {{\n        {start}\n    }}\n    when Dive.fell -> WAIT\n}}\n")
    };
    let manifest = |dive_starts: &str| {
        format!("[[machine]]\nfile = \"Keeper.machine\"\n\n[[machine]]\nfile = \"Dive.machine\"\n{dive_starts}")
    };
    let errors = |dir: &std::path::Path| -> Vec<String> {
        match load("keeper", Arc::new(Folder::new(dir))) {
            Ok(_) => Vec::new(),
            Err(found) => found
                .iter()
                .map(|d| d.to_string().replace(&format!("{}/", dir.display()), ""))
                .collect(),
        }
    };
    let forgot = temp_behaviour(&[
        ("behaviour.toml", &manifest("start = false\n")),
        ("Keeper.machine", &keeper("Dive: restart")),
        ("Dive.machine", dive),
    ]);
    assert_eq!(
        errors(&forgot),
        ["Keeper.machine:6: error: `Dive` takes side: start it with `Dive: restart(side = …)`"]
    );
    let launched = temp_behaviour(&[
        ("behaviour.toml", &manifest("")),
        ("Keeper.machine", &keeper("Dive: restart(side = 1)")),
        ("Dive.machine", dive),
    ]);
    assert_eq!(
        errors(&launched),
        ["behaviour.toml: error: `Dive` starts with the behaviour and takes side: give them in its `[[machine]]` entry (`params = { side = … }`), or start it from a machine with `start = false`"]
    );
    let whole = temp_behaviour(&[
        ("behaviour.toml", &manifest("start = false\n")),
        ("Keeper.machine", &keeper("Dive: restart(side = 1)")),
        ("Dive.machine", dive),
    ]);
    let b = load("keeper", Arc::new(Folder::new(&whole))).unwrap();
    assert!(proclaim_behaviour::check_behaviour(&b).is_empty());
    // Each label runs the globals and is shown as written.
    let shown = |m: usize| -> Vec<(String, String)> {
        let ts = &b.machines[m].machine.transitions;
        ts.iter()
            .map(|t| (t.label.to_string(), t.shown().to_string()))
            .collect()
    };
    assert!(
        shown(0).contains(&("Dive_fell".into(), "Dive.fell".into())),
        "{:?}",
        shown(0)
    );
    assert!(
        shown(1).contains(&("Dive_side == 1".into(), "side == 1".into())),
        "{:?}",
        shown(1)
    );
    let machines: Vec<(&proclaim_fsm::Machine, bool)> =
        b.machines.iter().map(|m| (&m.machine, m.start)).collect();
    let dot = proclaim_behaviour::behaviour_to_dot("keeper", &machines);
    assert!(dot.contains("label=\"Dive(side: int) → fell\""), "{dot}");
    assert!(dot.contains("label=\"starts (side)\""), "{dot}");
    let modules = proclaim_behaviour::modules(&b);
    let launch =
        proclaim_behaviour::launch_manifest(&b, &modules, "Dive", &str::to_string).unwrap();
    assert!(
        launch.contains("# In the whole behaviour, Keeper gives them as it starts Dive."),
        "{launch}"
    );
    assert!(launch.contains("[machine.params]\nside = 0\n"), "{launch}");
    let alone = temp_behaviour(&[("Dive.machine", dive), ("behaviour.toml", &launch)]);
    assert_eq!(errors(&alone), Vec::<String>::new());
    // Read anew while running: the keeper's start is lowered again; a dive whose parameters
    // changed is refused, since the keeper was linked to the old ones.
    std::fs::write(
        whole.join("Keeper.machine"),
        keeper("Dive: restart(side = 0)"),
    )
    .unwrap();
    let reread = (b.machines[0].loader)().expect("the keeper reads again");
    assert!(reread
        .statements()
        .iter()
        .any(|s| s.to_string() == "Dive_side = 0;"));
    let wider = dive.replace("param side: int\n", "param side: int\nparam power: int\n");
    std::fs::write(whole.join("Dive.machine"), wider).unwrap();
    let refused = (b.machines[1].loader)().unwrap_err();
    assert!(
        refused[0].to_string().ends_with("`Dive`'s parameters or outcomes changed: the machines that start it were read with the old ones, so run the behaviour again"),
        "{refused:?}"
    );
}

fn repo_behaviour(name: &str) -> proclaim_behaviour::Behaviour {
    load(name, Arc::new(Folder::new(behaviour_dir(name)))).expect("loads")
}

#[test]
fn behaviour_diagrams_are_stable() {
    for name in ["game_controller", "microwave"] {
        let b = repo_behaviour(name);
        let machines: Vec<(&proclaim_fsm::Machine, bool)> =
            b.machines.iter().map(|m| (&m.machine, m.start)).collect();
        insta::assert_snapshot!(
            format!("{name}_machines"),
            proclaim_behaviour::behaviour_to_dot(name, &machines)
        );
        let modules = proclaim_behaviour::modules(&b);
        let centre = &b.machines[0].machine.name;
        insta::assert_snapshot!(
            format!("{name}_deps"),
            proclaim_behaviour::module_diagram(&modules, centre).unwrap()
        );
    }
}

#[test]
fn a_posting_nobody_hears_and_a_label_nobody_answers_go_to_unknown() {
    let dir = temp_behaviour(&[
        ("behaviour.toml", "[[machine]]\nfile = \"M.machine\"\n"),
        (
            "M.machine",
            "machine M\nstate A {\n  entry {\n    Beep: twice\n  }\n  when ghost -> A\n}\n",
        ),
    ]);
    let b = load("faulty", Arc::new(Folder::new(&dir))).unwrap();
    let dot = proclaim_behaviour::module_diagram(&proclaim_behaviour::modules(&b), "M").unwrap();
    assert!(
        dot.contains("unknown -> \"M\" [color=red, fontcolor=red, label=\"ghost\"];"),
        "{dot}"
    );
    assert!(
        dot.contains("\"M\" -> unknown [color=red, fontcolor=red, label=\"Beep\"];"),
        "{dot}"
    );
    let err =
        proclaim_behaviour::module_diagram(&proclaim_behaviour::modules(&b), "N").unwrap_err();
    assert_eq!(err.to_string(), "no module `N`; the behaviour has M");
}

#[test]
fn launch_manifests_start_exactly_what_a_machine_needs() {
    let b = repo_behaviour("game_controller");
    let modules = proclaim_behaviour::modules(&b);
    assert_eq!(
        proclaim_behaviour::launch_manifest(&b, &modules, "Placer", &str::to_string).unwrap(),
        "# The smallest behaviour that runs Placer: written by `proclaim deps --launch Placer`.\n\
         dictionary = \"../nao.toml\"\n\n[[machine]]\nfile = \"Placer.machine\"\n"
    );
    let m = repo_behaviour("microwave");
    let text = proclaim_behaviour::launch_manifest(
        &m,
        &proclaim_behaviour::modules(&m),
        "Microwave",
        &str::to_string,
    )
    .unwrap();
    assert!(
        text.contains("[[theory]]\nfile = \"../../theories/microwave.dl\"\n"),
        "{text}"
    );
    assert!(
        text.contains("[impersonator]\nscript = \"kitchen.script\"\n"),
        "{text}"
    );
    assert!(
        text.contains("[[module]]\nname = \"magnetron\"\n"),
        "{text}"
    );
    // The manifest loads beside the original.
    let parsed = proclaim_behaviour::parse_manifest("behaviour.toml", &text).unwrap();
    assert_eq!(parsed.machines.len(), 1);
    assert_eq!(parsed.theories.len(), 1);
}

/// The Kouretes paper's formulas, written as a skeleton behaviour into a fresh folder.
fn skeleton(formulas: &str) -> (PathBuf, Vec<String>) {
    let (defs, errors) = proclaim_behaviour::parse_liveness("f.liveness", formulas);
    assert!(errors.is_empty(), "{errors:?}");
    let (machines, warnings) = proclaim_behaviour::liveness_machines("f.liveness", &defs);
    assert!(warnings.is_empty(), "{warnings:?}");
    let mut files: Vec<(String, String)> = machines
        .iter()
        .map(|m| (format!("{}.machine", m.name), m.text.clone()))
        .collect();
    let mut manifest = String::new();
    for m in &machines {
        manifest.push_str(&format!(
            "[[machine]]\nfile = \"{}.machine\"\nstart = {}\n",
            m.name, m.start
        ));
    }
    files.push(("behaviour.toml".into(), manifest));
    let refs: Vec<(&str, &str)> = files
        .iter()
        .map(|(a, b)| (a.as_str(), b.as_str()))
        .collect();
    let names = files.iter().map(|(f, _)| f.clone()).collect();
    (temp_behaviour(&refs), names)
}

#[test]
fn liveness_formulas_of_the_test_behaviour_become_a_skeleton_machine() {
    let (dir, files) = skeleton(
        "TestBehavior = (Play | NoPlay)+\nPlay = SitDownAndStare | StandUpAndScan  # refined\n",
    );
    assert_eq!(files, ["TestBehavior.machine", "behaviour.toml"]);
    let text = std::fs::read_to_string(dir.join("TestBehavior.machine")).unwrap();
    insta::assert_snapshot!("liveness_test_behaviour_machine", text);
    let b = load("test", Arc::new(Folder::new(&dir))).unwrap();
    let open: Vec<String> = proclaim_behaviour::check_behaviour(&b)
        .iter()
        .filter(|d| d.severity == proclaim_fsm::Severity::Error)
        .map(|d| d.message.clone())
        .collect();
    assert_eq!(open.len(), 8, "{open:#?}");
    assert_eq!(
        open[0],
        "label `choosePlay` is answered by no expert and posted by no module"
    );
}

/// KSE's attack protocol (`attack = center || center-for || center-for`) is one machine with a
/// parallel state (an AND-state, §3.2): its roles run side by side as regions and it ends when
/// every role has.
#[tokio::test(start_paused = true)]
async fn the_attack_protocol_starts_its_roles_together_and_ends_when_all_are_done() {
    let (dir, files) = skeleton("attack = center || center-for || center-for\n");
    assert_eq!(files, ["attack.machine", "behaviour.toml"]);
    let b = load("attack", Arc::new(Folder::new(&dir))).unwrap();
    let text = std::fs::read_to_string(dir.join("attack.machine")).unwrap();
    assert!(
        text.contains("parallel Parallel {\n    when done -> End"),
        "{text}"
    );
    let open: Vec<String> = proclaim_behaviour::check_behaviour(&b)
        .iter()
        .map(|d| d.message.clone())
        .collect();
    assert_eq!(
        open,
        [
            "label `centerDone` is answered by no expert and posted by no module",
            "label `center_forDone` is answered by no expert and posted by no module",
        ]
    );
    // Filled in by a script: the roles finish at 1 s and 2 s, and the protocol ends then.
    let board = Whiteboard::local();
    let options = LaunchOptions {
        script: Some(
            parse_script("at 1s centerDone = true\nat 2s center_forDone = true\n").unwrap(),
        ),
        ..Default::default()
    };
    let mut running = launch(&b, &board, options).await.unwrap();
    let (mut entered, mut fired) = (Vec::new(), Vec::new());
    let deadline = tokio::time::Instant::now() + Duration::from_secs(10);
    while let Ok(Some(e)) = tokio::time::timeout_at(deadline, running.events.recv()).await {
        if let proclaim_runner::Event::Entered { state, at, .. } = &e {
            entered.push(format!("{:.1}s {state}", at.as_secs_f64()));
        }
        if let proclaim_runner::Event::Fired { label, .. } = &e {
            fired.push(label.clone());
        }
        if running.observe(&e) {
            break;
        }
    }
    running.stop().await;
    let roles = |c: &str, f: &str, f2: &str| {
        format!("Parallel.centerBranch.{c}, Parallel.center_forBranch.{f}, Parallel.center_forBranch2.{f2}")
    };
    assert_eq!(
        entered,
        [
            format!("0.0s {}", roles("center", "center_for", "center_for2")),
            format!(
                "1.0s {}",
                roles("centerBranchEnd", "center_for", "center_for2")
            ),
            format!(
                "2.0s {}",
                roles(
                    "centerBranchEnd",
                    "center_forBranchEnd",
                    "center_forBranchEnd2"
                )
            ),
            "2.0s End".to_string(),
        ]
    );
    // The two center-for roles end in one ringlet, then the protocol is done.
    assert_eq!(
        fired,
        ["centerDone", "center_forDone && center_forDone", "done"],
        "{fired:?}"
    );
}

/// The Kouretes paper's robot formula (a player takes the center or the center-for role) with
/// a parallel part beside it: the defined activity is a state holding its choice, inside a
/// region of the parallel state the `||` is, and `check` finds only the open labels.
#[test]
fn a_defined_activity_is_a_nested_state_inside_a_region_of_the_parallel_part() {
    let (dir, files) = skeleton("Striker = (Attack || Track)+\nAttack = center | center-for\n");
    assert_eq!(files, ["Striker.machine", "behaviour.toml"]);
    let b = load("striker", Arc::new(Folder::new(&dir))).unwrap();
    let striker = &b.machines[0].machine;
    let composites: Vec<(&str, bool)> = (striker.composites.iter())
        .filter(|c| !c.atomic)
        .map(|c| (c.name.as_str(), c.parallel))
        .collect();
    assert_eq!(
        composites,
        [
            ("Parallel", true),
            ("Parallel.AttackBranch", false),
            ("Parallel.AttackBranch.Attack", false),
            ("Parallel.TrackBranch", false),
        ]
    );
    let mut found: Vec<String> = proclaim_behaviour::check_behaviour(&b)
        .iter()
        .map(|d| d.message.clone())
        .collect();
    found.sort();
    assert_eq!(
        found,
        [
            "label `TrackDone` is answered by no expert and posted by no module",
            "label `againAttack` is answered by no expert and posted by no module",
            "label `centerDone` is answered by no expert and posted by no module",
            "label `center_forDone` is answered by no expert and posted by no module",
            "label `choosecenter_for` is answered by no expert and posted by no module",
            "label `choosecenter` is answered by no expert and posted by no module",
        ]
    );
}

#[test]
fn liveness_errors_name_their_lines() {
    let (_, errors) = proclaim_behaviour::parse_liveness(
        "f.liveness",
        "A = B . (C | D\nno equals here\nA = B\nE = [F\nG = H ||\n",
    );
    let got: Vec<String> = errors.iter().map(ToString::to_string).collect();
    assert_eq!(
        got,
        [
            "f.liveness:1: error: in the formula of `A`: missing `)`",
            "f.liveness:2: error: a formula is `Name = activities` (no `=` here)",
            "f.liveness:4: error: in the formula of `E`: missing `]`",
            "f.liveness:5: error: in the formula of `G`: the formula ends too early",
        ]
    );
}

/// The Griffith team's own one-minute microwave (gufsm, Qfsm files in the corpus): four
/// machines that talk only through variables. The timer declares `currentTime` its own and
/// binds `buttonPushed` and `doorOpen` to the whiteboard (`extern`); `timeLeft`, `motor`,
/// `light` and `sound` are globals the others read in their labels. The script plays the
/// kitchen: the button pushed once (30 s), the door opened for a moment while it cooks.
#[tokio::test(start_paused = true)]
async fn the_teams_gufsm_microwave_runs_on_variables_alone() {
    let Some(corpus) = crate::corpus_dir() else {
        eprintln!("skipped: ../shared/corpus is absent");
        return;
    };
    let corpus = corpus.join("mipal/machines");
    let parts = ["Timer", "Cook", "Light", "Bell"];
    let mut files: Vec<(String, String)> = parts
        .iter()
        .map(|p| {
            let file = format!("Examples__OneMinuteMicrowave__Microwave{p}.fsm");
            let text = std::fs::read_to_string(corpus.join(&file)).expect("corpus file");
            (file, text)
        })
        .collect();
    let manifest: String = files
        .iter()
        .map(|(f, _)| format!("[[machine]]\nfile = \"{f}\"\n"))
        .collect();
    files.push(("behaviour.toml".into(), manifest));
    let borrowed: Vec<(&str, &str)> = files
        .iter()
        .map(|(f, t)| (f.as_str(), t.as_str()))
        .collect();
    let dir = crate::behaviour_folder("gufsm-microwave", &borrowed);
    let script = "\
        buttonPushed = false
        doorOpen = false
        at 1s buttonPushed = true
        at 1500ms buttonPushed = false
        at 10s doorOpen = true
        at 12s doorOpen = false
    ";
    let (trace, board) = run_folder(
        "microwave",
        &dir,
        Some(script),
        Duration::from_secs(40),
        &[],
    )
    .await;
    let mut said: Vec<&str> = trace
        .iter()
        .map(String::as_str)
        .filter(|l| l.contains("posts QSay") || l.contains("posts LEDS"))
        .collect();
    // Machines woken by the same change run in no set order: compare each instant's lines
    // by machine.
    let time = |l: &str| l.split('s').next().unwrap().parse::<f64>().unwrap();
    said.sort_by(|a, b| {
        time(a)
            .total_cmp(&time(b))
            .then(a.split(' ').nth(1).cmp(&b.split(' ').nth(1)))
    });
    assert_eq!(
        said,
        [
            "0.000s Examples__OneMinuteMicrowave__MicrowaveCook posts QSay: stop",
            "0.000s Examples__OneMinuteMicrowave__MicrowaveLight posts LEDS: Face Off",
            // Pushed at 1 s: thirty seconds on the clock, the timer says time is left.
            "1.500s Examples__OneMinuteMicrowave__MicrowaveCook posts QSay: Cooking",
            "1.500s Examples__OneMinuteMicrowave__MicrowaveLight posts LEDS: Face Off",
            "1.500s Examples__OneMinuteMicrowave__MicrowaveLight posts LEDS: Face Blue",
            // The door opens: the magnetron stops, the light stays on; shut, it cooks on.
            "10.000s Examples__OneMinuteMicrowave__MicrowaveCook posts QSay: stop",
            "12.000s Examples__OneMinuteMicrowave__MicrowaveCook posts QSay: Cooking",
            // The door held the count back: the timer's `timeout(1000000)` counts from when it
            // entered TEST (9.5 s), so the tick due at 10.5 s comes when the door shuts, at
            // 12 s: 1.5 s late, and the thirty seconds end at 33 s.
            // The bell's RING state says it on entry and again on exit, as the team drew it.
            "33.000s Examples__OneMinuteMicrowave__MicrowaveBell posts QSay: DIIIIING, DIIIING",
            "33.000s Examples__OneMinuteMicrowave__MicrowaveBell posts QSay: DIIIIING, DIIIING",
            "33.000s Examples__OneMinuteMicrowave__MicrowaveCook posts QSay: stop",
            "33.000s Examples__OneMinuteMicrowave__MicrowaveLight posts LEDS: Face Blue",
            "33.000s Examples__OneMinuteMicrowave__MicrowaveLight posts LEDS: Face Off",
        ],
        "{trace:#?}"
    );
    // Nothing was asked of an expert: every label is over variables.
    assert!(
        !trace.iter().any(|l| l.contains("no expert answers")),
        "{trace:#?}"
    );
    assert_eq!(board.stats().queries, 0);
}

/// `machines/shootout`: three machines that cooperate through variables alone: counters (the
/// kicker's own `kicks`, the keeper's own `seen`), remembered values (`best` run of goals) and
/// computed postings (`post("NaoMotionPlayer", "kick " + aim)`, `postv("Score", goals, dived)`).
#[tokio::test(start_paused = true)]
async fn the_shootout_keeps_score_through_variables() {
    let (trace, board) = run("shootout", None, Duration::from_secs(30)).await;
    let shown: Vec<&str> = trace
        .iter()
        .map(String::as_str)
        .filter(|l| {
            l.contains("posts NaoMotionPlayer")
                || l.contains("posts KeeperDive")
                || l.contains("posts Score:")
                || l.contains("posts Say")
                || l.contains("finished")
        })
        .collect();
    assert_eq!(
        shown,
        [
            "2.000s Kicker posts NaoMotionPlayer: kick 2",
            "2.000s Keeper posts KeeperDive: 2",
            "2.000s Scoreboard posts Score: 0 1",
            "4.000s Kicker posts NaoMotionPlayer: kick 1",
            "4.000s Keeper posts KeeperDive: 0",
            "4.000s Scoreboard posts Score: 1 2",
            "6.000s Kicker posts NaoMotionPlayer: kick 0",
            "6.000s Keeper posts KeeperDive: 1",
            "6.000s Scoreboard posts Score: 2 3",
            "8.000s Kicker posts NaoMotionPlayer: kick 2",
            "8.000s Keeper posts KeeperDive: 2",
            "8.000s Scoreboard posts Score: 2 4",
            "10.000s Kicker posts NaoMotionPlayer: kick 1",
            "10.000s Keeper posts KeeperDive: 0",
            "10.000s Scoreboard posts Score: 3 5",
            "10.000s Kicker posts Say: five kicks, 3 goals, best run 2",
            "10.000s Kicker finished in DONE",
        ],
        "{trace:#?}"
    );
    use proclaim_board::Value;
    assert_eq!(
        board.latest("Score").unwrap().value,
        Value::List(vec![Value::Int(3), Value::Int(5)])
    );
    assert_eq!(board.stats().queries, 0, "labels over variables ask nobody");
    assert_eq!(board.truth("KeeperIsRunning"), Some(false));
}

#[test]
fn a_theory_entry_sets_its_experts_search_budget() {
    let dir = temp_behaviour(&[
        (
            "behaviour.toml",
            "[[machine]]\nfile = \"A.machine\"\n\n[[theory]]\nfile = \"t.dl\"\nbudget = 1000\n",
        ),
        ("A.machine", "machine A\nstate S {\n  when b -> S\n}\n"),
        ("t.dl", "=> b.\n"),
    ]);
    let behaviour = load("budgeted", Arc::new(Folder::new(&dir))).unwrap();
    assert_eq!(behaviour.theories[0].limits.steps, 1000);
    let unbudgeted = temp_behaviour(&[
        (
            "behaviour.toml",
            "[[machine]]\nfile = \"A.machine\"\n\n[[theory]]\nfile = \"t.dl\"\n",
        ),
        ("A.machine", "machine A\nstate S {\n  when b -> S\n}\n"),
        ("t.dl", "=> b.\n"),
    ]);
    let behaviour = load("default", Arc::new(Folder::new(&unbudgeted))).unwrap();
    assert_eq!(
        behaviour.theories[0].limits,
        proclaim_cdl::SearchLimits::default()
    );
}

/// Whatever the formulas name their activities, the skeleton reads back: names a generated
/// state would repeat (`Kick . Kick . Kick2`, `Choose2`) are numbered on, and words the format
/// keeps (`entry`, `done`) are written with `_` after them.
#[test]
fn a_skeleton_reads_back_whatever_its_activities_are_named() {
    for formulas in [
        "B = Kick . Kick . Kick2\n",
        "B = (Choose2 | x) . Repeat2 . End . End2+\n",
        "B = entry . done . (when | state)* . history\n",
        "B = P . P\nP = PEnd . (Q || Q)\nQ = a | a\n",
    ] {
        let (dir, _) = skeleton(formulas);
        let b = load("skeleton", Arc::new(Folder::new(&dir)))
            .unwrap_or_else(|e| panic!("{formulas}: {e:?}"));
        let errors: Vec<String> = proclaim_behaviour::check_behaviour(&b)
            .iter()
            .filter(|d| d.severity == proclaim_fsm::Severity::Error)
            .map(|d| d.message.clone())
            .filter(|m| !m.ends_with("is answered by no expert and posted by no module"))
            .collect();
        assert!(errors.is_empty(), "{formulas}: {errors:?}");
    }
}
