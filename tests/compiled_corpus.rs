//! The shared corpus's machines that `proclaim run` runs, compiled to C (here) and to Rust (in
//! `compiled_rust.rs`'s one workspace), write the interpreter's trace byte for byte: the
//! Griffith team's one-minute microwave of four gufsm machines talking through whiteboard
//! variables (`extern`) alone, and the machines that run alone once a script answers their
//! label atoms, three of them controlling machines a behaviour of their own does not hold
//! (`proclaim run --force` runs those, as a compiled program does). Skipped when the corpus is
//! absent. The corpus's other machines call host functions the interpreter does not have
//! either, compute fractions, post text to a whiteboard value a machine reads or time out after
//! a variable (each refused with file and line, tested below), or only name another file.

use super::compiled::{assert_same, build, gcc_missing, scratch, splitmix, traces};
use std::path::PathBuf;

/// A corpus behaviour to compile and the runs to hold to the interpreter's: name, script,
/// `--for`.
pub(crate) struct CorpusBehaviour {
    pub name: String,
    pub folder: PathBuf,
    pub runs: Vec<(String, String, Option<String>)>,
}

/// A folder holding the corpus's `files` (from `mipal/machines`) and a manifest running them in
/// that order: a copy under the tests' temporary folder, never in the repository.
fn corpus_behaviour(tag: &str, files: &[&str]) -> Option<PathBuf> {
    let corpus = crate::corpus_dir()?.join("mipal/machines");
    let folder = scratch(&format!("{tag}-corpus"));
    let mut manifest = String::new();
    for file in files {
        std::fs::copy(corpus.join(file), folder.join(file)).expect("the corpus file copies");
        manifest.push_str(&format!("[[machine]]\nfile = \"{file}\"\n"));
    }
    std::fs::write(folder.join("behaviour.toml"), manifest).unwrap();
    Some(folder)
}

/// A corpus machine that runs alone: its file (a T/A pair by its T file, its partner beside
/// it) and the label atoms no theory answers, which a script sets (the behaviour's own script
/// sets each false, so that the compiled program takes them from its host).
struct Alone {
    tag: &'static str,
    /// `mipal/machines` or `mipal/testfiles`.
    from: &'static str,
    files: &'static [&'static str],
    atoms: &'static [&'static str],
    /// Whether seeded scripts may set its atoms at will: not for a machine that, on some
    /// values, moves round a cycle of states in no time (the interpreter then never stops
    /// under `--virtual-clock`: the getter-up while the motion it plays is not yet running).
    seeded: bool,
    /// Scripts of what the robot would do (name, script, `--for`).
    scenes: &'static [(&'static str, &'static str, &'static str)],
}

