//! No circle of files inside a crate: each file (a folder counts as one) uses only files that
//! do not use it back, however far round, so each can be read, tested and replaced knowing only
//! what it uses.

use super::rust_code::{code_only, library_files};
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// The first segments of the paths after each `crate::` in `code` (`crate::{a, b::c}` names
/// `a` and `b`).
fn used(code: &str) -> BTreeSet<String> {
    let mut names = BTreeSet::new();
    let word = |text: &str| -> String {
        text.chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect()
    };
    for (at, _) in code.match_indices("crate::") {
        let rest = &code[at + "crate::".len()..];
        if let Some(group) = rest.strip_prefix('{') {
            let group = &group[..group.find('}').unwrap_or(group.len())];
            names.extend(group.split(',').map(|item| word(item.trim())));
        } else {
            names.insert(word(rest));
        }
    }
    names.retain(|n| !n.is_empty());
    names
}

/// Each crate's files (by first path segment under `src`) and the files each uses.
fn graphs(root: &Path) -> BTreeMap<String, BTreeMap<String, BTreeSet<String>>> {
    let mut graphs: BTreeMap<String, BTreeMap<String, BTreeSet<String>>> = BTreeMap::new();
    for (krate, path, text) in library_files(root) {
        let src = if krate == "proclaim" {
            root.join("src")
        } else {
            root.join("crates").join(&krate).join("src")
        };
        let relative = path.strip_prefix(&src).unwrap();
        let first = relative.iter().next().unwrap().to_string_lossy();
        let node = first.trim_end_matches(".rs").to_string();
        let code = code_only(&text);
        let code = code.split("#[cfg(test)]").next().unwrap_or_default();
        let uses = graphs
            .entry(krate)
            .or_default()
            .entry(node.clone())
            .or_default();
        uses.extend(used(code).into_iter().filter(|n| *n != node));
    }
    for graph in graphs.values_mut() {
        let nodes: BTreeSet<String> = graph.keys().cloned().collect();
        for uses in graph.values_mut() {
            uses.retain(|n| nodes.contains(n));
        }
    }
    graphs
}

/// The files of `graph` that reach themselves, each with those of its circle.
fn circles(graph: &BTreeMap<String, BTreeSet<String>>) -> BTreeSet<BTreeSet<String>> {
    let reach = |from: &String| -> BTreeSet<String> {
        let mut seen = BTreeSet::new();
        let mut todo: Vec<&String> = graph[from].iter().collect();
        while let Some(n) = todo.pop() {
            if seen.insert(n.clone()) {
                todo.extend(graph[n].iter());
            }
        }
        seen
    };
    let reaches: BTreeMap<&String, BTreeSet<String>> =
        graph.keys().map(|n| (n, reach(n))).collect();
    let mut found = BTreeSet::new();
    for (n, r) in &reaches {
        if r.contains(*n) {
            let circle: BTreeSet<String> = r
                .iter()
                .filter(|m| reaches[*m].contains(*n))
                .cloned()
                .collect();
            found.insert(circle);
        }
    }
    found
}

#[test]
fn no_crate_has_a_circle_of_files() {
    let graphs = graphs(Path::new(env!("CARGO_MANIFEST_DIR")));
    assert!(graphs.len() > 10, "the scan finds the crates");
    let mut problems = Vec::new();
    for (krate, graph) in &graphs {
        for circle in circles(graph) {
            let names: Vec<&str> = circle.iter().map(String::as_str).collect();
            problems.push(format!("{krate}: {}", names.join(" → ")));
        }
    }
    assert!(
        problems.is_empty(),
        "circles of files (move what two files share into a third, below both):\n{}",
        problems.join("\n")
    );
}

#[test]
fn a_circle_is_found_and_uses_are_read_from_code() {
    let code = "use crate::{a, b::c};\nfn f() { crate::d::e(); }\n";
    assert_eq!(used(code), ["a", "b", "d"].map(String::from).into());
    let graph: BTreeMap<String, BTreeSet<String>> = [
        ("a", vec!["b"]),
        ("b", vec!["c"]),
        ("c", vec!["a"]),
        ("d", vec!["a"]),
    ]
    .into_iter()
    .map(|(n, uses)| (n.to_string(), uses.into_iter().map(String::from).collect()))
    .collect();
    let found = circles(&graph);
    assert_eq!(found.len(), 1);
    assert_eq!(
        found.into_iter().next().unwrap(),
        ["a", "b", "c"].map(String::from).into()
    );
}
