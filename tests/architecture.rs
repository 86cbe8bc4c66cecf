//! ARCHITECTURE.md's claims that can be checked cheaply, held to the repository: the picture of
//! the crates against the manifests (every crate drawn with exactly the proclaim crates its
//! `Cargo.toml` depends on, each on a layer above all of them), the binary's and Zenoh's "does
//! not", the crates that do no I/O, the map's length and that it holds no measured figure; and
//! that no file names a path outside the repository but the shared corpus; and what the code
//! itself must keep: every library crate tests itself, one name per thing (`type_names`), no
//! library function over eighty lines (`function_length`).

mod file_circles;
mod function_length;
mod ringlet_meaning;
mod rust_code;
mod type_names;

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
    let mut last_layer = 0;
    for line in block.lines().filter(|l| !l.trim().is_empty()) {
        let line = line.trim_start();
        let (layer, rest) = match line.split_once(' ') {
            Some((n, rest)) if n.parse::<usize>().is_ok() => (n.parse().unwrap(), rest),
            // A second line of the numbered line above it.
            _ => (last_layer, line),
        };
        last_layer = layer;
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
    dependencies(&format!("crates/{name}/Cargo.toml"), "proclaim-")
}

/// The dependencies whose names start with `prefix` (that prefix taken off) that the manifest at
/// `manifest` (from the repository's root) lists under `[dependencies]`.
fn dependencies(manifest: &str, prefix: &str) -> BTreeSet<String> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(manifest);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut section = "";
    let mut deps = BTreeSet::new();
    for line in text.lines().map(str::trim) {
        if line.starts_with('[') {
            section = line;
        } else if section == "[dependencies]" {
            if let Some(dep) = line.strip_prefix(prefix) {
                let end = dep
                    .find(|c: char| !(c.is_alphanumeric() || c == '-' || c == '_'))
                    .unwrap_or(dep.len());
                deps.insert(dep[..end].to_string());
            }
        }
    }
    deps
}

/// The crates under `crates/`, by folder name.
fn crates_on_disk() -> BTreeSet<String> {
    std::fs::read_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join("crates"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect()
}

fn architecture_text() -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("ARCHITECTURE.md"))
        .expect("ARCHITECTURE.md")
}

#[test]
fn the_crates_picture_is_what_the_manifests_say() {
    let picture = picture();
    let on_disk = crates_on_disk();
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

/// The binary's line of the picture: every crate but capi (the C library is built on its own)
/// and host-board (what compiled programs run on), and zenoh only as its optional feature.
#[test]
fn the_binary_depends_on_every_crate_but_capi() {
    assert!(architecture_text().contains("the binary) ─▶ every crate below but capi, host-board"));
    let mut expected = crates_on_disk();
    expected.remove("capi");
    expected.remove("host-board");
    assert_eq!(dependencies("Cargo.toml", "proclaim-"), expected);
    let manifest =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("Cargo.toml")).unwrap();
    assert!(manifest.contains("proclaim-zenoh = { workspace = true, optional = true }"));
}

/// "the only crate that depends on Zenoh".
#[test]
fn only_the_zenoh_crate_depends_on_zenoh() {
    for name in crates_on_disk() {
        let zenoh = dependencies(&format!("crates/{name}/Cargo.toml"), "zenoh");
        assert_eq!(zenoh.contains(""), name == "zenoh", "`{name}` and Zenoh");
    }
    assert!(
        !dependencies("Cargo.toml", "zenoh").contains(""),
        "the binary uses Zenoh through proclaim-zenoh"
    );
}

