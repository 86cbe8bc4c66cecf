//! `run --record`, `replay` and `test`: a run's whiteboard kept, printed, replayed as a test.

use super::{record_run, stderr, stdout, temp_file};
use crate::proclaim;

#[test]
fn record_keeps_every_whiteboard_message_and_replay_prints_it() {
    let record = temp_file("microwave-record.jsonl", b"");
    let o = proclaim(&[
        "run",
        "microwave",
        "--virtual-clock",
        "--record",
        record.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let out = stdout(&o);
    let posted: usize = out
        .lines()
        .find_map(|l| l.trim().strip_suffix(" unanswerable)"))
        .and_then(|l| l.split(' ').next())
        .and_then(|n| n.parse().ok())
        .expect("the postings count");
    let text = std::fs::read_to_string(&record).unwrap();
    let messages = text
        .lines()
        .filter(|l| !l.starts_with(r#"{"ringlet""#) && !l.starts_with(r#"{"event""#))
        .count();
    assert_eq!(messages, posted, "every posting recorded");
    assert!(
        text.lines().any(|l| l.starts_with(r#"{"ringlet":{"#))
            && text.lines().any(|l| l.starts_with(r#"{"event":"entered""#)),
        "and every ringlet and event, for `proclaim test`"
    );
    assert!(
        out.contains(&format!("{posted} messages recorded in")),
        "{out}"
    );
    assert!(
        text.contains(r#"{"at_us":1000000,"module":"impersonator","seq":"#),
        "the script's posting at 1 s"
    );
    let o = proclaim(&["replay", record.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(
        stdout(&o).contains("   1.000s #") && stdout(&o).contains("impersonator   doorOpen = true"),
        "{}",
        stdout(&o)
    );
}

/// A recorded run is a regression test: `proclaim test` replays what came from outside the
/// behaviour (here the kitchen script's impersonator) at the rounds it came, passes on the
/// behaviour that made the recording, in real time and on the virtual clock, and names the
/// first difference once a machine file is changed.
#[test]
fn a_recorded_run_is_a_test_that_names_the_first_difference() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("proclaim-recorded-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let oven = dir.join("oven");
    std::fs::create_dir_all(&oven).unwrap();
    let manifest = std::fs::read_to_string(root.join("machines/microwave/behaviour.toml"))
        .unwrap()
        .replace(
            "../../theories/microwave.dl",
            &root.join("theories/microwave.dl").display().to_string(),
        );
    std::fs::write(oven.join("behaviour.toml"), manifest).unwrap();
    for file in ["Microwave.machine", "kitchen.script"] {
        std::fs::copy(root.join("machines/microwave").join(file), oven.join(file)).unwrap();
    }
    let oven = oven.to_str().unwrap();
    let virtual_run = dir.join("virtual.jsonl");
    let real_run = dir.join("real.jsonl");
    let recorded = proclaim(&[
        "run",
        oven,
        "--virtual-clock",
        "--for",
        "8s",
        "--record",
        virtual_run.to_str().unwrap(),
    ]);
    assert!(recorded.status.success(), "{}", stderr(&recorded));
    let recorded = proclaim(&[
        "run",
        oven,
        "--for",
        "5s",
        "--record",
        real_run.to_str().unwrap(),
    ]);
    assert!(recorded.status.success(), "{}", stderr(&recorded));

    // Both recordings as a suite (a folder), on the behaviour that made them.
    let suite = proclaim(&["test", oven, dir.to_str().unwrap()]);
    assert_eq!(
        suite.status.code(),
        Some(0),
        "{}{}",
        stdout(&suite),
        stderr(&suite)
    );
    assert!(
        stdout(&suite).ends_with("2 passed, 0 failed\n"),
        "{}",
        stdout(&suite)
    );

    // The machine now lights the lamp another way when the door opens.
    let machine = dir.join("oven/Microwave.machine");
    let text = std::fs::read_to_string(&machine).unwrap();
    std::fs::write(&machine, text.replace("Light: on\n", "Light: bright\n")).unwrap();
    let changed = proclaim(&["test", oven, virtual_run.to_str().unwrap()]);
    assert_eq!(changed.status.code(), Some(1), "{}", stderr(&changed));
    let out = stdout(&changed);
    assert!(
        out.contains(": round ")
            && out.contains("Microwave: expected posts Light: on, found posts Light: bright"),
        "{out}"
    );

    let not_a_recording = temp_file("trace.jsonl", b"{\"event\":\"entered\"}\n");
    let bad = proclaim(&["test", oven, not_a_recording.to_str().unwrap()]);
    assert_eq!(bad.status.code(), Some(2));
    assert!(stderr(&bad).contains("not a recording"), "{}", stderr(&bad));
}

/// Recordings of the built-in behaviours replay as recorded: sub-machines started and stopped,
/// `timeout`s, the GameController receiver on its socket (outside), variables alone.
#[test]
fn the_built_in_behaviours_recorded_replay_the_same() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("proclaim-replays-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for behaviour in ["game_controller", "shootout", "microwave"] {
        let recording = dir.join(format!("{behaviour}.jsonl"));
        let run = proclaim(&[
            "run",
            behaviour,
            "--virtual-clock",
            "--for",
            "70s",
            "--record",
            recording.to_str().unwrap(),
        ]);
        assert!(run.status.success(), "{behaviour}: {}", stderr(&run));
        let test = proclaim(&["test", behaviour, recording.to_str().unwrap()]);
        assert_eq!(
            test.status.code(),
            Some(0),
            "{behaviour}: {}{}",
            stdout(&test),
            stderr(&test)
        );
    }
}

/// A recording made when traces showed the lowered label (`Dive_side < 0`, `Dive_landed`,
/// `TRUE` for `done`) still replays, and covers what it covered: both read it as written now.
#[test]
fn a_recording_with_the_lowered_labels_of_before_still_replays() {
    let recording = temp_file("keeper-lowered.jsonl", b"");
    let run = proclaim(&[
        "run",
        "keeper",
        "--virtual-clock",
        "--for",
        "10s",
        "--record",
        recording.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", stderr(&run));
    let coverage = || {
        let o = proclaim(&["test", "keeper", recording.to_str().unwrap(), "--coverage"]);
        let out = stdout(&o);
        out[out.find("coverage:").expect("a coverage report")..].to_string()
    };
    let now = coverage();
    let text = std::fs::read_to_string(&recording).unwrap();
    let older = text
        .replace(r#""label":"side < 0""#, r#""label":"Dive_side < 0""#)
        .replace(r#""label":"Dive.landed""#, r#""label":"Dive_landed""#);
    assert_ne!(
        older, text,
        "the keeper fires on its parameter and the dive's outcome"
    );
    std::fs::write(&recording, older).unwrap();
    let test = proclaim(&["test", "keeper", recording.to_str().unwrap()]);
    assert_eq!(
        test.status.code(),
        Some(0),
        "{}{}",
        stdout(&test),
        stderr(&test)
    );
    assert_eq!(coverage(), now);
}

/// `test --coverage` says what recordings never exercised: the microwave's own kitchen script
/// never opens the door while cooking, so the priority `DoorCut > Timer` never decides an answer
/// and COOKING -> OPEN never fires; a second recording that opens the door mid-minute covers both.
#[test]
fn test_coverage_names_the_priority_no_recording_exercised() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("proclaim-coverage-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let kitchen = dir.join("kitchen.jsonl");
    let record =
        |path: &std::path::Path, extra: &[&str]| record_run("microwave", "70s", path, extra);
    record(&kitchen, &[]);
    let o = proclaim(&["test", "microwave", kitchen.to_str().unwrap(), "--coverage"]);
    let said = stdout(&o);
    assert_eq!(o.status.code(), Some(0), "{said}{}", stderr(&o));
    for line in [
        "  priorities deciding an answer: 2 of 4\n",
        "    never: microwave: DoorCut > Timer\n",
        "    never: Microwave: COOKING -> OPEN (~cook && light)\n",
    ] {
        assert!(said.contains(line), "{line:?} in\n{said}");
    }
    let door = dir.join("door.jsonl");
    let script = dir.join("door.script");
    std::fs::write(
        &script,
        "doorOpen = false\ntimeLeft = false\nat 1s timeLeft = true\nat 10s doorOpen = true\n",
    )
    .unwrap();
    record(&door, &["--script", script.to_str().unwrap()]);
    let o = proclaim(&[
        "test",
        "microwave",
        dir.to_str().unwrap(),
        "--coverage",
        "--json",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(stderr(&o).contains("2 passed, 0 failed"), "{}", stderr(&o));
    let json: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let exercised = |kind: &str, what: &str| {
        json[kind]
            .as_array()
            .unwrap()
            .iter()
            .find(|c| c["what"] == what)
            .unwrap_or_else(|| panic!("{what} in {json}"))["exercised"]
            .as_bool()
            .unwrap()
    };
    assert!(exercised("priorities", "microwave: DoorCut > Timer"));
    assert!(exercised(
        "transitions",
        "Microwave: COOKING -> OPEN (~cook && light)"
    ));
    assert!(!exercised(
        "transitions",
        "Microwave: OPEN -> COOKING (cook)"
    ));
}

/// A chart's coverage is of what was written: the keeper's match enters every step of its
/// nested dive and fires the dive's penalty, which lowering copies to each step; each is
/// listed once, exercised when any copy was.
#[test]
fn test_coverage_of_a_chart_lists_each_written_state_and_transition_once() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("proclaim-coverage-chart-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let recording = dir.join("match.jsonl");
    record_run("machines/keeper", "7s", &recording, &[]);
    let o = proclaim(&[
        "test",
        "machines/keeper",
        recording.to_str().unwrap(),
        "--coverage",
        "--json",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let json: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let listed = |kind: &str, what: &str| -> Vec<bool> {
        json[kind]
            .as_array()
            .unwrap()
            .iter()
            .filter(|c| c["what"] == what)
            .map(|c| c["exercised"].as_bool().unwrap())
            .collect()
    };
    assert_eq!(listed("states", "Keeper.DIVE.RIGHT"), [true], "{json}");
    assert_eq!(
        listed("transitions", "Keeper: DIVE -> PENALIZED (penalized)"),
        [true],
        "{json}"
    );
    assert_eq!(
        listed("transitions", "Keeper: GUARD -> PENALIZED (penalized)"),
        [false],
        "{json}"
    );
}

/// `test --update` accepts a deliberate change: a recording that the changed behaviour no longer
/// matches is recorded again on it (the same outside replayed), the changed round is shown, and
/// the new recording then passes; one that still matches is left alone.
#[test]
fn test_update_records_a_deliberate_change_again_and_shows_the_round() {
    let theory = std::fs::read_to_string("theories/microwave.dl").unwrap();
    let machine = std::fs::read_to_string("machines/microwave/Microwave.machine").unwrap();
    let kitchen = std::fs::read_to_string("machines/microwave/kitchen.script").unwrap();
    let manifest = std::fs::read_to_string("machines/microwave/behaviour.toml")
        .unwrap()
        .replace("../../theories/microwave.dl", "microwave.dl");
    let files = [
        ("behaviour.toml", manifest.as_str()),
        ("Microwave.machine", machine.as_str()),
        ("microwave.dl", theory.as_str()),
        ("kitchen.script", kitchen.as_str()),
    ];
    let folder = crate::behaviour_folder("update", &files);
    let behaviour = folder.to_str().unwrap();
    let recording = folder.join("kitchen.jsonl");
    record_run(behaviour, "70s", &recording, &[]);
    let recorded = recording.to_str().unwrap();
    let o = proclaim(&["test", behaviour, recorded, "--update"]);
    assert_eq!(o.status.code(), Some(0), "{}", stdout(&o));
    assert!(stdout(&o).starts_with("ok "), "unchanged: {}", stdout(&o));
    // Cooking (the last state to light the oven) now lights it brighter.
    let at = machine.rfind("Light: on").unwrap();
    let changed = format!("{}Light: bright{}", &machine[..at], &machine[at + 9..]);
    std::fs::write(folder.join("Microwave.machine"), changed).unwrap();
    let o = proclaim(&["test", behaviour, recorded]);
    assert_eq!(o.status.code(), Some(1), "{}", stdout(&o));
    let o = proclaim(&["test", behaviour, recorded, "--update"]);
    let said = stdout(&o);
    assert_eq!(o.status.code(), Some(0), "{said}{}", stderr(&o));
    assert!(
        said.contains(": recorded again, 1 round changed\n"),
        "{said}"
    );
    assert!(
        said.contains("    - 4.000s Microwave  posts Light: on\n    + 4.000s Microwave  posts Light: bright\n"),
        "{said}"
    );
    let o = proclaim(&["test", behaviour, recorded]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "the new recording passes: {}",
        stdout(&o)
    );
}
