//! The `proclaim` binary as users run it, one file a command: output lines, JSON, exit codes
//! and errors. The helpers below are shared by the files.

mod check;
mod compile;
mod gc_sim;
mod gen_bench;
mod machine_files;
mod prove;
mod record_test;
mod run;
mod table_explain;
mod verify;
mod waiting;

use crate::proclaim;
use std::io::Write;
use std::process::Output;

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// `proclaim run BEHAVIOUR --virtual-clock --for FOR --record PATH EXTRA…`, which must succeed.
fn record_run(behaviour: &str, run_for: &str, path: &std::path::Path, extra: &[&str]) {
    let mut args = vec!["run", behaviour, "--virtual-clock", "--for", run_for];
    args.extend(["--record", path.to_str().unwrap()]);
    args.extend(extra);
    let run = crate::proclaim(&args);
    assert!(run.status.success(), "{behaviour}: {}", stderr(&run));
}

fn temp_file(name: &str, text: &[u8]) -> std::path::PathBuf {
    let path = crate::own_folder("proclaim-cli").join(name);
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

fn generated(family: &str, size: u64) -> std::path::PathBuf {
    let mut text = Vec::new();
    proclaim_gen::Family::parse(family, &[size])
        .unwrap()
        .write(&mut text, proclaim_gen::Format::Dl)
        .unwrap();
    temp_file(&format!("{family}-{size}.dl"), &text)
}
