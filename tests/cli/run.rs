//! `run`: behaviours played to the end, watched, stepped, asked, on the virtual clock, logged.

use super::waiting::{Lines, Running};
use super::{stderr, stdout, temp_file};
use crate::proclaim;
use std::io::Write;
use std::process::Command;

#[test]
fn run_plays_the_built_in_game_over_udp_to_finished_and_the_trace_replays() {
    let trace = temp_file("game.jsonl", b"");
    let o = proclaim(&[
        "run",
        "game_controller",
        "--for",
        "60s",
        "--trace",
        trace.to_str().unwrap(),
    ]);
    let out = stdout(&o);
    assert_eq!(o.status.code(), Some(0), "{out}\n{}", stderr(&o));
    let states: Vec<&str> = out
        .lines()
        .filter(|l| l.contains("GameController  →"))
        .map(|l| l.rsplit(' ').next().unwrap())
        .collect();
    assert_eq!(
        states,
        [
            "INITIAL",
            "READY",
            "SET",
            "PLAYING",
            "PENALIZED",
            "PLAYING",
            "FINISHED"
        ],
        "{out}"
    );
    assert!(
        out.contains("stopped: every machine that started is in a final state"),
        "{out}"
    );
    // FINISHED's entry runs before the run ends: the robot says so and sits.
    let tail: Vec<&str> = out.lines().rev().take(8).collect();
    for said in [
        "posts Say: game over",
        "posts NaoMotionPlayer: play sit",
        "finished in FINISHED",
    ] {
        assert!(tail.iter().any(|l| l.ends_with(said)), "{said}:\n{out}");
    }
    assert!(
        out.contains("readyReceived = true  (gamecontroller)"),
        "{out}"
    );
    // The replay prints the same trace lines.
    let replayed = proclaim(&["replay", trace.to_str().unwrap()]);
    assert_eq!(replayed.status.code(), Some(0), "{}", stderr(&replayed));
    let timed = |l: &&str| {
        let first = l.split_whitespace().next().unwrap_or("");
        first
            .strip_suffix('s')
            .is_some_and(|t| t.parse::<f64>().is_ok())
    };
    let live: Vec<&str> = out.lines().filter(timed).collect();
    let replayed = stdout(&replayed);
    let again: Vec<&str> = replayed.lines().collect();
    assert_eq!(again, live);
}

