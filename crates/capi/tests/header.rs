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
