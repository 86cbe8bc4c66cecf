//! Checkpoints (`proclaim run --checkpoint-at`, `--resume`; `docs/spec/behaviour.md` §3.4): a
//! run written down at a round and taken up in a new process plays the rest of the
//! uninterrupted run's trace byte for byte, and a checkpoint the behaviour no longer fits is
//! refused, saying why.

use crate::proclaim;
use std::path::{Path, PathBuf};

/// The shipped behaviours that run alone on the virtual clock (no program, sensor or team).
const SHIPPED: [&str; 6] = [
    "keeper",
    "microwave",
    "press",
    "search",
    "shootout",
    "subsumption",
];

fn scratch(tag: &str) -> PathBuf {
    crate::fresh_folder(&format!("proclaim-checkpoint-{tag}"))
}

/// `proclaim run BEHAVIOUR --virtual-clock --for 90s --trace TRACE` with `extra`; the trace's
/// lines and what the run printed.
fn run(behaviour: &str, trace: &Path, extra: &[&str]) -> (Vec<String>, String) {
    let trace_arg = trace.to_str().unwrap();
    let mut args = vec![
        "run",
        behaviour,
        "--virtual-clock",
        "--for",
        "90s",
        "--trace",
        trace_arg,
    ];
    args.extend_from_slice(extra);
    let out = proclaim(&args);
    let printed = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(out.status.code().is_some_and(|c| c < 2), "{printed}");
    let text = std::fs::read_to_string(trace).unwrap_or_default();
    (text.lines().map(str::to_string).collect(), printed)
}

/// The round of a trace line.
fn round_of(line: &str) -> u64 {
    let event: serde_json::Value = serde_json::from_str(line).unwrap();
    event["round"].as_u64().unwrap_or(0)
}

#[test]
fn every_shipped_behaviour_taken_up_from_a_checkpoint_plays_the_rest_of_its_run_byte_for_byte() {
    for behaviour in SHIPPED {
        let dir = scratch(behaviour);
        let (whole, _) = run(behaviour, &dir.join("whole.jsonl"), &[]);
        let last = whole.last().map_or(1, |l| round_of(l));
        // The first round, and three more spread over the run.
        for at in [1, last / 4, last / 2, last * 3 / 4].map(|r| r.max(1)) {
            let file = dir.join(format!("at{at}.json"));
            let file_arg = file.to_str().unwrap();
            let at_arg = at.to_string();
            let (written, printed) = run(
                behaviour,
                &dir.join(format!("written{at}.jsonl")),
                &["--checkpoint-at", &at_arg, "--checkpoint-file", file_arg],
            );
            assert_eq!(written, whole, "{behaviour}: a checkpoint changed the run");
            assert!(
                file.exists(),
                "{behaviour}: no checkpoint at {at}:\n{printed}"
            );
            let checkpoint: serde_json::Value =
                serde_json::from_str(&std::fs::read_to_string(&file).unwrap()).unwrap();
            let round = checkpoint["round"].as_u64().unwrap();
            assert!(
                round >= at,
                "{behaviour}: checkpoint at {round}, asked {at}"
            );
            let (rest, printed) = run(
                behaviour,
                &dir.join(format!("rest{at}.jsonl")),
                &["--resume", file_arg],
            );
            let before = whole.len() - rest.len();
            assert_eq!(
                whole[before..],
                rest[..],
                "{behaviour} taken up at round {round}:\n{printed}"
            );
            assert!(
                whole[..before].iter().all(|l| round_of(l) <= round)
                    && rest.iter().all(|l| round_of(l) >= round),
                "{behaviour}: the resumed trace does not begin at round {round}"
            );
        }
    }
}

/// The search (`machines/search`) taken up at every round: a checkpoint taken while the head
/// turns inside the search keeps when the search began, which its give-up counts from.
#[test]
fn a_composite_timed_as_a_whole_taken_up_at_any_round_gives_up_when_the_whole_run_did() {
    let dir = scratch("search-every-round");
    let (whole, _) = run("search", &dir.join("whole.jsonl"), &[]);
    let last = whole.last().map_or(1, |l| round_of(l));
    let mut inside = 0;
    for at in 1..=last {
        let file = dir.join(format!("at{at}.json"));
        let file_arg = file.to_str().unwrap();
        let at_arg = at.to_string();
        run(
            "search",
            &dir.join(format!("written{at}.jsonl")),
            &["--checkpoint-at", &at_arg, "--checkpoint-file", file_arg],
        );
        let Ok(text) = std::fs::read_to_string(&file) else {
            continue;
        };
        inside += usize::from(text.contains("\"composites\"") && text.contains("LOOK."));
        let (rest, printed) = run(
            "search",
            &dir.join(format!("rest{at}.jsonl")),
            &["--resume", file_arg],
        );
        assert_eq!(
            whole[whole.len() - rest.len()..],
            rest[..],
            "the search taken up at round {at}:\n{printed}"
        );
    }
    assert!(inside > 3, "checkpoints taken inside the search: {inside}");
}