/// The corpus machines that import, compile and run alone (found by compiling every one of
/// them: the guide, "Deploying a behaviour").
const ALONE: [Alone; 8] = [
    Alone {
        tag: "vlad-placer",
        from: "mipal/machines",
        files: &["VladPlacer.fsm"],
        atoms: &[
            "NaoMotionPlayerIsRunning",
            "yellowIsVisible",
            "shortChestButtonPressed",
        ],
        seeded: true,
        scenes: &[],
    },
    Alone {
        tag: "getup",
        from: "mipal/testfiles",
        files: &["TGetup.txt", "AGetup.txt"],
        atoms: &[
            "get_up_from_back_lie_downIsRunning",
            "get_up_from_front_lie_downIsRunning",
            "side_to_lie_downIsRunning",
            "robotFallenRight",
            "robotFallenLeft",
            "robotFallenForward",
            "robotFallenBack",
        ],
        seeded: false,
        scenes: &[
            ("right", "at 1s side_to_lie_downIsRunning = true\nat 1s robotFallenRight = true\nat 2s robotFallenRight = false\nat 3s side_to_lie_downIsRunning = false\n", "4s"),
            ("forward", "at 750ms get_up_from_front_lie_downIsRunning = true\nat 750ms robotFallenForward = true\nat 1234ms robotFallenForward = false\nat 2500ms get_up_from_front_lie_downIsRunning = false\n", "3s"),
            ("back", "at 300ms get_up_from_back_lie_downIsRunning = true\nat 300ms robotFallenBack = true\nat 900ms robotFallenBack = false\nat 1100ms get_up_from_back_lie_downIsRunning = false\n", "2s"),
        ],
    },
    Alone {
        tag: "obstacle-avoidance",
        from: "mipal/testfiles",
        files: &["TObstacleAvoidance.txt", "AObstacleAvoidance.txt"],
        atoms: &["obstacleRight", "obstacleAhead", "obstacleLeft"],
        seeded: false,
        // Any obstacle to a side spins it (TurnLeft and TurnRight loop on themselves): it
        // runs, but only waits.
        scenes: &[(
            "ahead",
            "obstacleAhead = true\nat 1s obstacleAhead = false\n",
            "2s",
        )],
    },
    Alone {
        tag: "oa",
        from: "mipal/testfiles",
        files: &["Toa.txt", "Aoa.txt"],
        atoms: &[
            "ObstacleAhead",
            "ObstacleLeft",
            "ObstacleRight",
            "ObstacleIsArising",
        ],
        seeded: false,
        scenes: &[(
            "arising",
            "at 500ms ObstacleIsArising = true\nat 800ms ObstacleIsArising = false\nat 1200ms ObstacleRight = true\nat 1500ms ObstacleRight = false\nat 1700ms ObstacleIsArising = true\nat 1700ms ObstacleIsArising = false\n",
            "3s",
        )],
    },
    Alone {
        tag: "microwave-timer-kripke",
        from: "mipal/machines",
        files: &["Examples__OneMinuteMicrowave__MicrowaveTimerKripke.fsm"],
        atoms: &[],
        seeded: false,
        scenes: &[],
    },
    // These three start and suspend machines of the team's whole player that a behaviour of
    // their own does not hold (`proclaim run` wants `--force`), and read the ball's place from
    // the whiteboard by name alone.
    Alone {
        tag: "goalie-eugene",
        from: "mipal/machines",
        files: &["SMGoalieEugene.fsm"],
        atoms: &[],
        seeded: false,
        scenes: &[],
    },
    Alone {
        tag: "head-ball-tracker-fair",
        from: "mipal/machines",
        files: &["SMHeadBallTrackerFair.fsm"],
        atoms: &[],
        seeded: false,
        scenes: &[],
    },
    Alone {
        tag: "head-ball-tracker-fair-find",
        from: "mipal/machines",
        files: &["SMHeadBallTrackerFairFind.fsm"],
        atoms: &[],
        seeded: false,
        scenes: &[],
    },
];

