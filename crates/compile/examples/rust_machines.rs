//! Measures compiled machines on one core, compiled to Rust: a behaviour of copies of the
//! microwave's machine (one theory, whose inputs they share) is compiled to a Cargo project,
//! built with `cargo build --release`, and run by `rust_rounds.rs.txt` for seconds of robot time,
//! one round a millisecond; it prints the processor time, and the time a round and a ringlet
//! took. One machine gives one ringlet of the microwave, beside `thousand_machines` for C.
//!
//! `cargo run --release -p proclaim-compile --example rust_machines [MACHINES [SECONDS]]`

use proclaim_behaviour::{load, Folder};
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};
use std::sync::Arc;

#[path = "common/microwave_copies.rs"]
mod microwave_copies;

const ROUNDS: &str = include_str!("rust_rounds.rs.txt");

/// Where the project is built: beside the workspace's own builds, so its crates build once.
fn target_dir(root: &Path) -> PathBuf {
    std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| root.join("target"))
        .join("rust-machines")
}

fn main() -> ExitCode {
    let mut args = std::env::args().skip(1);
    let machines: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(1000);
    let seconds: String = args.next().unwrap_or_else(|| "20".into());
    let Some(root) = proclaim_compile::source_repository() else {
        eprintln!("the repository's crates are not here");
        return ExitCode::FAILURE;
    };
    let dir = std::env::temp_dir().join(format!("proclaim-rust-machines-{}", std::process::id()));
    let folder = dir.join("behaviour");
    let out = dir.join("project");
    std::fs::create_dir_all(&folder).expect("a scratch folder");
    microwave_copies::copies(&root, &folder, machines);
    let behaviour = match load("machines", Arc::new(Folder::new(&folder))) {
        Ok(b) => b,
        Err(problems) => {
            for p in problems {
                eprintln!("{p}");
            }
            return ExitCode::FAILURE;
        }
    };
    let compiled = match proclaim_compile::compile_behaviour_rust(&behaviour, None) {
        Ok(c) => c,
        Err(refusal) => {
            eprintln!("{refusal}");
            return ExitCode::FAILURE;
        }
    };
    for (file, text) in &compiled.files {
        let text = if file == "src/main.rs" { ROUNDS } else { text };
        let path = out.join(file);
        std::fs::create_dir_all(path.parent().expect("a folder")).expect("a folder made");
        std::fs::write(path, text).expect("a compiled file written");
    }
    let target = target_dir(&root);
    let built = Command::new(std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into()))
        .args(["build", "--release", "--offline", "--quiet"])
        .current_dir(&out)
        .env("CARGO_TARGET_DIR", &target)
        .status();
    if !matches!(built, Ok(s) if s.success()) {
        eprintln!("cargo build failed in {}", out.display());
        return ExitCode::FAILURE;
    }
    let status = Command::new(target.join("release/behaviour-machines"))
        .arg(&seconds)
        .status();
    let _ = std::fs::remove_dir_all(&dir);
    match status {
        Ok(s) if s.success() => ExitCode::SUCCESS,
        _ => ExitCode::FAILURE,
    }
}