/// A counter that goes round a loop on a timeout, so a run has many rounds at many moments.
const COUNTER: &str = "machine Counter
initial Counting

state Counting {
    entry {
        int n;
        n = n + 1;
    }
    when n >= 40 -> Done
    when after_ms(100) -> Counting
}

state Done {
}
";

#[test]
fn a_checkpoint_the_behaviour_no_longer_fits_is_refused_saying_why_and_one_that_fits_goes_on() {
    let dir = crate::behaviour_folder(
        "checkpoint-fit",
        &[
            (
                "behaviour.toml",
                "[[machine]]\nfile = \"Counter.machine\"\n",
            ),
            ("Counter.machine", COUNTER),
        ],
    );
    let folder = dir.to_str().unwrap();
    let file = dir.join("at10.json");
    let file_arg = file.to_str().unwrap();
    let (_, printed) = run(
        folder,
        &dir.join("whole.jsonl"),
        &["--checkpoint-at", "10", "--checkpoint-file", file_arg],
    );
    assert!(printed.contains("checkpoint at round 10"), "{printed}");
    let machine = dir.join("Counter.machine");
    let resume = |changed: &str| {
        std::fs::write(&machine, changed).unwrap();
        let out = proclaim(&[
            "run",
            folder,
            "--virtual-clock",
            "--for",
            "10s",
            "--resume",
            file_arg,
        ]);
        let printed = format!(
            "{}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        );
        (out.status.code(), printed)
    };
    let (code, printed) = resume(&COUNTER.replace("Counting", "Tally"));
    assert_eq!(code, Some(2), "{printed}");
    assert!(
        printed.contains(
            "Counter is in state Counting in the checkpoint, which the machine no longer has"
        ),
        "{printed}"
    );
    let (code, printed) = resume(&COUNTER.replace("int n;", "float n;"));
    assert_eq!(code, Some(2), "{printed}");
    assert!(
        printed.contains("Counter: `n` was int in the checkpoint and is float now"),
        "{printed}"
    );
    let (code, printed) = resume(&COUNTER.replace("int n;", "int n;\n        int m;"));
    assert_eq!(code, Some(0), "{printed}");
    assert!(
        printed.contains("`m` is new; it starts at zero"),
        "{printed}"
    );
    assert!(printed.contains("finished in Done"), "{printed}");

    // A header edited by hand that no longer says what the schedule holds.
    let written = std::fs::read_to_string(&file).unwrap();
    let edited = written.replacen("\"round\":10,", "\"round\":11,", 1);
    assert_ne!(edited, written, "the header's round is written first");
    std::fs::write(&file, edited).unwrap();
    let (code, printed) = resume(COUNTER);
    assert_eq!(code, Some(2), "{printed}");
    assert!(printed.contains("its header says round 11 at"), "{printed}");

    std::fs::write(
        &file,
        "{\"format\": \"proclaim checkpoint\", \"version\": 99}",
    )
    .unwrap();
    let (code, printed) = resume(COUNTER);
    assert_eq!(code, Some(2), "{printed}");
    assert!(
        printed.contains("a checkpoint of version 99, and this proclaim reads version 1"),
        "{printed}"
    );
}

#[test]
fn a_checkpoint_file_with_no_checkpoint_asked_is_refused() {
    let out = proclaim(&[
        "run",
        "press",
        "--virtual-clock",
        "--checkpoint-file",
        "c.json",
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("--checkpoint-file says where checkpoints go"),
        "{stderr}"
    );
}

#[test]
fn a_run_whose_state_is_not_all_its_own_is_refused_a_checkpoint_by_name() {
    let out = proclaim(&[
        "run",
        "game_controller",
        "--virtual-clock",
        "--for",
        "1s",
        "--checkpoint-at",
        "5",
        "--checkpoint-file",
        "/nonexistent/never.json",
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("no checkpoint can be taken: `gamecontroller` keeps state of its own"),
        "{stderr}"
    );
}

/// A recording, a trace or a checkpoint past a gigabyte (a wrong path, a disk image) is
/// refused before it is read, saying what it should have been; the file here is sparse, so
/// the test takes no disk.
#[test]
fn a_file_larger_than_a_recording_trace_or_checkpoint_can_be_is_refused_unread() {
    let dir = scratch("huge");
    let huge = dir.join("huge.jsonl");
    let file = std::fs::File::create(&huge).unwrap();
    file.set_len((1 << 30) + 1).unwrap();
    let huge = huge.to_str().unwrap();
    let cases: [(&[&str], &str); 4] = [
        (&["test", "microwave", huge], "a recording"),
        (
            &["run", "microwave", "--branch", huge, "--at", "3"],
            "a recording",
        ),
        (&["replay", huge], "a trace or a recording"),
        (
            &["run", "microwave", "--virtual-clock", "--resume", huge],
            "a checkpoint",
        ),
    ];
    for (args, what) in cases {
        let out = proclaim(args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(
            stderr.contains(&format!(
                "huge.jsonl: 1073741825 bytes, more than {what} here can be (1073741824 at most)"
            )),
            "{args:?}: {stderr}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
