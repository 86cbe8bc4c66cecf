//! Machine files named on the command line: native `.machine`, Qfsm `.fsm`, or either file of
//! a T/A pair.

use crate::failure::Failure;
use proclaim_fsm::{import_qfsm, import_ta, is_native, parse_machine, partner_of, Imported};
use std::path::Path;

/// A native or Qfsm file, or either file of a T/A pair (its partner is found beside it); `None`
/// for anything else (a theory).
pub fn machine_file(name: &str) -> Result<Option<Imported>, Failure> {
    let path = Path::new(name);
    let file_name = path
        .file_name()
        .and_then(|f| f.to_str())
        .unwrap_or_default();
    let read = |p: &Path| {
        std::fs::read_to_string(p).map_err(|error| Failure::Read {
            path: p.to_path_buf(),
            error,
        })
    };
    if is_native(name) {
        return Ok(Some(parse_machine(name, &read(path)?)));
    }
    if path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("fsm"))
    {
        let stem = path
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("machine");
        return Ok(Some(import_qfsm(name, &read(path)?, stem)));
    }
    let is_table =
        file_name.ends_with(".txt") && (file_name.starts_with('T') || file_name.starts_with('A'));
    let Some(partner) = partner_of(path).filter(|p| is_table && p.exists()) else {
        return Ok(None);
    };
    let (t, a) = if file_name.starts_with('T') {
        (path.to_path_buf(), partner)
    } else {
        (partner, path.to_path_buf())
    };
    let machine = file_name[1..].trim_end_matches(".txt");
    let show = |p: &Path| p.display().to_string();
    Ok(Some(import_ta(
        machine,
        &show(&t),
        &read(&t)?,
        &show(&a),
        &read(&a)?,
    )))
}
