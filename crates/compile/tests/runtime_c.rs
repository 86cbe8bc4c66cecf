//! The C runtime and host harness (`crates/compile/c/`) are real C: compiled alone, with and
//! without subsumption, as strictly as a generated behaviour, around a behaviour written by hand
//! (`c/check/`), and run.

use crate::common::{gcc_missing, scratch};
use std::path::Path;
use std::process::{Command, Stdio};

fn gcc(dir: &Path, args: &[&str]) {
    let c = Path::new(env!("CARGO_MANIFEST_DIR")).join("c");
    let o = Command::new("gcc")
        .args(args)
        .arg(format!("-I{}", c.join("check").display()))
        .arg(format!("-I{}", c.display()))
        .current_dir(dir)
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "gcc {args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
}

#[test]
fn the_runtime_and_harness_compile_alone_and_run_a_behaviour_written_by_hand() {
    if gcc_missing() {
        return;
    }
    let c = Path::new(env!("CARGO_MANIFEST_DIR")).join("c");
    let behaviour = c.join("check").join("behaviour.c");
    let harness = c.join("harness.c");
    for suppressed in ["0", "1"] {
        let dir = scratch(&format!("runtime-c-{suppressed}"));
        let define = format!("-DBEHAVIOUR_SUPPRESSED={suppressed}");
        let strict = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic"];
        let mut core = strict.to_vec();
        core.extend(["-ffreestanding", &define, "-c", "-o", "behaviour.o"]);
        core.push(behaviour.to_str().unwrap());
        gcc(&dir, &core);
        let mut host = strict.to_vec();
        host.extend([&define, "-o", "door", "behaviour.o"]);
        host.push(harness.to_str().unwrap());
        gcc(&dir, &host);
        let mut run = Command::new(dir.join("door"))
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .spawn()
            .unwrap();
        use std::io::Write;
        run.stdin
            .take()
            .unwrap()
            .write_all(b"open = false\n")
            .unwrap();
        let out = run.wait_with_output().unwrap();
        assert!(out.status.success());
        let trace = String::from_utf8(out.stdout).unwrap();
        let events: Vec<&str> = trace
            .lines()
            .map(|l| {
                l.split("\"event\":\"")
                    .nth(1)
                    .unwrap_or("")
                    .split('"')
                    .next()
                    .unwrap()
            })
            .collect();
        assert_eq!(
            events,
            ["posted", "entered", "posted", "finished"],
            "{trace}"
        );
        assert!(
            trace.contains("\"type\":\"Light\",\"content\":\"on\""),
            "{trace}"
        );
    }
}
