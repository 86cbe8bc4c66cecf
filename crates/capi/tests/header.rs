//! The checked-in `include/proclaim.h` is what cbindgen makes of the sources now: CI runs this, so
//! a change to the API that forgets the header fails. `PROCLAIM_BLESS=1` rewrites the header.

use std::path::Path;

#[test]
fn the_checked_in_header_is_current() {
    let crate_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let config =
        cbindgen::Config::from_file(crate_dir.join("cbindgen.toml")).expect("cbindgen.toml reads");
    let bindings = cbindgen::Builder::new()
        .with_crate(crate_dir)
        .with_config(config)
        .generate()
        .expect("cbindgen reads the crate");
    let mut generated = Vec::new();
    bindings.write(&mut generated);
    let generated = String::from_utf8(generated).expect("the header is UTF-8");

    let header = crate_dir.join("include/proclaim.h");
    if std::env::var_os("PROCLAIM_BLESS").is_some() {
        std::fs::write(&header, &generated).expect("the header is writable");
        return;
    }
    let checked_in = std::fs::read_to_string(&header).unwrap_or_default();
    if checked_in != generated {
        let first_difference = checked_in
            .lines()
            .zip(generated.lines())
            .position(|(a, b)| a != b)
            .unwrap_or(checked_in.lines().count().min(generated.lines().count()));
        panic!(
            "include/proclaim.h is stale (first difference at line {}); run \
             `PROCLAIM_BLESS=1 cargo test -p proclaim-capi --test tests header` and commit it",
            first_difference + 1
        );
    }
}

/// Each function of the header with its comment and its parameters' names.
fn functions(header: &str) -> Vec<(String, String, Vec<String>)> {
    let lines: Vec<&str> = header.lines().collect();
    let mut found = Vec::new();
    let mut i = 0;
    while i < lines.len() {
        let line = lines[i];
        let Some(open) = line.find("proclaim_").filter(|_| {
            !line.starts_with("//") && !line.starts_with("typedef") && line.contains('(')
        }) else {
            i += 1;
            continue;
        };
        let name = line[open..line.find('(').unwrap()].to_string();
        let mut declaration = String::new();
        let mut end = i;
        while end < lines.len() {
            declaration.push_str(lines[end]);
            if lines[end].trim_end().ends_with(");") {
                break;
            }
            end += 1;
        }
        let inside =
            &declaration[declaration.find('(').unwrap() + 1..declaration.rfind(')').unwrap()];
        let parameters = inside
            .split(',')
            .map(|p| {
                p.trim()
                    .rsplit(|c: char| !(c.is_alphanumeric() || c == '_'))
                    .next()
                    .unwrap_or("")
                    .to_string()
            })
            .filter(|p| !p.is_empty() && p != "void")
            .collect();
        let mut comment = Vec::new();
        let mut j = i;
        while j > 0 && lines[j - 1].starts_with("//") {
            j -= 1;
            comment.push(lines[j]);
        }
        comment.reverse();
        found.push((name, comment.join("\n"), parameters));
        i = end + 1;
    }
    found
}

/// C users read the header, not the Rust: every function says what it does and names each of
/// its parameters there (Python's stub is held to the extension the same way by stubtest).
#[test]
fn every_function_in_the_header_names_each_of_its_parameters() {
    let header =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("include/proclaim.h"))
            .expect("the header reads");
    let functions = functions(&header);
    assert!(
        functions.len() >= 20,
        "the functions were found: {}",
        functions.len()
    );
    let mut silent = Vec::new();
    for (name, comment, parameters) in &functions {
        if comment.is_empty() {
            silent.push(format!("{name}: no comment"));
        }
        let words: Vec<&str> = comment
            .split(|c: char| !(c.is_alphanumeric() || c == '_'))
            .collect();
        for p in parameters {
            if !words.contains(&p.as_str()) {
                silent.push(format!("{name}: `{p}` is not named in its comment"));
            }
        }
    }
    assert!(silent.is_empty(), "{}", silent.join("\n"));
}

#[test]
fn a_declaration_is_read_with_its_comment_and_parameters() {
    let header = "// Frees `text`.\nvoid proclaim_string_free(char *text);\n\n// Two.\nint proclaim_two(const struct A *a,\n                 uint32_t b_out);\n";
    assert_eq!(
        functions(header),
        [
            (
                "proclaim_string_free".to_string(),
                "// Frees `text`.".to_string(),
                vec!["text".to_string()]
            ),
            (
                "proclaim_two".to_string(),
                "// Two.".to_string(),
                vec!["a".to_string(), "b_out".to_string()]
            ),
        ]
    );
}
