//! A behaviour compiled to a Cargo project (`proclaim compile B --target rust`), built and run
//! with `--script`, `--virtual-clock` and `--trace`, writes the same trace as `proclaim run`
//! with those options, byte for byte: every behaviour the C target's tests compile (the shipped
//! ones, each construct's, the seeded random ones, the shared corpus's when present, the
//! verifier's random ones that compile). The projects are built together, in one Cargo
//! workspace, into one target folder kept under the tests' temporary folder, so the crates they
//! depend on build once.

use super::compiled::{
    assert_same, behaviour_of, construct_cases, game_controller_runs, random_behaviour,
    runs_of_press_or_shootout, scratch, seeded_moment, splitmix, subsumption_runs, Case,
};
use super::monitor::{http, proclaim_serving, serving, Running};
use crate::proclaim;
use serde_json::Value as Json;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

/// One behaviour to compile and the runs to hold to the interpreter's.
struct Compiled {
    name: String,
    folder: PathBuf,
    /// Name, script, and `--for`.
    runs: Vec<(String, String, Option<String>)>,
}

/// The microwave on its own script, on the door opening while cooking, and on seeded scripts
/// of the door and the timer at any millisecond, rounds' moments included.
fn microwave() -> Compiled {
    let kitchen = std::fs::read_to_string("machines/microwave/kitchen.script").unwrap();
    let mut runs = vec![
        ("kitchen".to_string(), kitchen, None),
        (
            "door".to_string(),
            "doorOpen = false\ntimeLeft = false\nat 1s timeLeft = true\nat 10s doorOpen = true\n"
                .to_string(),
            Some("12s".to_string()),
        ),
    ];
    let mut seed = 0x5eed_0033_7275;
    for n in 0..6 {
        let mut script = String::new();
        if splitmix(&mut seed) % 3 != 0 {
            script.push_str("doorOpen = false\n");
        }
        for _ in 0..1 + splitmix(&mut seed) % 8 {
            let at = seeded_moment(&mut |n| splitmix(&mut seed) % n, 0, 5_000);
            let atom = ["doorOpen", "timeLeft"][(splitmix(&mut seed) % 2) as usize];
            let value = splitmix(&mut seed) % 2 == 0;
            script.push_str(&format!("at {at}ms {atom} = {value}\n"));
        }
        let run_for = if n % 2 == 0 { "6s" } else { "70s" };
        runs.push((format!("random{n}"), script, Some(run_for.to_string())));
    }
    Compiled {
        name: "microwave".into(),
        folder: "machines/microwave".into(),
        runs,
    }
}

/// Press and shootout to their ends, and stopped at seeded times with postings no label reads.
fn shipped(name: &str) -> Compiled {
    let runs = runs_of_press_or_shootout(name, 3);
    Compiled {
        name: name.into(),
        folder: format!("machines/{name}").into(),
        runs,
    }
}

fn from_case(case: Case) -> Compiled {
    let files: Vec<(&str, &str)> = case
        .files
        .iter()
        .map(|(f, t)| (f.as_str(), t.as_str()))
        .collect();
    Compiled {
        name: case.name.into(),
        folder: behaviour_of(&format!("rust-{}", case.name), &files),
        runs: vec![(
            case.name.to_string(),
            case.script.to_string(),
            case.run_for.map(str::to_string),
        )],
    }
}

fn random(seed: u64) -> Compiled {
    let files = random_behaviour(0x0033_0000 + seed);
    let name = format!("random-behaviour{seed}");
    let borrowed: Vec<(&str, &str)> = files
        .iter()
        .map(|(f, t)| (f.as_str(), t.as_str()))
        .collect();
    Compiled {
        folder: behaviour_of(&format!("rust-{name}"), &borrowed),
        runs: vec![(name.clone(), String::new(), Some("300ms".into()))],
        name,
    }
}

