//! A behaviour compiled to freestanding C (`proclaim compile B --target c`), its core built with
//! `gcc -std=c99 -Wall -Wextra -Werror -ffreestanding` and run by its host harness on a script,
//! writes the same trace as `proclaim run --virtual-clock --trace` on that script, byte for
//! byte (the shipped behaviours that compile, each construct of the activity language, seeded
//! random behaviours); what cannot be compiled is refused with its file and line.

use crate::proclaim;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

pub(crate) fn scratch(name: &str) -> PathBuf {
    crate::fresh_folder(&format!("proclaim-compiled-{name}"))
}

/// Whether gcc is here: a skip said on stderr, or with `CI` set a failure.
pub(crate) fn gcc_missing() -> bool {
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
pub(crate) fn build(behaviour: &str, dir: &Path) {
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
pub(crate) fn traces(
    behaviour: &str,
    dir: &Path,
    name: &str,
    script: &str,
    run_for: Option<&str>,
) -> (String, String) {
    let script_path = dir.join(format!("{name}.script"));
    std::fs::write(&script_path, script).unwrap();
    let trace_path = dir.join(format!("{name}.jsonl"));
    // `--force`: a compiled program runs what `check` would stop (`proclaim compile` warns of
    // it), so the interpreter runs it too.
    let mut args = vec![
        "run",
        behaviour,
        "--virtual-clock",
        "--force",
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

pub(crate) fn assert_same(name: &str, interpreted: &str, compiled: &str) {
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
pub(crate) fn splitmix(state: &mut u64) -> u64 {
    *state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// A seeded moment for a script's step, `from` plus less than `span` milliseconds, `next(n)`
/// drawing below `n`: every other one moved up onto the ring period's beat (where an idle
/// behaviour's rounds fall, so the step is due just as a round is, the first round's moment
/// included), the rest at any millisecond.
pub(crate) fn seeded_moment(next: &mut impl FnMut(u64) -> u64, from: u64, span: u64) -> u64 {
    let period = 100;
    let at = from + next(span);
    if next(2) == 0 {
        at.div_ceil(period) * period
    } else {
        at
    }
}

/// Runs of press or shootout (neither ships a script): its own to the end, then `seeded`
/// scripts of postings no label reads (news to nobody) at any millisecond, rounds' moments
/// included, each stopped at a seeded time. Name, script and `--for` of each.
pub(crate) fn runs_of_press_or_shootout(
    name: &str,
    seeded: usize,
) -> Vec<(String, String, Option<String>)> {
    let mut runs = vec![(format!("{name}-own"), String::new(), None)];
    let mut seed = 0x5eed_0033 ^ name.len() as u64;
    for n in 0..seeded {
        let mut script = String::new();
        for _ in 0..splitmix(&mut seed) % 5 {
            let at = seeded_moment(&mut |n| splitmix(&mut seed) % n, 0, 12_000);
            let value = splitmix(&mut seed) % 2 == 0;
            script.push_str(&format!("at {at}ms crowd = {value}\n"));
        }
        let run_for = format!("{}ms", 1 + splitmix(&mut seed) % 12_000);
        runs.push((format!("{name}-random{n}"), script, Some(run_for)));
    }
    runs
}

/// A lamp on timeouts, ending when the theory says no light.
const BLINK: &str = "machine Blink\ninitial ON\nstate ON {\n    entry {\n        Lamp: on\n    }\n    when timeout(250ms) -> OFF\n}\nstate OFF {\n    entry {\n        Lamp: off\n    }\n    when timeout(1s) && !light -> END\n    when timeout(400ms) -> ON\n}\nstate END {\n    entry {\n        Lamp: gone\n    }\n}\n";

/// A watcher of theory outputs posting a quoted text and a theory input.
const WATCH: &str = "machine Watch\ninitial WAIT\nstate WAIT {\n    when light || cook -> SEEN\n}\nstate SEEN {\n    entry {\n        Seen: \"yes\"\n        doorOpen: false\n    }\n    when TRUE -> DONE\n}\nstate DONE {\n}\n";

/// The module the blinking behaviours declare.
const MODULES: &str = "[[module]]\nname = \"lamp\"\nreads = [\"Lamp\", \"Seen\"]\n";

/// Wrapping arithmetic, division by zero, truth values in arithmetic.
const ARITH: &str = "machine Arith\ninitial A\nstate A {\n    entry {\n        q = 7 / 0;\n        r = -7 % 0;\n        d = -7 / 2;\n        e = -7 % 3;\n        big = 9223372036854775807;\n        over = big + 1;\n        under = -over - 1;\n        minus = over / -1;\n        rest = over % -1;\n        product = big * 3;\n        t = 3 < 4;\n        u = t + 1;\n        v = -t;\n        w = t == 1;\n        x = max(t, 1);\n        y = min(1, t);\n        z = abs(-5) * abs(over + 1);\n        same = (q != r) || !(d <= e) && u >= 2 && 2 > 1;\n    }\n    when u == 2 && d / -3 -> B\n}\nstate B {\n}\n";

/// Typed variables converting what is assigned.
const TYPES: &str = "machine Types\ninitial A\nstate A {\n    entry {\n        int n;\n        bool b;\n        char c;\n        n = 2 < 3;\n        b = 5;\n        c = b;\n        b = 0;\n        b = false;\n        g = 1;\n        g = true;\n        g = 1 == 1;\n        g = 1;\n    }\n    when n && !b -> B\n}\nstate B {\n}\n";

/// Computed postings and prints.
const SPEAKER: &str = "machine Speaker\ninitial A\nstate A {\n    entry {\n        int n;\n        n = 41 + 1;\n        post(\"Out\", n * 2);\n        post(\"Text\", \"n is \" + n + \", big \" + (n > 40));\n        post(\"Two\", \"a\", \"\");\n        post(\"Three\", \"\", \"hi\");\n        post_int(\"Whole\", n == 42);\n        postv(\"List\", 1, n > 1, \"x y\", -3);\n        say(\"said \" + n);\n        speech(\"spoken\");\n        say_state_name();\n        speak_state_name();\n        print(\"printed \" + n);\n        print_int(n);\n        print_state_name();\n        Plain: 12\n        Word: \"quoted\"\n        Truth: true\n    }\n}\n";

/// `for` loops, one stopped at the loop limit.
const LOOP: &str = "machine Loop\ninitial L\nstate L {\n    entry {\n        int i;\n        int sum;\n        for (i = 0; i < 10; i = i + 1) {\n            sum = sum + i;\n            last = i;\n        }\n        for (;;) {\n            i = 3;\n        }\n        for (k = 0; k < 3; k = k + 1) post(\"K\", k * k);\n    }\n    when sum == 45 -> M\n}\nstate M {\n    entry {\n        print_int(sum);\n    }\n}\n";

/// A machine controlling a sub-machine with every command.
const BOSS: &str = "machine Boss\ninitial START\nstate START {\n    entry {\n        start(\"Worker\");\n        Worker: On\n        step = 1;\n    }\n    when timeout(5ms) -> PAUSE\n}\nstate PAUSE {\n    entry {\n        suspend(\"Worker\");\n        step = 2;\n    }\n    when timeout(10ms) -> GO\n}\nstate GO {\n    entry {\n        resume(\"Worker\");\n        Worker: hello\n        step = 3;\n    }\n    when timeout(7ms) -> AGAIN\n}\nstate AGAIN {\n    entry {\n        restart(\"Worker\");\n        step = 4;\n    }\n    when timeout(20ms) -> STOP\n}\nstate STOP {\n    entry {\n        stop(\"Worker\");\n        Worker: suspend\n        Worker: resume\n    }\n    when timeout(3ms) -> END\n}\nstate END {\n    entry {\n        Worker: restart\n        print(\"bye\");\n    }\n}\n";

/// The sub-machine.
const WORKER: &str = "machine Worker\ninitial W1\nstate W1 {\n    entry {\n        int count;\n        count = count + 1;\n    }\n    internal {\n        ticks = ticks + 1;\n    }\n    when timeout(4ms) -> W2\n}\nstate W2 {\n    entry {\n        count = count + 10;\n    }\n    when count > 100 -> W3\n    when timeout(3ms) -> W1\n}\nstate W3 {\n}\n";

/// A label over a global another machine changes, and a time test already past.
const WATCHER: &str = "machine Watcher\ninitial W\nstate W {\n    when step == 4 && timeout(1ms) -> SEEN\n}\nstate SEEN {\n}\n";

/// A watcher of whiteboard variables: asking `q`, which no expert answers, reads the snapshot,
/// so a later posting of `e` is news though `&&` never read it.
const EXTERN_WATCHER: &str = "machine W\ninitial S\nstate S {\n    entry {\n        extern e;\n    }\n    when q && e -> T\n    when timeout(1s) -> T\n}\nstate T {\n    entry {\n        print_int(n);\n    }\n}\n";

/// A poster of whiteboard variables: assignments, postings of constants and of values, a read
/// in OnEntry (live) and in Internal (the snapshot, then its own posting).
/// Whiteboard values read by name alone: a type never posted (no value: a comparison is false,
/// arithmetic keeps none, an assignment makes it 0), a type another machine posts, a
/// sub-machine's `WorkerIsRunning`, an atom no expert answers that a machine posts, a script's atom that is also
/// a theory input (asked of the impersonator, read as the value it posted), a theory input
/// posted as a whole number.
const BOARD_READER: &str = "machine Reader\ninitial A\nstate A {\n    entry {\n        int n = 5;\n        n = never + 1;\n        k = level;\n    }\n    when never == 1 || never != 1 -> Z\n    when level > 2 && WorkerIsRunning -> B\n    when timeout(2s) -> Z\n}\nstate B {\n    entry {\n        k = level * 10 + n;\n        Worker: Off\n    }\n    when cook && !WorkerIsRunning && !busy -> C\n}\nstate C {\n    entry {\n        d = doorOpen;\n        print_int(k);\n    }\n    when doorOpen && !cook -> D\n}\nstate D {\n    entry {\n        d = doorOpen;\n    }\n}\nstate Z {\n}\n";

const BOARD_POSTER: &str = "machine Poster\ninitial P\nstate P {\n    entry {\n        level: 1\n        timeLeft: 0\n        busy: 0\n    }\n    when timeout(300ms) -> Q\n}\nstate Q {\n    entry {\n        level: 3\n        timeLeft: 7\n        Worker: On\n    }\n}\n";

const EXTERN_POSTER: &str = "machine P\ninitial A\nstate A {\n    entry {\n        extern e;\n        extern n;\n        n = 5;\n        post(\"n\", n + 2);\n        e = true;\n        e: 0\n        post_int(\"m\", e == 0);\n        g = n;\n    }\n    internal {\n        n = n + 1;\n        g = n * 2;\n    }\n    when n > 9 -> B\n}\nstate B {\n    entry {\n        print_int(n);\n        e = 1;\n        n: 3\n    }\n    when timeout(200ms) -> C\n}\nstate C {\n}\n";

/// The time tests in their units.
/// A guard penalised at 500 ms that counts to 3 while it waits out a 2 s timeout, then waits
/// for ever for a word the script never says: a run with no `--for` ends at the first still
/// round after that, and no sooner. No module declares `penalised`: the run's script answers it,
/// as the impersonator, in the compiled programs as in the interpreter.
const GUARD: &str = "machine Guard\ninitial Ready\nstate Ready {\n    when penalised -> Penalised\n}\nstate Penalised {\n    entry { n = 0; }\n    internal { n = min(n + 1, 3); }\n    when timeout(2s) -> Waiting\n}\nstate Waiting {\n    when ~penalised -> Ready\n}\n";

const TIME: &str = "machine T\ninitial A\nstate A {\n    when timeout(300000) -> B\n}\nstate B {\n    when after_ms(250) -> C\n}\nstate C {\n    when after(1) && after_ms(3s) -> D\n}\nstate D {\n    when timeout(2s) -> E\n}\nstate E {\n}\n";

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
    // Seeded random scripts: the door and the timer at any millisecond, rounds' moments
    // included, the door sometimes never posted (unknown to the theory).
    let mut seed = 0x5eed_0033;
    for n in 0..60 {
        let mut script = String::new();
        if splitmix(&mut seed) % 3 != 0 {
            script.push_str("doorOpen = false\n");
        }
        let steps = 1 + splitmix(&mut seed) % 8;
        for _ in 0..steps {
            let at = seeded_moment(&mut |n| splitmix(&mut seed) % n, 0, 5_000);
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
fn what_the_slice_cannot_compile_is_refused_with_file_and_line_for_either_target() {
    let out = scratch("refused");
    let team =
        "machines/striker/Player.machine:13: cannot be compiled: `team.majority(vote)`: a team aggregate";
    for (behaviour, target, expected) in [
        ("machines/striker", "c", format!("{team} (a freestanding C behaviour has no network to its team's boards)")),
        ("machines/striker", "rust", format!("{team} (a compiled Rust behaviour joins no team: its `--listen` or `--connect` whiteboard is not a team's, whose teammates' postings it would aggregate; run it with `proclaim run --member`)")),
    ] {
        let o = proclaim(&[
            "compile",
            behaviour,
            "--target",
            target,
            "-o",
            out.to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(2), "{behaviour} to {target}");
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(
            stderr.contains(&expected),
            "{behaviour} to {target}: {stderr}"
        );
    }
    // The team's quorum is refused as its aggregates are (it would read a value nobody posts).
    let quorum = crate::behaviour_folder(
        "refused-quorum",
        &[
            ("Q.machine", "machine Q
initial A
state A {
    when team.quorum -> B
}
state B { }
"),
            ("behaviour.toml", "[[machine]]\nfile = \"Q.machine\"\n\n[team]\nname = \"blue\"\nmember = \"robot1\"\nsize = 3\n"),
        ],
    );
    let o = proclaim(&[
        "compile",
        quorum.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(
        o.status.code(),
        Some(2),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(
        String::from_utf8_lossy(&o.stderr)
            .contains("Q.machine:4: cannot be compiled: `team.quorum`: the team's quorum"),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    // A clause fact is refused at its own line (a theory's refusal pointed at line 1).
    let keeper = crate::behaviour_folder(
        "refused-clause",
        &[
            (
                "G.machine",
                "machine G\ninitial A\nstate A {\n    when diveLeft -> B\n}\nstate B { }\n",
            ),
            (
                "g.dl",
                "% a keeper\ninput{ballLeft, ballCentre, ballRight}.\nL: ballLeft => diveLeft.\n\\/{~ballLeft, ~diveRight}.\noutput{diveLeft}.\n",
            ),
            (
                "behaviour.toml",
                "[[machine]]\nfile = \"G.machine\"\n[[theory]]\nfile = \"g.dl\"\n",
            ),
        ],
    );
    for target in ["c", "rust"] {
        let o = proclaim(&[
            "compile",
            keeper.to_str().unwrap(),
            "--target",
            target,
            "-o",
            out.to_str().unwrap(),
        ]);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{stderr}");
        assert!(
            stderr.contains("g.dl:4: cannot be compiled: a clause fact"),
            "{stderr}"
        );
    }
}

#[test]
fn two_machines_on_timeouts_and_a_theory_and_one_without_theories_write_the_same_trace() {
    if gcc_missing() {
        return;
    }
    let blink = BLINK;
    // The watcher posts a quoted text and a theory input, and moves on `TRUE`.
    let watch = WATCH;
    let theory = std::fs::read_to_string("theories/microwave.dl").unwrap();
    let modules = MODULES;
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

/// Writes a behaviour of `files` (name, text) into a fresh folder.
pub(crate) fn behaviour_of(name: &str, files: &[(&str, &str)]) -> PathBuf {
    let folder = scratch(&format!("{name}-behaviour"));
    for (file, text) in files {
        std::fs::write(folder.join(file), text).unwrap();
    }
    folder
}

/// Compiles the behaviour in `folder`, runs both on `script` for `run_for`, and holds the traces
/// equal; the interpreter's trace.
fn same_trace(name: &str, folder: &Path, script: &str, run_for: Option<&str>) -> String {
    let dir = scratch(name);
    let behaviour = folder.to_str().unwrap();
    build(behaviour, &dir);
    let (interpreted, compiled) = traces(behaviour, &dir, name, script, run_for);
    assert_same(name, &interpreted, &compiled);
    interpreted
}

/// The behaviours whose labels a process answers (a Python program, a Prolog knowledge base),
/// run as `proclaim run --virtual-clock` runs them: the script sets the process's atoms, and the
/// process is left out.
pub(crate) fn expert_runs(name: &str) -> Vec<(String, String, Option<String>)> {
    let fixed = match name {
        "ball" => vec!["ballNear = false\nat 450ms ballNear = true\n".to_string()],
        _ => {
            let own = std::fs::read_to_string("machines/referee/match.script").unwrap();
            vec![
                format!("{own}offside = false\nat 650ms offside = true\nat 1.2s offside = false\n"),
                format!("{own}at 300ms offside = true\n"),
            ]
        }
    };
    fixed
        .into_iter()
        .enumerate()
        .map(|(i, script)| (format!("{name}-{i}"), script, Some("2s".to_string())))
        .collect()
}

#[test]
fn a_process_experts_atoms_come_from_the_script_as_when_the_interpreter_leaves_it_out() {
    if gcc_missing() {
        return;
    }
    for name in ["ball", "referee"] {
        let behaviour = format!("machines/{name}");
        let dir = scratch(&format!("expert-{name}"));
        build(&behaviour, &dir);
        for (case, script, run_for) in expert_runs(name) {
            let (interpreted, compiled) =
                traces(&behaviour, &dir, &case, &script, run_for.as_deref());
            assert!(interpreted.contains("\"fired\""), "{case}: {interpreted}");
            assert_same(&case, &interpreted, &compiled);
        }
    }
}

#[test]
fn the_shipped_behaviours_of_variables_and_sub_machines_write_the_interpreters_trace() {
    if gcc_missing() {
        return;
    }
    for behaviour in ["machines/press", "machines/shootout"] {
        let name = behaviour.trim_start_matches("machines/");
        let dir = scratch(name);
        build(behaviour, &dir);
        let cases = runs_of_press_or_shootout(name, 12);
        for (case, script, run_for) in &cases {
            let (interpreted, compiled) = traces(behaviour, &dir, case, script, run_for.as_deref());
            assert_same(case, &interpreted, &compiled);
        }
        let (whole, _) = traces(behaviour, &dir, name, "", None);
        assert!(
            whole.lines().last().unwrap_or("").contains("\"finished\""),
            "{name} runs to its end: {whole}"
        );
    }
}

#[test]
fn a_posting_due_at_a_rounds_moment_comes_before_that_round_interpreted_and_compiled() {
    if gcc_missing() {
        return;
    }
    // Postings no current label reads, each due just as a round is: the shoot-out's kicks come
    // every two seconds (a chain of rounds that fire at once), the game's READY rings every
    // ring period, the button unread there; and a step timed for the first round's moment,
    // which is that round's, not the script's start.
    let cases = [
        (
            "machines/shootout",
            "at 100ms crowd = true\nat 2000ms crowd = false\nat 2100ms crowd = true\nat 4000ms crowd = false\n",
            "5s",
            "\"type\":\"crowd\",\"content\":\"false\",\"round\":",
            "\"fired\",\"machine\":\"Kicker\",\"from\":1,\"to\":2,\"label\":\"kicks < 5 && timeout(2000000)\",\"round\":22,",
        ),
        (
            "machines/game_controller",
            "readyReceived = false\npenaltyReceived = false\nsetReceived = false\nplayingReceived = false\nfinishedReceived = false\ninitialReceived = false\nshortChestButtonPressed = false\nat 1s readyReceived = true\nat 2500ms shortChestButtonPressed = true\nat 2800ms shortChestButtonPressed = false\n",
            "3s",
            "\"type\":\"shortChestButtonPressed\",\"content\":\"true\",\"round\":",
            "\"answered\",\"machine\":\"GameController\",\"atom\":\"penaltyReceived\",\"value\":false,\"by\":{\"expert\":\"impersonator\"},\"round\":30,\"at_us\":2500000}",
        ),
        (
            "machines/subsumption",
            "ballSeen = false\nballNear = false\natBall = false\nobstacle = false\nat 0ms obstacle = true\nat 300ms ballSeen = true\n",
            "1s",
            "\"type\":\"obstacle\",\"content\":\"true\",\"round\":1,\"at_us\":0}",
            "\"entered\",\"machine\":\"Walk\",\"state\":\"SEARCH\",\"id\":1,\"round\":1,",
        ),
    ];
    for (behaviour, script, run_for, posted, round) in cases {
        let name = behaviour.trim_start_matches("machines/");
        let dir = scratch(&format!("on-the-moment-{name}"));
        build(behaviour, &dir);
        let (interpreted, compiled) = traces(behaviour, &dir, name, script, Some(run_for));
        let at = |what: &str| {
            interpreted
                .find(what)
                .unwrap_or_else(|| panic!("{name}: no {what} in {interpreted}"))
        };
        assert!(
            at(posted) < at(round),
            "{name}: the posting comes before its round's events: {interpreted}"
        );
        assert_same(name, &interpreted, &compiled);
    }
}

/// The subsumption behaviour's runs: its own script, and seeded ones of its story at other
/// milliseconds (the ball seen, an obstacle for a while, the ball near and reached), with a
/// few steps at any time (rounds' moments included), stopped at any time.
pub(crate) fn subsumption_runs() -> Vec<(String, String, Option<String>)> {
    let field = std::fs::read_to_string("machines/subsumption/field.script").unwrap();
    let mut runs = vec![("subsumption-own".to_string(), field, None)];
    let atoms = ["ballSeen", "ballNear", "atBall", "obstacle"];
    let mut seed = 0x5eed_0033_5b5b;
    for n in 0..6 {
        let mut next = |below: u64| splitmix(&mut seed) % below;
        let mut script: String = atoms.iter().map(|a| format!("{a} = false\n")).collect();
        let seen = next(1_500);
        let obstacle = 500 + next(2_500);
        let near = obstacle + next(800);
        let clear = obstacle + 100 + next(1_400);
        let at_ball = 3_000 + next(3_000);
        for (at, step) in [
            (seen, "ballSeen = true"),
            (obstacle, "obstacle = true"),
            (near, "ballNear = true"),
            (clear, "obstacle = false"),
            (at_ball, "atBall = true"),
        ] {
            script.push_str(&format!("at {at}ms {step}\n"));
        }
        for _ in 0..next(3) {
            let at = seeded_moment(&mut next, 0, 6_000);
            let atom = atoms[next(4) as usize];
            let value = next(2) == 0;
            script.push_str(&format!("at {at}ms {atom} = {value}\n"));
        }
        let run_for = format!("{}ms", 1_000 + next(7_000));
        runs.push((format!("subsumption-random{n}"), script, Some(run_for)));
    }
    runs
}

/// The keeper's runs (`machines/keeper`, a dive of nested states): its own match, and seeded
/// ones in which the ball, its side and the referee's penalty come at any millisecond, rounds'
/// moments included, so that a penalty meets every step of the dive.
pub(crate) fn keeper_runs() -> Vec<(String, String, Option<String>)> {
    let atoms = ["ballComing", "ballLeft", "penalized"];
    match_runs("keeper", &atoms, 0x5eed_0048_4b50)
}

/// Runs of a keeper-shaped behaviour `name`: its own `match.script` for 7 s, and eight seeded
/// ones: every atom false, the ball coming within 2 s, then 2 to 9 of `atoms` set at any
/// millisecond of 5 s, each run stopped between 1 and 6 s.
fn match_runs(name: &str, atoms: &[&str], mut seed: u64) -> Vec<(String, String, Option<String>)> {
    let own = std::fs::read_to_string(format!("machines/{name}/match.script")).unwrap();
    let mut runs = vec![(format!("{name}-own"), own, Some("7s".to_string()))];
    for n in 0..8 {
        let mut next = |below: u64| splitmix(&mut seed) % below;
        let mut script: String = atoms.iter().map(|a| format!("{a} = false\n")).collect();
        let ball = seeded_moment(&mut next, 0, 2_000);
        script.push_str(&format!("at {ball}ms ballComing = true\n"));
        for _ in 0..2 + next(8) {
            let at = seeded_moment(&mut next, 0, 5_000);
            let atom = atoms[next(atoms.len() as u64) as usize];
            let value = next(2) == 0;
            script.push_str(&format!("at {at}ms {atom} = {value}\n"));
        }
        let run_for = format!("{}ms", 1_000 + next(5_000));
        runs.push((format!("{name}-random{n}"), script, Some(run_for)));
    }
    runs
}

/// Builds shipped behaviour `behaviour` to C in a scratch folder `tag`, holds each of `runs`
/// to the interpreter's trace byte for byte, and says in how many the interpreted trace holds
/// `reached` (so a test can tell its runs went where they are for).
fn runs_agree(
    behaviour: &str,
    tag: &str,
    runs: &[(String, String, Option<String>)],
    reached: &str,
) -> usize {
    let dir = scratch(tag);
    build(behaviour, &dir);
    let mut count = 0;
    for (name, script, run_for) in runs {
        let (interpreted, compiled) = traces(behaviour, &dir, name, script, run_for.as_deref());
        count += usize::from(interpreted.contains(reached));
        assert_same(name, &interpreted, &compiled);
    }
    count
}

#[test]
fn the_keepers_nested_dive_compiles_to_the_interpreters_trace() {
    if gcc_missing() {
        return;
    }
    let runs = keeper_runs();
    let dived = runs_agree("machines/keeper", "keeper", &runs, "DIVE.AIM");
    assert!(
        dived * 2 > runs.len(),
        "most runs dived ({dived} of {})",
        runs.len()
    );
}

/// The search's runs (`machines/search`, a composite whose 3 s count from its entry): its own
/// ball, and seeded ones in which the ball comes and goes at any millisecond, rounds' moments
/// included, so that it meets every turn of the head and the search's give-up.
pub(crate) fn search_runs() -> Vec<(String, String, Option<String>)> {
    let own = std::fs::read_to_string("machines/search/ball.script").unwrap();
    let mut runs = vec![("search-own".to_string(), own, Some("8s".to_string()))];
    let mut seed = 0x5eed_0048_5ea4;
    for n in 0..8 {
        let mut next = |below: u64| splitmix(&mut seed) % below;
        let mut script = String::from("ballSeen = false\n");
        for _ in 0..1 + next(6) {
            let at = seeded_moment(&mut next, 0, 9_000);
            script.push_str(&format!("at {at}ms ballSeen = {}\n", next(2) == 0));
        }
        let run_for = format!("{}ms", 2_000 + next(8_000));
        runs.push((format!("search-random{n}"), script, Some(run_for)));
    }
    runs
}

#[test]
fn the_searchs_composite_time_test_compiles_to_the_interpreters_trace() {
    if gcc_missing() {
        return;
    }
    let runs = search_runs();
    let gave_up = runs_agree("machines/search", "search", &runs, "\"GIVE_UP\"");
    assert!(
        gave_up * 2 > runs.len(),
        "most runs gave a search up ({gave_up} of {})",
        runs.len()
    );
}

/// The tracker's runs (a head and legs side by side, `docs/spec/behaviour.md` §3.2): its own
/// script, and seeded ones of the ball seen, lost and near at any millisecond.
pub(crate) fn tracker_runs() -> Vec<(String, String, Option<String>)> {
    let own = std::fs::read_to_string("machines/tracker/ball.script").unwrap();
    let mut runs = vec![("tracker-own".to_string(), own, Some("5s".to_string()))];
    let mut seed = 0x5eed_0048_7a4c;
    for n in 0..8 {
        let mut next = |below: u64| splitmix(&mut seed) % below;
        let mut script = String::from("ballSeen = false\nballNear = false\ngameOver = false\n");
        for _ in 0..1 + next(8) {
            let at = seeded_moment(&mut next, 0, 6_000);
            let atom = ["ballSeen", "ballNear", "ballSeen", "gameOver"][next(4) as usize];
            script.push_str(&format!("at {at}ms {atom} = {}\n", next(3) != 0));
        }
        let run_for = format!("{}ms", 2_000 + next(6_000));
        runs.push((format!("tracker-random{n}"), script, Some(run_for)));
    }
    runs
}

/// Regions lower to the flat form every target reads, so a compiled head and legs side by
/// side write the interpreter's trace byte for byte.
#[test]
fn the_trackers_regions_compile_to_the_interpreters_trace() {
    if gcc_missing() {
        return;
    }
    let runs = tracker_runs();
    let both = runs_agree(
        "machines/tracker",
        "tracker",
        &runs,
        "\"PLAY.HEAD.TRACK, PLAY.LEGS.WALK\"",
    );
    assert!(both > 0, "some run walked while tracking");
}

/// The whole goalkeeper's runs (`machines/goalkeeper`: a head region beside a body region
/// whose dive nests and starts a sub-machine): its own match, and seeded ones in which the
/// ball is seen, comes and leaves and the referee penalizes at any millisecond.
pub(crate) fn goalkeeper_runs() -> Vec<(String, String, Option<String>)> {
    let atoms = ["ballSeen", "ballComing", "ballLeft", "penalized"];
    match_runs("goalkeeper", &atoms, 0x5eed_0048_9c4b)
}

/// A dive nested in one region beside a head in another, its fall a sub-machine given its
/// side: compiled, it writes the interpreter's trace byte for byte.
#[test]
fn the_whole_goalkeepers_regions_and_dive_compile_to_the_interpreters_trace() {
    if gcc_missing() {
        return;
    }
    let runs = goalkeeper_runs();
    let braced = runs_agree(
        "machines/goalkeeper",
        "goalkeeper",
        &runs,
        "\"PLAY.HEAD.BRACE, PLAY.BODY.DIVE.",
    );
    assert!(
        braced * 2 > runs.len(),
        "most runs braced the head in a dive ({braced} of {})",
        runs.len()
    );
}

/// The GameController behaviour's runs, its sensors' atoms from the script: a whole game with
/// a penalty and the chest button, one where the script sets only some atoms (the rest no
/// expert answers), and seeded games of any order at any millisecond, stopped at any time.
pub(crate) fn game_controller_runs() -> Vec<(String, String, Option<String>)> {
    let states = ["initial", "ready", "set", "playing", "penalty", "finished"];
    let all_false: String = states
        .iter()
        .map(|s| format!("{s}Received = false\n"))
        .chain(["shortChestButtonPressed = false\n".to_string()])
        .collect();
    let game = format!("{all_false}at 500ms initialReceived = true\nat 1s initialReceived = false\nat 1s readyReceived = true\nat 2s readyReceived = false\nat 2s setReceived = true\nat 3s setReceived = false\nat 3s playingReceived = true\nat 4s penaltyReceived = true\nat 4500ms shortChestButtonPressed = true\nat 4600ms shortChestButtonPressed = false\nat 5s penaltyReceived = false\nat 6s playingReceived = false\nat 6s finishedReceived = true\n");
    let some = "readyReceived = false\nshortChestButtonPressed = false\nat 1s readyReceived = true\nat 2550ms shortChestButtonPressed = true\n";
    let mut runs = vec![
        ("gc-game".to_string(), game, Some("8s".to_string())),
        (
            "gc-some".to_string(),
            some.to_string(),
            Some("4s".to_string()),
        ),
    ];
    let mut seed = 0x5eed_0033_6c6c;
    for n in 0..6 {
        let mut next = |below: u64| splitmix(&mut seed) % below;
        let mut script = all_false.clone();
        let mut at = 0;
        let mut now = "initial";
        // At any millisecond, rounds' moments included: a posting due just as a round is (the
        // button, unread in most states) comes before that round, in the interpreter as in the
        // compiled hosts (`docs/spec/behaviour.md` §3.1).
        for _ in 0..3 + next(6) {
            at = seeded_moment(&mut next, at + 1, 1_500);
            let then = states[next(states.len() as u64) as usize];
            script.push_str(&format!(
                "at {at}ms {now}Received = false\nat {at}ms {then}Received = true\n"
            ));
            now = then;
        }
        for _ in 0..next(3) {
            let press = seeded_moment(&mut next, 0, at + 1);
            let release = seeded_moment(&mut next, press + 50, 400);
            script.push_str(&format!("at {press}ms shortChestButtonPressed = true\nat {release}ms shortChestButtonPressed = false\n"));
        }
        let run_for = format!("{}ms", 1 + next(at + 2_000));
        runs.push((format!("gc-random{n}"), script, Some(run_for)));
    }
    runs
}

#[test]
fn sensors_atoms_come_from_the_script_as_when_the_interpreter_leaves_the_sensors_out() {
    if gcc_missing() {
        return;
    }
    let behaviour = "machines/game_controller";
    let dir = scratch("game_controller");
    build(behaviour, &dir);
    let mut moved = 0;
    for (case, script, run_for) in game_controller_runs() {
        let (interpreted, compiled) = traces(behaviour, &dir, &case, &script, run_for.as_deref());
        assert_same(&case, &interpreted, &compiled);
        moved += interpreted.matches("\"fired\"").count();
    }
    assert!(moved > 20, "the games move the machines: {moved} firings");
    // A script that sets none of a sensor's atoms would have the interpreter run the sensor.
    let mut program = Command::new(dir.join("behaviour"))
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::io::Write::write_all(
        &mut program.stdin.take().unwrap(),
        b"at 1s readyReceived = true\n",
    )
    .unwrap();
    let out = program.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains(
            "sets none of the atoms the module `chestButton` answers (shortChestButtonPressed)"
        ),
        "{stderr}"
    );
}

#[test]
fn suppression_holds_back_and_hands_over_as_the_interpreter_does() {
    if gcc_missing() {
        return;
    }
    let behaviour = "machines/subsumption";
    let dir = scratch("subsumption");
    build(behaviour, &dir);
    let mut held_back = 0;
    for (case, script, run_for) in subsumption_runs() {
        let (interpreted, compiled) = traces(behaviour, &dir, &case, &script, run_for.as_deref());
        assert_same(&case, &interpreted, &compiled);
        held_back += usize::from(interpreted.contains("\"took_over\""));
    }
    assert!(held_back >= 3, "runs where a hold ran out: {held_back}");
    let trace = construct_trace("layers");
    assert!(
        trace.contains("\"suppressed\"") && trace.contains("\"took_over\""),
        "the layers hold each other back: {trace}"
    );
}

/// The construct case `name` written out, compiled, and held to the interpreter's trace, which
/// it returns.
fn construct_trace(name: &str) -> String {
    let case = construct_cases()
        .into_iter()
        .find(|c| c.name == name)
        .unwrap();
    let files: Vec<(&str, &str)> = case
        .files
        .iter()
        .map(|(f, t)| (f.as_str(), t.as_str()))
        .collect();
    let folder = behaviour_of(name, &files);
    same_trace(name, &folder, case.script, case.run_for)
}

/// A theory's input group holds in a compiled program as in the reasoner: setting one atom true
/// makes the others false (`docs/spec/cdl.md` §1), so the keeper follows the ball to the centre.
#[test]
fn an_input_group_moves_as_the_reasoners_session_moves_it() {
    if gcc_missing() {
        return;
    }
    let trace = construct_trace("group");
    assert!(
        trace.contains("\"state\":\"Centre\""),
        "the keeper follows the ball: {trace}"
    );
}

#[test]
fn whiteboard_variables_are_read_through_the_snapshot_and_posted_when_assigned() {
    if gcc_missing() {
        return;
    }
    let trace = construct_trace("externs");
    // The poster counts `n` up to 10 through its own postings, and the watcher sees it.
    assert!(
        trace.contains("\"type\":\"n\",\"content\":\"10\"") && trace.contains("\"text\":\"10\""),
        "{trace}"
    );
}

#[test]
fn whiteboard_values_read_by_name_alone_are_the_runners_including_none_and_who_posted() {
    if gcc_missing() {
        return;
    }
    let trace = construct_trace("board");
    for (what, expected) in [
        (
            "no value plus one is assigned as 0",
            "\"variable\":\"n\",\"value\":\"0\"",
        ),
        (
            "a running state is read from its poster",
            "\"atom\":\"WorkerIsRunning\",\"value\":true,\"by\":{\"posted\":\"Worker\"}",
        ),
        (
            "a stop is posted too",
            "\"atom\":\"WorkerIsRunning\",\"value\":false,\"by\":{\"posted\":\"Worker\"}",
        ),
        (
            "an atom no expert answers is read from its poster",
            "\"atom\":\"busy\",\"value\":false,\"by\":{\"posted\":\"Poster\"}",
        ),
        (
            "a whole number sets a theory input",
            "\"atom\":\"cook\",\"value\":true",
        ),
        ("a posted type is read", "\"text\":\"30\""),
        (
            "a script's atom that is a theory input is asked of the impersonator",
            "\"atom\":\"doorOpen\",\"value\":true,\"by\":{\"expert\":\"impersonator\"}",
        ),
        ("the reader ends in D", "\"state\":\"D\""),
    ] {
        assert!(trace.contains(expected), "{what}: {trace}");
    }
}

/// Whole numbers come from outside as a sensor posts them (here the script's, in C through
/// `behaviour_outside`): the kicker copies a bearing into a variable and compares the copy, as
/// the interpreter does, and a bearing beyond the manifest's `[ranges]` is warned of once per
/// value, in the interpreter's words (issue 44: a compiled behaviour read them as truths).
#[test]
fn whole_numbers_from_outside_are_read_and_held_to_the_declared_range_as_the_runner_does() {
    if gcc_missing() {
        return;
    }
    let trace = construct_trace("outside");
    for (what, expected) in [
        ("a copied bearing turns left", "\"label\":\"rr > 5\""),
        ("and right", "\"label\":\"rr < -5\""),
        (
            "a bearing beyond the range is warned of",
            "posted ballRR = -80, outside its declared range -50..50 (the manifest's [ranges])",
        ),
        ("another one too", "posted ballRR = 90, outside"),
        ("`+1` is the number", "\"content\":\"1\""),
    ] {
        assert!(trace.contains(expected), "{what}: {trace}");
    }
    assert_eq!(trace.matches("ballRR = -80, outside").count(), 1, "{trace}");
}

#[test]
fn arithmetic_is_the_runners_wrapping_c_arithmetic() {
    if gcc_missing() {
        return;
    }
    let machine = ARITH;
    let folder = behaviour_of(
        "arith",
        &[
            ("behaviour.toml", "[[machine]]\nfile = \"Arith.machine\"\n"),
            ("Arith.machine", machine),
        ],
    );
    let trace = same_trace("arith", &folder, "", None);
    assert!(
        trace.contains("\"variable\":\"over\",\"value\":\"-9223372036854775808\""),
        "{trace}"
    );
    assert!(
        trace.contains("\"variable\":\"x\",\"value\":\"true\""),
        "{trace}"
    );
}

#[test]
fn a_typed_variable_converts_what_is_assigned_and_a_change_of_kind_is_a_change() {
    if gcc_missing() {
        return;
    }
    let machine = TYPES;
    let folder = behaviour_of(
        "types",
        &[
            ("behaviour.toml", "[[machine]]\nfile = \"Types.machine\"\n"),
            ("Types.machine", machine),
        ],
    );
    let trace = same_trace("types", &folder, "", None);
    assert!(
        trace.contains("\"variable\":\"n\",\"value\":\"1\""),
        "{trace}"
    );
}

#[test]
fn postings_and_prints_carry_the_runners_text() {
    if gcc_missing() {
        return;
    }
    let machine = SPEAKER;
    let folder = behaviour_of(
        "say",
        &[
            (
                "behaviour.toml",
                "[[machine]]\nfile = \"Speaker.machine\"\n",
            ),
            ("Speaker.machine", machine),
        ],
    );
    let trace = same_trace("say", &folder, "", None);
    assert!(trace.contains("\"content\":\"1 true x y -3\""), "{trace}");
}

#[test]
fn for_loops_run_and_stop_at_the_runners_loop_limit() {
    if gcc_missing() {
        return;
    }
    let machine = LOOP;
    let folder = behaviour_of(
        "loop",
        &[
            ("behaviour.toml", "[[machine]]\nfile = \"Loop.machine\"\n"),
            ("Loop.machine", machine),
        ],
    );
    let trace = same_trace("loop", &folder, "", None);
    assert!(trace.contains("stopped after 100000 rounds"), "{trace}");
}

#[test]
fn sub_machines_obey_on_off_suspend_resume_and_restart_as_the_runner_does() {
    if gcc_missing() {
        return;
    }
    let boss = BOSS;
    let worker = WORKER;
    // A label over a global that another machine changes, and a time test already past.
    let watcher = WATCHER;
    let folder = behaviour_of(
        "control",
        &[
            ("behaviour.toml", "[[machine]]\nfile = \"Boss.machine\"\n[[machine]]\nfile = \"Worker.machine\"\nstart = false\n[[machine]]\nfile = \"Watcher.machine\"\n"),
            ("Boss.machine", boss),
            ("Worker.machine", worker),
            ("Watcher.machine", watcher),
        ],
    );
    let trace = same_trace("control", &folder, "", Some("2s"));
    for command in ["On", "Off", "suspend", "resume", "restart", "hello"] {
        assert!(
            trace.contains(&format!("\"command\":\"{command}\"")),
            "{command}: {trace}"
        );
    }
}

/// A random behaviour of up to three machines over four globals and typed variables of their
/// own: assignments of random arithmetic, computed postings, prints, loops, the first machine
/// controlling the others; every label a random condition and a time test (so time passes
/// between moves, and a run of `--for` ends).
pub(crate) fn random_behaviour(seed: u64) -> Vec<(String, String)> {
    let mut state = seed;
    let mut next = move |n: u64| splitmix(&mut state) % n;
    let globals = ["g0", "g1", "g2", "g3"];
    let constants = [
        "0",
        "1",
        "2",
        "3",
        "-1",
        "7",
        "100",
        "9223372036854775807",
        "-9223372036854775807",
        "true",
        "false",
    ];
    fn expression(
        next: &mut impl FnMut(u64) -> u64,
        depth: u32,
        names: &[String],
        constants: &[&str],
    ) -> String {
        if depth == 0 || next(10) < 3 {
            return if next(2) == 0 {
                constants[next(constants.len() as u64) as usize].to_string()
            } else {
                names[next(names.len() as u64) as usize].clone()
            };
        }
        let choice = next(17);
        let mut sub = || expression(next, depth - 1, names, constants);
        let ops = [
            "+", "-", "*", "/", "%", "<", "<=", ">", ">=", "==", "!=", "&&", "||",
        ];
        match choice {
            13 => format!("!({})", sub()),
            14 => format!("-({})", sub()),
            15 => format!("min({}, {})", sub(), sub()),
            16 => format!("max({}, {})", sub(), sub()),
            k => format!("({} {} {})", sub(), ops[k as usize], sub()),
        }
    }
    let machines = 1 + next(3) as usize;
    let mut manifest = String::new();
    let mut files = Vec::new();
    for m in 0..machines {
        manifest.push_str(&format!("[[machine]]\nfile = \"M{m}.machine\"\n"));
        if m > 0 && next(2) == 0 {
            manifest.push_str("start = false\n");
        }
        let own: Vec<String> = (0..2).map(|j| format!("l{m}_{j}")).collect();
        let names: Vec<String> = globals
            .iter()
            .map(|g| g.to_string())
            .chain(own.iter().cloned())
            .collect();
        let states = 2 + next(3);
        let mut text = format!("machine M{m}\ninitial S0\n");
        for s in 0..states {
            text.push_str(&format!("state S{s} {{\n"));
            for section in ["entry", "exit", "internal"] {
                if section != "entry" && next(2) == 0 {
                    continue;
                }
                text.push_str(&format!("    {section} {{\n"));
                if section == "entry" && s == 0 {
                    for v in &own {
                        text.push_str(&format!(
                            "        {} {v};\n",
                            ["int", "bool", "char"][next(3) as usize]
                        ));
                    }
                    if m == 0 {
                        for g in globals {
                            text.push_str(&format!("        {g} = {g};\n"));
                        }
                    }
                }
                for _ in 0..next(5) {
                    let k = next(100);
                    // Internal activities change only the machine's own variables: a global
                    // changed every ringlet would be news every round, and time would stand.
                    let line = if section == "internal" && !(55..78).contains(&k) {
                        format!(
                            "{} = {};",
                            own[next(2) as usize],
                            expression(&mut next, 2, &names, &constants)
                        )
                    } else if k < 55 {
                        format!(
                            "{} = {};",
                            names[next(6) as usize],
                            expression(&mut next, 2, &names, &constants)
                        )
                    } else if k < 65 {
                        format!(
                            "post(\"Out{m}\", {});",
                            expression(&mut next, 2, &names, &constants)
                        )
                    } else if k < 72 {
                        format!(
                            "say(\"v is \" + {} + \" and \" + {});",
                            names[next(6) as usize],
                            names[next(6) as usize]
                        )
                    } else if k < 78 {
                        format!(
                            "print_int({});",
                            expression(&mut next, 1, &names, &constants)
                        )
                    } else if k < 84 {
                        format!(
                            "for (i{m} = 0; i{m} < {}; i{m} = i{m} + 1) {{ {} = {} + i{m}; }}",
                            next(5),
                            globals[next(4) as usize],
                            globals[next(4) as usize]
                        )
                    } else if m == 0 && machines > 1 {
                        let word = ["On", "Off", "suspend", "resume", "restart"][next(5) as usize];
                        format!("M{}: {word}", 1 + next(machines as u64 - 1))
                    } else {
                        format!(
                            "postv(\"List{m}\", {}, {});",
                            expression(&mut next, 1, &names, &constants),
                            expression(&mut next, 1, &names, &constants)
                        )
                    };
                    text.push_str(&format!("        {line}\n"));
                }
                text.push_str("    }\n");
            }
            for _ in 0..next(4) {
                let target = next(states);
                let ms = [1, 2, 5, 10, 50][next(5) as usize];
                let condition = expression(&mut next, 2, &names, &constants);
                if next(2) == 0 {
                    text.push_str(&format!(
                        "    when {condition} && timeout({ms}ms) -> S{target}\n"
                    ));
                } else {
                    text.push_str(&format!(
                        "    when timeout({ms}ms) && {condition} -> S{target}\n"
                    ));
                }
            }
            text.push_str("}\n");
        }
        files.push((format!("M{m}.machine"), text));
    }
    files.push(("behaviour.toml".into(), manifest));
    files
}

#[test]
fn seeded_random_behaviours_of_variables_write_the_interpreters_trace() {
    if gcc_missing() {
        return;
    }
    let mut moved = 0;
    for seed in 0..24u64 {
        let files = random_behaviour(0x0033_0000 + seed);
        let name = format!("random-behaviour{seed}");
        let borrowed: Vec<(&str, &str)> = files
            .iter()
            .map(|(f, t)| (f.as_str(), t.as_str()))
            .collect();
        let folder = behaviour_of(&name, &borrowed);
        let trace = same_trace(&name, &folder, "", Some("300ms"));
        moved += usize::from(trace.contains("\"fired\""));
    }
    assert!(moved >= 12, "most random behaviours move: {moved} of 24");
}

#[test]
fn what_an_activity_cannot_compile_is_refused_at_its_line_for_either_target() {
    let out = scratch("refused-activity");
    for (body, expected) in [
        ("float speed;", "a `float` variable"),
        (
            "extern Other;",
            "`extern Other`, which is also a machine's name",
        ),
        (
            "extern d;\n        post(\"d\", \"hi\");",
            "a posting of text to `d`, a whiteboard value",
        ),
        (
            "extern d;\n        d: \"12\"",
            "the text \"12\" posted to `d`, a whiteboard value",
        ),
        (
            "x = ballDistance + 1;\n        ballDistance: \"far\"",
            "the text \"far\" posted to `ballDistance`, a whiteboard value",
        ),
        ("x = Other + 1;", "`Other`, which is no variable"),
        ("x = 2.5;", "the number `2.5`"),
        ("x = \"text\";", "the text \"text\""),
        ("kick(3);", "the call `kick`"),
        ("msleep(5);", "`msleep`"),
        ("x = sqrt(4);", "`sqrt(4)`"),
        ("x = team.min(d);", "a team aggregate"),
        (
            "post(\"Say\", \"12\" + 1);",
            "text that may read as a number",
        ),
        ("Other: reload", "no file to read again"),
    ] {
        let machine = format!("machine M\ninitial A\nstate A {{\n    entry {{\n        {body}\n    }}\n    when timeout(1s) -> B\n}}\nstate B {{\n}}\n");
        let other = "machine Other\ninitial O\nstate O {\n}\n";
        let folder = behaviour_of(
            "refused-activity",
            &[
                ("behaviour.toml", "[[machine]]\nfile = \"M.machine\"\n[[machine]]\nfile = \"Other.machine\"\nstart = false\n"),
                ("M.machine", &machine),
                ("Other.machine", other),
            ],
        );
        for target in ["c", "rust"] {
            let o = proclaim(&[
                "compile",
                folder.to_str().unwrap(),
                "--target",
                target,
                "-o",
                out.to_str().unwrap(),
            ]);
            assert_eq!(o.status.code(), Some(2), "{body} to {target}");
            let stderr = String::from_utf8_lossy(&o.stderr);
            assert!(
                stderr.contains("M.machine:3: cannot be compiled: "),
                "{body} to {target}: {stderr}"
            );
            assert!(stderr.contains(expected), "{body} to {target}: {stderr}");
        }
    }
}

#[test]
fn the_time_tests_timeout_after_ms_and_after_come_due_as_the_runners() {
    if gcc_missing() {
        return;
    }
    let machine = TIME;
    let folder = behaviour_of(
        "time",
        &[
            ("behaviour.toml", "[[machine]]\nfile = \"T.machine\"\n"),
            ("T.machine", machine),
        ],
    );
    let trace = same_trace("time", &folder, "", None);
    assert!(trace.contains("\"at_us\":3550000"), "{trace}");
}

/// Three layers posting two suppressed types on their own timeouts, so holds run out between
/// ringlets, behind one or two lower postings, live or not.
const LAYERS: &str = "[[machine]]\nfile = \"Low.machine\"\n[[machine]]\nfile = \"Mid.machine\"\npriority = 1\n[[machine]]\nfile = \"High.machine\"\npriority = 3\n[suppress]\ncmd = { hold = \"300ms\" }\nbeep = { hold = \"150ms\" }\n[[module]]\nname = \"legs\"\nreads = [\"cmd\", \"beep\"]\n";
const LOW: &str = "machine Low\ninitial A\nstate A {\n    internal {\n        cmd: low\n    }\n    when timeout(250ms) -> B\n}\nstate B {\n    entry {\n        cmd: lowB\n        beep: low\n    }\n    when timeout(130ms) -> A\n}\n";
const MID: &str = "machine Mid\ninitial A\nstate A {\n    entry {\n        cmd: mid\n    }\n    when timeout(350ms) -> B\n}\nstate B {\n    entry {\n        beep: mid\n    }\n    when timeout(220ms) -> A\n}\n";
const HIGH: &str = "machine High\ninitial A\nstate A {\n    when timeout(600ms) -> B\n}\nstate B {\n    entry {\n        cmd: high\n        beep: high\n    }\n    when timeout(90ms) -> A\n}\n";

/// A behaviour the tests above compile, as files, with a script and a time to stop at.
pub(crate) struct Case {
    pub name: &'static str,
    pub files: Vec<(String, String)>,
    pub script: &'static str,
    pub run_for: Option<&'static str>,
}

/// A keeper whose theory reads one input group: the ball is left, centre or right.
const KEEPER_THEORY: &str = "input{ballLeft, ballCentre, ballRight}.\nL: ballLeft => diveLeft.\nR: ballRight => diveRight.\nC: ballCentre => stay.\nN: ~ballLeft => notLeft.\noutput{diveLeft, diveRight, stay, notLeft}.\n";

/// It moves only as the group's update moves the theory's inputs: the ball seen right makes
/// it no longer left (`notLeft`), and seen in the centre no longer right.
const KEEPER: &str = "machine Keeper\ninitial Wait\nstate Wait {\n    when diveLeft -> Left\n}\nstate Left {\n    when diveRight && notLeft -> Right\n}\nstate Right {\n    when stay && !diveRight -> Centre\n}\nstate Centre {\n}\n";

/// The behaviours of the tests above that each hold to one construct: one machine each, the
/// controlling three, and the blinking two (with and without a theory).
pub(crate) fn construct_cases() -> Vec<Case> {
    let one = |name: &'static str, machine: &str, text: &str, run_for| Case {
        name,
        files: vec![
            (
                "behaviour.toml".into(),
                format!("[[machine]]\nfile = \"{machine}.machine\"\n"),
            ),
            (format!("{machine}.machine"), text.into()),
        ],
        script: "",
        run_for,
    };
    let theory = std::fs::read_to_string("theories/microwave.dl").unwrap();
    vec![
        one("arith", "Arith", ARITH, None),
        one("types", "Types", TYPES, None),
        one("say", "Speaker", SPEAKER, None),
        one("loop", "Loop", LOOP, None),
        one("time", "T", TIME, None),
        Case {
            name: "still",
            files: vec![
                ("behaviour.toml".into(), "[[machine]]\nfile = \"Guard.machine\"\n".into()),
                ("Guard.machine".into(), GUARD.into()),
            ],
            script: "penalised = false\nat 500ms penalised = true\n",
            run_for: None,
        },
        Case {
            name: "layers",
            files: vec![
                ("behaviour.toml".into(), LAYERS.into()),
                ("Low.machine".into(), LOW.into()),
                ("Mid.machine".into(), MID.into()),
                ("High.machine".into(), HIGH.into()),
            ],
            script: "",
            run_for: Some("3s"),
        },
        Case {
            name: "control",
            files: vec![
                ("behaviour.toml".into(), "[[machine]]\nfile = \"Boss.machine\"\n[[machine]]\nfile = \"Worker.machine\"\nstart = false\n[[machine]]\nfile = \"Watcher.machine\"\n".into()),
                ("Boss.machine".into(), BOSS.into()),
                ("Worker.machine".into(), WORKER.into()),
                ("Watcher.machine".into(), WATCHER.into()),
            ],
            script: "",
            run_for: Some("2s"),
        },
        Case {
            name: "both",
            files: vec![
                ("behaviour.toml".into(), format!("[[machine]]\nfile = \"Blink.machine\"\n[[machine]]\nfile = \"Watch.machine\"\n[[theory]]\nfile = \"microwave.dl\"\n{MODULES}")),
                ("Blink.machine".into(), BLINK.into()),
                ("Watch.machine".into(), WATCH.into()),
                ("microwave.dl".into(), theory),
            ],
            script: "at 700ms doorOpen = true\n",
            run_for: Some("5s"),
        },
        Case {
            name: "externs",
            files: vec![
                ("behaviour.toml".into(), "[[machine]]\nfile = \"W.machine\"\n[[machine]]\nfile = \"P.machine\"\n[impersonator]\nscript = \"own.script\"\n".into()),
                ("W.machine".into(), EXTERN_WATCHER.into()),
                ("P.machine".into(), EXTERN_POSTER.into()),
                ("own.script".into(), "q = false\n".into()),
            ],
            script: "at 170ms e = true\nat 333ms e = false\nat 400ms n = true\n",
            run_for: Some("2s"),
        },
        Case {
            name: "board",
            files: vec![
                ("behaviour.toml".into(), "[[machine]]\nfile = \"Reader.machine\"\n[[machine]]\nfile = \"Poster.machine\"\n[[machine]]\nfile = \"Worker.machine\"\nstart = false\n[[theory]]\nfile = \"microwave.dl\"\n[impersonator]\nscript = \"own.script\"\n".into()),
                ("Reader.machine".into(), BOARD_READER.into()),
                ("Poster.machine".into(), BOARD_POSTER.into()),
                ("Worker.machine".into(), "machine Worker\ninitial W\nstate W {\n}\n".into()),
                ("microwave.dl".into(), std::fs::read_to_string("theories/microwave.dl").unwrap()),
                ("own.script".into(), "doorOpen = false\n".into()),
            ],
            script: "doorOpen = false\nat 900ms doorOpen = true\n",
            run_for: Some("3s"),
        },
        Case {
            name: "group",
            files: vec![
                ("behaviour.toml".into(), "[[machine]]\nfile = \"Keeper.machine\"\n[[theory]]\nfile = \"keeper.dl\"\n".into()),
                ("Keeper.machine".into(), KEEPER.into()),
                ("keeper.dl".into(), KEEPER_THEORY.into()),
            ],
            script: "at 100ms ballLeft = true\nat 200ms ballRight = true\nat 400ms ballCentre = true\n",
            run_for: Some("1s"),
        },
        Case {
            name: "alone",
            files: vec![
                ("behaviour.toml".into(), format!("[[machine]]\nfile = \"Blink.machine\"\n{MODULES}")),
                ("Blink.machine".into(), BLINK.replace("timeout(1s) && !light", "timeout(1s)")),
            ],
            script: "",
            run_for: Some("5s"),
        },
        Case {
            name: "outside",
            files: ["behaviour.toml", "Kicker.machine", "sightings.script"]
                .iter()
                .map(|f| {
                    let text = std::fs::read_to_string(format!("tests/outside/{f}")).unwrap();
                    (f.to_string(), text)
                })
                .collect(),
            script: include_str!("outside/sightings.script"),
            run_for: Some("1200ms"),
        },
    ]
}

/// A run with no end given, whose only outside is its script, ends at the first round after the
/// script's last step that changes nothing with no time test to come (`docs/spec/behaviour.md`
/// §3.1): the interpreter says so, and the compiled program with no duration ends at that round.
#[test]
fn a_run_with_no_end_given_ends_at_the_first_still_round_after_its_script() {
    let files: Vec<(String, String)> = construct_cases()
        .into_iter()
        .find(|c| c.name == "still")
        .unwrap()
        .files;
    let files: Vec<(&str, &str)> = files
        .iter()
        .map(|(f, t)| (f.as_str(), t.as_str()))
        .collect();
    let folder = behaviour_of("still-run", &files);
    let script = folder.join("penalised.script");
    std::fs::write(&script, "penalised = false\nat 500ms penalised = true\n").unwrap();
    let run = proclaim(&[
        "run",
        folder.to_str().unwrap(),
        "--virtual-clock",
        "--script",
        script.to_str().unwrap(),
    ]);
    let out = String::from_utf8_lossy(&run.stdout);
    assert!(run.status.success(), "{out}");
    // The timeout fires at 2.5 s; the round after it (the period's, 2.6 s) is the first still one.
    assert!(
        out.contains("2.500s Guard         → Waiting")
            && out.contains("stopped: the script is over and the machines are still (no change, no time test to come), after 2.600 s"),
        "{out}"
    );
    if gcc_missing() {
        return;
    }
    let trace = construct_trace("still");
    assert!(
        trace
            .contains("\"atom\":\"penalised\",\"value\":true,\"by\":{\"expert\":\"impersonator\"}"),
        "the script answers the atom no module declares: {trace}"
    );
    let last = trace.lines().last().unwrap_or_default();
    assert!(
        last.contains("\"at_us\":2600000"),
        "ends at the still round: {last}"
    );
    // `n` counts 1, 2, 3 (its entry's 0 is no change), each a change that keeps the run going.
    assert_eq!(trace.matches("\"variable\":\"n\"").count(), 3, "{trace}");
}

/// Machines that go round a cycle of `TRUE` transitions hold time still (a round takes none):
/// `check` warns of the cycle; the interpreter and the compiled program both halt after the
/// same number of rounds with no wait, saying why, instead of running for ever at one moment.
#[test]
fn a_cycle_that_takes_no_time_is_warned_of_and_halted_interpreted_and_compiled() {
    let folder = crate::behaviour_folder(
        "timeless",
        &[
            ("Loop.machine", "machine Loop\ninitial A\nstate A {\n    when TRUE -> B\n}\nstate B {\n    when TRUE -> A\n}\n"),
            ("behaviour.toml", "[[machine]]\nfile = \"Loop.machine\"\n"),
        ],
    );
    let behaviour = folder.to_str().unwrap();
    let checked = proclaim(&["check", behaviour]);
    let said = String::from_utf8_lossy(&checked.stderr);
    assert!(
        said.contains("A -> B -> A goes round at one moment for ever"),
        "{said}"
    );
    let why = "10000 rounds fired one after another with no wait: the machines go round a cycle that takes no time, so time cannot pass";
    let run = proclaim(&["run", behaviour, "--virtual-clock", "--for", "60s"]);
    let out = String::from_utf8_lossy(&run.stdout);
    assert_eq!(run.status.code(), Some(1), "{out}");
    assert!(
        out.contains(&format!("Loop  halted: {why} (in state")),
        "{out}"
    );
    if gcc_missing() {
        return;
    }
    let dir = scratch("timeless");
    build(behaviour, &dir);
    let compiled = Command::new(dir.join("behaviour"))
        .arg("60s")
        .stdin(std::process::Stdio::null())
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&compiled.stderr);
    assert_eq!(compiled.status.code(), Some(1), "{said}");
    assert!(said.contains(&format!("halted: {why}")), "{said}");
}
