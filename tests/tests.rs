//! The one integration-test binary of the command line and what spans crates: the binary, the
//! monitor in a browser, behaviours run whole, the whiteboard in and across processes, the
//! shipped theories and the property tests. Each library crate tests itself beside it.

mod architecture;
mod behaviours;
mod book;
mod branches;
mod checkpoints;
mod cli;
mod compiled;
mod compiled_corpus;
mod compiled_rust;
mod compiled_verify;
mod editor;
mod monitor;
mod mutants;
#[cfg(feature = "zenoh")]
mod network;
#[cfg(feature = "zenoh")]
mod partition;
mod programs;
mod properties;
mod subsumption;
mod theories;
mod verify_cli;
mod whiteboard;

/// The binary run with `args`, as a user runs it (no colour).
pub fn proclaim(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_proclaim"))
        .args(args)
        .env("NO_COLOR", "1")
        .output()
        .expect("the binary runs")
}

/// The shared corpus (`../shared/corpus` from the repository's root), when present beside it.
#[allow(dead_code)]
pub fn corpus_dir() -> Option<std::path::PathBuf> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/corpus");
    dir.is_dir().then_some(dir)
}

/// A fresh folder holding a behaviour's files (`behaviour.toml` and its machines), unique to
/// this test process and `tag`.
#[allow(dead_code)]
pub fn behaviour_folder(tag: &str, files: &[(&str, &str)]) -> std::path::PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("proclaim-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, text) in files {
        std::fs::write(dir.join(name), text).unwrap();
    }
    dir
}