/// Compiles each behaviour into `projects/NAME` and makes the folder one Cargo workspace of
/// them (each project is its own workspace as written; here they share one lock and build).
/// The microwave is compiled `--whiteboard`, for the monitor's page, and so depends on this
/// repository's `proclaim-runtime`: the others' copies of it (the same files) give way to it, as
/// one lock holds one package of a name. `a_compiled_behaviour_builds_from_crates_io_alone`
/// builds a copy.
fn write_projects(behaviours: &[Compiled], projects: &Path) {
    let mut members = Vec::new();
    let runtime = std::fs::canonicalize("crates/runtime").unwrap();
    for b in behaviours {
        let dir = projects.join(&b.name);
        let mut args = vec![
            "compile",
            b.folder.to_str().unwrap(),
            "--target",
            "rust",
            "-o",
            dir.to_str().unwrap(),
        ];
        if b.name == "microwave" {
            args.push("--whiteboard");
        }
        let o = proclaim(&args);
        assert!(
            o.status.success(),
            "{}: {}",
            b.name,
            String::from_utf8_lossy(&o.stderr)
        );
        let manifest = dir.join("Cargo.toml");
        let text = std::fs::read_to_string(&manifest).unwrap();
        let name = format!("behaviour-{}", b.name);
        let copy = dir.join("runtime");
        if copy.exists() {
            std::fs::remove_dir_all(&copy).unwrap();
        }
        let text = text
            .replace("[workspace]\n", "")
            .replace(
                "{ path = \"runtime\" }",
                &format!("{{ path = {runtime:?} }}"),
            )
            .lines()
            .map(|l| {
                if l.starts_with("name = ") {
                    format!("name = \"{name}\"")
                } else {
                    l.to_string()
                }
            })
            .collect::<Vec<_>>()
            .join("\n");
        std::fs::write(&manifest, text).unwrap();
        let lock = dir.join("Cargo.lock");
        if lock.exists() {
            std::fs::rename(&lock, projects.join("Cargo.lock")).unwrap();
        }
        members.push(format!("{:?}", b.name));
    }
    std::fs::write(
        projects.join("Cargo.toml"),
        format!(
            "[workspace]\nmembers = [{}]\nresolver = \"2\"\n",
            members.join(", ")
        ),
    )
    .unwrap();
}

/// Builds every project; the folder of the programs.
fn build_projects(projects: &Path) -> PathBuf {
    let target = Path::new(env!("CARGO_TARGET_TMPDIR")).join("rust-behaviours");
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let o = Command::new(cargo)
        .args(["build", "--offline", "--workspace", "--quiet"])
        .current_dir(projects)
        .env("CARGO_TARGET_DIR", &target)
        // Sixty-odd programs: without debug information and incremental caches they link
        // faster and take a fraction of the disk.
        .env("CARGO_PROFILE_DEV_DEBUG", "0")
        .env("CARGO_INCREMENTAL", "0")
        .output()
        .expect("cargo runs");
    assert!(
        o.status.success(),
        "the compiled behaviours build:\n{}",
        String::from_utf8_lossy(&o.stderr)
    );
    target.join("debug")
}

