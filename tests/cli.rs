//! The `proclaim` binary as users run it: output lines, JSON, exit codes and errors.

use crate::proclaim;
use std::io::Write;
use std::process::{Command, Output};

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn temp_file(name: &str, text: &[u8]) -> std::path::PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("proclaim-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::File::create(&path)
        .unwrap()
        .write_all(text)
        .unwrap();
    path
}

/// Every record of a `check --json` report has the same keys, whichever reader found it.
fn assert_one_problem_shape(report: &serde_json::Value) {
    let keys = [
        "column", "file", "hint", "label", "line", "message", "severity",
    ];
    for problem in report.as_array().expect("an array") {
        let mut found: Vec<&str> = problem
            .as_object()
            .expect("an object")
            .keys()
            .map(String::as_str)
            .collect();
        found.sort();
        assert_eq!(found, keys, "{problem}");
    }
}

/// `args` → (exit code, stdout) with stdout compared exactly.
fn check(args: &[&str], code: i32, expect: &str) {
    let o = proclaim(args);
    assert_eq!(
        o.status.code(),
        Some(code),
        "{args:?}\nstderr: {}",
        stderr(&o)
    );
    assert_eq!(stdout(&o), expect, "{args:?}");
}

#[test]
fn prove_prints_one_line_per_answer() {
    check(
        &["prove", "tweety", "fly", "~fly"],
        0,
        "+beta fly\n-beta ~fly\n",
    );
    check(
        &[
            "prove",
            "tweety",
            "fly",
            "--alg",
            "all",
            "--set",
            "penguin=true",
        ],
        0,
        "-mu fly\n-pi fly\n-beta fly\n-alpha fly\n-delta fly\n",
    );
    check(&["prove", "blocking", "e", "--alg", "pi"], 0, "-pi e\n");
    check(
        &[
            "prove",
            "microwave",
            "\\/{cook, light}",
            "--set",
            "doorOpen=true",
        ],
        0,
        "+beta \\/{cook, light}\n",
    );
}

