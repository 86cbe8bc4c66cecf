//! Measures 1,000 compiled machines at 1 kHz on one core: a behaviour of 1,000 copies of the
//! microwave's machine (one theory, whose inputs they share) is compiled to freestanding C, built
//! with `gcc -O2`, and run by `thousand_machines.c` for 20 seconds of robot time, one round a
//! millisecond; it prints the processor time as a fraction of one core. Needs gcc.
//!
//! `cargo run --release -p proclaim-compile --example thousand_machines [MACHINES [SECONDS]]`

use proclaim_behaviour::{load, Folder};
use std::path::Path;
use std::process::{Command, ExitCode};
use std::sync::Arc;

#[path = "common/microwave_copies.rs"]
mod microwave_copies;

const HOST: &str = include_str!("thousand_machines.c");

fn main() -> ExitCode {
    let mut args = std::env::args().skip(1);
    let machines: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(1000);
    let seconds: String = args.next().unwrap_or_else(|| "20".into());
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let dir = std::env::temp_dir().join(format!("proclaim-thousand-{}", std::process::id()));
    let folder = dir.join("behaviour");
    let out = dir.join("c");
    std::fs::create_dir_all(&folder).expect("a scratch folder");
    std::fs::create_dir_all(&out).expect("a scratch folder");
    microwave_copies::copies(&root, &folder, machines);
    let behaviour = match load("thousand", Arc::new(Folder::new(&folder))) {
        Ok(b) => b,
        Err(problems) => {
            for p in problems {
                eprintln!("{p}");
            }
            return ExitCode::FAILURE;
        }
    };
    let compiled = match proclaim_compile::compile_behaviour(&behaviour) {
        Ok(c) => c,
        Err(refusal) => {
            eprintln!("{refusal}");
            return ExitCode::FAILURE;
        }
    };
    let mut core = Vec::new();
    for (file, text) in &compiled.files {
        std::fs::write(out.join(file), text).expect("a compiled file written");
        if file.ends_with(".c") && file != "main.c" {
            core.push(file.clone());
        }
    }
    std::fs::write(out.join("bench.c"), HOST).expect("the host written");
    let gcc = |args: &[&str]| {
        let status = Command::new("gcc").args(args).current_dir(&out).status();
        matches!(status, Ok(s) if s.success())
    };
    let mut build = vec![
        "-std=c99",
        "-O2",
        "-Wall",
        "-Wextra",
        "-Werror",
        "-ffreestanding",
        "-c",
    ];
    build.extend(core.iter().map(String::as_str));
    let objects: Vec<String> = core.iter().map(|c| c.replace(".c", ".o")).collect();
    let mut link = vec![
        "-std=c99",
        "-O2",
        "-D_POSIX_C_SOURCE=199309L",
        "bench.c",
        "-o",
        "bench",
    ];
    link.extend(objects.iter().map(String::as_str));
    if !gcc(&build) || !gcc(&link) {
        eprintln!("gcc failed in {}", out.display());
        return ExitCode::FAILURE;
    }
    let size = Command::new("size").arg("bench").current_dir(&out).output();
    if let Ok(size) = size {
        print!("{}", String::from_utf8_lossy(&size.stdout));
    }
    let status = Command::new(out.join("bench")).arg(&seconds).status();
    let _ = std::fs::remove_dir_all(&dir);
    match status {
        Ok(s) if s.success() => ExitCode::SUCCESS,
        _ => ExitCode::FAILURE,
    }
}
