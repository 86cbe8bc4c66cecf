//! examples/cpp/microwave.cpp, compiled with the system's g++ against this crate's static
//! library and run: its answers are the Rust session's. examples/c/table.c, as C: its CSV is the
//! Rust truth table's on every theory of theories/. examples/c/bench.c too, run briefly so it
//! keeps compiling. examples/c/dead_handles.c: every freed handle answers `DEAD_HANDLE`, and
//! valgrind sees no read of freed memory. examples/c/load_loop.c: a hundred loads, good and bad,
//! leave no byte lost to valgrind (a thousand before a release: `cargo nextest run -p
//! proclaim-capi --run-ignored all`). Skipped (with a message) where g++ (or valgrind, for
//! that part) is missing, unless `CI` is set, where that is a failure.

use proclaim_cdl::{load, Algorithm, Engine, Language, Session};
use std::path::{Path, PathBuf};
use std::process::Command;

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The static library this test binary's own build made: cargo builds this crate as the
/// dependency of its tests with every crate type it declares, staticlib included, into
/// `<target>/<profile>/deps/`, so the library is as current as the test. Only where it is
/// missing is it built here, by cargo, into the same target directory and profile. (Building
/// it here every time cost a second build of the library and its dependencies: `-p` resolves
/// other features than the workspace's build, and both builds write the same file.)
fn static_library() -> PathBuf {
    let test_binary = std::env::current_exe().expect("the test knows where it is");
    let deps = test_binary
        .parent()
        .expect("test binaries live in <target>/<profile>/deps");
    let library = deps.join("libproclaim_capi.a");
    if library.exists() {
        return library;
    }
    let profile_dir = deps.parent().expect("<target>/<profile>/deps");
    let target_dir = profile_dir.parent().expect("<target>/<profile>");
    let mut cargo = Command::new(env!("CARGO"));
    cargo
        .args(["build", "--quiet", "-p", "proclaim-capi", "--lib"])
        .env("CARGO_TARGET_DIR", target_dir)
        .current_dir(workspace());
    if profile_dir.file_name().is_some_and(|p| p == "release") {
        cargo.arg("--release");
    }
    let built = cargo.output().expect("cargo runs");
    assert!(
        built.status.success(),
        "building {} failed: {}",
        library.display(),
        String::from_utf8_lossy(&built.stderr)
    );
    let library = profile_dir.join("libproclaim_capi.a");
    assert!(library.exists(), "{} is missing", library.display());
    library
}

/// `examples/c/NAME.c` compiled as C11 (warnings are errors) and linked with the library.
fn compile_c(name: &str, optimise: bool) -> PathBuf {
    let root = workspace();
    let program = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("{name}-c"));
    // g++'s driver compiles a `.c` file as C when told the language.
    let compiled = Command::new("g++")
        .args(["-x", "c", "-std=c11", "-Wall", "-Wextra", "-Werror"])
        .args(optimise.then_some("-O2"))
        .arg("-I")
        .arg(root.join("crates/capi/include"))
        .arg(root.join(format!("examples/c/{name}.c")))
        .args(["-x", "none"])
        .arg(static_library())
        .args(["-lpthread", "-ldl", "-lm", "-o"])
        .arg(&program)
        .output()
        .expect("g++ runs");
    assert!(
        compiled.status.success(),
        "g++ failed on {name}.c:\n{}",
        String::from_utf8_lossy(&compiled.stderr)
    );
    program
}

/// Whether `tool` is missing here: a skip said on stderr, or with `CI` set a failure (`.ci/run`
/// installs what the tests need).
fn is_missing(tool: &str, needed_for: &str) -> bool {
    let missing = Command::new(tool).arg("--version").output().is_err();
    if missing {
        assert!(
            std::env::var_os("CI").is_none(),
            "{tool} is missing, and CI must {needed_for}"
        );
        eprintln!("skipped: {tool} is not installed, so this test cannot {needed_for}");
    }
    missing
}

fn gpp_is_missing() -> bool {
    is_missing("g++", "build the C and C++ examples")
}

/// What the example prints, from the Rust session.
fn expected_output(theory_text: &str) -> String {
    let theory = load(theory_text, Language::Dl).unwrap();
    let door = theory.atom("doorOpen").unwrap();
    let time = theory.atom("timeLeft").unwrap();
    let cook = theory.lit("cook").unwrap();
    let mut session = Session::new(Engine::new(theory));
    let mut out = String::new();
    for door_open in [false, true] {
        for time_left in [false, true] {
            session.set_input(door, Some(door_open)).unwrap();
            session.set_input(time, Some(time_left)).unwrap();
            out += &format!("doorOpen={door_open} timeLeft={time_left} cook:");
            for algorithm in Algorithm::ALL {
                out += &format!(" {}={}", algorithm.name(), session.prove(algorithm, cook));
            }
            out += "\n";
        }
    }
    out
}