#[test]
fn prove_json() {
    let o = proclaim(&[
        "prove",
        "offside",
        "offside",
        "--set",
        "fewerThanTwoOpponentsBetween=true",
        "--json",
    ]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(
        v,
        serde_json::json!([{"algorithm": "beta", "query": "offside", "proved": true}])
    );
}

#[test]
fn bad_input_exits_2_and_says_why() {
    // An atom the theory never mentions is not provable (as SPINdle and Deimos answer it):
    // `-` under every algorithm, a warning with a did-you-mean, exit 0.
    let o = proclaim(&["prove", "tweety", "flyy", "--alg", "all"]);
    assert_eq!(o.status.code(), Some(0));
    assert_eq!(
        stdout(&o),
        "-mu flyy\n-pi flyy\n-beta flyy\n-alpha flyy\n-delta flyy\n"
    );
    assert!(
        stderr(&o).contains("warning: the theory has no atom `flyy`"),
        "{}",
        stderr(&o)
    );
    assert!(stderr(&o).contains("did you mean `fly`?"), "{}", stderr(&o));
    // Inside a clause it is still an error: the clause means something else than was written.
    let o = proclaim(&["prove", "tweety", "\\/{flyy, fly}"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    // No query: every conclusion.
    let o = proclaim(&["prove", "tweety"]);
    assert_eq!(o.status.code(), Some(0));
    assert_eq!(stdout(&o), "+beta bird\n+beta fly\n");
    let o = proclaim(&["prove", "microwave", "cook", "--set", "door=true"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("its inputs are doorOpen, timeLeft"),
        "{}",
        stderr(&o)
    );
    let o = proclaim(&["prove", "microwave", "cook", "--set", "doorOpen=maybe"]);
    assert!(
        stderr(&o).contains("use true, false or unknown"),
        "{}",
        stderr(&o)
    );
    let o = proclaim(&["prove", "/no/such/theory.dl", "a"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("cannot read /no/such/theory.dl"),
        "{}",
        stderr(&o)
    );
    let o = proclaim(&["prove"]);
    assert_eq!(o.status.code(), Some(2));
}

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
        "<embedded>/offside.dl: ok (5 atoms, 5 rules, 4 priorities, 4 inputs, 1 output)\n",
    );
}

#[test]
fn a_theory_with_errors_is_refused_by_prove() {
    let bad = temp_file("refused.dl", b"a => b\nc.\n");
    let o = proclaim(&["prove", bad.to_str().unwrap(), "b"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("did you forget the `.`"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn table_formats() {
    check(
        &["table", "microwave", "--format", "csv"],
        0,
        "doorOpen,timeLeft,beta cook,beta light\nfalse,false,false,false\nfalse,true,true,true\ntrue,false,false,true\ntrue,true,false,true\n",
    );
    let o = proclaim(&["table", "microwave", "--format", "json"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["rows"][1]["outputs"]["beta cook"], true);
    let o = proclaim(&["table", "offside"]);
    assert!(
        stdout(&o).starts_with("fewerThanTwoOpponentsBetween  inOwnHalf"),
        "{}",
        stdout(&o)
    );
}

#[test]
fn explain_tree() {
    let o = proclaim(&["explain", "blocking", "e", "--alg", "pi", "--depth", "0"]);
    assert_eq!(o.status.code(), Some(0));
    assert_eq!(
        stdout(&o),
        "-pi e\n  supported by R4: a => e\n  attacker R7 stands: its antecedent is supported and no applicable rule for e beats it\n"
    );
}

#[test]
fn gen_writes_the_family_and_its_expected_answer() {
    let o = proclaim(&["gen", "chain", "3"]);
    assert_eq!(
        stdout(&o),
        "a0.\nr1: a0 => a1.\nr2: a1 => a2.\nr3: a2 => a3.\n"
    );
    assert!(
        stderr(&o).contains("expected: +beta a3 +pi a3"),
        "{}",
        stderr(&o)
    );
    let o = proclaim(&["gen", "levels", "0", "--format", "dfl"]);
    assert_eq!(
        stdout(&o),
        "r0: => a0\nr1: a1 => -a0\nr2: => a1\nr3: a2 => -a1\nr4: => a2\nr3 > r2\n"
    );
    let o = proclaim(&["gen", "tree", "2", "2"]);
    assert_eq!(
        stdout(&o),
        "r0: a1, a2 => a0.\nr1: a3, a4 => a1.\nr2: a5, a6 => a2.\na3.\na4.\na5.\na6.\n"
    );
    let o = proclaim(&["gen", "teams", "0"]);
    assert_eq!(
        stdout(&o),
        "r0: => a0.\nr1: => a0.\nr2: => ~a0.\nr3: => ~a0.\nr0 > r2.\nr1 > r3.\n"
    );
    let o = proclaim(&["gen", "bogus", "3"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("unknown family `bogus`"));
}

#[test]
fn generated_families_give_their_expected_answers() {
    for (family, sizes) in [
        ("chain", vec![50]),
        ("chains", vec![50]),
        ("circle", vec![50]),
        ("circles", vec![50]),
        ("levels", vec![20]),
        ("levels-", vec![20]),
        ("teams", vec![3]),
        ("tree", vec![4, 3]),
        ("dag", vec![10, 3]),
        ("mix", vec![3, 2, 4]),
        ("attack-ring", vec![1001]),
        ("pairs-ring", vec![40]),
        ("priority-ring", vec![40]),
        ("defeater-ring", vec![200]),
        ("clique", vec![31]),
        ("ladder", vec![4]),
    ] {
        let f = proclaim_gen::Family::parse(family, &sizes).unwrap();
        let mut text = Vec::new();
        f.write(&mut text, proclaim_gen::Format::Dl).unwrap();
        let path = temp_file(&format!("{family}.dl"), &text);
        let expect: Vec<String> = f
            .expected()
            .iter()
            .map(|e| format!("--expect={e}"))
            .collect();
        let mut args = vec!["bench-run", path.to_str().unwrap()];
        args.extend(expect.iter().map(String::as_str));
        let o = proclaim(&args);
        let m: serde_json::Value = serde_json::from_slice(&o.stdout)
            .unwrap_or_else(|_| panic!("{family}: {}", stderr(&o)));
        assert_eq!(m["answers_ok"], true, "{family}");
        assert_eq!(
            m["rules"].as_u64().unwrap() as u128,
            f.rule_count() + facts(&f),
            "{family}"
        );
    }
}

/// Facts are unit clauses, which become rules `-> l` of the checked theory.
fn facts(f: &proclaim_gen::Family) -> u128 {
    use proclaim_gen::Family::*;
    match *f {
        Chain(_) | Chains(_) => 1,
        Tree(n, k) => (k as u128).pow(n as u32),
        Dag(_, k) => k as u128,
        Mix(m, n, _) => 2 * (m * n) as u128,
        _ => 0,
    }
}

#[test]
fn a_hundred_megabytes_of_garbage_is_refused_cleanly() {
    // Printable garbage with some structure-like characters, so the parser works for it.
    let mut garbage = Vec::with_capacity(100 << 20);
    let mut x: u64 = 0x2545F4914F6CDD1D;
    let alphabet = b"ab~.,:{}=>-\\/%\" \n$R1";
    while garbage.len() < 100 << 20 {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        garbage.push(alphabet[(x % alphabet.len() as u64) as usize]);
    }
    let path = temp_file("garbage.dl", &garbage);
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
fn gc_sim_plays_to_the_sensor_command_over_udp() {
    let port = std::net::UdpSocket::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port();
    let sensor = Command::new(env!("CARGO_BIN_EXE_proclaim"))
        .args([
            "sensor",
            "gamecontroller",
            "--bind",
            "127.0.0.1",
            "--port",
            &port.to_string(),
        ])
        .args(["--team", "18", "--player", "2", "--for", "4s"])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let script = temp_file(
        "game.txt",
        b"# a quick game\n0s initial\n200ms ready kick=5\n400ms set\n600ms playing\n700ms penalty team=18 player=2 secs=5\n1s finished\n",
    );
    let sim = std::thread::spawn(move || {
        std::thread::sleep(std::time::Duration::from_millis(800));
        let to = format!("127.0.0.1:{port}");
        proclaim(&[
            "gc-sim",
            "--script",
            script.to_str().unwrap(),
            "--to",
            &to,
            "--interval",
            "50",
        ])
    });
    let sim = sim.join().unwrap();
    let sensor = sensor.wait_with_output().unwrap();
    assert_eq!(sim.status.code(), Some(0), "{}", stderr(&sim));
    assert!(
        stdout(&sim).contains("PLAYING (kicking team 5"),
        "{}",
        stdout(&sim)
    );
    let out = stdout(&sensor);
    let states: Vec<&str> = out
        .lines()
        .filter(|l| l.contains("gameState"))
        .map(|l| l.rsplit(' ').next().unwrap())
        .collect();
    assert_eq!(
        states,
        [
            "\"INITIAL\"",
            "\"READY\"",
            "\"SET\"",
            "\"PLAYING\"",
            "\"FINISHED\""
        ],
        "{out}"
    );
    assert!(out.contains("penaltyReceived = true"), "{out}");
    assert!(out.contains("weKickOff = false"), "{out}");
    assert!(stderr(&sensor).contains("0 ignored"), "{}", stderr(&sensor));
}

#[test]
fn gc_sim_reports_script_errors_by_line() {
    let script = temp_file("bad-game.txt", b"0s initial\n1s dance\nsoon playing\n");
    let o = proclaim(&["gc-sim", "--script", script.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    let err = stderr(&o);
    assert!(
        err.contains("bad-game.txt:2: error: unknown event `dance`"),
        "{err}"
    );
    assert!(
        err.contains("bad-game.txt:3: error: `soon` is not a time"),
        "{err}"
    );
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
fn draw_writes_dot_and_renders_through_graphviz() {
    let t = temp_file("TDoor.txt", b"0\topen\t1\n1\t~open\t0\n");
    temp_file(
        "ADoor.txt",
        b"1\tOpen|OnEntry Light: On;/\n0\tShut|OnEntry /\n",
    );
    let o = proclaim(&["draw", t.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(
        stdout(&o).starts_with("digraph \"Door\" {"),
        "{}",
        stdout(&o)
    );
    assert!(stdout(&o).contains("s0 -> s1 [label=\"1: open\"];"));
    let svg = t.with_file_name("door.svg");
    let o = proclaim(&["draw", t.to_str().unwrap(), "-o", svg.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let graphviz = std::process::Command::new("dot").arg("-V").output().is_ok();
    if graphviz {
        let text = std::fs::read_to_string(&svg).unwrap();
        assert!(text.contains("<svg") && text.contains("Open (1)"), "{text}");
    } else {
        assert!(
            stderr(&o).contains("Render it with `dot -Tsvg"),
            "{}",
            stderr(&o)
        );
        assert!(svg.with_extension("dot").exists());
    }
    let o = proclaim(&["draw", "tweety"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("is not a machine file"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn a_bad_query_is_called_a_query() {
    let o = proclaim(&["prove", "tweety", "fly ~"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("error: the query has 1 error"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn import_writes_native_files_that_check_and_import_again_unchanged() {
    let t = temp_file(
        "TBlink.txt",
        b"1\tTRUE\t2\n2\tstop\t1\n2\ttimeout(500000)\t1\n",
    );
    temp_file(
        "ABlink.txt",
        b"2\tOn|OnEntry LEDS: Chest On;/ OnExit LEDS: Chest Off;/\n1\tOff|OnEntry C++: msleep(100);/\n",
    );
    let out = t.with_file_name("imported");
    let o = proclaim(&["import", t.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let file = out.join("Blink.machine");
    let first = std::fs::read_to_string(&file).unwrap();
    assert!(
        first.contains("initial Off\n")
            && first.contains("when timeout(500000) -> Off\n    when stop -> Off"),
        "{first}"
    );
    check(
        &["check", file.to_str().unwrap()],
        0,
        &format!(
            "{}: ok (1 machine, 2 states, 3 transitions, 0 warnings)\n",
            file.display()
        ),
    );
    // Importing the native file again writes the same machine.
    let again = t.with_file_name("again");
    let o = proclaim(&[
        "import",
        file.to_str().unwrap(),
        "-o",
        again.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let second = std::fs::read_to_string(again.join("Blink.machine")).unwrap();
    let body = |text: &str| text.lines().skip(1).collect::<Vec<_>>().join("\n");
    assert_eq!(body(&second), body(&first));

    let bad = temp_file("bad.machine", b"machine M\nstate A {\n  when -> A\n}\n");
    let o = proclaim(&[
        "import",
        bad.to_str().unwrap(),
        "-o",
        again.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("bad.machine:3: error: a transition needs a label"),
        "{}",
        stderr(&o)
    );
    let o = proclaim(&["import", "offside", "-o", again.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("offside is not a machine file"),
        "{}",
        stderr(&o)
    );
}

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
    let o = proclaim(&["run", "microwave", "--for", "soon"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("--for soon: not a duration"),
        "{}",
        stderr(&o)
    );
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
    let child = Command::new(env!("CARGO_BIN_EXE_proclaim"))
        // `go` is answered by nobody (a behaviour being written): --force runs it all the same.
        .args([
            "run",
            dir.to_str().unwrap(),
            "--watch",
            "--for",
            "20s",
            "--force",
        ])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_millis(1500));
    std::fs::write(&machine, "machine W\nstate Wait {\n  when -> Done\n}\n").unwrap();
    std::thread::sleep(std::time::Duration::from_millis(1000));
    std::fs::write(
        &machine,
        "machine W\nstate Wait {\n  when TRUE -> Done\n}\nstate Done {\n}\n",
    )
    .unwrap();
    let o = child.wait_with_output().unwrap();
    let out = stdout(&o);
    assert_eq!(o.status.code(), Some(0), "{out}\n{}", stderr(&o));
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
        stderr(&o).contains("W.machine:3: warning: label `go` is answered by no expert"),
        "--force shows what check found as warnings: {}",
        stderr(&o)
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
fn check_draw_deps_and_liveness_on_behaviours() {
    let repo = env!("CARGO_MANIFEST_DIR");
    let gc = format!("{repo}/machines/game_controller");
    check(
        &["check", &gc],
        0,
        &format!("{gc}: ok (2 machines, 0 theories, 2 sensors; 0 errors, 0 warnings)\n"),
    );
    // Built-in behaviours are found by name too.
    let o = proclaim(&["deps", "game_controller", "--module", "GameController"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(
        stdout(&o).contains(
            "\"gamecontroller\" -> \"GameController\" [color=green4, label=\"readyReceived\"];"
        ),
        "{}",
        stdout(&o)
    );
    let o = proclaim(&["deps", "game_controller", "--module", "Nobody"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains(
            "no module `Nobody`; the behaviour has GameController, Placer, gamecontroller"
        ),
        "{}",
        stderr(&o)
    );

    let svg = temp_file("gc.svg", b"");
    let o = proclaim(&["draw", "game_controller", "-o", svg.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let has_graphviz = Command::new("dot").arg("-V").output().is_ok();
    if has_graphviz {
        let text = std::fs::read_to_string(&svg).unwrap();
        assert!(text.contains("<svg") && text.contains("Placer"), "{text}");
    } else {
        let dot = std::fs::read_to_string(svg.with_extension("dot")).unwrap();
        assert!(dot.contains("subgraph cluster_1"), "{dot}");
    }

    let formulas = temp_file(
        "test.liveness",
        b"TestBehavior = (Play | NoPlay)+\nPlay = SitDownAndStare | StandUpAndScan\n",
    );
    let out = formulas.with_file_name("skeleton");
    let o = proclaim(&[
        "liveness",
        formulas.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let o = proclaim(&["check", out.to_str().unwrap(), "--json"]);
    assert_eq!(o.status.code(), Some(1), "open labels are errors");
    let report: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_one_problem_shape(&report);
    let messages: Vec<&str> = report
        .as_array()
        .unwrap()
        .iter()
        .map(|d| d["message"].as_str().unwrap())
        .collect();
    assert_eq!(messages.len(), 8, "{messages:#?}");
    assert!(
        messages.contains(&"label `againPlay` is answered by no expert and posted by no module")
    );

    let bad = temp_file("bad.liveness", b"A = (B | C\n");
    let o = proclaim(&[
        "liveness",
        bad.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("bad.liveness:1: error: in the formula of `A`: missing `)`"),
        "{}",
        stderr(&o)
    );
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
fn import_writes_a_label_it_cannot_read_as_a_comment_and_fails() {
    let fsm = temp_file(
        "Kicker.fsm",
        br#"<qfsmproject><machine name="FSM" initialstate="0">
<state code="0" description="OnEntry { int n; n = n + 1; postv(&quot;walk&quot;, n, -n); }">Start</state>
<state code="1" description="">End</state>
<transition><from>0</from><to>1</to><inputs>ball &amp;&amp; </inputs></transition>
<transition><from>0</from><to>-1</to><inputs>x</inputs></transition>
<transition><from>0</from><to>1</to><inputs>n &gt; 2</inputs></transition>
</machine></qfsmproject>"#,
    );
    let out_dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("proclaim-import-bad-{}", std::process::id()));
    let o = proclaim(&[
        "import",
        fsm.to_str().unwrap(),
        "-o",
        out_dir.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(
        err.contains("Kicker.fsm:4: error: label `ball &&`"),
        "{err}"
    );
    assert!(
        err.contains("Kicker.fsm:5: warning: a transition without `<from>` or `<to>`"),
        "{err}"
    );
    // Named after its file, not its `name="FSM"`; the unread label kept as a comment.
    let text = std::fs::read_to_string(out_dir.join("Kicker.machine")).unwrap();
    assert!(
        text.contains("machine Kicker\ndescription \"FSM\"\n"),
        "{text}"
    );
    assert!(
        text.contains("    // not read (line 4: expected a name, a number, a string, `(`, `!` or `-`, found the end (at column 9)): when ball && -> End\n"),
        "{text}"
    );
    assert!(
        text.contains("        n = n + 1;\n        postv(\"walk\", n, -n);\n"),
        "{text}"
    );
    assert!(text.contains("    when n > 2 -> End\n"), "{text}");
}

#[test]
fn deps_launch_writes_a_manifest_that_runs_from_where_it_is_written() {
    let elsewhere = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("proclaim-launch-{}", std::process::id()));
    std::fs::create_dir_all(&elsewhere).unwrap();
    let manifest = elsewhere.join("placer.toml");
    let o = proclaim(&[
        "deps",
        "machines/game_controller",
        "--launch",
        "Placer",
        "-o",
        manifest.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let o = proclaim(&["run", manifest.to_str().unwrap(), "--for", "5s"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(
        stdout(&o).contains("Placer  finished in IN_POSITION"),
        "{}",
        stdout(&o)
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
fn set_takes_declared_inputs_only_and_one_of_a_group() {
    let theory = temp_file(
        "group.dl",
        b"input{throwIn, goalKick, openPlay}.\nR1: openPlay => restartFree.\nR2: throwIn => handsAllowed.\nR3: goalKick => ~handsAllowed.\noutput{restartFree}.\noutput{handsAllowed}.\n",
    );
    let path = theory.to_str().unwrap();
    let o = proclaim(&["prove", path, "restartFree", "--set", "restartFree=true"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("`restartFree` is not an input of the theory, so it is concluded, not set (its inputs are throwIn, goalKick, openPlay)"),
        "{}",
        stderr(&o)
    );
    let o = proclaim(&[
        "prove",
        path,
        "restartFree",
        "--set",
        "throwIn=true",
        "--set",
        "goalKick=true",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o)
            .contains("`goalKick` and `throwIn` are one input group, of which exactly one is true"),
        "{}",
        stderr(&o)
    );
    // One of the group true makes the others false.
    let o = proclaim(&[
        "prove",
        path,
        "~openPlay",
        "~goalKick",
        "--alg",
        "mu",
        "--set",
        "throwIn=true",
    ]);
    assert_eq!(
        stdout(&o),
        "+mu ~openPlay\n+mu ~goalKick\n",
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
fn explain_json_names_goals_rules_and_their_roles() {
    let o = proclaim(&[
        "explain",
        "offside",
        "offside",
        "--set",
        "fewerThanTwoOpponentsBetween=true",
        "--set",
        "behindBall=true",
        "--json",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let json: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    let root = &json[0];
    assert_eq!(
        root["goal"],
        serde_json::json!({"algorithm": "beta", "literal": "offside", "proved": false})
    );
    let roles: Vec<(String, String)> = root["because"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|n| {
            Some((
                n["rule"].as_str()?.to_string(),
                n["role"].as_str()?.to_string(),
            ))
        })
        .collect();
    assert_eq!(
        roles,
        [
            ("Exposed".to_string(), "supports".to_string()),
            ("Usually".to_string(), "beaten".to_string()),
            ("OwnHalf".to_string(), "discounted".to_string()),
            ("Behind".to_string(), "stands".to_string()),
            ("ThrowIn".to_string(), "discounted".to_string()),
        ]
    );
    assert_eq!(root["because"][1]["beaten_by"], "Exposed");
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

#[test]
fn prove_in_spindles_form() {
    let o = proclaim(&["prove", "tweety", "fly", "~fly", "--format", "spindle"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(stdout(&o), "-D fly\n+d fly\n-D -fly\n-d -fly\n");
    let o = proclaim(&[
        "prove",
        "tweety",
        "--format",
        "spindle",
        "--set",
        "penguin=true",
    ]);
    assert!(
        stdout(&o).contains("+D penguin\n+d penguin\n"),
        "{}",
        stdout(&o)
    );
    assert!(stdout(&o).contains("-D fly\n-d fly\n"), "{}", stdout(&o));
}

fn generated(family: &str, size: u64) -> std::path::PathBuf {
    let mut text = Vec::new();
    proclaim_gen::Family::parse(family, &[size])
        .unwrap()
        .write(&mut text, proclaim_gen::Format::Dl)
        .unwrap();
    temp_file(&format!("{family}-{size}.dl"), &text)
}

#[test]
fn prove_prints_an_undecided_answer_and_exits_3() {
    let ladder = temp_file(
        "crossed-ladder.dl",
        proclaim_gen::crossed_ladder().as_bytes(),
    );
    let path = ladder.to_str().unwrap();
    check(
        &["prove", path, "t0", "~t0", "--budget", "1000"],
        3,
        "?beta t0  (undecided: search budget of 1000 steps spent in an attack cycle of 24 goals; raise it with --budget)\n-beta ~t0\n",
    );
    check(&["prove", path, "t0"], 0, "+beta t0\n");
    let o = proclaim(&["prove", path, "t0", "--json", "--budget", "1000"]);
    let answers: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(answers[0]["proved"], serde_json::Value::Null);
    assert!(answers[0]["undecided"]
        .as_str()
        .unwrap()
        .contains("24 goals"));
    let o = proclaim(&[
        "prove", path, "t0", "--format", "spindle", "--budget", "1000",
    ]);
    assert_eq!(
        (o.status.code(), stdout(&o).as_str()),
        (Some(3), "-D t0\n?d t0\n")
    );
    assert!(
        stderr(&o).contains("`beta t0` is undecided"),
        "{}",
        stderr(&o)
    );
    // Every atom in SPINdle's form: the same `?`, explained, and the exit status that says so.
    let o = proclaim(&["prove", path, "--format", "spindle", "--budget", "1000"]);
    assert_eq!(o.status.code(), Some(3));
    assert!(stdout(&o).contains("-D t0\n?d t0\n"), "{}", stdout(&o));
    assert!(
        stderr(&o).contains("`beta t0` is undecided"),
        "{}",
        stderr(&o)
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
fn bench_times_the_users_own_files() {
    let ladder = generated("ladder", 3);
    let o = proclaim(&["bench", ladder.to_str().unwrap(), "clique:9", "--json"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let rows: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(rows[0]["case"], "ladder-3.dl");
    assert_eq!(rows[0]["rules"], 30);
    assert_eq!(rows[0]["undecided"], 0);
    assert_eq!(rows[1]["case"], "clique(9)");
    assert_eq!(rows[1]["answers_ok"], true);
    check(&["bench", "no-such-theory.dl"], 2, "");
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

#[test]
fn verify_finds_the_seeded_interlock_fault_and_its_script_replays_it() {
    let machine = std::fs::read_to_string("machines/microwave/Microwave.machine").unwrap();
    // The fault: COOKING no longer leaves when the theory stops the magnetron.
    let faulty: String = machine
        .lines()
        .filter(|l| !l.contains("when ~cook"))
        .map(|l| format!("{l}\n"))
        .collect();
    assert_ne!(faulty, machine);
    let manifest = std::fs::read_to_string("machines/microwave/behaviour.toml")
        .unwrap()
        .replace("../../theories/", "");
    let dir = crate::behaviour_folder(
        "verify-fault",
        &[
            ("behaviour.toml", &manifest),
            ("Microwave.machine", &faulty),
            (
                "microwave.dl",
                &std::fs::read_to_string("theories/microwave.dl").unwrap(),
            ),
            (
                "kitchen.script",
                &std::fs::read_to_string("machines/microwave/kitchen.script").unwrap(),
            ),
        ],
    );
    let d = dir.to_str().unwrap();

    // The original holds; the fault fails (exit 1) with its counterexample by rounds.
    let o = proclaim(&["verify", "microwave"]);
    assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
    assert!(
        stdout(&o).contains("door interlock: holds"),
        "{}",
        stdout(&o)
    );
    let script = dir.join("counterexample.script");
    let o = proclaim(&["verify", d, "--counterexample", script.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}{}", stdout(&o), stderr(&o));
    let out = stdout(&o);
    assert!(out.contains("door interlock: FAILS"), "{out}");
    assert!(
        out.contains("Microwave: IDLE -> COOKING (when cook)"),
        "{out}"
    );
    assert!(
        out.contains("round 2\n    Microwave: COOKING stays; reads doorOpen = true"),
        "{out}"
    );

    // JSON, a budget too small (exit 3), a bad property (exit 2, located).
    let o = proclaim(&["verify", d, "--json"]);
    let json: serde_json::Value = serde_json::from_str(&stdout(&o)).expect("JSON");
    assert_eq!(json["report"]["properties"][0]["verdict"], "fails");
    let o = proclaim(&["verify", "microwave", "--max-states", "5"]);
    assert_eq!(o.status.code(), Some(3), "{}", stdout(&o));
    let o = proclaim(&["verify", "microwave", "--never", "Microwave.BAKING"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("column 1"), "{}", stderr(&o));

    // The script replays the counterexample: the door opens while the magnetron stays on.
    // (One machine: the runner's schedule, racing tasks or rounds, makes no difference here.)
    let o = proclaim(&[
        "run",
        d,
        "--script",
        script.to_str().unwrap(),
        "--virtual-clock",
        "--for",
        "2s",
    ]);
    let run = stdout(&o);
    let opened = run.find("posts doorOpen: true").expect("the door opens");
    let on = run
        .rfind("posts Magnetron: on")
        .expect("the magnetron goes on");
    assert!(on < opened, "{run}");
    assert!(!run[opened..].contains("Magnetron: off"), "{run}");

    // Beside the script, that run's trace for `replay --monitor`: the same story.
    let traced = std::fs::read_to_string(script.with_extension("jsonl")).unwrap();
    let opened = traced
        .find(r#""type":"doorOpen","content":"true""#)
        .expect("the door opens in the trace");
    assert!(traced[..opened].contains(r#""type":"Magnetron","content":"on""#));
    assert!(!traced[opened..].contains(r#""type":"Magnetron","content":"off""#));
    let o = proclaim(&["replay", script.with_extension("jsonl").to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
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

/// `prove FILE` with no query prints every conclusion (as lines, as JSON, in SPINdle's form)
/// exactly as asking for each literal prints it, on generated theories of several families in
/// both languages, under every algorithm.
#[test]
fn every_conclusion_is_what_each_literal_asked_alone_answers() {
    use proclaim_gen::Format::{Dfl, Dl};
    for (family, sizes, format) in [
        ("chain", vec![20], Dl),
        ("circle", vec![12], Dfl),
        ("teams", vec![2], Dfl),
        ("tree", vec![3, 3], Dfl),
        ("dag", vec![6, 3], Dl),
        ("levels-", vec![6], Dl),
        ("mix", vec![2, 2, 3], Dl),
        ("attack-ring", vec![9], Dl),
        ("clique", vec![5], Dl),
    ] {
        let f = proclaim_gen::Family::parse(family, &sizes).unwrap();
        let mut text = Vec::new();
        f.write(&mut text, format).unwrap();
        let (name, language) = match format {
            Dl => (format!("every-{family}.dl"), proclaim_cdl::Language::Dl),
            Dfl => (format!("every-{family}.dfl"), proclaim_cdl::Language::Dfl),
        };
        let path = temp_file(&name, &text);
        let path = path.to_str().unwrap();
        let theory = proclaim_cdl::load(std::str::from_utf8(&text).unwrap(), language).unwrap();
        let mut names: Vec<&str> = (0..theory.atom_count() as u32)
            .map(|a| theory.atom_name(proclaim_cdl::Atom(a)))
            .collect();
        names.sort();
        let lits: Vec<String> = names
            .iter()
            .flat_map(|n| [n.to_string(), format!("~{n}")])
            .collect();
        let run = |extra: &[&str], each: bool| {
            let mut args = vec!["prove", path];
            if each {
                args.extend(lits.iter().map(String::as_str));
            }
            args.extend(extra);
            let o = proclaim(&args);
            assert_eq!(
                o.status.code(),
                Some(0),
                "{family} {args:?}: {}",
                stderr(&o)
            );
            stdout(&o)
        };
        // Lines: every answer but the `-` ones, algorithm by algorithm.
        let lines = |out: String| {
            let mut kept: Vec<String> = out
                .lines()
                .filter(|l| !l.starts_with('-'))
                .map(String::from)
                .collect();
            kept.sort();
            kept
        };
        let all = ["--alg", "all"];
        assert_eq!(lines(run(&all, false)), lines(run(&all, true)), "{family}");
        let json = |out: String| {
            let value: serde_json::Value = serde_json::from_str(&out).unwrap();
            let mut kept: Vec<String> = value
                .as_array()
                .unwrap()
                .iter()
                .filter(|a| a["proved"] != false)
                .map(|a| a.to_string())
                .collect();
            kept.sort();
            kept
        };
        let all_json = ["--alg", "all", "--json"];
        assert_eq!(
            json(run(&all_json, false)),
            json(run(&all_json, true)),
            "{family}"
        );
        // SPINdle's form lists every literal, atoms by name: the same bytes either way.
        let spindle = ["--format", "spindle"];
        assert_eq!(run(&spindle, false), run(&spindle, true), "{family}");
    }
}

/// `bench --all` runs every conclusion, one query and `wc -w` as processes of their own and
/// reports each one's best and median time.
#[test]
fn bench_all_times_every_conclusion_against_one_query() {
    let o = proclaim(&[
        "bench",
        "--all",
        "--json",
        "--repeat",
        "2",
        "chain:200",
        "tree:3:3",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let cases: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let cases = cases.as_array().unwrap();
    assert_eq!(cases.len(), 2);
    assert_eq!(cases[0]["query"], "beta a200");
    for case in cases {
        for timing in ["every_conclusion", "one_query"] {
            let (best, median) = (&case[timing]["best_ms"], &case[timing]["median_ms"]);
            assert!(best.as_f64().unwrap() > 0.0, "{case}");
            assert!(best.as_f64() <= median.as_f64(), "{case}");
        }
    }
    let o = proclaim(&["bench", "--all", "chain:nope"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
}

#[test]
fn compile_writes_a_theory_as_freestanding_c_and_refuses_what_it_cannot() {
    let out = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("proclaim-compile-{}", std::process::id()));
    let o = proclaim(&[
        "compile",
        "theories/microwave.dl",
        "--target",
        "c",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(
        stdout(&o),
        format!(
            "microwave: 2 inputs, 2 outputs, 6 rules: a table of 2 bytes (a decision diagram would take 5 nodes, 25 bytes); wrote {}\n",
            out.join("microwave.c").display()
        )
    );
    let header = std::fs::read_to_string(out.join("microwave.h")).unwrap();
    assert!(header.contains("#define MICROWAVE_COOK 0"), "{header}");
    match Command::new("gcc")
        .args([
            "-std=c99",
            "-Wall",
            "-Wextra",
            "-Werror",
            "-ffreestanding",
            "-c",
        ])
        .arg(out.join("microwave.c"))
        .arg("-o")
        .arg(out.join("microwave.o"))
        .output()
    {
        Ok(gcc) => assert!(gcc.status.success(), "{}", stderr(&gcc)),
        Err(_) => assert!(
            std::env::var_os("CI").is_none(),
            "gcc is missing, and CI must build the compiled theory"
        ),
    }
    // Not built yet: said so, exit 2.
    let o = proclaim(&[
        "compile",
        "microwave",
        "--target",
        "rust",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("--target rust is not built yet"),
        "{}",
        stderr(&o)
    );
    // An answer undecided within the budget is refused, not guessed.
    let ladder = temp_file("ladder.dl", proclaim_gen::crossed_ladder().as_bytes());
    let o = proclaim(&[
        "compile",
        ladder.to_str().unwrap(),
        "--budget",
        "1000",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("undecided within the search budget"),
        "{}",
        stderr(&o)
    );
}