/// The behaviour of one machine that runs alone: its own script (every atom false) to 5 s, its
/// scenes, then (where that cannot spin) `seeded` scripts setting its atoms at any
/// millisecond, stopped at a seeded time.
fn alone(machine: &Alone, seeded: usize) -> Option<CorpusBehaviour> {
    let corpus = crate::corpus_dir()?.join(machine.from);
    let folder = scratch(&format!("{}-corpus", machine.tag));
    for file in machine.files {
        std::fs::copy(corpus.join(file), folder.join(file)).expect("the corpus file copies");
    }
    let own: String = machine
        .atoms
        .iter()
        .map(|a| format!("{a} = false\n"))
        .collect();
    std::fs::write(folder.join("own.script"), &own).unwrap();
    let mut manifest = format!("[[machine]]\nfile = \"{}\"\n", machine.files[0]);
    if !machine.atoms.is_empty() {
        manifest.push_str("[impersonator]\nscript = \"own.script\"\n");
    }
    std::fs::write(folder.join("behaviour.toml"), manifest).unwrap();
    let mut runs = vec![(machine.tag.to_string(), own, Some("5s".to_string()))];
    for (scene, script, run_for) in machine.scenes {
        runs.push((
            format!("{}-{scene}", machine.tag),
            script.to_string(),
            Some(run_for.to_string()),
        ));
    }
    let seeded = if machine.seeded { seeded } else { 0 };
    let mut seed = 0x5eed_0033_e100 ^ machine.tag.len() as u64;
    for n in 0..seeded {
        let mut script = String::new();
        for atom in machine.atoms {
            if splitmix(&mut seed) % 4 != 0 {
                script.push_str(&format!("{atom} = {}\n", splitmix(&mut seed) % 3 == 0));
            }
        }
        for _ in 0..1 + splitmix(&mut seed) % 8 {
            let at = match splitmix(&mut seed) % 3 {
                0 => 100 * (splitmix(&mut seed) % 40),
                _ => splitmix(&mut seed) % 4_000,
            };
            let atom = machine.atoms[(splitmix(&mut seed) % machine.atoms.len() as u64) as usize];
            let value = splitmix(&mut seed) % 2 == 0;
            script.push_str(&format!("at {at}ms {atom} = {value}\n"));
        }
        let run_for = format!("{}ms", 500 + splitmix(&mut seed) % 5_000);
        runs.push((format!("{}-random{n}", machine.tag), script, Some(run_for)));
    }
    Some(CorpusBehaviour {
        name: machine.tag.into(),
        folder,
        runs,
    })
}

/// The team's microwave: timer, cook, light and bell, bound by `extern buttonPushed` and
/// `extern doorOpen` and the global `timeLeft`. Runs: tests/behaviours.rs's script (the button,
/// then the door open and shut while cooking, to the bell), and `seeded` scripts of the button
/// and the door at any millisecond, some on the ring period's beat, stopped at a seeded time.
pub(crate) fn gufsm_microwave(seeded: usize) -> Option<CorpusBehaviour> {
    let files: Vec<String> = ["Timer", "Cook", "Light", "Bell"]
        .iter()
        .map(|p| format!("Examples__OneMinuteMicrowave__Microwave{p}.fsm"))
        .collect();
    let borrowed: Vec<&str> = files.iter().map(String::as_str).collect();
    let folder = corpus_behaviour("gufsm-microwave", &borrowed)?;
    let mut runs = vec![(
        "gufsm-microwave".to_string(),
        "buttonPushed = false\ndoorOpen = false\nat 1s buttonPushed = true\nat 1500ms buttonPushed = false\nat 10s doorOpen = true\nat 12s doorOpen = false\n".to_string(),
        Some("40s".to_string()),
    )];
    let mut seed = 0x5eed_0033_e000;
    for n in 0..seeded {
        let mut script = String::new();
        for atom in ["buttonPushed", "doorOpen"] {
            if splitmix(&mut seed) % 3 != 0 {
                script.push_str(&format!("{atom} = {}\n", splitmix(&mut seed) % 4 == 0));
            }
        }
        for _ in 0..1 + splitmix(&mut seed) % 10 {
            // Every third on a tenth of a second: the ring period's beat, where a round and a
            // posting meet.
            let at = match splitmix(&mut seed) % 3 {
                0 => 100 * (splitmix(&mut seed) % 60),
                _ => splitmix(&mut seed) % 6_000,
            };
            let atom = ["buttonPushed", "doorOpen"][(splitmix(&mut seed) % 2) as usize];
            let value = splitmix(&mut seed) % 2 == 0;
            script.push_str(&format!("at {at}ms {atom} = {value}\n"));
        }
        let run_for = format!("{}ms", 1_000 + splitmix(&mut seed) % 40_000);
        runs.push((format!("gufsm-microwave-random{n}"), script, Some(run_for)));
    }
    Some(CorpusBehaviour {
        name: "gufsm-microwave".into(),
        folder,
        runs,
    })
}

