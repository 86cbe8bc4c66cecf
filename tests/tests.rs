//! The one integration-test binary: one module per area.

mod behaviours;
mod cli;
mod experts;
mod gamecontroller;
mod machines;
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