#[test]
fn run_refuses_what_it_cannot_run() {
    let o = proclaim(&["run", "no_such_behaviour"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("no behaviour `no_such_behaviour`: not a folder with a behaviour.toml, not machines/no_such_behaviour, and not a built-in one (game_controller, microwave, shootout)"),
        "{}",
        stderr(&o)
    );
    // A path is looked for as itself, not under machines/.
    let o = proclaim(&["run", "no/such/folder"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("no behaviour `no/such/folder`: not a folder with a behaviour.toml, and not a built-in one"),
        "{}",
        stderr(&o)
    );
    let o = proclaim(&["run", "microwave", "--for", "soon"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("--for soon: not a duration"),
        "{}",
        stderr(&o)
    );
    // A lease too short closes links that work; one that is no duration says how to write one.
    for (lease, said) in [
        ("50ms", "50ms: a lease is from 200ms to 600s"),
        ("soon", "`soon` is not a duration (write 1s, 500ms or 2.5s)"),
    ] {
        let o = proclaim(&["run", "microwave", "--lease", lease, "--listen"]);
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        assert!(stderr(&o).contains(said), "{}", stderr(&o));
    }
    let bad = temp_file("bad.jsonl", b"{\"event\":\"entered\"}\n");
    let o = proclaim(&["replay", bad.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("bad.jsonl: line 1: not a trace event: missing field `machine`"),
        "{}",
        stderr(&o)
    );
    let bad = temp_file(
        "bad-record.jsonl",
        b"{\"at_us\":0,\"module\":\"m\",\"seq\":1,\"type\":\"doorOpen\",\"value\":true}\n{\"at_us\":5}\n",
    );
    let o = proclaim(&["replay", bad.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("bad-record.jsonl: line 2: not a recorded message"),
        "{}",
        stderr(&o)
    );
    let o = proclaim(&["replay", bad.to_str().unwrap(), "--speed", "0"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("--speed must be a positive number"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn run_watch_rereads_a_changed_machine_and_a_broken_edit_changes_nothing() {
    let dir = crate::behaviour_folder(
        "watch",
        &[
            ("behaviour.toml", "[[machine]]\nfile = \"W.machine\"\n"),
            (
                "W.machine",
                "machine W\nstate Wait {\n  when go -> Done\n}\nstate Done {\n}\n",
            ),
        ],
    );
    let machine = dir.join("W.machine");
    let mut child = Running(
        Command::new(env!("CARGO_BIN_EXE_proclaim"))
            // `go` is answered by nobody (a behaviour being written): --force runs it all the same.
            .args([
                "run",
                dir.to_str().unwrap(),
                "--watch",
                "--for",
                "60s",
                "--force",
            ])
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap(),
    );
    let mut printed = Lines::of(child.0.stdout.take().unwrap());
    let mut said = Lines::of(child.0.stderr.take().unwrap());
    // Each save once the one before it has been seen: no sleep a loaded machine can outrun.
    said.wait_for("--watch: a save to a machine's file rereads the machine");
    std::fs::write(&machine, "machine W\nstate Wait {\n  when -> Done\n}\n").unwrap();
    printed.wait_for("W  reload failed, runs on unchanged:");
    std::fs::write(
        &machine,
        "machine W\nstate Wait {\n  when TRUE -> Done\n}\nstate Done {\n}\n",
    )
    .unwrap();
    let status = child.0.wait().unwrap();
    let (out, err) = (printed.all(), said.all());
    assert_eq!(status.code(), Some(0), "{out}\n{err}");
    assert!(
        out.contains("W  reload failed, runs on unchanged:"),
        "{out}"
    );
    assert!(
        out.contains("W.machine:3: error: a transition needs a label"),
        "{out}"
    );
    assert!(out.contains("W  reloaded, in Wait"), "{out}");
    // Each save is read once, however many file events it makes.
    assert_eq!(
        out.matches("its file changed; rereading").count(),
        2,
        "{out}"
    );
    assert!(
        err.contains("W.machine:3: warning: label `go` is answered by no expert"),
        "--force shows what check found as warnings: {err}"
    );
    assert!(out.contains("W  → Done"), "{out}");
    assert!(
        out.contains("stopped: every machine that started is in a final state"),
        "{out}"
    );
}

#[test]
fn run_step_rings_once_per_enter_and_reads_answers_typed_at_the_prompt() {
    let dir = crate::behaviour_folder(
        "step",
        &[
            ("behaviour.toml", "[[machine]]\nfile = \"M.machine\"\n"),
            ("M.machine", "machine M\nstate A {\n  entry {\n    Say: hello\n  }\n  when go -> B\n}\nstate B {\n}\n"),
        ],
    );
    let mut child = Command::new(env!("CARGO_BIN_EXE_proclaim"))
        .args(["run", dir.to_str().unwrap(), "--step"])
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    child
        .stdin
        .take()
        .unwrap()
        .write_all(b"\n\ngo=true\n\n\n")
        .unwrap();
    let o = child.wait_with_output().unwrap();
    let out = stdout(&o);
    assert_eq!(o.status.code(), Some(0), "{out}\n{}", stderr(&o));
    // Each prompt (`step N> `) is followed by what that step printed, on the same line.
    let shown: Vec<String> = out
        .lines()
        .map(|l| match l.find("> ") {
            Some(i) if l.starts_with("step ") => &l[i + 2..],
            _ => l,
        })
        .map(|l| {
            let words: Vec<&str> = l.split_whitespace().collect();
            match words.first() {
                Some(w) if w.ends_with('s') && w[..w.len() - 1].parse::<f64>().is_ok() => {
                    words[1..].join(" ")
                }
                _ => words.join(" "),
            }
        })
        .filter(|l| l.starts_with("M"))
        .collect();
    assert_eq!(
        shown,
        [
            "M: A (running)",
            "M → A",
            "M posts Say: hello",
            "M go: no expert answers it, counted false",
            "M: A (running)",
            "M: A (running)",
            "M: A (running)",
            "M go = true (as posted by you)",
            "M fires on go",
            "M: B (running)",
            "M → B",
            "M finished in B",
            "M: B (running)",
        ],
        "{out}"
    );
    assert!(
        out.contains("whiteboard: MIsRunning=true, Say=\"hello\", go=true"),
        "{out}"
    );
    assert!(
        out.ends_with("stopped: every machine that started is in a final state or halted\n"),
        "{out}"
    );
}

#[test]
fn a_virtual_clock_runs_a_minute_of_microwave_at_once_and_the_same_every_time() {
    let run = || {
        let started = std::time::Instant::now();
        let o = proclaim(&["run", "microwave", "--virtual-clock"]);
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
        (stdout(&o), started.elapsed())
    };
    let (first, took) = run();
    let states: Vec<String> = first
        .lines()
        .filter(|l| l.contains('→'))
        .map(|l| l.split_whitespace().collect::<Vec<_>>().join(" "))
        .collect();
    assert_eq!(
        states,
        [
            "0.000s Microwave → IDLE",
            "1.000s Microwave → OPEN",
            "3.000s Microwave → IDLE",
            "4.000s Microwave → COOKING",
            "64.000s Microwave → DONE",
        ],
        "{first}"
    );
    // What the script sets shows in the trace, once each time it changes.
    assert!(
        first.contains("   1.000s impersonator  posts doorOpen: true\n"),
        "{first}"
    );
    assert_eq!(first.matches("posts doorOpen").count(), 3, "{first}");
    assert!(
        took < std::time::Duration::from_secs(20),
        "64 s of behaviour on the virtual clock took {took:?}"
    );
    assert_eq!(run().0, first, "the same trace every time");
    let o = proclaim(&[
        "run",
        "microwave",
        "--virtual-clock",
        "--connect",
        "tcp/127.0.0.1:1",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("cannot --listen or --connect"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn run_ask_puts_a_person_in_place_of_the_experts() {
    let dir = crate::behaviour_folder(
        "ask",
        &[
            ("behaviour.toml", "[[machine]]\nfile = \"A.machine\"\n"),
            (
                "A.machine",
                "machine A\nstate S {\n  when ready -> T\n}\nstate T {\n}\n",
            ),
        ],
    );
    let mut child = Command::new(env!("CARGO_BIN_EXE_proclaim"))
        .args(["run", dir.to_str().unwrap(), "--ask", "ready"])
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    {
        use std::io::Write;
        let stdin = child.stdin.as_mut().unwrap();
        writeln!(stdin, "maybe").unwrap();
        writeln!(stdin, "n").unwrap();
        writeln!(stdin, "y").unwrap();
    }
    let o = child.wait_with_output().unwrap();
    let out = stdout(&o);
    assert_eq!(o.status.code(), Some(0), "{out}\n{}", stderr(&o));
    assert!(out.contains("please answer y or n"), "{out}");
    assert!(out.contains("ready = false  (person)"), "{out}");
    assert!(out.contains("ready = true  (person)"), "{out}");
    assert!(out.contains("finished in T"), "{out}");
    assert!(
        !stderr(&o).contains("answered by no expert"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn logs_show_the_crates_spans_with_v_and_as_json() {
    // Nothing extra by default: the trace is the output.
    let quiet = proclaim(&["run", "microwave", "--for", "300ms"]);
    assert!(
        !stderr(&quiet).contains("query answered"),
        "{}",
        stderr(&quiet)
    );
    let o = proclaim(&["run", "microwave", "--for", "300ms", "-vv"]);
    let log = stderr(&o);
    assert!(
        log.contains("machine{name=Microwave}") && log.contains("query answered"),
        "{log}"
    );
    let o = proclaim(&[
        "run",
        "microwave",
        "--for",
        "300ms",
        "-vv",
        "--log-format",
        "json",
    ]);
    let line = stderr(&o)
        .lines()
        .find(|l| l.contains("query answered"))
        .map(str::to_string)
        .unwrap_or_else(|| panic!("{}", stderr(&o)));
    let event: serde_json::Value = serde_json::from_str(&line).unwrap();
    assert_eq!(event["level"], "DEBUG");
    assert_eq!(
        event["fields"]["atom"]
            .as_str()
            .map(|a| a == "cook" || a == "light"),
        Some(true)
    );
    assert_eq!(event["span"]["name"], "machine");
    // RUST_LOG decides when set.
    let o = Command::new(env!("CARGO_BIN_EXE_proclaim"))
        .args(["run", "microwave", "--for", "300ms"])
        .env("NO_COLOR", "1")
        .env("RUST_LOG", "proclaim_board=debug")
        .output()
        .unwrap();
    assert!(stderr(&o).contains("query answered"), "{}", stderr(&o));
}

#[test]
fn a_label_nobody_answers_is_warned_once_not_at_every_ring() {
    let dir = crate::behaviour_folder(
        "warn-once",
        &[
            ("behaviour.toml", "[[machine]]\nfile = \"M.machine\"\n"),
            (
                "M.machine",
                "machine M\nstate A {\n  when go -> B\n}\nstate B {\n}\n",
            ),
        ],
    );
    // Ten rings a second for a second, each asking for `go`.
    let o = proclaim(&["run", dir.to_str().unwrap(), "--force", "--for", "1s"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let warned = stderr(&o)
        .lines()
        .filter(|l| l.contains("query for an atom no module answers"))
        .count();
    assert_eq!(warned, 1, "{}", stderr(&o));
}

/// A run whose script stands in for the GameController opens no socket for it: with the real
/// GameController's port taken (here by the test, as by another run or CI job), two such runs
/// side by side on the virtual clock both play to the end. The receiver once bound 0.0.0.0:3838
/// first and was left out after.
#[test]
fn a_sensor_the_script_stands_in_for_opens_no_socket_and_runs_side_by_side() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("machines");
    let dir = temp_file("hermetic.script", b"")
        .with_extension("")
        .join("game");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::copy(
        root.join("nao.toml"),
        dir.parent().unwrap().join("nao.toml"),
    )
    .unwrap();
    for file in ["GameController.machine", "Placer.machine"] {
        std::fs::copy(root.join("game_controller").join(file), dir.join(file)).unwrap();
    }
    // Listening for a real GameController: the receiver would bind 0.0.0.0:3838.
    let manifest = std::fs::read_to_string(root.join("game_controller/behaviour.toml"))
        .unwrap()
        .replace("simulator = true", "simulator = false");
    std::fs::write(dir.join("behaviour.toml"), manifest).unwrap();
    let script = temp_file(
        "hermetic.script",
        b"at 1s readyReceived = true\nat 2s readyReceived = false\nat 2s setReceived = true\nat 3s setReceived = false\nat 3s playingReceived = true\n",
    );
    let _taken = std::net::UdpSocket::bind("0.0.0.0:3838");
    let args = [
        "run",
        dir.to_str().unwrap(),
        "--virtual-clock",
        "--for",
        "5s",
        "--script",
        script.to_str().unwrap(),
    ];
    let start = || {
        Command::new(env!("CARGO_BIN_EXE_proclaim"))
            .args(args)
            .output()
    };
    let (one, two) = std::thread::scope(|s| {
        let one = s.spawn(start);
        let two = s.spawn(start);
        (one.join().unwrap().unwrap(), two.join().unwrap().unwrap())
    });
    for o in [one, two] {
        let out = stdout(&o);
        assert_eq!(o.status.code(), Some(0), "{out}\n{}", stderr(&o));
        assert!(
            out.contains("left out gamecontroller: the script impersonates"),
            "{out}"
        );
        assert!(!out.contains("listening for the GameController"), "{out}");
        assert!(out.contains("GameController  → PLAYING"), "{out}");
    }
}

/// A time test too long for any clock (`after(1e300)`) never comes due; it once panicked
/// converting the seconds to a `Duration`.
#[test]
fn a_time_test_too_long_for_any_clock_never_comes_due() {
    let dir = crate::behaviour_folder(
        "forever",
        &[
            ("F.machine", "machine F\ninitial A\nstate A {\n    when after(1e300) -> B\n    when after(1s) -> C\n}\nstate B { }\nstate C { }\n"),
            ("behaviour.toml", "[[machine]]\nfile = \"F.machine\"\n"),
        ],
    );
    let o = crate::proclaim(&[
        "run",
        dir.to_str().unwrap(),
        "--virtual-clock",
        "--for",
        "3s",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(stdout(&o).contains("F  → C"), "{}", stdout(&o));
}

/// With no script and nothing else outside, a run with no `--for` ends at its first still
/// round and says that nothing outside posts (`docs/spec/behaviour.md` §3.1).
#[test]
fn a_run_alone_with_no_script_ends_when_its_machines_are_still() {
    let folder = crate::behaviour_folder(
        "alone-still",
        &[
            ("behaviour.toml", "[[machine]]\nfile = \"Wait.machine\"\n"),
            (
                "Wait.machine",
                "machine Wait\ninitial W\nstate W {\n    when go -> Done\n}\nstate Done {\n}\n",
            ),
        ],
    );
    let o = proclaim(&[
        "run",
        folder.to_str().unwrap(),
        "--virtual-clock",
        "--force",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(
        stdout(&o).contains("stopped: nothing outside posts and the machines are still (no change, no time test to come), after 0.100 s"),
        "{}",
        stdout(&o)
    );
}

/// A transition without a target acts and stays (§3.2): it fires three times at the moment `go`
/// comes, running only its own actions (the state's OnEntry ran once and its OnExit runs once,
/// when it leaves), and the state's time test counts on from its entry: it leaves at 0.3 s,
/// not 0.3 s after the last firing. `explain` says which stayed.
#[test]
fn a_transition_that_stays_acts_without_leaving_and_its_state_keeps_its_clock() {
    let dir = crate::behaviour_folder(
        "stays",
        &[
            (
                "behaviour.toml",
                "[[machine]]\nfile = \"C.machine\"\n\n[impersonator]\nscript = \"go.script\"\n",
            ),
            ("go.script", "go = false\nat 0.1s go = true\n"),
            (
                "C.machine",
                "machine C\ninitial COUNT\nstate COUNT {\n  entry {\n    int n;\n    Entered: yes\n  }\n  exit {\n    Left: yes\n  }\n  when n < 3 && go {\n    n = n + 1;\n  }\n  when after_ms(300) -> DONE\n}\nstate DONE {\n}\n",
            ),
        ],
    );
    let recording = dir.join("run.jsonl");
    let o = proclaim(&[
        "run",
        dir.to_str().unwrap(),
        "--virtual-clock",
        "--for",
        "2s",
        "--record",
        recording.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    let machine: Vec<String> = out
        .lines()
        .filter(|l| l.contains(" C ") && !l.contains(" = "))
        .map(|l| l.split_whitespace().collect::<Vec<_>>().join(" "))
        .collect();
    assert_eq!(
        machine,
        [
            "0.000s C → COUNT",
            "0.000s C posts Entered: yes",
            "0.100s C fires on n < 3 && go",
            "0.100s C fires on n < 3 && go",
            "0.100s C fires on n < 3 && go",
            "0.300s C fires on after_ms(300)",
            "0.300s C posts Left: yes",
            "0.300s C → DONE",
            "0.300s C finished in DONE",
        ],
        "{out}"
    );
    // `explain` says it stayed, in the first round it fired (round 2, at 0.1 s).
    let o = proclaim(&[
        "explain",
        dir.to_str().unwrap(),
        "C",
        "--recording",
        recording.to_str().unwrap(),
        "--round",
        "2",
    ]);
    let said = stdout(&o);
    assert!(
        said.contains("  1. stays when n < 3 && go: fired (n = 0, go = true)\n  2. -> DONE when after_ms(300): not tried"),
        "{said}{}",
        stderr(&o)
    );
}