#[test]
fn the_cpp_example_answers_as_the_rust_session_does() {
    if gpp_is_missing() {
        return;
    }
    let root = workspace();
    let program = Path::new(env!("CARGO_TARGET_TMPDIR")).join("microwave-cpp");
    let compiled = Command::new("g++")
        .args(["-std=c++17", "-Wall", "-Wextra", "-Werror", "-I"])
        .arg(root.join("crates/capi/include"))
        .arg(root.join("examples/cpp/microwave.cpp"))
        .arg(static_library())
        // What Rust's standard library needs from the system when linked statically.
        .args(["-lpthread", "-ldl", "-lm", "-o"])
        .arg(&program)
        .output()
        .expect("g++ runs");
    assert!(
        compiled.status.success(),
        "g++ failed:\n{}",
        String::from_utf8_lossy(&compiled.stderr)
    );

    let theory_path = root.join("theories/microwave.dl");
    let run = Command::new(&program)
        .arg(&theory_path)
        .output()
        .expect("the example runs");
    assert!(
        run.status.success(),
        "the example failed:\n{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let theory_text = std::fs::read_to_string(&theory_path).unwrap();
    assert_eq!(
        String::from_utf8(run.stdout).unwrap(),
        expected_output(&theory_text)
    );

    // A theory that does not load: the message the C API rendered, on stderr, and exit 1.
    let broken = Path::new(env!("CARGO_TARGET_TMPDIR")).join("broken-microwave.dl");
    std::fs::write(&broken, "input{doorOpen}.\nTimer: timeLeft => .\n").unwrap();
    let run = Command::new(&program).arg(&broken).output().unwrap();
    let stderr = String::from_utf8(run.stderr).unwrap();
    assert_eq!(run.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("broken-microwave.dl does not load (1 error)"),
        "{stderr}"
    );
    assert!(stderr.contains("2 │ Timer: timeLeft => ."), "{stderr}");

    // A file that is not there: the library's error names it.
    let missing = Path::new(env!("CARGO_TARGET_TMPDIR")).join("no-such-microwave.dl");
    let run = Command::new(&program).arg(&missing).output().unwrap();
    let stderr = String::from_utf8(run.stderr).unwrap();
    assert_eq!(run.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.starts_with(&format!("{} cannot be read", missing.display())),
        "{stderr}"
    );
}

#[test]
fn the_c_timing_loop_builds_and_runs() {
    if gpp_is_missing() {
        return;
    }
    let root = workspace();
    let program = compile_c("bench", true);
    let run = Command::new(&program)
        .arg(root.join("theories/microwave.dl"))
        .args(["101", "3"])
        .output()
        .expect("the timing loop runs");
    let stdout = String::from_utf8(run.stdout).unwrap();
    assert!(
        run.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let lines: Vec<&str> = stdout.lines().collect();
    assert_eq!(lines.len(), 2, "{stdout}");
    for (line, way) in lines.iter().zip(["by name", "by handle"]) {
        assert!(line.starts_with(&format!("set + prove {way}")), "{stdout}");
        assert!(
            line.ends_with("ns per iteration (3 runs of 101 iterations)"),
            "{stdout}"
        );
    }
    let usage = Command::new(&program)
        .arg(root.join("theories/microwave.dl"))
        .args(["10", "0"])
        .output()
        .unwrap();
    assert_eq!(usage.status.code(), Some(2));
}

/// `proclaim table --format csv`'s text, from the Rust table.
fn expected_csv(theory_text: &str) -> String {
    let theory = load(theory_text, Language::Dl).unwrap();
    let table = proclaim_cdl::truth_table(std::sync::Arc::new(Engine::new(theory))).unwrap();
    let header: Vec<&str> = table
        .inputs
        .iter()
        .map(String::as_str)
        .chain(table.columns.iter().map(|c| c.heading.as_str()))
        .collect();
    let mut out = header.join(",") + "\n";
    for row in &table.rows {
        let mut cells: Vec<String> = row.inputs.iter().map(bool::to_string).collect();
        match &row.outputs {
            Some(values) => cells.extend(values.iter().map(bool::to_string)),
            None => cells.extend(table.columns.iter().map(|_| "inconsistent".to_string())),
        }
        out += &(cells.join(",") + "\n");
    }
    out
}

#[test]
fn the_c_table_example_prints_the_rust_truth_table_of_every_theory() {
    if gpp_is_missing() {
        return;
    }
    let program = compile_c("table", false);
    let root = workspace().join("theories");
    let mut theories = 0;
    for dir in [root.clone(), root.join("classics")] {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().is_none_or(|e| e != "dl") {
                continue;
            }
            let run = Command::new(&program).arg(&path).output().unwrap();
            assert!(
                run.status.success(),
                "{}: {}",
                path.display(),
                String::from_utf8_lossy(&run.stderr)
            );
            let text = std::fs::read_to_string(&path).unwrap();
            assert_eq!(
                String::from_utf8(run.stdout).unwrap(),
                expected_csv(&text),
                "{}",
                path.display()
            );
            theories += 1;
        }
    }
    assert!(theories >= 9, "only {theories} theories found");
    let run = Command::new(&program).output().unwrap();
    assert_eq!(run.status.code(), Some(2), "no theory named: usage");
}

fn valgrind_is_missing() -> bool {
    is_missing("valgrind", "check the dead-handle example's memory use")
}

#[test]
fn the_c_dead_handle_example_gets_dead_handle_for_every_freed_handle() {
    if gpp_is_missing() {
        return;
    }
    let program = compile_c("dead_handles", false);
    let run = Command::new(&program).output().expect("the example runs");
    let stdout = String::from_utf8(run.stdout).unwrap();
    assert!(
        run.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&run.stderr)
    );
    assert!(!stdout.contains("FAILED"), "{stdout}");
    let dead = stdout
        .lines()
        .filter(|l| l.ends_with(": dead handle"))
        .count();
    assert_eq!(dead, 13, "{stdout}");

    // No read of freed memory behind the answers, and nothing lost: the freed handles' headers
    // stay, listed by the library, so valgrind counts them still reachable.
    if valgrind_is_missing() {
        return;
    }
    let checked = Command::new("valgrind")
        .args(["--error-exitcode=99", "--leak-check=full", "-q"])
        .arg(&program)
        .output()
        .expect("valgrind runs");
    assert!(
        checked.status.success(),
        "valgrind: {}",
        String::from_utf8_lossy(&checked.stderr)
    );
}