/// README's test command names no package, so it runs the workspace's default members: the
/// binary and every crate but zenoh (whose suite `.ci/run` runs with the feature on). A crate
/// added under `crates/` and left out of that list would never be tested by it.
#[test]
fn the_default_members_are_every_crate_but_zenoh() {
    let manifest =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("Cargo.toml")).unwrap();
    let list = manifest
        .split_once("default-members = [")
        .and_then(|(_, rest)| rest.split_once(']'))
        .expect("Cargo.toml has default-members")
        .0;
    let members: BTreeSet<String> = list
        .split(',')
        .map(|m| m.trim().trim_matches('"').to_string())
        .filter(|m| !m.is_empty())
        .collect();
    let mut expected: BTreeSet<String> = crates_on_disk()
        .into_iter()
        .filter(|name| name != "zenoh")
        .map(|name| format!("crates/{name}"))
        .collect();
    expected.insert(".".to_string());
    assert_eq!(members, expected);
    let ci =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join(".ci/run")).unwrap();
    assert!(
        ci.contains("-p proclaim-zenoh"),
        ".ci/run tests the Zenoh crate on its own"
    );
}

/// The crates whose paragraphs say they do no I/O, are pure, or open no sockets and read no
/// files: none of their library code names the file system, the network or processes.
#[test]
fn the_crates_without_io_name_none() {
    let io = [
        "std::fs",
        "tokio::fs",
        "std::net",
        "tokio::net",
        "std::process",
        "tokio::process",
    ];
    for name in [
        "syntax",
        "cdl",
        "fsm",
        "gamecontroller",
        "gen",
        "runner",
        "verify",
    ] {
        let src = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("crates/{name}/src"));
        for (file, text) in repository_texts(&src) {
            for word in io {
                assert!(!text.contains(word), "{} names {word}", file.display());
            }
        }
    }
}

/// "Library crates test themselves": each crate under `crates/` holds a test of its own, in its
/// `src` or its `tests`.
#[test]
fn every_library_crate_tests_itself() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let crates = crates_on_disk();
    assert!(crates.len() > 10, "{crates:?}");
    for name in crates {
        let dir = root.join("crates").join(&name);
        let mut texts = repository_texts(&dir.join("src"));
        if dir.join("tests").is_dir() {
            texts.extend(repository_texts(&dir.join("tests")));
        }
        assert!(
            texts
                .iter()
                .any(|(_, text)| text.contains("#[test]") || text.contains("#[tokio::test")),
            "crates/{name} tests nothing of its own"
        );
    }
}

/// The map stays a map: short, and with no measured figure (those are README's, under "Speed").
#[test]
fn architecture_is_short_and_holds_no_measured_figure() {
    let text = architecture_text();
    let lines = text.lines().count();
    assert!(
        lines < 250,
        "ARCHITECTURE.md has {lines} lines; a map has fewer than 250"
    );
    let units = [
        "ns", "µs", "us", "ms", "s", "min", "KiB", "MiB", "GiB", "kB", "KB", "MB", "GB", "%", "×",
    ];
    for (number, line) in text.lines().enumerate() {
        let chars: Vec<char> = line.chars().collect();
        let mut i = 0;
        while i < chars.len() {
            if !chars[i].is_ascii_digit() {
                i += 1;
                continue;
            }
            while i < chars.len() && (chars[i].is_ascii_digit() || ",._".contains(chars[i])) {
                i += 1;
            }
            let mut j = i;
            if j < chars.len() && chars[j] == ' ' {
                j += 1;
            }
            let word: String = chars[j..]
                .iter()
                .take_while(|c| c.is_alphabetic() || "%×".contains(**c))
                .collect();
            assert!(
                !units.contains(&word.as_str()),
                "ARCHITECTURE.md:{}: a measured figure (`{}`) belongs in README's \"Speed\"",
                number + 1,
                line.trim()
            );
        }
    }
}

