//! No library function over eighty lines: a longer one does several jobs, and each job reads
//! better as a named stage of its own.

use super::rust_code::{code_only, functions, library_files};
use std::path::Path;

const LONGEST_BODY: usize = 80;

#[test]
fn no_library_function_is_longer_than_eighty_lines() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut counted = 0;
    let mut long = Vec::new();
    for (_, path, text) in library_files(root) {
        let file = path
            .strip_prefix(root)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        for function in functions(&code_only(&text)) {
            counted += 1;
            if function.body_lines > LONGEST_BODY {
                long.push(format!(
                    "{file}:{} `{}`: {} lines",
                    function.line, function.name, function.body_lines
                ));
            }
        }
    }
    assert!(counted > 1000, "the scan finds the workspace's functions");
    assert!(
        long.is_empty(),
        "functions longer than {LONGEST_BODY} lines (split each into named stages):\n{}",
        long.join("\n")
    );
}
