//! ARCHITECTURE.md's picture of the crates, held to the manifests: every crate drawn with exactly
//! the proclaim crates its `Cargo.toml` depends on, each on a layer above all of them.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// The crates the picture draws, each with its layer and what it says it depends on.
fn picture() -> BTreeMap<String, (usize, BTreeSet<String>)> {
    let text =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("ARCHITECTURE.md"))
            .expect("ARCHITECTURE.md");
    let block = text
        .split("The crates in layers")
        .nth(1)
        .and_then(|rest| rest.split("```").nth(1))
        .expect("the crates' picture");
    let mut crates = BTreeMap::new();
    for line in block.lines().filter(|l| !l.trim().is_empty()) {
        let line = line.trim_start();
        let (layer, rest) = match line.split_once(' ') {
            Some((n, rest)) if n.parse::<usize>().is_ok() => (n.parse().unwrap(), rest),
            // A second line of the layer above.
            _ => (crates.values().map(|(l, _)| *l).max().unwrap_or(0), line),
        };
        // Several crates a line, each `name ─▶ a, b` or a bare `name`, separated by wide gaps.
        for entry in rest.split("    ").map(str::trim).filter(|e| !e.is_empty()) {
            let (name, deps) = match entry.split_once(" ─▶ ") {
                Some((name, deps)) => (name.trim(), deps),
                None => (entry, ""),
            };
            if name.contains('/') || name.contains(' ') {
                continue; // the binary and python/, described rather than listed
            }
            let deps = deps
                .split(',')
                .map(str::trim)
                .filter(|d| !d.is_empty())
                .map(str::to_string)
                .collect();
            crates.insert(name.to_string(), (layer, deps));
        }
    }
    crates
}

/// The proclaim crates `crates/NAME/Cargo.toml` lists under `[dependencies]`.
fn manifest_dependencies(name: &str) -> BTreeSet<String> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("crates/{name}/Cargo.toml"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut section = "";
    let mut deps = BTreeSet::new();
    for line in text.lines().map(str::trim) {
        if line.starts_with('[') {
            section = line;
        } else if section == "[dependencies]" {
            if let Some(dep) = line.strip_prefix("proclaim-") {
                let end = dep
                    .find(|c: char| !(c.is_alphanumeric() || c == '-'))
                    .unwrap_or(dep.len());
                deps.insert(dep[..end].to_string());
            }
        }
    }
    deps
}

#[test]
fn the_crates_picture_is_what_the_manifests_say() {
    let picture = picture();
    let on_disk: BTreeSet<String> =
        std::fs::read_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join("crates"))
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
    assert_eq!(
        picture.keys().cloned().collect::<BTreeSet<_>>(),
        on_disk,
        "every crate under crates/ is drawn, and nothing else"
    );
    for (name, (layer, drawn)) in &picture {
        assert_eq!(drawn, &manifest_dependencies(name), "`{name}`'s arrows");
        for dep in drawn {
            assert!(
                picture[dep].0 < *layer,
                "`{name}` (layer {layer}) uses `{dep}` on a layer not below it"
            );
        }
    }
}