/// Every corpus behaviour these tests compile, `seeded` random runs each.
pub(crate) fn corpus_behaviours(seeded: usize) -> Vec<CorpusBehaviour> {
    let mut behaviours: Vec<CorpusBehaviour> = gufsm_microwave(seeded).into_iter().collect();
    behaviours.extend(ALONE.iter().filter_map(|m| alone(m, seeded)));
    behaviours
}

#[test]
fn the_corpus_machines_compiled_to_c_write_the_interpreters_trace() {
    if crate::corpus_dir().is_none() {
        eprintln!("skipped: ../shared/corpus is absent");
        return;
    }
    if gcc_missing() {
        return;
    }
    let behaviours = corpus_behaviours(24);
    assert_eq!(behaviours.len(), 1 + ALONE.len());
    let mut moved = 0;
    for b in &behaviours {
        let dir = scratch(&format!("{}-c", b.name));
        let folder = b.folder.to_str().unwrap();
        build(folder, &dir);
        for (name, script, run_for) in &b.runs {
            let (interpreted, compiled) = traces(folder, &dir, name, script, run_for.as_deref());
            assert!(
                interpreted.contains("\"entered\""),
                "{name}: the run did something"
            );
            assert_same(name, &interpreted, &compiled);
            moved += usize::from(interpreted.contains("\"fired\""));
        }
    }
    assert!(moved > 40, "most runs move: {moved}");
}

#[test]
fn corpus_machines_a_target_cannot_have_are_refused_with_file_and_line() {
    let Some(corpus) = crate::corpus_dir() else {
        eprintln!("skipped: ../shared/corpus is absent");
        return;
    };
    let out = scratch("corpus-refused-out");
    // The seed paper's GameController (its team call is a host function; its label atoms come
    // from the script), and one of each other kind of refusal the corpus meets.
    let refused: [(&str, &[&str], &str); 6] = [
        (
            "mipal/testfiles",
            &["TGameController.txt", "AGameController.txt"],
            "TGameController.txt:2: cannot be compiled: the host function `postTeamI_AmPlaying`",
        ),
        (
            "mipal/machines",
            &["GameController.fsm"],
            "GameController.fsm:10: cannot be compiled: the host function `msleep`",
        ),
        (
            "mipal/machines",
            &["SMGoalie.fsm"],
            "SMGoalie.fsm:9: cannot be compiled: the number `0.8`",
        ),
        (
            "mipal/machines",
            &["SMGetToGoal.fsm"],
            "SMGetToGoal.fsm:10: cannot be compiled: a posting of text to `gunaowalk_ready`, a whiteboard value",
        ),
        (
            "mipal/machines",
            &["SMHeadFindTestRene.fsm"],
            "SMHeadFindTestRene.fsm:9: cannot be compiled: `tan(horiz_fov / 2)` (its value is a fraction",
        ),
        (
            "mipal/machines",
            &["VladHeadTracker.fsm"],
            "VladHeadTracker.fsm:27: cannot be compiled: `timeout(period)` (only a constant time",
        ),
    ];
    for (from, files, expected) in refused {
        let folder = scratch(&format!("corpus-refused-{}", files[0]));
        for file in files {
            std::fs::copy(corpus.join(from).join(file), folder.join(file)).unwrap();
        }
        let script = "initialReceived = false\nshortChestButtonPressed = false\n";
        std::fs::write(folder.join("own.script"), script).unwrap();
        let manifest = format!(
            "[[machine]]\nfile = \"{}\"\n[impersonator]\nscript = \"own.script\"\n",
            files[0]
        );
        std::fs::write(folder.join("behaviour.toml"), manifest).unwrap();
        for target in ["c", "rust"] {
            let o = crate::proclaim(&[
                "compile",
                folder.to_str().unwrap(),
                "--target",
                target,
                "-o",
                out.to_str().unwrap(),
            ]);
            assert_eq!(o.status.code(), Some(2), "{} to {target}", files[0]);
            let stderr = String::from_utf8_lossy(&o.stderr);
            assert!(
                stderr.contains(expected),
                "{} to {target}: {stderr}",
                files[0]
            );
        }
    }
}
