//! One name per thing: no public type name is defined in two crates, so a reader who meets a
//! name knows which crate's concept it is.

use super::rust_code::{code_only, library_files};
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// The public types (`pub struct`, `pub enum`, `pub trait`, `pub type`) each crate defines,
/// by name.
fn public_types(root: &Path) -> BTreeMap<String, BTreeSet<String>> {
    let mut defined: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (krate, path, text) in library_files(root) {
        for (number, line) in code_only(&text).lines().enumerate() {
            let line = line.trim_start();
            for keyword in ["pub struct ", "pub enum ", "pub trait ", "pub type "] {
                let Some(rest) = line.strip_prefix(keyword) else {
                    continue;
                };
                let name: String = rest
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect();
                let file = path.strip_prefix(root).unwrap().display();
                defined
                    .entry(name)
                    .or_default()
                    .insert(format!("{krate} ({file}:{})", number + 1));
            }
        }
    }
    defined
}

#[test]
fn no_public_type_name_is_defined_in_two_crates() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let types = public_types(root);
    assert!(
        types.contains_key("Engine") && types.contains_key("Whiteboard"),
        "the scan finds the workspace's types"
    );
    let crate_of = |place: &String| place.split(' ').next().unwrap_or_default().to_string();
    let twice: Vec<String> = types
        .iter()
        .filter(|(_, places)| places.iter().map(crate_of).collect::<BTreeSet<_>>().len() > 1)
        .map(|(name, places)| {
            let places: Vec<&str> = places.iter().map(String::as_str).collect();
            format!("{name}: {}", places.join(", "))
        })
        .collect();
    assert!(
        twice.is_empty(),
        "a public type name defined in two crates (rename the less central one to say what it \
         is):\n{}",
        twice.join("\n")
    );
}