/// The interpreter's trace and the compiled program's, for one run.
fn traces(
    folder: &Path,
    program: &Path,
    dir: &Path,
    run: &(String, String, Option<String>),
) -> (String, String) {
    let (name, script, run_for) = run;
    let script_path = dir.join(format!("{name}.script"));
    std::fs::write(&script_path, script).unwrap();
    let mut options = vec![
        "--virtual-clock".to_string(),
        "--script".into(),
        script_path.to_str().unwrap().into(),
    ];
    if let Some(d) = run_for {
        options.extend(["--for".to_string(), d.clone()]);
    }
    let interpreted_path = dir.join(format!("{name}.interpreted.jsonl"));
    let compiled_path = dir.join(format!("{name}.compiled.jsonl"));
    // `--force`: a compiled program runs what `check` would stop, so the interpreter does too.
    let mut args = vec![
        "run".to_string(),
        folder.to_str().unwrap().into(),
        "--force".into(),
    ];
    args.extend(options.iter().cloned());
    args.extend(["--trace".into(), interpreted_path.to_str().unwrap().into()]);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let o = proclaim(&args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let record_path = dir.join(format!("{name}.compiled-record.jsonl"));
    let o = Command::new(program)
        .args(&options)
        .args(["--trace", compiled_path.to_str().unwrap()])
        .args(["--record", record_path.to_str().unwrap()])
        .output()
        .expect("the compiled behaviour runs");
    assert!(
        o.status.success(),
        "the compiled behaviour failed on {name}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    // The compiled program's recording, replayed on the interpreter, is the same run.
    let o = proclaim(&[
        "test",
        folder.to_str().unwrap(),
        record_path.to_str().unwrap(),
    ]);
    assert!(
        o.status.success(),
        "the interpreter's replay of the compiled program's recording of {name}:\n{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    (
        std::fs::read_to_string(interpreted_path).unwrap(),
        std::fs::read_to_string(compiled_path).unwrap(),
    )
}

#[test]
fn behaviours_compiled_to_rust_write_the_interpreters_trace_byte_for_byte() {
    let mut behaviours = vec![microwave(), shipped("press"), shipped("shootout")];
    behaviours.push(Compiled {
        name: "subsumption".into(),
        folder: "machines/subsumption".into(),
        runs: subsumption_runs(),
    });
    behaviours.push(Compiled {
        name: "keeper".into(),
        folder: "machines/keeper".into(),
        runs: super::compiled::keeper_runs(),
    });
    behaviours.push(Compiled {
        name: "search".into(),
        folder: "machines/search".into(),
        runs: super::compiled::search_runs(),
    });
    behaviours.push(Compiled {
        name: "tracker".into(),
        folder: "machines/tracker".into(),
        runs: super::compiled::tracker_runs(),
    });
    behaviours.push(Compiled {
        name: "goalkeeper".into(),
        folder: "machines/goalkeeper".into(),
        runs: super::compiled::goalkeeper_runs(),
    });
    behaviours.push(Compiled {
        name: "game_controller".into(),
        folder: "machines/game_controller".into(),
        runs: game_controller_runs(),
    });
    for name in ["ball", "referee"] {
        behaviours.push(Compiled {
            name: name.into(),
            folder: format!("machines/{name}").into(),
            runs: super::compiled::expert_runs(name),
        });
    }
    behaviours.extend(construct_cases().into_iter().map(from_case));
    behaviours.extend((0..24).map(random));
    behaviours.extend(
        super::compiled_corpus::corpus_behaviours(6)
            .into_iter()
            .map(|b| Compiled {
                name: b.name,
                folder: b.folder,
                runs: b.runs,
            }),
    );
    // The verifier's random behaviours, run below with a bound (some spin).
    let verified = super::compiled_verify::compiled_seeds();
    behaviours.extend(verified.iter().map(|g| Compiled {
        name: g.name.clone(),
        folder: g.folder.clone(),
        runs: Vec::new(),
    }));
    let projects = scratch("rust-projects");
    write_projects(&behaviours, &projects);
    let programs = build_projects(&projects);
    let runs = scratch("rust-runs");
    let mut moved = 0;
    for b in &behaviours {
        let program = programs.join(format!("behaviour-{}", b.name));
        for run in &b.runs {
            let (interpreted, compiled) = traces(&b.folder, &program, &runs, run);
            assert!(!interpreted.is_empty(), "{}: the run did something", run.0);
            assert_same(&run.0, &interpreted, &compiled);
            moved += usize::from(interpreted.contains("\"fired\""));
        }
    }
    assert!(moved > 30, "most runs move: {moved}");
    for g in &verified {
        let interpreted = super::compiled_verify::interpreted(g, &runs);
        let script = runs.join(format!("{}.script", g.name));
        let trace = runs.join(format!("{}.compiled.jsonl", g.name));
        let mut command = Command::new(programs.join(format!("behaviour-{}", g.name)));
        command.args([
            "--virtual-clock",
            "--script",
            script.to_str().unwrap(),
            "--for",
            &g.run_for,
            "--trace",
            trace.to_str().unwrap(),
        ]);
        let program = super::compiled_verify::bounded_run(command, &trace);
        super::compiled_verify::assert_same_bounded(&g.name, interpreted, program);
    }
    // Without `--script`, both play the behaviour's own script.
    for name in ["microwave", "subsumption"] {
        let interpreted_path = runs.join(format!("{name}-own-script.interpreted.jsonl"));
        let compiled_path = runs.join(format!("{name}-own-script.compiled.jsonl"));
        let folder = format!("machines/{name}");
        let o = proclaim(&[
            "run",
            &folder,
            "--virtual-clock",
            "--trace",
            interpreted_path.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let o = Command::new(programs.join(format!("behaviour-{name}")))
            .args([
                "--virtual-clock",
                "--trace",
                compiled_path.to_str().unwrap(),
            ])
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let interpreted = std::fs::read_to_string(&interpreted_path).unwrap();
        assert!(
            interpreted.contains("\"impersonator\""),
            "{name} plays its script"
        );
        assert_same(
            &format!("{name} without --script"),
            &interpreted,
            &std::fs::read_to_string(&compiled_path).unwrap(),
        );
    }
    // A script that sets none of a sensor's atoms would have the interpreter run the sensor.
    let script = runs.join("no-chest.script");
    std::fs::write(&script, "at 1s readyReceived = true\n").unwrap();
    let o = Command::new(programs.join("behaviour-game_controller"))
        .args(["--virtual-clock", "--script", script.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        stderr.contains("sets none of the atoms the module `chestButton` answers"),
        "{stderr}"
    );
    the_compiled_microwave_shows_its_run_on_the_monitors_page(
        &programs.join("behaviour-microwave"),
        &runs,
    );
    bad_options_are_refused_with_what_is_wrong(&programs.join("behaviour-microwave"));
}

/// A behaviour compiled without `--whiteboard` is a project of crates.io crates alone: every
/// package it builds from a path is inside it, no file of it names this repository, and no
/// tokio, board, monitor or runner is among its packages. It builds offline in a folder
/// outside the repository, writes the interpreter's trace, and says how to get the whiteboard
/// it was compiled without.
#[test]
fn a_compiled_behaviour_builds_from_crates_io_alone() {
    let project = std::env::temp_dir().join(format!("proclaim-alone-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&project);
    let o = proclaim(&[
        "compile",
        "machines/microwave",
        "--target",
        "rust",
        "-o",
        project.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let repository = std::fs::canonicalize(".").unwrap();
    let mut files = vec![project.clone()];
    while let Some(path) = files.pop() {
        if path.is_dir() {
            files.extend(std::fs::read_dir(&path).unwrap().map(|e| e.unwrap().path()));
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(
            !text.contains(repository.to_str().unwrap()),
            "{} names the repository",
            path.display()
        );
    }
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let o = Command::new(&cargo)
        .args(["metadata", "--offline", "--format-version", "1"])
        .current_dir(&project)
        .output()
        .expect("cargo runs");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let metadata: Json = serde_json::from_slice(&o.stdout).unwrap();
    let packages = metadata["packages"].as_array().unwrap();
    for p in packages {
        let name = p["name"].as_str().unwrap();
        assert!(
            ![
                "tokio",
                "proclaim-board",
                "proclaim-monitor",
                "proclaim-runner"
            ]
            .contains(&name),
            "{name} is built by a behaviour compiled without --whiteboard"
        );
        if p["source"].is_null() {
            let manifest = p["manifest_path"].as_str().unwrap();
            assert!(
                Path::new(manifest).starts_with(&project),
                "{name} is built from {manifest}, outside the project"
            );
        }
    }
    let target = Path::new(env!("CARGO_TARGET_TMPDIR")).join("rust-alone");
    let o = Command::new(&cargo)
        .args(["build", "--offline", "--quiet"])
        .current_dir(&project)
        .env("CARGO_TARGET_DIR", &target)
        .env("CARGO_PROFILE_DEV_DEBUG", "0")
        .output()
        .expect("cargo runs");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let program = target.join("debug/behaviour-microwave");
    let runs = scratch("rust-alone-runs");
    let run = microwave().runs.swap_remove(0);
    let (interpreted, compiled) = traces(Path::new("machines/microwave"), &program, &runs, &run);
    assert_same("microwave built alone", &interpreted, &compiled);
    let o = Command::new(&program).arg("--monitor").output().unwrap();
    assert_eq!(o.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        stderr.contains("compiled without the whiteboard") && stderr.contains("--whiteboard"),
        "{stderr}"
    );
    let _ = std::fs::remove_dir_all(&project);
}

/// Options that do not go together, or a page or board the program cannot have, end the
/// program at once with exit 2 and say why.
fn bad_options_are_refused_with_what_is_wrong(program: &Path) {
    let cases: [(&[&str], &str); 6] = [
        (&["--monitor-read-only"], "is said of a `--monitor` page"),
        (
            &["--listen", "--connect", "tcp/127.0.0.1:1"],
            "`--listen` and `--connect` exclude each other",
        ),
        (&["--board", "team"], "`--board` names a whiteboard shared"),
        (
            &["--virtual-clock", "--listen"],
            "cannot `--listen` or `--connect`",
        ),
        (
            &["--monitor", "localhost:80"],
            "--monitor localhost:80: not an address to listen on",
        ),
        // The tests build the project without the `network` feature.
        (
            &["--connect", "tcp/127.0.0.1:1"],
            "build it with `cargo build --release --features network`",
        ),
    ];
    for (args, why) in cases {
        let o = Command::new(program).args(args).output().unwrap();
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains(why), "{args:?}: {stderr}");
    }
}

/// Starts a compiled program with `args` and reads its standard error up to the monitor's URL.
fn serving_program(program: &Path, args: &[&str]) -> (Running, String) {
    let mut command = Command::new(program);
    command.args(args);
    serving(command, true, "monitor: ")
}

/// Ctrl-C to a compiled program, which ends its run as a finished one.
pub(crate) fn interrupt(program: &mut std::process::Child) {
    let sent = Command::new("kill")
        .args(["-INT", &program.id().to_string()])
        .status()
        .unwrap();
    assert!(sent.success());
    let ended = program.wait().unwrap();
    assert!(
        ended.success(),
        "Ctrl-C ends the run as a finished one: {ended}"
    );
}

fn json_at(url: &str, path: &str) -> Json {
    let (status, body) = http(url, "GET", path, None);
    assert_eq!(status, 200, "{path}: {body}");
    serde_json::from_str(&body).unwrap()
}

/// The page's frame once it shows the microwave in `state` (within 20 s).
fn frame_once(url: &str, state: &str) -> Json {
    let deadline = Instant::now() + Duration::from_secs(20);
    loop {
        let frame = json_at(url, "/api/frame");
        if frame["machines"][0]["state_name"] == state {
            return frame;
        }
        assert!(
            Instant::now() < deadline,
            "the page never shows {state}: {frame}"
        );
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// `--monitor`: the page draws the machines as `proclaim run --monitor` draws them, shows the
/// run's whiteboard and where the run ended; on the real clock a posting from the page comes
/// into the run, pause and step hold and ring its rounds, Ctrl-C ends it with its trace and
/// recording whole, and the recording replays.
fn the_compiled_microwave_shows_its_run_on_the_monitors_page(program: &Path, runs: &Path) {
    let (_interpreted, interpreted_url) = proclaim_serving(
        &[
            "run",
            "machines/microwave",
            "--monitor",
            "127.0.0.1:0",
            "--for",
            "60s",
        ],
        "monitor: ",
    );
    let (_compiled, url) = serving_program(
        program,
        &[
            "--virtual-clock",
            "--monitor",
            "127.0.0.1:0",
            "--trace",
            "/dev/null",
        ],
    );
    let model = json_at(&url, "/api/model");
    assert_eq!(model, json_at(&interpreted_url, "/api/model"));
    assert_eq!(model["charts"][0]["name"], "Microwave");
    // The page shows where the virtual run ended once it has.
    let frame = frame_once(&url, "DONE");
    let magnetron = frame["board"]
        .as_array()
        .unwrap()
        .iter()
        .find(|row| row["type"] == "Magnetron")
        .cloned()
        .unwrap_or_else(|| panic!("the run's postings are on the board: {frame}"));
    assert_eq!(
        (magnetron["value"].as_str(), magnetron["by"].as_str()),
        (Some("\"off\""), Some("Microwave")),
        "{frame}"
    );

    let script = runs.join("idle.script");
    std::fs::write(&script, "doorOpen = false\ntimeLeft = false\n").unwrap();
    let trace = runs.join("monitored.compiled.jsonl");
    let record = runs.join("monitored.compiled-record.jsonl");
    let (mut running, url) = serving_program(
        program,
        &[
            "--script",
            script.to_str().unwrap(),
            "--monitor",
            "127.0.0.1:0",
            "--trace",
            trace.to_str().unwrap(),
            "--record",
            record.to_str().unwrap(),
        ],
    );
    // Paused, the run holds the page's posting until it is stepped.
    let control = |action: &str| {
        let body = format!(r#"{{"action":"{action}"}}"#);
        let (status, why) = http(&url, "POST", "/api/control", Some(&body));
        assert!((200..300).contains(&status), "{action}: {status} {why}");
    };
    control("pause");
    let (status, body) = http(
        &url,
        "POST",
        "/api/post",
        Some(r#"{"type":"timeLeft","value":"true"}"#),
    );
    assert_eq!(status, 200, "{body}");
    std::thread::sleep(Duration::from_millis(500));
    let frame = json_at(&url, "/api/frame");
    assert_eq!(frame["machines"][0]["state_name"], "IDLE", "{frame}");
    assert_eq!(frame["stepping"]["paused"], true, "{frame}");
    control("step");
    frame_once(&url, "COOKING");
    control("resume");
    interrupt(&mut running.0);
    let trace = std::fs::read_to_string(&trace).unwrap();
    assert!(
        trace.contains(r#""fired","machine":"Microwave","from":1,"to":3,"label":"cook""#),
        "{trace}"
    );
    let o = proclaim(&["test", "machines/microwave", record.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stdout));
}
