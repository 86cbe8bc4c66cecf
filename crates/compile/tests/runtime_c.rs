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
    for (suppressed, ranges) in [("0", "0"), ("1", "0"), ("0", "1")] {
        let dir = scratch(&format!("runtime-c-{suppressed}-{ranges}"));
        let define = format!("-DBEHAVIOUR_SUPPRESSED={suppressed}");
        let ranged = format!("-DBEHAVIOUR_RANGES={ranges}");
        let strict = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic"];
        let mut core = strict.to_vec();
        core.extend([
            "-ffreestanding",
            &define,
            &ranged,
            "-c",
            "-o",
            "behaviour.o",
        ]);
        core.push(behaviour.to_str().unwrap());
        gcc(&dir, &core);
        let mut host = strict.to_vec();
        host.extend([&define, &ranged, "-o", "door", "behaviour.o"]);
        host.push(harness.to_str().unwrap());
        gcc(&dir, &host);
        let mut run = Command::new(dir.join("door"))
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .spawn()
            .unwrap();
        use std::io::Write;
        // With a range of 0..1 that remembers two values: 7 is said once, 8 too, 9 with the
        // note that later values are not said, and 10 not at all; 1 lies inside.
        let script: &[u8] = if ranges == "1" {
            b"open = false\nLight = 7\nLight = 7\nLight = 8\nLight = 9\nLight = 10\nLight = +1\n"
        } else {
            b"open = false\n"
        };
        run.stdin.take().unwrap().write_all(script).unwrap();
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
            .filter(|e| *e != "warned")
            .collect();
        let posted_first = if ranges == "1" { 6 } else { 1 };
        let mut expected = vec!["posted"; posted_first];
        expected.extend(["entered", "posted", "finished"]);
        assert_eq!(events, expected, "{trace}");
        assert!(
            trace.contains("\"type\":\"Light\",\"content\":\"on\""),
            "{trace}"
        );
        let warned: Vec<&str> = trace.lines().filter(|l| l.contains("warned")).collect();
        if ranges == "1" {
            assert_eq!(warned.len(), 3, "{trace}");
            assert!(warned[0].contains("posted Light = 7, outside its declared range 0..1"));
            assert!(warned[1].contains("posted Light = 8, outside"));
            assert!(
                warned[2].contains("posted Light = 9, outside")
                    && warned[2].contains("later values are not said")
            );
        } else {
            assert!(warned.is_empty(), "{trace}");
        }
    }
}
