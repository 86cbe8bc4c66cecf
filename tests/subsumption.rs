//! Subsumption on the whiteboard (`machines/subsumption`): a Reflex layer suppresses a Walk
//! layer's postings to `walk` for its hold, what readers of the board see, the trace, the
//! replay of a recording, `check`'s placed errors, `verify`'s refusal and the diagram's mark.

use crate::proclaim;
use proclaim_behaviour::testing::run_scripted;
use proclaim_behaviour::{launch, load, Folder, LaunchOptions};
use proclaim_board::Whiteboard;
use proclaim_runner::Event;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Duration;

fn example() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("machines/subsumption")
}

fn field_script() -> String {
    std::fs::read_to_string(example().join("field.script")).unwrap()
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

#[test]
fn the_reflex_suppresses_the_walk_while_it_holds_and_the_walk_takes_over_after() {
    let run = run_scripted(example(), &field_script(), Duration::from_secs(30)).unwrap();
    assert!(run.finished, "{:#?}", run.trace);
    let about_walk: Vec<String> = run
        .trace
        .iter()
        .filter(|l| l.contains(" walk: "))
        .map(|l| l.split_whitespace().collect::<Vec<_>>().join(" "))
        .filter(|l| !l.contains("posts walk: back @2") || l.starts_with("2.000s"))
        .collect();
    assert_eq!(
        about_walk,
        [
            "0.000s Walk posts walk: turn",
            "1.000s Walk posts walk: forward",
            // Reflex, one layer up, backs off while the obstacle is seen (every ringlet;
            // all but its first posting are left out here).
            "2.000s Reflex posts walk: back @2",
            // The ball comes near: Walk's command is suppressed, no reader sees it.
            "2.500s Walk suppressed walk: slow @0 (held by Reflex @2 until 3.000s)",
            // The obstacle went at 3s; Reflex's last posting at 2.9s held until 3.4s.
            "3.400s Walk takes over walk: slow @0 (the hold above ran out)",
            "5.000s Walk posts walk: stop",
        ],
        "{:#?}",
        run.trace
    );
    let suppressed: Vec<&Event> = run
        .events
        .iter()
        .filter(|e| matches!(e, Event::Suppressed { .. }))
        .collect();
    assert_eq!(suppressed.len(), 1, "{suppressed:#?}");
    let json = serde_json::to_string(suppressed[0]).unwrap();
    assert!(
        json.starts_with(r#"{"event":"suppressed","machine":"Walk","type":"walk","content":"slow","priority":0,"by":"Reflex","by_priority":2,"until_us":3000000,"#),
        "{json}"
    );
    let walk = run.board.latest("walk").unwrap();
    assert_eq!(
        (walk.value.to_string(), &*walk.module, walk.priority),
        ("\"stop\"".to_string(), "Walk", 0)
    );
}

/// The schedule wakes for a hold running out, not only at its ring period: with rounds every
/// 400 ms, Reflex's last posting at 2.9 s holds until 3.35 s, and Walk takes over then.
#[test]
fn the_takeover_comes_when_the_hold_runs_out_between_ring_periods() {
    let manifest = std::fs::read_to_string(example().join("behaviour.toml"))
        .unwrap()
        .replace("description", "ring_period = \"400ms\"\ndescription")
        .replace("hold = \"500ms\"", "hold = \"450ms\"");
    let files: Vec<(&str, String)> = vec![
        ("behaviour.toml", manifest),
        (
            "Walk.machine",
            std::fs::read_to_string(example().join("Walk.machine")).unwrap(),
        ),
        (
            "Reflex.machine",
            std::fs::read_to_string(example().join("Reflex.machine")).unwrap(),
        ),
        ("field.script", field_script()),
    ];
    let files: Vec<(&str, &str)> = files.iter().map(|(n, t)| (*n, t.as_str())).collect();
    let dir = crate::behaviour_folder("subsumption-ring", &files);
    let run = run_scripted(&dir, &field_script(), Duration::from_secs(30)).unwrap();
    let takeover: Vec<&String> = run
        .trace
        .iter()
        .filter(|l| l.contains("takes over"))
        .collect();
    assert_eq!(takeover.len(), 1, "{:#?}", run.trace);
    assert!(
        takeover[0].trim_start().starts_with("3.350s Walk"),
        "{:#?}",
        run.trace
    );
}

/// What a module reading `walk` sees: never the suppressed `slow` while Reflex holds the type,
/// and then Walk's `slow` once the hold has run out, carrying each poster's priority.
#[tokio::test(start_paused = true)]
async fn a_reader_never_sees_a_suppressed_posting() {
    let behaviour = load("subsumption", Arc::new(Folder::new(example()))).unwrap();
    let board = Whiteboard::local();
    let mut legs = board.subscribe("walk");
    let mut running = launch(&behaviour, &board, LaunchOptions::default())
        .await
        .unwrap();
    let deadline = tokio::time::Instant::now() + Duration::from_secs(30);
    while let Ok(Some(event)) = tokio::time::timeout_at(deadline, running.events.recv()).await {
        if running.observe(&event) {
            break;
        }
    }
    running.stop().await;
    let mut seen: Vec<(String, String, u32)> = Vec::new();
    while let Some(m) = legs.try_next() {
        let value = m.value.to_string().trim_matches('"').to_string();
        if value == "slow" {
            assert_eq!(
                m.time,
                Duration::from_millis(3400),
                "slow seen before the hold ran out"
            );
        }
        if seen.last().is_none_or(|(v, _, _)| *v != value) {
            seen.push((value, m.module.to_string(), m.priority));
        }
    }
    let seen: Vec<(&str, &str, u32)> = seen
        .iter()
        .map(|(v, m, p)| (v.as_str(), m.as_str(), *p))
        .collect();
    assert_eq!(
        seen,
        [
            ("turn", "Walk", 0),
            ("forward", "Walk", 0),
            ("back", "Reflex", 2),
            ("slow", "Walk", 0),
            ("stop", "Walk", 0),
        ]
    );
}

/// A recording replays exactly (the holds are timed by the rounds' moments), on the virtual
/// clock and in real time; with a shorter hold the replay differs, and says where.
#[test]
fn a_recorded_subsumption_run_replays_exactly_and_a_changed_hold_is_caught() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("proclaim-subsumption-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let copy = dir.join("behaviour");
    std::fs::create_dir_all(&copy).unwrap();
    for file in [
        "behaviour.toml",
        "Walk.machine",
        "Reflex.machine",
        "field.script",
    ] {
        std::fs::copy(example().join(file), copy.join(file)).unwrap();
    }
    let recordings = dir.join("recordings");
    std::fs::create_dir_all(&recordings).unwrap();
    let folder = copy.to_str().unwrap();
    for (name, clock) in [("virtual.jsonl", true), ("real.jsonl", false)] {
        let path = recordings.join(name);
        let mut args = vec!["run", folder, "--record", path.to_str().unwrap()];
        if clock {
            args.push("--virtual-clock");
        }
        let o = proclaim(&args);
        assert!(o.status.success(), "{}", text(&o.stderr));
        assert!(text(&o.stdout).contains("Walk          suppressed walk: slow @0"));
    }
    let suite = proclaim(&["test", folder, recordings.to_str().unwrap()]);
    assert_eq!(suite.status.code(), Some(0), "{}", text(&suite.stdout));
    assert!(text(&suite.stdout).ends_with("2 passed, 0 failed\n"));

    let manifest = copy.join("behaviour.toml");
    let shorter = std::fs::read_to_string(&manifest)
        .unwrap()
        .replace("hold = \"500ms\"", "hold = \"50ms\"");
    std::fs::write(&manifest, shorter).unwrap();
    let virtual_run = recordings.join("virtual.jsonl");
    let changed = proclaim(&["test", folder, virtual_run.to_str().unwrap()]);
    assert_eq!(changed.status.code(), Some(1), "{}", text(&changed.stderr));
    assert!(
        text(&changed.stdout).contains(": round ")
            && text(&changed.stdout).contains("found takes over walk: forward"),
        "{}",
        text(&changed.stdout)
    );
}

/// Every bad `[suppress]` entry is an error at its place in the manifest (line, column).
#[test]
fn check_places_each_bad_suppress_entry() {
    let machine = "machine Walk\nstate S {\n  entry {\n    walk: forward\n  }\n}\n";
    let cases: &[(&str, usize, usize, &str)] = &[
        (
            "[suppress]\nwlk = { hold = \"500ms\" }\n",
            6,
            1,
            "`suppress` names `wlk`, which no machine of the behaviour posts; did you mean `walk`?",
        ),
        (
            "[suppress]\nwalk = { hold = \"soon\" }\n",
            6,
            17,
            "hold = \"soon\" for `walk` is not a duration above zero (write 500ms, 2s or 1.5s)",
        ),
        (
            "[suppress]\nwalk = { hold = \"0s\" }\n",
            6,
            17,
            "hold = \"0s\" for `walk` is not a duration above zero (write 500ms, 2s or 1.5s)",
        ),
        (
            "[suppress.walk]\nhold = \"1s\"\n[suppress.kick]\nhold = \"1s\"\n",
            7,
            11,
            "`suppress` names `kick`, which no machine of the behaviour posts",
        ),
    ];
    for (i, (table, line, column, message)) in cases.iter().enumerate() {
        let manifest = format!("[[machine]]\nfile = \"Walk.machine\"\npriority = 1\n\n{table}");
        let dir = crate::behaviour_folder(
            &format!("suppress-{i}"),
            &[("behaviour.toml", &manifest), ("Walk.machine", machine)],
        );
        let errors = load("bad", Arc::new(Folder::new(&dir))).err().unwrap();
        let found: Vec<(Option<usize>, Option<usize>, String)> = errors
            .iter()
            .filter(|e| e.is_error())
            .map(|e| (e.line, e.column, e.message.clone()))
            .collect();
        assert_eq!(
            found,
            [(Some(*line), Some(*column), message.to_string())],
            "case {i}"
        );
        assert!(errors[0].file.ends_with("behaviour.toml") && errors[0].is_error());
    }
    // A layer's priority on a behaviour that suppresses nothing it posts is a warning.
    let dir = crate::behaviour_folder(
        "suppress-none",
        &[
            (
                "behaviour.toml",
                "[[machine]]\nfile = \"Walk.machine\"\npriority = 3\n",
            ),
            ("Walk.machine", machine),
        ],
    );
    let loaded = load("lone", Arc::new(Folder::new(&dir))).unwrap();
    let warnings: Vec<String> = loaded.warnings.iter().map(|w| w.message.clone()).collect();
    assert_eq!(
        warnings,
        ["machine `Walk` has priority = 3, but posts no type of [suppress]: its priority changes nothing"]
    );
    let concurrent = "schedule = \"concurrent\"\n[[machine]]\nfile = \"Walk.machine\"\n\n[suppress]\nwalk = { hold = \"1s\" }\n";
    let dir = crate::behaviour_folder(
        "suppress-concurrent",
        &[("behaviour.toml", concurrent), ("Walk.machine", machine)],
    );
    let errors = load("bad", Arc::new(Folder::new(&dir))).err().unwrap();
    assert!(
        errors[0]
            .to_string()
            .ends_with("behaviour.toml:6: error: `suppress` needs the round schedule: under schedule = \"concurrent\" there is no round's moment to time `walk`'s hold by"),
        "{errors:#?}"
    );
}

#[test]
fn verify_refuses_a_behaviour_with_suppression_rather_than_answer_wrongly() {
    let o = proclaim(&[
        "verify",
        example().to_str().unwrap(),
        "--reachable",
        "Walk.KICK",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        text(&o.stderr).contains(
            "the behaviour declares [suppress] for `walk`: verify does not model subsumption yet"
        ),
        "{}",
        text(&o.stderr)
    );
}

#[test]
fn the_dependency_diagram_marks_the_suppressing_edge() {
    let o = proclaim(&["deps", example().to_str().unwrap()]);
    let dot = text(&o.stdout);
    assert!(o.status.success(), "{}", text(&o.stderr));
    assert!(
        dot.contains(r#""Reflex" -> "legs" [color=blue4, fontcolor=blue4, penwidth=2, arrowhead=odot, label="walk @2 S 500ms"];"#),
        "{dot}"
    );
    assert!(
        dot.contains(r#""Walk" -> "legs" [style=dashed, label="walk @0"];"#),
        "{dot}"
    );
    // Only the suppressed type is marked.
    assert!(dot.contains(r#""Walk" -> "legs" [label="kick"];"#), "{dot}");
}