/// Every file of the repository that is text, with its path: code, tests, documents, scripts,
/// manifests (not build output, caches or git's own files).
fn repository_texts(root: &Path) -> Vec<(std::path::PathBuf, String)> {
    // Folders of tools' output: a venv, caches, fuzzing's inputs and findings.
    const SKIPPED: [&str; 7] = [
        ".venv",
        "__pycache__",
        ".pytest_cache",
        ".mypy_cache",
        "node_modules",
        "corpus",
        "artifacts",
    ];
    let mut files = Vec::new();
    let mut folders = vec![root.to_path_buf()];
    while let Some(folder) = folders.pop() {
        for entry in std::fs::read_dir(&folder).unwrap() {
            let path = entry.unwrap().path();
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            if name == ".git" {
                // A clone's folder, or a worktree's file naming where its repository is.
                continue;
            }
            if path.is_dir() {
                if !(name.starts_with("target") || SKIPPED.contains(&name.as_str())) {
                    folders.push(path);
                }
            } else if let Ok(text) = std::fs::read_to_string(&path) {
                files.push((path, text));
            }
        }
    }
    files
}

/// The relative paths a text names: each run of `../` and what follows it up to a character no
/// path has (a sentence's closing `.` left out).
fn relative_paths(text: &str) -> Vec<&str> {
    let in_path = |c: char| c.is_ascii_alphanumeric() || "_-./*".contains(c);
    let mut paths = Vec::new();
    let mut from = 0;
    while let Some(at) = text[from..].find("../").map(|i| from + i) {
        let starts_a_path = !text[..at].ends_with(in_path);
        let end = text[at..]
            .find(|c: char| !in_path(c))
            .map_or(text.len(), |i| at + i);
        if starts_a_path {
            let path = &text[at..end];
            let path = match path.strip_suffix('.') {
                Some(shorter) if !shorter.ends_with('.') => shorter,
                _ => path,
            };
            paths.push(path);
        }
        from = end.max(at + 3);
    }
    paths
}

/// `relative` read from `folder`, `..` taken off as it comes (no file system access).
fn resolve(folder: &Path, relative: &str) -> std::path::PathBuf {
    let mut path = folder.to_path_buf();
    for part in relative.split('/') {
        match part {
            ".." => {
                path.pop();
            }
            "" | "." => {}
            part => path.push(part),
        }
    }
    path
}

/// A clone of the repository alone is enough to read what its code and documents cite: no file
/// names a path outside it (the specs the code implements once lived beside it), except
/// the shared corpus of real user files, which the tests read when it is there and skip without.
/// A relative path counts as inside when, read from some folder of the repository, it names
/// something that exists in the repository.
#[test]
fn no_file_names_a_path_outside_the_repository_but_the_shared_corpus() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let outside = root.parent().expect("the repository has a parent folder");
    let corpus = outside.join("shared/corpus");
    // Text that is data, not a reference: a Qfsm link file, as the importer's test feeds it.
    let data = [(
        "crates/fsm/tests/machines.rs",
        concat!("..", "/DefaultMachines/SMGetUp.fsm"),
    )];
    let texts = repository_texts(root);
    let mut folders: Vec<std::path::PathBuf> = texts
        .iter()
        .filter_map(|(path, _)| path.parent().map(Path::to_path_buf))
        .collect();
    folders.sort();
    folders.dedup();
    let mut found = Vec::new();
    for (file, text) in &texts {
        let name = file
            .strip_prefix(root)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        for relative in relative_paths(text) {
            let names_the_corpus = folders
                .iter()
                .any(|folder| resolve(folder, relative).starts_with(&corpus));
            let names_something_inside = folders.iter().any(|folder| {
                let path = resolve(folder, relative);
                path.starts_with(root) && path.exists()
            });
            if !(names_the_corpus
                || names_something_inside
                || data.contains(&(name.as_str(), relative)))
            {
                found.push(format!("{name}: {relative}"));
            }
        }
        if text.contains(&format!("{}/", outside.display())) {
            found.push(format!(
                "{name}: an absolute path under {}",
                outside.display()
            ));
        }
    }
    assert!(
        found.is_empty(),
        "paths outside the repository:\n{}",
        found.join("\n")
    );
}
