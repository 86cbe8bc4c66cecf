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

/// A fresh, empty folder `NAME-PID` in Cargo's scratch folder for tests ([`own_folder`]).
#[allow(dead_code)]
pub fn fresh_folder(name: &str) -> std::path::PathBuf {
    let dir = own_folder(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The folder `NAME-PID` in Cargo's scratch folder for tests, this test process's own, made if
/// missing. Folders of the same name that test processes now ended left, untouched for ten
/// minutes, are removed first, so the last run's are there to look into and a developer's disk
/// does not fill run by run. (Where `/proc` cannot say which processes live, nothing is
/// removed; the ten minutes spare a process `/proc` does not show, in another PID namespace.)
#[allow(dead_code)]
pub fn own_folder(name: &str) -> std::path::PathBuf {
    let root = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"));
    let me = std::process::id();
    let ended = |pid: u32| {
        pid != me
            && std::path::Path::new("/proc/self").exists()
            && !std::path::Path::new(&format!("/proc/{pid}")).exists()
    };
    for entry in std::fs::read_dir(root).into_iter().flatten().flatten() {
        let file = entry.file_name();
        let pid =
            (file.to_str()).and_then(|f| f.strip_prefix(name)?.strip_prefix('-')?.parse().ok());
        let idle = (entry.metadata().and_then(|m| m.modified()).ok())
            .and_then(|t| t.elapsed().ok())
            .is_some_and(|d| d > std::time::Duration::from_secs(600));
        if idle && pid.is_some_and(ended) {
            let _ = std::fs::remove_dir_all(entry.path());
        }
    }
    let dir = root.join(format!("{name}-{me}"));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A fresh folder holding a behaviour's files (`behaviour.toml` and its machines), unique to
/// this test process and `tag`.
#[allow(dead_code)]
pub fn behaviour_folder(tag: &str, files: &[(&str, &str)]) -> std::path::PathBuf {
    let dir = own_folder(&format!("proclaim-{tag}"));
    for (name, text) in files {
        std::fs::write(dir.join(name), text).unwrap();
    }
    dir
}
