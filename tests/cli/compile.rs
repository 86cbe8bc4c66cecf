//! `compile`: a theory written as freestanding C, and what it refuses.

use super::{stderr, stdout, temp_file};
use crate::proclaim;
use std::process::Command;

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
    // A theory has no Rust target: said so, exit 2.
    let o = proclaim(&[
        "compile",
        "theories/microwave.dl",
        "--target",
        "rust",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("--target rust compiles a behaviour (a folder)"),
        "{}",
        stderr(&o)
    );
    // So a name there is a behaviour's: `microwave` is the built-in behaviour (the built-in
    // theory under --target c).
    let project = out.join("microwave-rs");
    let o = proclaim(&[
        "compile",
        "microwave",
        "--target",
        "rust",
        "-o",
        project.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let manifest = std::fs::read_to_string(project.join("Cargo.toml")).unwrap();
    assert!(
        manifest.contains("name = \"behaviour-microwave\""),
        "{manifest}"
    );
    let o = proclaim(&[
        "compile",
        "nosuch",
        "--target",
        "rust",
        "-o",
        project.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("no behaviour `nosuch`"),
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

#[test]
fn compiling_what_run_refuses_without_force_says_so_and_compiles() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!(
        "proclaim-compile-unanswered-{}",
        std::process::id()
    ));
    let behaviour = dir.join("behaviour");
    std::fs::create_dir_all(&behaviour).unwrap();
    std::fs::write(
        behaviour.join("behaviour.toml"),
        "[[machine]]\nfile = \"M.machine\"\n",
    )
    .unwrap();
    std::fs::write(
        behaviour.join("M.machine"),
        "machine M\ninitial A\nstate A {\n    when nobody -> B\n}\nstate B {\n}\n",
    )
    .unwrap();
    let o = proclaim(&["run", behaviour.to_str().unwrap(), "--for", "1s"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let o = proclaim(&[
        "compile",
        behaviour.to_str().unwrap(),
        "--target",
        "c",
        "-o",
        dir.join("c").to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let said = stderr(&o);
    assert!(
        said.contains("M.machine:4: warning: label `nobody` is answered by no expert")
            && said.contains("the compiled program runs it as `run --force` does"),
        "{said}"
    );
}

/// `--whiteboard` belongs to a behaviour compiled to Rust: said of a theory or of the C target
/// it is refused with exit 2 and why, and nothing is written.
#[test]
fn whiteboard_is_refused_where_it_means_nothing() {
    let out = std::env::temp_dir().join(format!("proclaim-whiteboard-{}", std::process::id()));
    let cases: [(&[&str], &str); 2] = [
        (
            &["theories/microwave.dl"],
            "--whiteboard is said of a behaviour compiled with --target rust",
        ),
        (
            &["machines/microwave", "--target", "c"],
            "--whiteboard is said of --target rust",
        ),
    ];
    for (args, why) in cases {
        let mut all = vec!["compile"];
        all.extend_from_slice(args);
        all.extend(["--whiteboard", "-o", out.to_str().unwrap()]);
        let o = proclaim(&all);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(why), "{args:?}: {}", stderr(&o));
        assert!(!out.exists(), "{args:?} wrote {}", out.display());
    }
}
