//! A ringlet's meaning is written once, in `proclaim-lower`'s `ringlet.rs`: no other library
//! crate (nor the Python package) reads a state's activities (`on_entry`, `on_exit`,
//! `internal`) or its transitions' order (`Machine::outgoing`) by itself, so a change to what
//! a ringlet runs (a statechart's exits) is made in one place and every back end follows; and
//! none matches on a statement's kinds (`StatementKind`) but the two that say what they are
//! (`proclaim-lower`'s walk that runs them and its reader for the back ends that print them).

use super::rust_code::{code_only, library_files};
use std::path::Path;

/// What reads a ringlet's parts around `proclaim-lower`: a field read or a method call.
const PARTS: [&str; 4] = [".on_entry", ".on_exit", ".internal", ".outgoing("];

/// The crates that may: the model's own (it defines them) and the one that says what they mean.
const OWNERS: [&str; 2] = ["fsm", "lower"];

/// Each `file:line: text` of `code` where it reads a part ([`PARTS`]) of a state.
fn reads(file: &str, code: &str) -> Vec<String> {
    let mut found = Vec::new();
    for (number, line) in code.lines().enumerate() {
        for part in PARTS {
            let hit = line.match_indices(part).any(|(at, _)| {
                let before = line[..at].chars().next_back();
                let after = line[at + part.len()..].chars().next();
                let name = |c: char| c.is_alphanumeric() || c == '_';
                // `0..internal` is a range; `.internal_x` another name; `.on_entry(` a method
                // of the reader's own.
                before.is_some_and(|c| name(c) || c == ')' || c == ']')
                    && (part.ends_with('(') || !after.is_some_and(|c| name(c) || c == '('))
            });
            if hit {
                found.push(format!("{file}:{}: {}", number + 1, line.trim()));
            }
        }
    }
    found
}

#[test]
fn only_the_lowered_form_reads_what_a_ringlet_runs() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut found = Vec::new();
    let mut owners_read = false;
    // The Python package is outside the workspace but reads machines as the crates do.
    let python = std::fs::read_dir(root.join("python/src"))
        .into_iter()
        .flatten();
    let python = python
        .flatten()
        .map(|entry| entry.path())
        .filter(|p| p.extension().is_some_and(|e| e == "rs"));
    let python = python.map(|path| {
        let text = std::fs::read_to_string(&path).unwrap_or_default();
        ("python".to_string(), path, text)
    });
    for (krate, path, text) in library_files(root).into_iter().chain(python) {
        let file = path.strip_prefix(root).unwrap().display().to_string();
        let hits = reads(&file, &code_only(&text));
        if OWNERS.contains(&krate.as_str()) {
            owners_read |= !hits.is_empty();
        } else {
            found.extend(hits);
        }
    }
    assert!(owners_read, "the scan finds the lowered form's own reads");
    assert!(
        found.is_empty(),
        "read a ringlet through proclaim_lower::RingletPlan instead:\n{}",
        found.join("\n")
    );
}

#[test]
fn the_scan_tells_a_field_read_from_a_name_that_only_begins_alike() {
    let code =
        "let a = state.on_exit;\nself.on_entry();\nlet b = x.internal_map;\nm.outgoing(id)\nfor i in 0..internal {}\n";
    assert_eq!(
        reads("f.rs", code),
        ["f.rs:1: let a = state.on_exit;", "f.rs:4: m.outgoing(id)"]
    );
}

#[test]
fn only_the_lowered_form_matches_on_the_kinds_of_statement() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut found = Vec::new();
    let mut lowered_matches = false;
    for (krate, path, text) in library_files(root) {
        let file = path.strip_prefix(root).unwrap().display().to_string();
        let hits: Vec<String> = code_only(&text)
            .lines()
            .enumerate()
            .filter(|(_, line)| line.contains("StatementKind::"))
            .map(|(n, line)| format!("{file}:{}: {}", n + 1, line.trim()))
            .collect();
        if OWNERS.contains(&krate.as_str()) {
            lowered_matches |= krate == "lower" && !hits.is_empty();
        } else {
            found.extend(hits);
        }
    }
    assert!(
        lowered_matches,
        "the scan finds the lowered form's own match"
    );
    assert!(
        found.is_empty(),
        "meet statements through proclaim_lower::read_statement (a StatementReader) instead:\n{}",
        found.join("\n")
    );
}
