//! A behaviour compiled to freestanding C (`proclaim compile B --target c`), its core built with
//! `gcc -std=c99 -Wall -Wextra -Werror -ffreestanding` and run by its host harness on a script,
//! writes the same trace as `proclaim run --virtual-clock --trace` on that script, byte for
//! byte; what the slice cannot compile is refused with its file and line.

use crate::proclaim;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("proclaim-compiled-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Whether gcc is here: a skip said on stderr, or with `CI` set a failure.
fn gcc_missing() -> bool {
    let missing = Command::new("gcc").arg("--version").output().is_err();
    if missing {
        assert!(
            std::env::var_os("CI").is_none(),
            "gcc is missing, and CI must build the compiled behaviour"
        );
        eprintln!("skipped: gcc is missing");
    }
    missing
}

fn gcc(dir: &Path, args: &[&str]) {
    let out = Command::new("gcc")
        .args(args)
        .current_dir(dir)
        .output()
        .expect("gcc runs");
    assert!(
        out.status.success(),
        "gcc {args:?} in {}:\n{}",
        dir.display(),
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Compiles `behaviour` into `dir` and builds the program `dir/behaviour`.
fn build(behaviour: &str, dir: &Path) {
    let o = proclaim(&[
        "compile",
        behaviour,
        "--target",
        "c",
        "-o",
        dir.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let mut core: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|f| f.ends_with(".c") && f != "main.c")
        .collect();
    core.sort();
    let mut args = vec![
        "-std=c99",
        "-Wall",
        "-Wextra",
        "-Werror",
        "-ffreestanding",
        "-c",
    ];
    args.extend(core.iter().map(String::as_str));
    gcc(dir, &args);
    let objects: Vec<String> = core.iter().map(|c| c.replace(".c", ".o")).collect();
    let mut args = vec![
        "-std=c99",
        "-Wall",
        "-Wextra",
        "-Werror",
        "main.c",
        "-o",
        "behaviour",
    ];
    args.extend(objects.iter().map(String::as_str));
    gcc(dir, &args);
}

/// The interpreter's trace and the compiled program's, for one script (and `--for`, if given).
fn traces(
    behaviour: &str,
    dir: &Path,
    name: &str,
    script: &str,
    run_for: Option<&str>,
) -> (String, String) {
    let script_path = dir.join(format!("{name}.script"));
    std::fs::write(&script_path, script).unwrap();
    let trace_path = dir.join(format!("{name}.jsonl"));
    let mut args = vec![
        "run",
        behaviour,
        "--virtual-clock",
        "--script",
        script_path.to_str().unwrap(),
        "--trace",
        trace_path.to_str().unwrap(),
    ];
    if let Some(d) = run_for {
        args.extend(["--for", d]);
    }
    let o = proclaim(&args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let interpreted = std::fs::read_to_string(&trace_path).unwrap();
    let mut program = Command::new(dir.join("behaviour"));
    program
        .args(run_for)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped());
    let mut child = program.spawn().expect("the compiled behaviour runs");
    std::io::Write::write_all(&mut child.stdin.take().unwrap(), script.as_bytes()).unwrap();
    let out = child.wait_with_output().unwrap();
    assert!(
        out.status.success(),
        "the compiled behaviour failed on {name}"
    );
    (interpreted, String::from_utf8(out.stdout).unwrap())
}

fn assert_same(name: &str, interpreted: &str, compiled: &str) {
    if interpreted != compiled {
        let line = interpreted
            .lines()
            .zip(compiled.lines())
            .position(|(a, b)| a != b)
            .unwrap_or_else(|| interpreted.lines().count().min(compiled.lines().count()));
        panic!(
            "{name}: the traces differ at line {}:\n  interpreted: {:?}\n  compiled:    {:?}",
            line + 1,
            interpreted.lines().nth(line),
            compiled.lines().nth(line)
        );
    }
}

/// A small seeded generator (SplitMix64).
fn splitmix(state: &mut u64) -> u64 {
    *state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

#[test]
fn the_compiled_microwave_writes_the_interpreters_trace_byte_for_byte() {
    if gcc_missing() {
        return;
    }
    let dir = scratch("microwave");
    build("machines/microwave", &dir);
    let kitchen = std::fs::read_to_string("machines/microwave/kitchen.script").unwrap();
    let mut cases: Vec<(String, String, Option<&str>)> = vec![
        // The behaviour's own script, to the end (the minute runs out: DONE is final).
        ("kitchen".into(), kitchen, None),
        // tests/behaviours.rs's: the door opens while cooking; stopped by --for.
        (
            "door".into(),
            "doorOpen = false\ntimeLeft = false\nat 1s timeLeft = true\nat 10s doorOpen = true\n"
                .into(),
            Some("12s"),
        ),
        // Times between rounds: news wakes a round at once.
        (
            "between".into(),
            "doorOpen = false\ntimeLeft = false\nat 1050ms timeLeft = true\nat 2333ms doorOpen = true\nat 2400ms doorOpen = false\nat 3s doorOpen = true\nat 3001ms doorOpen = false\n"
                .into(),
            None,
        ),
    ];
    // Seeded random scripts: the door and the timer at any millisecond, the door sometimes never
    // posted (unknown to the theory).
    let mut seed = 0x5eed_0033;
    for n in 0..60 {
        let mut script = String::new();
        if splitmix(&mut seed) % 3 != 0 {
            script.push_str("doorOpen = false\n");
        }
        let steps = 1 + splitmix(&mut seed) % 8;
        for _ in 0..steps {
            let at = splitmix(&mut seed) % 5_000;
            let atom = if splitmix(&mut seed) % 2 == 0 {
                "doorOpen"
            } else {
                "timeLeft"
            };
            let value = splitmix(&mut seed) % 2 == 0;
            script.push_str(&format!("at {at}ms {atom} = {value}\n"));
        }
        // Every other one long enough for the minute to run out.
        let run_for = if n % 2 == 0 { "6s" } else { "70s" };
        cases.push((format!("random{n}"), script, Some(run_for)));
    }
    for (name, script, run_for) in &cases {
        let (interpreted, compiled) = traces("machines/microwave", &dir, name, script, *run_for);
        assert!(
            interpreted.lines().count() > 10,
            "{name}: the run did something"
        );
        assert_same(name, &interpreted, &compiled);
    }
}

#[test]
fn what_the_slice_cannot_compile_is_refused_with_file_and_line() {
    let out = scratch("refused");
    for (behaviour, expected) in [
        (
            "machines/ball",
            "machines/ball/behaviour.toml:11: cannot be compiled: a Prolog or program expert",
        ),
        (
            "machines/press",
            "machines/press/Controller.machine:7: cannot be compiled: the statement `int waited;`",
        ),
        (
            "machines/subsumption",
            "machines/subsumption/behaviour.toml:15: cannot be compiled: suppression",
        ),
    ] {
        let o = proclaim(&[
            "compile",
            behaviour,
            "--target",
            "c",
            "-o",
            out.to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(2), "{behaviour}");
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(stderr.contains(expected), "{behaviour}: {stderr}");
    }
}

#[test]
fn two_machines_on_timeouts_and_a_theory_and_one_without_theories_write_the_same_trace() {
    if gcc_missing() {
        return;
    }
    let blink = "machine Blink\ninitial ON\nstate ON {\n    entry {\n        Lamp: on\n    }\n    when timeout(250ms) -> OFF\n}\nstate OFF {\n    entry {\n        Lamp: off\n    }\n    when timeout(1s) && !light -> END\n    when timeout(400ms) -> ON\n}\nstate END {\n    entry {\n        Lamp: gone\n    }\n}\n";
    // The watcher posts a quoted text and a theory input, and moves on `TRUE`.
    let watch = "machine Watch\ninitial WAIT\nstate WAIT {\n    when light || cook -> SEEN\n}\nstate SEEN {\n    entry {\n        Seen: \"yes\"\n        doorOpen: false\n    }\n    when TRUE -> DONE\n}\nstate DONE {\n}\n";
    let theory = std::fs::read_to_string("theories/microwave.dl").unwrap();
    let modules = "[[module]]\nname = \"lamp\"\nreads = [\"Lamp\", \"Seen\"]\n";
    let both = scratch("both-behaviour");
    std::fs::write(
        both.join("behaviour.toml"),
        format!("[[machine]]\nfile = \"Blink.machine\"\n[[machine]]\nfile = \"Watch.machine\"\n[[theory]]\nfile = \"microwave.dl\"\n{modules}"),
    )
    .unwrap();
    std::fs::write(both.join("Blink.machine"), blink).unwrap();
    std::fs::write(both.join("Watch.machine"), watch).unwrap();
    std::fs::write(both.join("microwave.dl"), &theory).unwrap();
    let alone = scratch("alone-behaviour");
    std::fs::write(
        alone.join("behaviour.toml"),
        format!("[[machine]]\nfile = \"Blink.machine\"\n{modules}"),
    )
    .unwrap();
    std::fs::write(
        alone.join("Blink.machine"),
        blink.replace("timeout(1s) && !light", "timeout(1s)"),
    )
    .unwrap();
    for (name, folder, script) in [
        ("both", &both, "at 700ms doorOpen = true\n"),
        ("alone", &alone, ""),
    ] {
        let dir = scratch(name);
        let behaviour = folder.to_str().unwrap();
        build(behaviour, &dir);
        let (interpreted, compiled) = traces(behaviour, &dir, name, script, Some("5s"));
        assert!(
            interpreted.lines().count() > 10,
            "{name}: the run did something"
        );
        assert_same(name, &interpreted, &compiled);
    }
}
