//! `check`: every problem of theories, machine files and behaviours, as text and as JSON.

use super::{assert_one_problem_shape, check, generated, stderr, stdout, temp_file};
use crate::proclaim;

#[test]
fn check_reports_every_error_and_exits_1() {
    let bad = temp_file("bad.dl", b"R1: a => b.\nR1: c => d.\nR1 > R7.\nx y.\n");
    let o = proclaim(&["check", bad.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    let err = stderr(&o);
    assert!(err.contains("rule label `R1` is used twice"), "{err}");
    assert!(err.contains("no rule is labelled `R7`"), "{err}");
    assert!(err.contains("unexpected `y`"), "{err}");
    assert!(err.contains("bad.dl:3:6"), "{err}");
    assert!(err.contains("3 errors found"), "{err}");
    let o = proclaim(&["check", bad.to_str().unwrap(), "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v.as_array().unwrap().len(), 3);
    assert_eq!(v[0]["line"], 2);
    assert_one_problem_shape(&v);
    check(
        &["check", "offside"],
        0,
        "<embedded>/offside.dl: ok (5 atoms, 5 rules, 4 priorities, 4 inputs, 1 output; 0 warnings)\n",
    );
}

/// A typo in a rule's condition (a first team's goalie) silently disabled the exception: the
/// warning said so with a did-you-mean, and CI could not fail on it. Each summary counts the
/// warnings printed above it; `--deny-warnings` fails on them.
#[test]
fn a_typo_in_a_rule_is_counted_and_fails_with_deny_warnings() {
    let dir = crate::behaviour_folder(
        "typo",
        &[
            ("goalie.dl", "input{ballNear}.\ninput{teammateCloser}.\nCome: ballNear => comeOut.\nMate: teamateCloser => ~comeOut.\nMate > Come.\noutput{comeOut}.\n"),
            ("Goalie.machine", "machine Goalie\ninitial WAIT\nstate WAIT {\n    when comeOut -> OUT\n}\nstate OUT { }\n"),
            ("behaviour.toml", "[[machine]]\nfile = \"Goalie.machine\"\n[[theory]]\nfile = \"goalie.dl\"\n[impersonator]\nscript = \"s.script\"\n"),
            ("s.script", "ballNear = true\nteammateCloser = true\n"),
        ],
    );
    let theory = dir.join("goalie.dl");
    let o = proclaim(&["check", theory.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(
        stdout(&o).ends_with("1 output; 2 warnings)\n"),
        "{}",
        stdout(&o)
    );
    assert!(
        stderr(&o).contains("did you mean `teammateCloser`?"),
        "{}",
        stderr(&o)
    );
    let o = proclaim(&["check", dir.to_str().unwrap()]);
    let printed = stderr(&o).matches("warning: ").count();
    assert_eq!(printed, 2, "{}", stderr(&o));
    assert!(
        stdout(&o).ends_with("0 errors, 2 warnings)\n"),
        "{}",
        stdout(&o)
    );
    let o = proclaim(&["check", "--deny-warnings", dir.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).ends_with("error: 2 warnings denied (--deny-warnings)\n"),
        "{}",
        stderr(&o)
    );
    check(&["check", "--deny-warnings", "offside"], 0, "<embedded>/offside.dl: ok (5 atoms, 5 rules, 4 priorities, 4 inputs, 1 output; 0 warnings)\n");
}

#[test]
fn ten_megabytes_of_garbage_are_refused_cleanly() {
    garbage_is_refused_cleanly(10 << 20);
}

#[test]
#[ignore = "before a release: a hundred megabytes (`--run-ignored all`)"]
fn a_hundred_megabytes_of_garbage_is_refused_cleanly() {
    garbage_is_refused_cleanly(100 << 20);
}

/// A source past the bound every reader holds (`MAX_SOURCE_BYTES`) is refused before a byte is
/// read, naming the file, its size and the bound: a theory named alone, and a machine of a
/// behaviour. (Sparse files: the test takes no disk.)
#[test]
fn a_source_larger_than_the_bound_is_refused_before_it_is_read() {
    let size = proclaim_syntax::MAX_SOURCE_BYTES + (44 << 20);
    let theory = temp_file("huge.dl", b"");
    std::fs::File::options()
        .write(true)
        .open(&theory)
        .and_then(|f| f.set_len(size))
        .unwrap();
    let o = proclaim(&["check", theory.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("huge.dl")
            && stderr(&o).contains("the file is 300 MiB, over the 256 MiB a source file may be"),
        "{}",
        stderr(&o)
    );
    let dir = crate::fresh_folder("huge-machine");
    std::fs::write(
        dir.join("behaviour.toml"),
        "[[machine]]\nfile = \"Big.machine\"\n",
    )
    .unwrap();
    std::fs::File::create(dir.join("Big.machine"))
        .and_then(|f| f.set_len(size))
        .unwrap();
    let o = proclaim(&["check", dir.to_str().unwrap()]);
    assert_ne!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("Big.machine") && stderr(&o).contains("over the 256 MiB"),
        "{}",
        stderr(&o)
    );
    std::fs::remove_file(theory).unwrap();
    let _ = std::fs::remove_dir_all(dir);
}

/// `size` bytes of garbage are refused with problems (not all shown), a binary file as not UTF-8.
fn garbage_is_refused_cleanly(size: usize) {
    // Printable garbage with some structure-like characters, so the parser works for it.
    let mut garbage = Vec::with_capacity(size);
    let mut x: u64 = 0x2545F4914F6CDD1D;
    let alphabet = b"ab~.,:{}=>-\\/%\" \n$R1";
    while garbage.len() < size {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        garbage.push(alphabet[(x % alphabet.len() as u64) as usize]);
    }
    let path = temp_file(&format!("garbage-{size}.dl"), &garbage);
    let o = proclaim(&["check", path.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("more problems not shown"),
        "{}",
        &stderr(&o)[..2000.min(stderr(&o).len())]
    );
    let binary = temp_file("binary.dl", &[0xff, 0xfe, 0x00, 0x41]);
    let o = proclaim(&["check", binary.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("not UTF-8"), "{}", stderr(&o));
    std::fs::remove_file(path).unwrap();
}

#[test]
fn check_reads_t_a_pairs_and_qfsm_files() {
    let Some(dir) = crate::corpus_dir() else {
        eprintln!("skipped: ../shared/corpus is absent");
        return;
    };
    let corpus = dir.join("mipal");
    let a = corpus.join("testfiles/AGameController.txt");
    let fsm = corpus.join("machines/SMGetUp.fsm");
    let o = proclaim(&["check", a.to_str().unwrap(), fsm.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(
        stdout(&o)
            .contains("AGameController.txt: ok (1 machine, 21 states, 51 transitions, 0 warnings)"),
        "{}",
        stdout(&o)
    );
    let broken = corpus.join("testfiles/TSensorsTester.txt");
    let o = proclaim(&["check", broken.to_str().unwrap(), "--json"]);
    assert_eq!(o.status.code(), Some(1));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v[0]["line"], 12);
    assert!(v[0]["message"].as_str().unwrap().contains("OnEnrtry"));
}

#[test]
fn a_behaviour_check_finds_errors_in_is_refused_by_run_and_checked_file_by_file() {
    let broken = crate::behaviour_folder(
        "check-files",
        &[
            (
                "behaviour.toml",
                "[[machine]]\nfile = \"A.machine\"\n[[machine]]\nfile = \"B.machine\"\n",
            ),
            ("A.machine", "machine A\nstate S {\n when x && -> S\n}\n"),
            ("B.machine", "machine B\nstate S {\n entry {\n"),
        ],
    );
    // Every file's problems, each with its own file and line.
    let o = proclaim(&["check", broken.to_str().unwrap(), "--json"]);
    assert_eq!(o.status.code(), Some(1));
    let report: serde_json::Value = serde_json::from_str(&stdout(&o)).expect("JSON");
    let places: Vec<(String, u64)> = report
        .as_array()
        .unwrap()
        .iter()
        .map(|r| {
            let file = r["file"].as_str().unwrap();
            let file = file.rsplit('/').next().unwrap().to_string();
            (file, r["line"].as_u64().unwrap())
        })
        .collect();
    assert_eq!(
        places,
        [("A.machine".to_string(), 3), ("B.machine".to_string(), 4)]
    );

    let unanswered = crate::behaviour_folder(
        "check-refuse",
        &[
            (
                "behaviour.toml",
                "[[machine]]\nfile = \"A.machine\"\n[[machine]]\nfile = \"Idle.machine\"\nstart = false\n",
            ),
            ("A.machine", "machine A\nstate S {\n when ready -> T\n}\nstate T {\n}\n"),
            ("Idle.machine", "machine Idle\nstate S {\n}\n"),
        ],
    );
    let o = proclaim(&["check", unanswered.to_str().unwrap()]);
    assert!(
        stderr(&o).contains("Idle.machine:1: warning: sub-machine `Idle` has `start = false` and no module posts `Idle: On`, so it never runs"),
        "{}",
        stderr(&o)
    );
    let o = proclaim(&["run", unanswered.to_str().unwrap(), "--for", "1s"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("A.machine:3: error: label `ready` is answered by no expert")
            && stderr(&o).contains("run it anyway with --force"),
        "{}",
        stderr(&o)
    );
    let o = proclaim(&[
        "run",
        unanswered.to_str().unwrap(),
        "--for",
        "1s",
        "--force",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    // A script that answers the label is as good as an expert.
    let script = temp_file(
        "ready.script",
        b"at 100ms ready = true\nat 200ms redy = true\n",
    );
    let o = proclaim(&[
        "run",
        unanswered.to_str().unwrap(),
        "--script",
        script.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(stdout(&o).contains("→ T"), "{}", stdout(&o));
    assert!(
        stderr(&o).contains(
            "ready.script:2: warning: `redy` is asked by no machine and read by no module; did you mean `ready`?"
        ),
        "{}",
        stderr(&o)
    );
}

#[test]
fn check_says_why_a_negated_output_is_not_queried_and_where_it_is_declared() {
    let dir = crate::behaviour_folder(
        "negated-output",
        &[
            (
                "behaviour.toml",
                "[[machine]]\nfile = \"M.machine\"\n[[theory]]\nfile = \"ref.dl\"\n[impersonator]\nscript = \"s.script\"\n",
            ),
            (
                "M.machine",
                "machine M\nstate A {\n  when ~expectPenalty -> B\n}\nstate B {\n}\n",
            ),
            (
                "ref.dl",
                "input{foul}.\nR: foul => expectPenalty.\n\noutput{~expectPenalty}.\n",
            ),
            ("s.script", "foul = false\nexpectPenalty = false\n"),
        ],
    );
    let o = proclaim(&["check", dir.to_str().unwrap()]);
    assert!(
        stderr(&o).contains("ref.dl:4: warning: output `~expectPenalty` of theory ref is queried by no machine; a label `~expectPenalty` asks for `expectPenalty` and negates its answer, so declare `output{expectPenalty}` for it"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn a_machine_files_errors_show_the_line_a_caret_and_a_near_name() {
    let machine = temp_file(
        "Typo.machine",
        b"machine M\nstate READY {\n  when go -> REDY\n}\n",
    );
    let o = proclaim(&["check", machine.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    let err = stderr(&o);
    assert!(
        err.contains("error: there is no state named `REDY`; did you mean `READY`?"),
        "{err}"
    );
    assert!(err.contains("Typo.machine:3:14"), "{err}");
    assert!(
        err.contains("3 │   when go -> REDY\n  │              ^^^^"),
        "{err}"
    );
}

#[test]
fn check_warns_where_only_a_search_decides_and_of_self_attacking_loops() {
    let ladder = temp_file(
        "crossed-ladder.dl",
        proclaim_gen::crossed_ladder().as_bytes(),
    );
    let o = proclaim(&["check", ladder.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0));
    assert!(
        stderr(&o).contains(
            "warning: rules attack each other in a cycle of 24 goals that only a search decides"
        ),
        "{}",
        stderr(&o)
    );
    // Structure decides a clique and the ladder itself: nothing to warn of.
    for (family, size) in [("clique", 30), ("ladder", 16)] {
        let o = proclaim(&["check", generated(family, size).to_str().unwrap()]);
        assert_eq!(stderr(&o), "", "{family}({size})");
    }
    let path = temp_file("self.dl", b"r3: => ~a2.\nr4: ~a2 => a2.\nr4 > r3.\n");
    let o = proclaim(&["check", path.to_str().unwrap()]);
    assert!(
        stderr(&o).contains(
            "warning: beta proves both `a2` and `~a2`, through a self-attacking loop: r4"
        ),
        "{}",
        stderr(&o)
    );
}

#[test]
fn check_refuses_a_team_label_without_a_team_and_a_shared_type_nobody_posts() {
    let player = include_str!("../../machines/striker/Player.machine");
    let voter = include_str!("../../machines/striker/Voter.machine");
    let manifest = include_str!("../../machines/striker/behaviour.toml");
    let folder = |tag: &str, manifest: &str| {
        crate::behaviour_folder(
            tag,
            &[
                ("behaviour.toml", manifest),
                ("Player.machine", player),
                ("Voter.machine", voter),
            ],
        )
    };
    let no_team: String = manifest
        .lines()
        .filter(|l| {
            !["[team]", "name = \"blue\"", "member", "shared", "size"]
                .iter()
                .any(|s| l.starts_with(s))
        })
        .map(|l| format!("{l}\n"))
        .collect();
    let dir = folder("no-team", &no_team);
    // The lines of the transitions that read the team.
    let line_of = |text: &str, what: &str| text.lines().position(|l| l.contains(what)).unwrap() + 1;
    let (when, votes) = (line_of(player, "-> STRIKER"), line_of(voter, "-> VOTE"));
    let o = proclaim(&["check", dir.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    for (file, line, word) in [
        ("Player", when, "team.majority(vote)"),
        ("Voter", votes, "team.argmin(ballDistance)"),
    ] {
        assert!(
            stderr(&o).contains(&format!("{file}.machine:{line}: error: label reads the team (`{word}`), but the manifest has no [team]")),
            "{}",
            stderr(&o)
        );
    }

    let misspelt = manifest.replace("[\"ballDistance\", ", "[\"ballDistnce\", ");
    let line = line_of(&misspelt, "ballDistnce");
    let dir = folder("misspelt-team", &misspelt);
    let o = proclaim(&["check", dir.to_str().unwrap(), "--json"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_one_problem_shape(&v);
    let problem = |text: &str| {
        v.as_array()
            .unwrap()
            .iter()
            .find(|p| p["message"].as_str().unwrap().contains(text))
            .unwrap_or_else(|| panic!("no problem says {text}: {v}"))
            .clone()
    };
    let unposted = problem("[team] shares `ballDistnce`, which no module of the behaviour posts");
    assert_eq!(unposted["line"], line);
    assert!(unposted["file"]
        .as_str()
        .unwrap()
        .ends_with("behaviour.toml"));
    assert_eq!(unposted["hint"], "did you mean `ballDistance`?");
    let unshared = problem(
        "label reads `team.argmin(ballDistance)`, but `ballDistance` is not shared with the team",
    );
    assert_eq!(unshared["line"], votes);

    // A vote or a quorum needs the team's size, from 1 robot up, and `quorum` is the team's.
    let unsized_team: String = manifest
        .lines()
        .filter(|l| !l.starts_with("size"))
        .map(|l| format!("{l}\n"))
        .collect();
    let dir = folder("unsized-team", &unsized_team);
    let o = proclaim(&["check", dir.to_str().unwrap(), "--json"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let unsized_problem = v
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["message"] == "label reads `team.majority`, but [team] does not say how many robots the team has")
        .unwrap_or_else(|| panic!("{v}"));
    assert_eq!(unsized_problem["line"], when);
    assert!(unsized_problem["hint"]
        .as_str()
        .unwrap()
        .starts_with("add size = N to [team]"));
    let size_line = line_of(manifest, "size = 3");
    let bad = manifest
        .replace("size = 3", "size = 0")
        .replace("\"vote\"]", "\"vote\", \"quorum\", \"size\"]");
    let dir = folder("zero-team", &bad);
    let o = proclaim(&["check", dir.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o)
            .lines()
            .any(|l| l.contains(&format!("behaviour.toml:{size_line}"))
                && l.contains("error: [team] size = 0: a team has from 1 to 1000 robots")),
        "{}",
        stderr(&o)
    );
    assert!(
        stderr(&o).contains("[team] shared `size`: `team.size` already says how many robots"),
        "{}",
        stderr(&o)
    );
    assert!(
        stderr(&o).contains("[team] shared `quorum`: `team.quorum` already says"),
        "{}",
        stderr(&o)
    );

    check(
        &["check", "machines/striker"],
        0,
        "machines/striker: ok (2 machines, 0 theories, 0 sensors; 0 errors, 0 warnings)\n",
    );
    // A team meets on a shared board, and a member needs a team.
    let o = proclaim(&["run", "machines/striker", "--for", "1s"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("robot1 of team `blue`, whose members meet on a shared whiteboard: add --listen, --connect ENDPOINT or --scout"), "{}", stderr(&o));
    let o = proclaim(&["run", "microwave", "--member", "robot2", "--for", "1s"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("--member robot2: the behaviour's manifest has no [team]"),
        "{}",
        stderr(&o)
    );
}

/// `[ranges]`: a range that cannot be read is an error at its value, one for a type no
/// machine reads a warning at its key with a near name; a run warns where a posting from
/// outside leaves its range, once per value, and not of a machine's own posting.
#[test]
fn declared_ranges_are_checked_and_a_run_says_where_the_world_left_one() {
    let machine = "machine Pump\ninitial IDLE\nstate IDLE {\n    entry { extern dose; }\n    when dose > 0 -> RUN\n}\nstate RUN {\n    entry { dose = 12; }\n    when dose <= 0 -> IDLE\n}\n";
    let dir = crate::behaviour_folder(
        "ranges",
        &[
            ("Pump.machine", machine),
            (
                "behaviour.toml",
                "[[machine]]\nfile = \"Pump.machine\"\n[impersonator]\nscript = \"s.script\"\n[ranges]\ndose = \"0..9\"\n",
            ),
            ("s.script", "dose = 3\nat 0.2s dose = 40\nat 0.3s dose = 40\nat 0.4s dose = -1\n"),
        ],
    );
    let o = proclaim(&["check", dir.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let o = proclaim(&[
        "run",
        dir.to_str().unwrap(),
        "--virtual-clock",
        "--for",
        "1s",
    ]);
    let out = stdout(&o);
    let warned: Vec<&str> = out.lines().filter(|l| l.contains("warning:")).collect();
    assert_eq!(warned.len(), 2, "{out}");
    assert!(
        warned[0].contains("impersonator")
            && warned[0].contains("posted dose = 40, outside its declared range 0..9"),
        "{out}"
    );
    assert!(warned[1].contains("dose = -1"), "{out}");

    let manifest = dir.join("behaviour.toml");
    std::fs::write(
        &manifest,
        "[[machine]]\nfile = \"Pump.machine\"\n[ranges]\ndose = \"9..0\"\ndoze = \"0..1\"\n",
    )
    .unwrap();
    let o = proclaim(&["check", dir.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(
        err.contains("range of `dose`: \"9..0\" is empty") && err.contains("behaviour.toml:4:8"),
        "{err}"
    );
    assert!(
        err.contains("`ranges` names `doze`, which no machine of the behaviour reads or binds with `extern`; did you mean `dose`?"),
        "{err}"
    );
}