/// The byte count of valgrind's leak summary line for `kind` ("definitely lost"), or 0 when it
/// printed no summary because every block was freed.
fn lost_bytes(report: &str, kind: &str) -> u64 {
    if report.contains("All heap blocks were freed") {
        return 0;
    }
    let line = report
        .lines()
        .find_map(|l| l.split_once(&format!("{kind}: ")))
        .unwrap_or_else(|| panic!("valgrind printed no `{kind}` line:\n{report}"));
    line.1
        .split_whitespace()
        .next()
        .and_then(|n| n.replace(',', "").parse().ok())
        .unwrap_or_else(|| panic!("valgrind's `{kind}` line has no count:\n{report}"))
}

#[test]
fn a_hundred_loads_good_and_bad_lose_no_memory() {
    loads_lose_no_memory(100);
}

#[test]
#[ignore = "before a release: the full thousand (`--run-ignored all`)"]
fn a_thousand_loads_good_and_bad_lose_no_memory() {
    loads_lose_no_memory(1_000);
}

/// examples/c/load_loop.c run for `rounds` rounds under valgrind: every answer as expected and
/// no byte definitely or indirectly lost (a leak in any round shows whatever the count).
fn loads_lose_no_memory(rounds: usize) {
    if gpp_is_missing() {
        return;
    }
    let program = compile_c("load_loop", false);
    let run = Command::new(&program).arg("3").output().unwrap();
    let stdout = String::from_utf8(run.stdout).unwrap();
    assert!(run.status.success(), "{stdout}");
    assert_eq!(stdout, "3 rounds, 0 failures\n");

    if is_missing("valgrind", "count the memory repeated loads lose") {
        return;
    }
    let checked = Command::new("valgrind")
        .args(["--leak-check=full", "--error-exitcode=99"])
        .arg(&program)
        .arg(rounds.to_string())
        .output()
        .expect("valgrind runs");
    let report = String::from_utf8_lossy(&checked.stderr);
    assert!(checked.status.success(), "valgrind found errors:\n{report}");
    assert_eq!(
        String::from_utf8(checked.stdout).unwrap(),
        format!("{rounds} rounds, 0 failures\n")
    );
    for kind in ["definitely lost", "indirectly lost"] {
        assert_eq!(lost_bytes(&report, kind), 0, "{kind}:\n{report}");
    }
}

/// Whether g++ compiles `body` (inside `main`, with the header) as C++.
fn compiles_as_cpp(name: &str, body: &str) -> bool {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"));
    let source = dir.join(format!("{name}.cpp"));
    std::fs::write(
        &source,
        format!("#include \"proclaim.h\"\nint main() {{\n  ProclaimSession *s = nullptr;\n  bool a;\n  {body}\n  return 0;\n}}\n"),
    )
    .unwrap();
    Command::new("g++")
        .args(["-std=c++17", "-fsyntax-only", "-I"])
        .arg(workspace().join("crates/capi/include"))
        .arg(&source)
        .output()
        .expect("g++ runs")
        .status
        .success()
}

#[test]
fn the_header_takes_algorithms_and_values_as_enums_so_cpp_refuses_a_bare_number() {
    if gpp_is_missing() {
        return;
    }
    for (name, body, compiles) in [
        (
            "enums",
            "proclaim_session_set(s, \"a\", PROCLAIM_VALUE_TRUE);\n  \
             proclaim_session_prove(s, \"a\", PROCLAIM_ALGORITHM_BETA, &a);",
            true,
        ),
        (
            "bare-algorithm",
            "proclaim_session_prove(s, \"a\", 42, &a);",
            false,
        ),
        ("bare-value", "proclaim_session_set(s, \"a\", 7);", false),
        (
            "swapped",
            "proclaim_session_prove(s, \"a\", PROCLAIM_VALUE_TRUE, &a);",
            false,
        ),
    ] {
        assert_eq!(compiles_as_cpp(name, body), compiles, "{name}: {body}");
    }
}
