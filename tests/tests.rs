//! The one integration-test binary: one module per area.

mod activities;
mod behaviours;
mod cli;
mod experts;
mod gamecontroller;
mod machines;
mod monitor;
#[cfg(feature = "zenoh")]
mod network;
mod properties;
mod reasoner;
mod runner;
mod syntax;
mod theories;
mod whiteboard;

/// Where the shared corpus and specs live, when present beside the project.
#[allow(dead_code)]
pub fn shared_dir() -> Option<std::path::PathBuf> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared");
    dir.is_dir().then_some(dir)
}

/// A fresh folder holding a behaviour's files (`behaviour.toml` and its machines), unique to
/// this test process and `tag`.
#[allow(dead_code)]
pub fn behaviour_folder(tag: &str, files: &[(&str, &str)]) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("proclaim-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, text) in files {
        std::fs::write(dir.join(name), text).unwrap();
    }
    dir
}

/// A theory only a search decides: ladder(6) of `benchmarks.md`, whose layers alone would be
/// decided without one, with one read across them (`t2` attacked from `t0`), so its 24 goals
/// are searched (`t0` is proved, after about 110,000 steps).
#[allow(dead_code)]
pub fn crossed_ladder() -> String {
    let mut text = Vec::new();
    proclaim_gen::Family::parse("ladder", &[6])
        .unwrap()
        .write(&mut text, proclaim_gen::Format::Dl)
        .unwrap();
    String::from_utf8(text).unwrap() + "x: t0 => ~t2.\n"
}
